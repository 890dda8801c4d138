"""The separate parts of a section (outer contours) that its wetted entries belong to, and
their submerged areas and widths."""

from __future__ import annotations

import numpy as np

from ..slicing.record import ShiftedPolygons

__all__ = [
    "entry_parts",
    "part_owners",
    "piece_extents",
    "piece_half_widths",
    "shared_piece_extents",
    "submerged_parts",
    "submerged_shares",
    "submerged_widths",
]


def _next(a: np.ndarray) -> np.ndarray:
    """Each point's successor along a closed contour (``np.roll(a, -1, axis=0)``)."""
    return np.concatenate((a[1:], a[:1]))


def entry_parts(sections):
    """Each entry's part, station by station (see :func:`part_owners`).

    Yields
    ------
    idx : (k,) int
        The entries of one station.
    parts, owner
        As :func:`part_owners` gives them.
    """
    station = np.asarray(sections.station)
    for st in np.unique(station):
        idx = np.flatnonzero(station == st)
        yield (idx, *part_owners(sections, idx, sections.polygons[int(st)]))


def part_owners(sections, idx: np.ndarray, contours) -> tuple[list, np.ndarray]:
    """The parts of one station and the part of each of its entries ``idx``.

    A part is an outer contour of the station (a float of a catamaran, a nacelle beside
    a fuselage); an entry belongs to the part whose width holds its keel and whose bottom
    is nearest its keel's depth.

    Parameters
    ----------
    sections : Sections
    idx : (k,) int
        The station's entries.
    contours : sequence of (q, 2) float
        The station's contours, in the sections' coordinates (``sections.polygons[st]``).

    Returns
    -------
    parts : list of (y_min, y_max, z_min, contour, area)
        The station's outer contours (m, m, m, (q, 2) points, m^2).
    owner : (k,) int
        Each entry's part, an index into ``parts``; -1 where no part holds its keel.
    """
    parts = []
    for c in contours:
        c = np.asarray(c, dtype=np.float64)
        if len(c) < 3:
            continue
        y, z = c[:, 0], c[:, 1]
        full = 0.5 * float(np.dot(y, _next(z)) - np.dot(z, _next(y)))
        if full > 0:  # an outer contour
            parts.append((float(y.min()), float(y.max()), float(z.min()), c, full))
    owner = np.full(len(idx), -1)
    for j, i in enumerate(idx):
        yk, zk = float(sections.y_keel[i]), -float(sections.penetration[i])
        best = None
        for k, (y0, y1, z0, _, _) in enumerate(parts):
            if y0 <= yk <= y1 and (best is None or abs(z0 - zk) < best[0]):
                best = (abs(z0 - zk), k)
        owner[j] = -1 if best is None else best[1]
    return parts, owner


def piece_extents(sections, i: int, contour: np.ndarray) -> tuple[float, float]:
    """How far entry ``i``'s own bottom reaches from its keel on each side (port: +y;
    starboard), m, along the part's ``contour`` that it shares with other entries (a
    float of a catamaran whose floats are joined by a tunnel roof in one closed surface).

    From the contour's point nearest the keel the bottom is followed each way while it
    goes on outwards: it ends where it turns vertical or back (a knuckle below the tunnel's
    wall, a round side's widest point), so that each float's bottom ends at its own
    edges, not at the part's.
    """
    c = np.asarray(contour, dtype=np.float64)
    yk, zk = float(sections.y_keel[i]), -float(sections.penetration[i])
    start = int(np.argmin((c[:, 0] - yk) ** 2 + (c[:, 1] - zk) ** 2))
    q = len(c)
    port = stbd = 0.0
    for step in (1, -1):
        here, sign = start, 0.0
        for _ in range(q - 1):
            nxt = (here + step) % q
            dy, dz = c[nxt, 0] - c[here, 0], c[nxt, 1] - c[here, 1]
            if sign == 0.0:
                sign = 1.0 if dy > 0 else -1.0
            if dy * sign <= 1e-6 * abs(dz):  # vertical or turning back
                break
            here = nxt
        reach = float(c[here, 0]) - yk
        port, stbd = max(port, reach), max(stbd, -reach)
    return port, stbd


def shared_piece_extents(sections) -> np.ndarray:
    """(2, n) how far each entry's own bottom reaches from its keel (port: +y, starboard),
    m, where several entries share a part (floats joined by a tunnel roof in one closed
    surface: :func:`piece_extents`); ``inf`` elsewhere."""
    n = len(sections)
    out = np.full((2, n), np.inf)
    station = np.asarray(sections.station)
    if len(np.unique(station)) == n:
        return out  # one entry per station: nothing is shared
    for idx, parts, owner in entry_parts(sections):
        if len(idx) < 2:
            continue
        for k in np.unique(owner[owner >= 0]):
            shared = idx[owner == k]
            for i in shared if len(shared) > 1 else ():
                out[:, i] = piece_extents(sections, int(i), parts[k][3])
    return out


def piece_half_widths(sections) -> np.ndarray:
    """(n,) half the width of each entry's own bottom, m: of its part
    (``part_half_beam``), or, where several entries share the part (floats joined by a
    tunnel roof), of its own bottom between its edges (:func:`shared_piece_extents`)."""
    half = np.array(sections.part_half_beam, dtype=np.float64)
    own = 0.5 * shared_piece_extents(sections).sum(axis=0)
    return np.minimum(half, own)


def submerged_parts(sections) -> tuple[np.ndarray, np.ndarray]:
    """Each wetted entry's area below the water and its part's whole area, m^2.

    An entry's part is as :func:`entry_parts` finds it. The pieces of one part (twin keels
    joined above the water) share its areas by their widths at the waterline. Holes are
    not subtracted.

    Returns
    -------
    below : (n,) float
        The entry's share of its part's area below ``z = 0``.
    whole : (n,) float
        The entry's share of its part's whole area.
    """
    below, whole, _ = _shares(sections)
    return below, whole


def submerged_widths(sections) -> np.ndarray:
    """(n,) each wetted entry's horizontal width under the water, m (the waterline's on a
    dry one): its share (as in
    :func:`submerged_parts`) of its part's breadth below ``z = 0``, at least its width at
    the waterline. A round section past its widest point is as wide as that point; a
    section wholly under water, as its part."""
    station = np.asarray(sections.station)
    stations, first, count = np.unique(station, return_index=True, return_counts=True)
    polygons = sections.polygons
    if isinstance(polygons, ShiftedPolygons):
        alone = polygons.contour_counts()[stations] == 1
    else:
        alone = np.array([len(polygons[int(st)]) == 1 for st in stations], dtype=bool)
    if not (alone & (count == 1)).all():
        return _shares(sections)[2]
    # one part and one entry at every station: the part's breadth below the water is
    # its points' below it, or the waterline's
    breadth = np.maximum(
        np.asarray(sections.half_beam_port + sections.half_beam_stbd, dtype=np.float64), 0.0
    )
    wet = np.asarray(sections.wetted, dtype=bool)
    own, at = stations[wet[first]], first[wet[first]]
    if isinstance(polygons, ShiftedPolygons):
        extent = polygons.extent_below(own)
    else:
        extent = np.array([_extent_below(polygons[int(st)][0]) for st in own])
    some = np.isfinite(extent)
    breadth[at[some]] = np.maximum(breadth[at[some]], extent[some])
    return breadth


def _extent_below(contour) -> float:
    """The lateral extent (m) of a contour's points at or below ``z = 0``; NaN: none."""
    c = np.asarray(contour, dtype=np.float64)
    y = c[c[:, 1] <= 0.0, 0] if len(c) else c[:0, 0]
    return float(y.max() - y.min()) if len(y) else np.nan


def submerged_shares(sections) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`submerged_parts` and :func:`submerged_widths` in one pass over the parts:
    the areas below the water and whole (m^2), and the breadth under the water (m)."""
    return _shares(sections)


def _shares(sections) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    n = len(sections)
    below, whole = np.zeros(n), np.zeros(n)
    width = np.asarray(sections.half_beam_port + sections.half_beam_stbd, dtype=np.float64)
    breadth = np.maximum(width, 0.0)
    for idx, parts, owner in entry_parts(sections):
        for k, (_, _, _, c, full) in enumerate(parts):
            mine = idx[owner == k]
            if not len(mine):
                continue
            total = width[mine].sum()
            share = width[mine] / total if total > 0 else np.full(len(mine), 1.0 / len(mine))
            q = _clipped(c)
            below[mine] = max(_area(q), 0.0) * share
            whole[mine] = full * share
            if len(q):
                wide = float(q[:, 0].max() - q[:, 0].min()) * share
                breadth[mine] = np.maximum(breadth[mine], wide)
    return below, whole, breadth


def _area(q: np.ndarray) -> float:
    """Signed area of a closed polygon, m^2."""
    if len(q) < 3:
        return 0.0
    y, z = q[:, 0], q[:, 1]
    return 0.5 * float(np.dot(y, _next(z)) - np.dot(z, _next(y)))


def _clipped(c: np.ndarray) -> np.ndarray:
    """One closed contour clipped to ``z <= 0`` (Sutherland-Hodgman), its points."""
    if len(c) < 3:
        return np.empty((0, 2))
    p1, p2 = c, _next(c)
    in1, in2 = p1[:, 1] <= 0.0, p2[:, 1] <= 0.0
    if not in1.any():
        return np.empty((0, 2))
    cross = in1 != in2
    with np.errstate(divide="ignore", invalid="ignore"):  # t is used only where it crosses
        t = p1[:, 1] / (p1[:, 1] - p2[:, 1])
        xing = p1 + t[:, None] * (p2 - p1)
    pts = np.empty((2 * len(c), 2))
    pts[0::2], pts[1::2] = p1, xing
    keep = np.empty(2 * len(c), dtype=bool)
    keep[0::2], keep[1::2] = in1, cross
    return pts[keep]
