"""The sides' contours for the MLM: each side's bottom as cut, continued past its edge on
a fictitious body, Wagner's contact on it and the pressure's change of sign.

Every array is per side (0: port, 1: starboard) and per section, ``(2, n)``, or sampled
along the side, ``(2, n, K)``.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from hullslice import InputError
from hullslice.solvers.contour import contour_heights, part_owners, wagner_root
from hullslice.solvers.section_parts import shared_piece_extents

#: Gauss-Legendre nodes over ``t`` in ``(0, t*)`` per side (the pressure's points).
NODES = 32
#: Points of the scan for the pressure's change of sign.
SCAN = 64
#: Samples of each side's contour as cut, and of its continued contour.
RAW, GRID = 129, 257
#: How far the continuation runs past a sharp edge, in edge half-widths.
SHARP_REACH = 4.0
_X, _WX = np.polynomial.legendre.leggauss(NODES)
U = 0.5 * (_X + 1.0)  # (0, 1)
WU = 0.5 * _WX


def side_contours(sections, method: str):
    """Each side's bottom as cut: heights ``f`` on an even grid from the keel (rising; a
    side that rises above the cut's height window goes on at its last slope), the side's
    extent ``E`` to its widest point (:func:`_extents`), the grid's step, the sides whose
    contour turns back down, and the sections read as their equivalent wedge (all of them
    for ``"wedge"``; under ``"auto"`` those whose bottom is flat at the keel or unsampled)."""
    n = len(sections)
    p = np.asarray(sections.penetration, dtype=np.float64)
    calm = np.maximum(np.stack([sections.half_beam_port, sections.half_beam_stbd]), 0.0)
    chine = np.asarray(sections.part_half_beam, dtype=np.float64)
    extent = _extents(sections)  # (2, n) from the polygons
    tb = np.tan(np.stack([sections.deadrise_port, sections.deadrise_stbd]))
    wedge = np.full(n, method == "wedge")
    if method != "wedge":
        reach = np.where(2.5 * calm < extent, 2.5 * calm, 1.02 * extent)
        reach = np.where(reach > 0, reach, 2.5 * np.maximum(calm, 1e-9))
        raw = contour_heights(sections, reach, RAW)
        ds = reach / (RAW - 1)
        # a side ends at its extent: past it lies another float's bottom or the tunnel's
        # roof between them, not this side's
        past = ds[..., None] * np.arange(RAW) > extent[..., None] * (1.0 + 1e-9)
        raw = np.where(past, np.nan, raw)
        finite = np.isfinite(raw)
        near = raw[:, :, : max(2, RAW // 10)]
        flat = np.any(np.all(np.abs(near) <= 1e-9 * p[None, :, None] + 1e-12, axis=2), axis=0)
        flat |= ~finite[:, :, 1].all(axis=0)
        wedge |= flat
        last = np.where(finite.all(axis=-1), RAW - 1, np.argmin(finite, axis=-1) - 1)
        last = np.maximum(last, 1)
        # inside its part's extent a side has a bottom at every y: where the sampled
        # heights stop short of it, the side rose above the cut's height window (a side
        # steeper than atan 4 there), and it goes on straight at its last slope
        gap = (last < RAW - 1) & ((last + 1) * ds < extent * (1.0 - 1e-9))
        if gap.any():
            j = np.arange(RAW)
            f_last = np.take_along_axis(raw, last[..., None], axis=-1)
            s_last = f_last - np.take_along_axis(raw, (last - 1)[..., None], axis=-1)
            steep = f_last + (j - last[..., None]) * s_last
            after = gap[..., None] & (j > last[..., None])
            raw = np.where(after, steep, raw)
            finite = np.isfinite(raw)
            last = np.where(gap, RAW - 1, last)
        edge_in = extent <= reach * (1.0 + 1e-12)
        filled = np.where(finite, raw, -np.inf)
        rising = np.maximum.accumulate(filled, axis=-1)
        drop = rising - np.where(finite, raw, rising)
        reentrant = np.any(drop > 1e-6 * p[None, :, None] + 1e-9, axis=-1)
        raw = np.where(np.isfinite(rising), rising, 0.0)
    else:
        reach = np.maximum(extent, 1e-12)
        ds = reach / (RAW - 1)
        raw = np.zeros((2, n, RAW))
        last = np.full((2, n), RAW - 1)
        edge_in = np.ones((2, n), dtype=bool)
        reentrant = np.zeros((2, n), dtype=bool)
    if wedge.any():  # the equivalent wedge, its chine at the section's widest point
        ext_w = np.broadcast_to(chine[wedge], (2, int(wedge.sum())))
        extent[:, wedge] = ext_w
        ds[:, wedge] = np.maximum(ext_w, 1e-12) / (RAW - 1)
        raw[:, wedge] = tb[:, wedge, None] * ds[:, wedge, None] * np.arange(RAW)
        last[:, wedge] = RAW - 1
        edge_in[:, wedge] = True
        reentrant[:, wedge] = False
    return raw, ds, last, extent, edge_in, reentrant, wedge


def continued_contours(sections, raw, ds, last, extent, edge_in, settings, cont_tan, cont_given):
    """The sides' contours for the contact, on an even grid of GRID points: the real
    bottom up to the departure point, a straight fictitious line past it (at a sharp
    edge, the edge; on a smooth side, where it becomes as steep as the continuation).

    Returns the heights (2, n, GRID) and their step, the edge ``e`` (the side's
    widest point), the line's ``(offset, slope)`` (``f = offset + slope y`` past the
    departure), which sides are sharp and smooth there, and the last sample of the real
    bottom with its slope ``(y_last, s_edge)`` (:class:`RealBottom` goes on with it)."""
    k_raw = raw.shape[-1]
    slope_raw = np.diff(raw, axis=-1) / ds[..., None]
    i_last = np.clip(last, 1, k_raw - 1)
    s_edge = np.take_along_axis(slope_raw, (i_last - 1)[..., None], axis=-1)[..., 0]
    y_last = i_last * ds
    e = np.where(edge_in, extent, y_last)
    bottom = RealBottom(raw, ds, y_last, s_edge)
    f_edge = bottom.height(e[..., None])[..., 0]
    tan_dep = math.tan(math.radians(settings["smooth_edge_deg"])) if cont_tan is None else cont_tan
    # a smooth side leaves its contour where it is first as steep as the continuation
    index = np.arange(k_raw - 1)
    steep_at = (slope_raw >= tan_dep) & (index <= (i_last - 1)[..., None])
    found = steep_at.any(axis=-1)
    i_dep = np.argmax(steep_at, axis=-1)
    # a side as steep as that from its keel on (a steep wedge) has nowhere to turn: its
    # widest point is a sharp edge whatever its slope there
    straight = found & (i_dep == 0)
    sharp = edge_in & ((np.degrees(np.arctan(s_edge)) < settings["smooth_edge_deg"]) | straight)
    smooth = edge_in & ~sharp
    if cont_tan is None:
        s_cont = s_edge
    else:
        s_cont = np.maximum(s_edge, cont_tan)  # the default: at least the tangent
        steep = sharp & (s_edge > cont_tan * (1.0 + 1e-9))
        if cont_given and steep.any():
            side, i = (int(a[0]) for a in np.nonzero(steep))
            raise InputError(
                f"solver 'mlm': continuation={settings['continuation']:g} deg is not "
                f"steeper than the bottom at the sharp edge of the section at x = "
                f"{float(sections.x[i]):.6g} m ({math.degrees(math.atan(s_edge[side, i])):.4g}"
                " deg there): give a steeper continuation or continuation=tangent"
            )
    d_smooth = np.where(found, i_dep * ds, e)
    f_smooth = np.where(found, np.take_along_axis(raw, i_dep[..., None], axis=-1)[..., 0], f_edge)
    s_smooth = np.where(found, tan_dep, np.maximum(s_edge, tan_dep))
    dep = np.where(smooth, d_smooth, e)
    f_dep = np.where(smooth, f_smooth, f_edge)
    slope = np.where(smooth, s_smooth, s_cont)
    end = np.where(edge_in, SHARP_REACH * e, e)
    step = end / (GRID - 1)
    y = step[..., None] * np.arange(GRID)
    inside = bottom.height(np.minimum(y, e[..., None]))
    line = f_dep[..., None] + (y - dep[..., None]) * slope[..., None]
    g = np.where(edge_in[..., None] & (y > dep[..., None]), line, inside)
    g = np.maximum.accumulate(g, axis=-1)
    return g, step, e, (f_dep - slope * dep, slope), sharp, smooth, (y_last, s_edge)


def contact(g, step, pen, edge_in, line):
    """Wagner's contact ``c`` of the penetrations ``pen`` (2, n) on the continued contours
    ``g`` (step ``step``), ``c' = dc/dh``, where it is held at the grid's end, and Wagner's
    integral there."""
    target = 0.5 * np.pi * pen
    c = wagner_root(g, step, target)
    end = step * (GRID - 1)
    capped = ~np.isfinite(c)
    c = np.where(capped, end, c)
    # c' = (pi / 2) / integral_0^{pi/2} f'(c sin t) sin t dt
    t = 0.5 * np.pi * U
    wt = 0.5 * np.pi * WU
    slope = np.diff(g, axis=-1) / step[..., None]
    fp_c = _slope_at(slope, step, c[..., None] * np.sin(t))
    denom = (fp_c * np.sin(t)) @ wt
    with np.errstate(divide="ignore", invalid="ignore"):
        cp = np.where(denom > 0, 0.5 * np.pi / denom, 0.0)
    cp = np.where(capped, 0.0, cp)
    i_end = _interp_rows(g, step, end[..., None] * np.sin(t)) @ wt  # Wagner's, at the end
    far = capped & edge_in
    if far.any():  # past the grid the continuation is straight: c grows as a wedge's
        offset, k_c = line
        rest = i_end - k_c * end - 0.5 * np.pi * offset  # decays as 1 / c
        with np.errstate(divide="ignore", invalid="ignore"):
            c_far = (0.5 * np.pi * (pen - offset) - rest) / k_c
        ok = far & (k_c > 0) & (c_far >= end)
        c = np.where(ok, c_far, c)
        cp = np.where(ok, 0.5 * np.pi / np.where(k_c > 0, k_c, 1.0), cp)
        capped = capped & ~ok
    return c, cp, capped, i_end


def sign_change(c, cp, slope, t_lim):
    """The interval ``(t_a, t_b)`` of ``(0, t_lim)`` where the velocity term's pressure is
    positive: ``t_a = 0`` where it is positive at the keel (else where it first turns
    positive: on a side steeper than ``atan(pi) = 72.3`` deg at the keel the bracket
    starts negative, rises and falls again), ``t_b`` where it next changes sign (``t_lim``
    where it does not); ``t_a = t_b`` where it is nowhere positive. ``slope(y)`` gives the
    real bottom's slope (:meth:`RealBottom.slope`). The first positive interval is taken: a
    second one further out (a bottom that turns flat again) is not loaded."""

    c_, cp_ = c[..., None], cp[..., None]

    def bracket(t):
        sin, cos = np.sin(t), np.cos(t)
        fp = slope(c_ * sin)
        return cp_ - 0.5 * cos - sin**2 / (2.0 * cos * (1.0 + fp**2))

    grid = t_lim[..., None] * np.linspace(0.0, 1.0, SCAN + 1)
    pos = bracket(grid) > 0.0
    some = pos.any(axis=-1)
    start = np.argmax(pos, axis=-1)  # first positive point
    after = pos | (np.arange(SCAN + 1) < start[..., None])
    end = np.where((~after).any(axis=-1), np.argmin(after, axis=-1), SCAN + 1)

    def root(j, rising):  # bisect between grid points j - 1 and j
        j = np.clip(j, 1, SCAN)
        lo = np.take_along_axis(grid, (j - 1)[..., None], axis=-1)[..., 0]
        hi = np.take_along_axis(grid, j[..., None], axis=-1)[..., 0]
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            up = (bracket(mid[..., None])[..., 0] > 0.0) != rising
            lo, hi = np.where(up, mid, lo), np.where(up, hi, mid)
        return 0.5 * (lo + hi)

    late = some & (start > 0)  # steep at the keel: the positive part starts further out
    t_a = np.where(late, root(start, True), 0.0) if late.any() else np.zeros_like(t_lim)
    t_b = np.where(end > SCAN, t_lim, root(end, False))
    return t_a, np.where(some, t_b, 0.0)


class RealBottom:
    """The real bottom of each side as cut: the samples ``raw`` ((2, n, K), every ``ds``
    from the keel) up to the last one, ``y_last``, then the last interval's slope
    ``s_last`` on to the widest point ((2, n) each). Its slopes between samples are taken
    once, when first asked for: the root of :func:`sign_change` asks for the slope some
    fifty times a call."""

    def __init__(self, raw, ds, y_last, s_last) -> None:
        self.raw, self.ds = raw, ds
        self.y_last, self.s_last = y_last[..., None], s_last[..., None]

    @functools.cached_property
    def slopes(self) -> np.ndarray:
        """The slopes between samples, (2, n, K - 1)."""
        return np.diff(self.raw, axis=-1) / np.where(self.ds > 0, self.ds, 1.0)[..., None]

    def __call__(self, y):
        """The height and the slope at ``y`` ((2, n, m))."""
        return self.height(y), self.slope(y)

    def height(self, y):
        """The height at ``y`` ((2, n, m))."""
        yc = np.minimum(y, self.y_last)
        return _interp_rows(self.raw, self.ds, yc) + np.maximum(y - self.y_last, 0.0) * self.s_last

    def slope(self, y):
        """The slope at ``y`` ((2, n, m)): the samples' slopes up to the last interval's
        middle, the last slope past ``y_last``."""
        y_top = (self.raw.shape[-1] - 1.5) * self.ds[..., None]
        fp = _slope_at(self.slopes, self.ds, np.minimum(y, y_top))
        return np.where(y >= self.y_last, self.s_last, fp)


def _extents(sections) -> np.ndarray:
    """(2, n): how far each side of each entry reaches from its keel (port: +y), m: to the
    edge of its station's polygons, or where the station has several, of its own part
    (:func:`~hullslice.solvers.section_parts.part_owners`; a float of a catamaran reaches no
    further than its own side); where several entries share a part (floats joined by a
    tunnel roof in one closed surface), to the ends of each one's own bottom
    (:func:`~hullslice.solvers.section_parts.shared_piece_extents`)."""
    n = len(sections)
    station = np.asarray(sections.station, dtype=np.int64)
    lo, hi = np.full(n, np.inf), np.full(n, -np.inf)
    for st in np.unique(station):
        idx = np.flatnonzero(station == st)
        contours = sections.polygons[int(st)]
        y0, y1 = np.inf, -np.inf
        for poly in contours:
            a = np.asarray(poly, dtype=np.float64)
            if len(a):
                y0, y1 = min(y0, float(a[:, 0].min())), max(y1, float(a[:, 0].max()))
        lo[idx], hi[idx] = y0, y1
        if len(contours) > 1:
            parts, owner = part_owners(sections, idx, contours)
            mine = owner >= 0
            lo[idx[mine]] = [parts[k][0] for k in owner[mine]]
            hi[idx[mine]] = [parts[k][1] for k in owner[mine]]
    yk = np.asarray(sections.y_keel, dtype=np.float64)
    out = np.stack([hi - yk, yk - lo]) if n else np.zeros((2, 0))
    out = np.minimum(out, shared_piece_extents(sections))
    chine = 2.0 * np.asarray(sections.part_half_beam, dtype=np.float64)
    out = np.where(np.isfinite(out), out, chine)
    return np.minimum(np.maximum(out, 0.0), np.maximum(chine, 1e-300))


def _interp_rows(f: np.ndarray, ds: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Rows of ``f`` ((2, n, K), sampled every ``ds`` (2, n) from 0), linearly at ``y``
    ((2, n, m)); held at the ends."""
    k = f.shape[-1]
    with np.errstate(invalid="ignore", divide="ignore"):
        x = np.where(ds[..., None] > 0, y / ds[..., None], 0.0)
    x = np.minimum(np.maximum(x, 0.0), k - 1)  # np.clip's values, without its wrapping
    i0 = np.minimum(np.maximum(np.floor(x).astype(np.int64), 0), k - 2)
    frac = x - i0
    at = _row_index(f, i0)
    flat = f.reshape(-1)
    return flat[at] * (1.0 - frac) + flat[at + 1] * frac


def _slope_at(slope: np.ndarray, ds: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The piecewise-constant slope ((2, n, K-1)) of rows sampled every ``ds`` at ``y``."""
    k = slope.shape[-1]
    with np.errstate(invalid="ignore", divide="ignore"):
        x = np.where(ds[..., None] > 0, y / ds[..., None], 0.0)
    i = np.minimum(np.maximum(np.floor(x).astype(np.int64), 0), k - 1)
    return slope.reshape(-1)[_row_index(slope, i)]


def _row_index(f: np.ndarray, i: np.ndarray) -> np.ndarray:
    """Flat indices into the C-ordered ``f`` ((..., K)) of ``i`` ((..., m), the same leading
    shape) along its rows: ``f.reshape(-1)[_row_index(f, i)]`` is ``np.take_along_axis(f,
    i, axis=-1)``, gathered at once rather than through an index per axis."""
    k = f.shape[-1]
    rows = np.arange(0, f.size, k).reshape(*f.shape[:-1], 1)
    return rows + i
