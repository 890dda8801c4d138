"""Wetted half-widths and submerged areas from a section's own contour.

A momentum-form solver needs, for each side of a wetted section, the half-width ``c`` that
the water wets (with the pile-up) and its rate ``dc/dp``. For a wedge they are
``gamma p / tan(beta)`` and ``gamma / tan(beta)``. For a section that is not a wedge (a
fuselage's round bottom) they come from the contour ``f(y)``, the height of the section's
bottom above its keel at the distance ``y`` from it:

``wagner``
    Wagner's condition (METHOD section 7; Wagner 1932),

        integral_0^{pi/2} f(c sin t) dt = (pi / 2) p,

    solved for ``c`` on each side, and its derivative
    ``dc/dp = (pi / 2) / integral_0^{pi/2} f'(c sin t) sin t dt``. A wedge gives
    ``c = (pi/2) p / tan(beta)``; a circle of radius ``R``, ``c^2 = 4 R p`` at small ``p``:
    at constant speed ``V`` the force per metre is ``2 pi rho R V^2`` (slamming coefficient
    ``2 pi``).
``von-karman``
    No pile-up: ``c`` is where the contour meets the calm water, ``f(c) = p``, and
    ``dc/dp = 1 / f'(c)``. A circle gives ``c^2 = 2 R p`` and the slamming coefficient ``pi``.

The contour is read from the station's polygons (the lowest crossing of each vertical
line, sampled at :data:`SAMPLES` points from the keel to a little past where Wagner's
``c`` can reach). A section whose contour is within :data:`WEDGE_TOLERANCE` of a straight
side at half its calm-water half-width and out to where the wetted half-width reaches
(``gamma`` times it) is a wedge: ``auto`` uses the closed form there, and on a flat bottom
(no keel).

The submerged area (for a buoyancy force) is the area of the station's polygons below the
water ``z = 0``, by the shoelace formula of the polygons clipped to that half-plane.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..errors import InputError
from .section_parts import _next, entry_parts, part_owners, shared_piece_extents, submerged_parts

__all__ = [
    "SAMPLES",
    "SECTION_METHODS",
    "WEDGE_TOLERANCE",
    "contour_half_widths",
    "contour_heights",
    "entry_parts",
    "part_owners",
    "submerged_parts",
    "wagner_root",
]

#: How the wetted half-width of a section is found, by name.
SECTION_METHODS: dict[str, str] = {
    "auto": "the closed form where a section is a wedge, its own contour elsewhere",
    "wedge": "the equivalent wedge of the section (closed form, gamma p / tan(beta))",
    "contour": "the section's own contour (Wagner's condition, or the calm-water crossing)",
}

#: Points at which each side's contour is sampled.
SAMPLES = 96
#: A side is a wedge when its height at half the calm-water half-width is within this
#: share of half the penetration.
WEDGE_TOLERANCE = 0.1
#: Most steps (Newton's, or halvings of the bracket) for Wagner's ``c``.
MAX_ROOT_STEPS = 110
#: Wagner's ``c`` is solved to this share of the side's extent (or to rounding).
ROOT_TOLERANCE = 1e-15
#: Gauss-Legendre nodes over ``t`` in ``(0, pi/2)`` for Wagner's condition.
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(32)
_T = (_NODES + 1.0) * np.pi / 4.0
_W = _WEIGHTS * np.pi / 4.0
_SIN = np.sin(_T)


def _edges(contours: Sequence[np.ndarray]) -> np.ndarray:
    """(m, 4) segments ``y1, z1, y2, z2`` of closed contours."""
    parts = []
    for c in contours:
        c = np.asarray(c, dtype=np.float64)
        if len(c) >= 2:
            parts.append(np.column_stack([c, _next(c)]))
    return np.concatenate(parts) if parts else np.empty((0, 4))


def _lowest(
    edges: np.ndarray,
    y: np.ndarray,
    edge_group: np.ndarray | None = None,
    y_group: np.ndarray | None = None,
) -> np.ndarray:
    """Lowest ``z`` of the contours on the vertical lines ``y`` (NaN where none crosses);
    with groups, of the edges of each line's own group only (many contours at once).

    Each edge meets only the lines of its group over its own span, found by a search in
    the lines sorted by group then ``y`` (a complex key ``group + i y`` sorts so, exactly).
    """
    y = np.asarray(y, dtype=np.float64)
    out = np.full(len(y), np.inf)
    y1, z1, y2, z2 = edges[:, 0], edges[:, 1], edges[:, 2], edges[:, 3]
    lo, hi = np.minimum(y1, y2), np.maximum(y1, y2)
    keep = hi > lo
    if keep.any() and len(y):
        eg = np.zeros(len(edges)) if edge_group is None else edge_group
        yg = np.zeros(len(y)) if y_group is None else y_group
        order = np.argsort(_key(yg, y), kind="stable")
        keys = _key(yg, y)[order]
        y1, z1, y2, z2, lo, hi, eg = (v[keep] for v in (y1, z1, y2, z2, lo, hi, eg))
        i0 = np.searchsorted(keys, _key(eg, lo), side="left")
        count = np.searchsorted(keys, _key(eg, hi), side="right") - i0  # i0 .. i0 + count - 1
        if count.sum():
            seg = np.repeat(np.arange(len(count)), count)
            line = order[np.arange(len(seg)) - np.repeat(np.cumsum(count) - count, count) + i0[seg]]
            with np.errstate(divide="ignore", invalid="ignore"):
                z = z1[seg] + (y[line] - y1[seg]) * (z2[seg] - z1[seg]) / (y2[seg] - y1[seg])
            np.minimum.at(out, line, z)
    return np.where(np.isfinite(out), out, np.nan)


def _key(group: np.ndarray, y: np.ndarray) -> np.ndarray:
    """``group + i y``: complex numbers sort by their real part, then their imaginary one
    (set apart, not multiplied: ``1j * inf`` is ``nan + inf j``)."""
    key = np.empty(len(y), dtype=np.complex128)
    key.real = group
    key.imag = y
    return key


def _heights(sections, p: np.ndarray, reach: np.ndarray, samples: int = SAMPLES) -> np.ndarray:
    """The height of each side's contour above its keel, (2, n, samples) m, sampled from
    the keel out to ``reach`` ((2, n) m); NaN past the side's extent."""
    n = len(sections)
    unit = np.linspace(0.0, 1.0, samples)
    station = np.asarray(sections.station, dtype=np.int64)
    stations, st_index = np.unique(station, return_inverse=True)
    per_station = [_edges(sections.polygons[int(st)]) for st in stations]
    sizes = np.array([len(e) for e in per_station], dtype=np.int64)
    edges = np.concatenate(per_station) if len(per_station) else np.empty((0, 4))
    yk = np.asarray(sections.y_keel, dtype=np.float64)
    lowest = _lowest(edges, yk, np.repeat(np.arange(len(stations)), sizes), st_index)
    # the contour scaled about the waterline so that its depth below the water at the keel
    # is the entry's penetration (they agree to the coordinate tolerance)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where((lowest < 0) & (p > 0), p / -lowest, 1.0)
    side = np.concatenate([reach[0][:, None] * unit, -reach[1][:, None] * unit], axis=1)
    y = yk[:, None] + side / ratio[:, None]  # (n, 2 SAMPLES)
    # each entry's edges: those of its station below the keel's height plus the reach,
    # over the sampled width
    first = np.concatenate([[0], np.cumsum(sizes)])[st_index]
    own = sizes[st_index]
    entry = np.repeat(np.arange(n), own)
    e = edges[np.arange(int(own.sum())) - np.repeat(np.cumsum(own) - own, own) + first[entry]]
    lo_y, hi_y = yk - reach[1] / ratio, yk + reach[0] / ratio
    z_top = lowest + 4.0 * np.maximum(reach[0], reach[1]) / ratio
    near = (
        (np.maximum(e[:, 0], e[:, 2]) >= lo_y[entry])
        & (np.minimum(e[:, 0], e[:, 2]) <= hi_y[entry])
        & (np.minimum(e[:, 1], e[:, 3]) <= z_top[entry])
    )
    lines = np.repeat(np.arange(n), 2 * samples)
    low = _lowest(e[near], y.ravel(), entry[near], lines).reshape(n, 2 * samples)
    heights = ratio[:, None] * (low - lowest[:, None])
    return np.moveaxis(heights.reshape(n, 2, samples), 1, 0)


def contour_heights(sections, reach: np.ndarray, samples: int = SAMPLES) -> np.ndarray:
    """The height above its keel of each side's bottom, sampled evenly from the keel out
    to ``reach``.

    Parameters
    ----------
    sections : Sections
        The wetted entries.
    reach : (2, n) float
        How far out to sample each side (port, starboard), m.
    samples : int
        Points per side, the keel's and the reach's included.

    Returns
    -------
    (2, n, samples) float
        Heights in m of the lowest crossing of each vertical line, scaled so that the
        depth at the keel is the entry's penetration; NaN past the side's extent (no
        crossing).
    """
    p = np.asarray(sections.penetration, dtype=np.float64)
    return _heights(sections, p, np.asarray(reach, dtype=np.float64), int(samples))


def wagner_root(g: np.ndarray, ds: np.ndarray, target: np.ndarray) -> np.ndarray:
    """Wagner's half-width ``c`` on sampled contours: where ``integral_0^{pi/2}
    g(c sin t) dt`` reaches ``target``.

    Parameters
    ----------
    g : (..., K) float
        Rising heights above the keel (m), sampled every ``ds`` from the keel.
    ds : (...) float
        The sampling step, m.
    target : (...) float
        ``(pi / 2) p``, m.

    Returns
    -------
    (...) float
        ``c`` in m, NaN where the contour's sampled width is too short to reach it.
    """
    k = g.shape[-1]
    extent = (k - 1) * ds

    def integral(c: np.ndarray) -> np.ndarray:
        return _interp(g, ds, c[..., None] * _SIN) @ _W

    past = ~(integral(extent) >= target)
    c = _wagner_root(g, ds, extent, np.broadcast_to(target, extent.shape), past)
    return np.where(past, np.nan, c)


def contour_half_widths(
    sections, law: str, method: str
) -> tuple[list[np.ndarray], list[np.ndarray], np.ndarray]:
    """Wetted half-width ``c`` and ``dc/dp`` of each side of each wetted entry.

    Parameters
    ----------
    sections : Sections
        The wetted entries.
    law : str
        ``"wagner"`` or ``"von-karman"`` (module notes).
    method : str
        ``"contour"`` (every entry from its contour) or ``"auto"`` (wedges left to the
        caller: their ``c`` is NaN).

    Returns
    -------
    c : [port, starboard] of (n,) float
        Wetted half-widths in m, NaN where the entry is a wedge (``auto``) or where the
        water passes the side's extent (the caller caps it at the chine).
    dc : [port, starboard] of (n,) float
        ``dc/dp``, 1.
    contour : (n,) bool
        Entries computed from their contour.

    Raises
    ------
    InputError
        ``contour`` asked for on a section with no keel (a flat bottom).
    """
    n = len(sections)
    p = np.asarray(sections.penetration, dtype=np.float64)
    calm = np.stack([sections.half_beam_port, sections.half_beam_stbd])  # (2, n)
    reach = 2.5 * np.maximum(calm, 0.0)
    heights = _heights(sections, p, reach)
    ds = reach / (SAMPLES - 1)  # (2, n)
    own = shared_piece_extents(sections)  # a float sharing its part ends at its own edges
    if np.isfinite(own).any():
        past = ds[..., None] * np.arange(SAMPLES) > own[..., None] * (1.0 + 1e-9)
        heights = np.where(past, np.nan, heights)
    gamma = 0.5 * np.pi if law == "wagner" else 1.0
    with np.errstate(invalid="ignore", divide="ignore"):
        # a wedge: a straight side from the keel out to where the wetted width can reach
        half = _interp(heights, ds, 0.5 * calm)
        far = _interp(heights, ds, np.minimum(gamma * calm, reach))
        straight = (np.abs(half / p - 0.5) <= 0.5 * WEDGE_TOLERANCE) & (
            np.abs(far / (p * np.minimum(gamma, reach / np.maximum(calm, 1e-300))) - 1.0)
            <= WEDGE_TOLERANCE
        )
        wedge = np.all(straight, axis=0)
        wedge |= np.any(calm <= 0, axis=0) | (p <= 0)
    near = heights[:, :, : max(2, SAMPLES // 10)]
    flat = np.any(np.all(np.abs(near) <= 1e-9 * p[None, :, None] + 1e-12, axis=2), axis=0)
    if method == "contour" and flat.any():
        i = int(np.flatnonzero(flat)[0])
        raise InputError(
            f"the section at x = {float(sections.x[i]):.6g} m has no keel (its bottom is "
            "flat at its lowest point): the contour method needs one; use "
            "section_method=auto or wedge"
        )
    used = ~wedge if method == "auto" else np.ones(n, dtype=bool)
    used &= np.all(calm > 0, axis=0) & (p > 0) & ~flat  # a flat bottom: the equivalent wedge
    c_out = np.full((2, n), np.nan)
    dc_out = np.full((2, n), np.nan)
    if used.any():
        f = heights[:, used, :]
        c, dc = _solve(f, ds[:, used], calm[:, used], p[used], law)
        c_out[:, used], dc_out[:, used] = c, dc
        # a side whose bottom does not rise where the water meets it, short of its part's
        # widest point (a sliver of a section a few micrometres deep, sampled below its
        # own keel) has a width but no rate: such an entry is its equivalent wedge, as a
        # flat bottom is (past the widest point the width is held and needs no rate)
        chine = np.asarray(sections.part_half_beam, dtype=np.float64)
        with np.errstate(invalid="ignore"):
            short = np.isfinite(c_out) & (c_out <= chine) & ~np.isfinite(dc_out)
        no_rate = np.any(short, axis=0)
        if no_rate.any():
            used &= ~no_rate
            c_out[:, no_rate] = dc_out[:, no_rate] = np.nan
    return [c_out[0], c_out[1]], [dc_out[0], dc_out[1]], used


def _interp(f: np.ndarray, ds: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Rows of ``f`` sampled every ``ds`` from 0, linearly at ``y`` (the same leading
    shape as ``ds``, and optionally one more axis)."""
    extra = y.ndim > ds.ndim
    step = ds[..., None] if extra else ds
    with np.errstate(invalid="ignore", divide="ignore"):
        x = np.where(step > 0, y / step, 0.0)
    k = f.shape[-1]
    i0 = np.clip(np.floor(x).astype(np.int64), 0, k - 2)
    frac = x - i0
    if not extra:
        i0, frac = i0[..., None], frac[..., None]
    a = np.take_along_axis(f, i0, axis=-1)
    b = np.take_along_axis(f, i0 + 1, axis=-1)
    out = a * (1.0 - frac) + b * frac
    return out if extra else out[..., 0]


def _solve(
    f: np.ndarray, ds: np.ndarray, calm: np.ndarray, p: np.ndarray, law: str
) -> tuple[np.ndarray, np.ndarray]:
    """``c`` and ``dc/dp`` of sides whose contour heights ``f`` ((2, m, K), NaN past the
    side's extent) are sampled every ``ds`` ((2, m)); NaN where the water passes it."""
    k = f.shape[-1]
    finite = np.isfinite(f)
    last = np.where(finite.all(axis=-1), k - 1, np.argmin(finite, axis=-1) - 1)  # (2, m)
    extent = np.maximum(last, 0) * ds
    # the side's bottom, rising: past its extent it stays at its last height (not used)
    g = np.where(finite, f, np.inf)
    g = np.maximum.accumulate(np.where(np.isfinite(g), g, -np.inf), axis=-1)
    top = np.take_along_axis(g, np.maximum(last, 0)[..., None], axis=-1)
    g = np.where(np.arange(k) <= last[..., None], g, top)
    slope = np.diff(g, axis=-1) / np.where(ds > 0, ds, 1.0)[..., None]  # per interval
    slope = np.concatenate([slope, slope[..., -1:]], axis=-1)
    bad = (last < 1) | ~np.isfinite(calm) | (calm <= 0)
    if law == "von-karman":
        c = calm.copy()
        lo = _interp(g, ds, np.maximum(c - ds, 0.0))
        hi = _interp(g, ds, np.minimum(c + ds, extent))
        width = np.minimum(c + ds, extent) - np.maximum(c - ds, 0.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            fp = (hi - lo) / width
            dc = np.where(fp > 0, 1.0 / fp, np.nan)
        past = bad | (c > extent)
        return np.where(past, np.nan, c), np.where(past, np.nan, dc)

    def integral(c: np.ndarray) -> np.ndarray:
        return _interp(g, ds, c[..., None] * _SIN) @ _W

    target = 0.5 * np.pi * p[None, :]
    past = bad | ~(integral(extent) >= target)
    c = _wagner_root(g, ds, extent, np.broadcast_to(target, extent.shape), past)
    y = c[..., None] * _SIN
    with np.errstate(invalid="ignore", divide="ignore"):
        idx = np.clip(np.floor(np.where(ds[..., None] > 0, y / ds[..., None], 0)), 0, k - 1)
        fprime = np.take_along_axis(slope, idx.astype(np.int64), axis=-1)
        denom = fprime @ (_SIN * _W)
        dc = np.where(denom > 0, 0.5 * np.pi / denom, np.nan)
    return np.where(past, np.nan, c), np.where(past, np.nan, dc)


def _wagner_root(
    g: np.ndarray, ds: np.ndarray, extent: np.ndarray, target: np.ndarray, past: np.ndarray
) -> np.ndarray:
    """The ``c`` in ``(0, extent)`` where ``integral_0^{pi/2} g(c sin t) dt`` (the
    quadrature of :data:`_W`) reaches ``target``, for each side: ``g`` ((..., K) rising
    heights sampled every ``ds``) is piecewise linear, and so is the integral in ``c``.

    Newton's steps inside a bracket (as Numerical Recipes' ``rtsafe``): a step lands on
    the root as soon as it starts on the root's linear piece, so a few steps solve it to
    rounding where 48 halvings of the bracket did before. Every point tried becomes an end
    of the bracket; a Newton step is taken only strictly inside it and only when it is at
    most half the step before the last, else the bracket is halved. An S-shaped condition
    (a V with a step), which sends plain Newton back and forth, is then bisected. Sides in
    ``past`` are left at any value.
    """
    k = g.shape[-1]
    flat = g.reshape(-1, k).ravel()
    base = (np.arange(g.reshape(-1, k).shape[0]) * k).reshape(g.shape[:-1])[..., None]
    step = np.where(ds > 0, ds, 1.0)[..., None]
    tol = ROOT_TOLERANCE * extent
    lo = np.zeros_like(extent)
    hi = np.where(past, 0.0, extent)
    c = 0.5 * (lo + hi)
    dx_old = dx = hi - lo  # the steps before the last and the last
    done = past | (hi - lo <= tol)
    for _ in range(MAX_ROOT_STEPS):
        x = np.where(ds[..., None] > 0, c[..., None] * _SIN / step, 0.0)
        i0 = np.clip(np.floor(x).astype(np.int64), 0, k - 2)
        a = flat[base + i0]
        b = flat[base + i0 + 1]
        frac = x - i0
        f = (a * (1.0 - frac) + b * frac) @ _W - target
        slope = ((b - a) / step) @ (_SIN * _W)
        lo = np.where(done | (f >= 0), lo, c)
        hi = np.where(done | (f < 0), hi, c)
        with np.errstate(invalid="ignore", divide="ignore"):
            newton = f / slope  # the Newton step back from c
        inside = (slope > 0) & (c - newton > lo) & (c - newton < hi)
        shrinking = np.abs(2.0 * newton) <= np.abs(dx_old)
        use = inside & shrinking
        dx_old, dx = dx, np.where(use, newton, c - 0.5 * (lo + hi))
        # c is the root to rounding where Newton's step back is negligible
        settled = (f == 0) | ((slope > 0) & (np.abs(newton) <= tol)) | (hi - lo <= tol)
        c = np.where(done | settled, c, c - dx)
        done = done | settled
        if done.all():
            break
    return c
