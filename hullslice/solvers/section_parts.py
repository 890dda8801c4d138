"""The separate parts of a section (outer contours) that its wetted entries belong to, and
their submerged areas."""

from __future__ import annotations

import numpy as np

__all__ = ["entry_parts", "part_owners", "submerged_parts"]


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
    n = len(sections)
    below, whole = np.zeros(n), np.zeros(n)
    width = np.asarray(sections.half_beam_port + sections.half_beam_stbd, dtype=np.float64)
    for idx, parts, owner in entry_parts(sections):
        for k, (_, _, _, c, full) in enumerate(parts):
            mine = idx[owner == k]
            if not len(mine):
                continue
            total = width[mine].sum()
            share = width[mine] / total if total > 0 else np.full(len(mine), 1.0 / len(mine))
            below[mine] = max(_clipped_area(c), 0.0) * share
            whole[mine] = full * share
    return below, whole


def _clipped_area(c: np.ndarray) -> float:
    """Signed area of one closed contour clipped to ``z <= 0`` (Sutherland-Hodgman)."""
    if len(c) < 3:
        return 0.0
    p1, p2 = c, _next(c)
    in1, in2 = p1[:, 1] <= 0.0, p2[:, 1] <= 0.0
    if not in1.any():
        return 0.0
    cross = in1 != in2
    with np.errstate(divide="ignore", invalid="ignore"):  # t is used only where it crosses
        t = p1[:, 1] / (p1[:, 1] - p2[:, 1])
        xing = p1 + t[:, None] * (p2 - p1)
    pts = np.empty((2 * len(c), 2))
    pts[0::2], pts[1::2] = p1, xing
    keep = np.empty(2 * len(c), dtype=bool)
    keep[0::2], keep[1::2] = in1, cross
    q = pts[keep]
    y, z = q[:, 0], q[:, 1]
    return 0.5 * float(np.dot(y, _next(z)) - np.dot(z, _next(y)))
