"""Each station's wetted properties against the height of the water, tabulated once.

Between two consecutive heights of a section's vertices the water crosses the same edges
of its contour, so the section's wetted pieces do not change: their keel, their parts and
the slopes where they meet the water are fixed, and the penetration and the distances from
the keel to the waterline are affine in the water's height. A :class:`WaterlineTable`
evaluates the sections (with :func:`~hullslice.kernel.wetted.wetted_properties`, the same code
as a fresh evaluation) at two heights inside every such interval, once, and keeps the
affine fits: an evaluation at another height then looks its interval up and evaluates the
fits, a few array operations for all stations at once, whatever the mesh.

The intervals' ends are the vertices' heights and the same heights raised by a fifth of the
tolerance (where the waterline points stop counting as a flat keel). An interval where
anything but the affine quantities may change (a part meeting the water in two pieces or
more; too narrow an interval to sample) is marked: an evaluation there, or
with the ``keel-fit`` estimator (cubic in the height), is left to the fresh evaluation.
Where each part of a section meets the water in two edges at most (a V, a U, a round
bottom: one wetted piece per part), an interval is evaluated with only the edges the
waterline crosses and those at the keel, so a table costs in proportion to the vertices.
Elsewhere every edge under the water is needed, a cost growing with their square; it is
bounded (:data:`BUDGET`). The table covers the heights up to a top, and is made again
higher when the water rises past it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .outline import Outline, prefix_index
from .wetted import side_tan, wetted_properties

__all__ = ["AFFINE", "BUDGET", "CONSTANT", "TABULATED", "WaterlineTable"]

#: Quantities evaluated from affine fits in the water's height (the penetration is the
#: water's height above the piece's keel, a vertex: exact).
AFFINE = ("half_beam", "half_beam_port", "half_beam_stbd")
#: Quantities constant over an interval (checked at both samples), by estimator.
CONSTANT = {
    "wedge": ("y_keel", "part_half_beam", "mass_share"),
    "waterline-slope": (
        "y_keel", "part_half_beam", "mass_share", "deadrise", "deadrise_port",
        "deadrise_stbd",
    ),
}  # fmt: skip
#: Estimators a table serves (``keel-fit`` is cubic in the height).
TABULATED = ("wedge", "waterline-slope")
#: At most this many edges are evaluated to make a table (a tenth of a second or so): a
#: table reaching higher is made lower, and none is made where the water alone needs more.
BUDGET = 300_000


@dataclass(frozen=True, eq=False)
class WaterlineTable:
    """The wetted properties of an :class:`~hullslice.kernel.outline.Outline`'s stations against
    the water's height ``level`` (same frame as the outline's heights), up to ``top``.

    Build with :meth:`of`; evaluate with :meth:`at`.
    """

    outline: Outline
    deadrise: str
    tol: float
    top: float
    heights: np.ndarray  # the break points' heights, sorted, unique
    bp_key: np.ndarray  # break points as station * (h + 1) + their height's rank
    bp_start: np.ndarray  # (s + 1,) each station's first break point
    v_start: np.ndarray  # (s + 1,) each station's first interval (virtual station)
    v_count: np.ndarray  # (s,) intervals tabulated per station
    e_start: np.ndarray  # (v + 1,) each interval's first entry
    exact: np.ndarray  # (v,) bool: the interval's fits hold
    station: np.ndarray  # (e,) entries' stations
    wet: np.ndarray  # (e,) bool: the entry is a wetted piece (else its station is dry)
    keel: np.ndarray  # (e,) height of the piece's keel (a vertex's), inf when dry
    slope: np.ndarray  # (e, 3) the AFFINE quantities: value = intercept + slope * level
    intercept: np.ndarray
    const: np.ndarray  # (e, c) the CONSTANT quantities of the estimator
    one_each: bool  # every interval has one entry (one piece, or dry)

    @classmethod
    def of(
        cls, outline: Outline, level: float, tol: float, deadrise: str, budget: int = BUDGET
    ) -> WaterlineTable | None:
        """The table of ``outline`` up to a little above ``level`` (as high again as the
        water is deep, less if that would evaluate more than ``budget`` edges); None if
        the water's own height needs more."""
        if outline.top < np.inf:
            raise ValueError(
                f"a waterline table needs the outline of every edge, not of those below "
                f"{outline.top:.6g} m (Outline.of's top)"
            )
        s = outline.n_stations
        # break points: vertex heights (each edge starts at one), and raised by tol / 5
        z = np.concatenate([outline.za, outline.za + tol / 5])
        st = np.concatenate([outline.station, outline.station])
        order = np.lexsort((z, st))
        z, st = z[order], st[order]
        keep = np.ones(len(z), dtype=bool)
        keep[1:] = (z[1:] != z[:-1]) | (st[1:] != st[:-1])
        z, st = z[keep], st[keep]
        bp_start = np.searchsorted(st, np.arange(s + 1))
        # break points as exact integer keys: station * (h + 1) + rank of the height
        heights = np.unique(z)
        bp_key = st * (len(heights) + 1) + np.searchsorted(heights, z)
        plan = _plan(
            outline,
            z=z,
            st=st,
            heights=heights,
            bp_key=bp_key,
            bp_start=bp_start,
            level=level,
            tol=tol,
            budget=budget,
        )
        if plan is None:
            return None
        top, v_count, entry_v, entry_edge, crowded = plan
        n_bp = np.diff(bp_start)
        v_start = np.concatenate([[0], np.cumsum(v_count)])
        nv = int(v_start[-1])
        v_station = np.repeat(np.arange(s), v_count)
        j = np.arange(nv) - v_start[v_station]
        first = bp_start[v_station]
        has_lo = j > 0
        has_hi = j < n_bp[v_station]
        z_end = np.concatenate([z, [np.nan]])  # one past the last, for empty sections
        lo = np.where(has_lo, z_end[np.maximum(first + j - 1, 0)], np.nan)
        hi = np.where(has_hi, z_end[first + j], np.nan)
        unit = _span(outline, tol)
        h_a = np.where(has_lo & has_hi, lo + (hi - lo) / 3.0, np.nan)
        h_b = np.where(has_lo & has_hi, lo + 2.0 * (hi - lo) / 3.0, np.nan)
        h_a = np.where(~has_lo, hi - 2.0 * unit, np.where(~has_hi, lo + unit, h_a))
        h_b = np.where(~has_lo, hi - unit, np.where(~has_hi, lo + 2.0 * unit, h_b))
        # a station without vertices (empty section): one dry interval
        empty = ~has_lo & ~has_hi
        h_a[empty], h_b[empty] = -2.0, -1.0
        sampled = (h_a < h_b) & ~(has_lo & (h_a <= lo)) & ~(has_hi & (h_b >= hi))
        # an interval too thin to sample inside (break points a rounding apart) is not
        # tabulated, and its edges are left out of the samples: a sample on a break point
        # would meet its chosen edges' ends at the water (some above by a rounding, some
        # below) and could open a piece that none of them closes
        inside = sampled[entry_v]
        entry_v, entry_edge = entry_v[inside], entry_edge[inside]

        def sample(h):
            virtual = _virtual(outline, v_station, h, entry_v, entry_edge)
            return wetted_properties(virtual, 0.0, tol, deadrise)

        pa, pb = sample(h_a), sample(h_b)
        # a part in several pieces: its submerged edges go to the piece whose waterline
        # interval holds their middle, which moves with the water; and its mass is shared
        # by the pieces' widths: not tabulated
        exact = sampled & ~crowded
        differ = np.bincount(pa["station"], minlength=nv) != np.bincount(
            pb["station"], minlength=nv
        )
        if differ.any():  # other pieces at the two samples: not tabulated there
            exact &= ~differ
            h_b = np.where(differ, h_a, h_b)
            pb = sample(h_b)
        ev = pa["station"]  # virtual station of each entry, sorted
        e_start = np.searchsorted(ev, np.arange(nv + 1))
        ha, hb = h_a[ev], h_b[ev]
        # affine quantities as columns: value = intercept + slope * level
        ya = np.stack([pa[key] for key in AFFINE], axis=1)
        yb = np.stack([pb[key] for key in AFFINE], axis=1)
        with np.errstate(invalid="ignore", divide="ignore"):
            slope = (yb - ya) / (hb - ha)[:, None]
        slope = np.where(np.isfinite(slope), slope, 0.0)
        intercept = ya - slope * ha[:, None]
        # the keel: the vertex height nearest to the one the sample implies
        wet = pa["penetration"] > 0.0
        keel = _nearest(z, heights, bp_key, bp_start, v_station[ev], ha - pa["penetration"])
        keel = np.where(wet, keel, np.inf)
        const = np.stack([pa[key] for key in CONSTANT[deadrise]], axis=1)
        changed = np.zeros(len(ev), dtype=bool)
        for key in CONSTANT[deadrise]:  # to rounding: heights are taken from the level
            a, b = pa[key], pb[key]
            changed |= ~np.isclose(a, b, rtol=1e-13, atol=1e-13 * unit, equal_nan=True)
        exact[ev[changed]] = False
        return cls(
            outline=outline,
            deadrise=deadrise,
            tol=tol,
            top=top,
            heights=heights,
            bp_key=bp_key,
            bp_start=bp_start,
            v_start=v_start,
            v_count=v_count,
            e_start=e_start,
            exact=exact,
            station=v_station[ev],
            wet=wet,
            keel=keel,
            slope=slope,
            intercept=intercept,
            const=const,
            one_each=bool(np.all(np.diff(e_start) == 1)),
        )

    def at(self, level: float, k0: int, k1: int) -> dict[str, np.ndarray] | None:
        """The properties of stations ``k0`` to ``k1 - 1`` with the water at ``level``, as
        :func:`~hullslice.kernel.wetted.wetted_properties` gives them for
        ``outline.window(k0, k1)``; None where the table does not serve (above its top, or
        an interval marked inexact)."""
        if level > self.top:
            return None
        out = self._evaluate(np.arange(k0, k1), level)
        if out is not None:
            out["area"] = self.outline.area[k0:k1]
        return out

    def at_each(self, stations: np.ndarray, levels: np.ndarray) -> dict[str, np.ndarray] | None:
        """The properties of each of ``stations`` with the water at its own entry of
        ``levels``, entries numbered by their place in ``stations`` (``station``), each
        the same as :meth:`at` gives it alone (no ``area``); None where the table does not
        serve one of them."""
        if len(stations) == 0 or np.max(levels) > self.top:
            return None
        return self._evaluate(np.asarray(stations), np.asarray(levels))

    def _evaluate(self, stations: np.ndarray, level) -> dict[str, np.ndarray] | None:
        """:meth:`at`'s properties of ``stations`` at ``level`` (one, or one each), their
        entries numbered by place in ``stations``; None where an interval is inexact."""
        # each station's break points under the level, counted by a search in integer keys
        # (station, rank of the height among all the table's heights): exact
        j = _under(self.heights, self.bp_key, stations, level) - self.bp_start[stations]
        v = self.v_start[stations] + j
        if not self.exact[v].all():
            return None
        first = self.e_start[v]
        if self.one_each:
            idx, slot = first, np.arange(len(stations))
        else:
            count = self.e_start[v + 1] - first
            idx = prefix_index(first, count)
            slot = np.repeat(np.arange(len(stations)), count)
        at = level if np.ndim(level) == 0 else level[slot]
        affine = self.intercept[idx] + self.slope[idx] * (at if np.ndim(at) == 0 else at[:, None])
        const = self.const[idx]
        out = {key: affine[:, i] for i, key in enumerate(AFFINE)}
        out.update({key: const[:, i] for i, key in enumerate(CONSTANT[self.deadrise])})
        # as a fresh evaluation computes it: the keel's height measured from the water (the
        # keel of a dry entry is infinitely high: no penetration)
        p = out["penetration"] = np.maximum(-(self.keel[idx] - at), 0.0)
        if self.deadrise == "wedge":  # a dry entry's 0 / 0 gives its NaN
            with np.errstate(divide="ignore", invalid="ignore"):
                t_port = side_tan(p, out["half_beam_port"])
                t_stbd = side_tan(p, out["half_beam_stbd"])
                t_mean = 2.0 / (1.0 / t_port + 1.0 / t_stbd)
            out["deadrise"] = np.arctan(t_mean)
            out["deadrise_port"] = np.arctan(t_port)
            out["deadrise_stbd"] = np.arctan(t_stbd)
        chine = self.outline.z_chine[stations] - level <= self.tol
        out["chine_wetted"] = chine[slot] & self.wet[idx]
        out["station"] = slot
        if not self.one_each:  # pieces in order along the waterline, as a fresh evaluation
            left = out["y_keel"] - out["half_beam_stbd"]
            order = np.lexsort((np.where(self.wet[idx], left, 0.0), slot))
            out = {key: val[order] for key, val in out.items()}
        return out


def _plan(
    outline: Outline,
    *,
    z: np.ndarray,
    st: np.ndarray,
    heights: np.ndarray,
    bp_key: np.ndarray,
    bp_start: np.ndarray,
    level: float,
    tol: float,
    budget: int,
) -> tuple[float, np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None:
    """Which edges each interval evaluates, and up to which top.

    An interval (virtual station) ``j`` of a station lies between its break points
    ``j - 1`` and ``j``. Where every part of a station meets each of its intervals in at
    most two edges (one wetted piece per part: a V, a U, a round bottom), an interval needs
    only the edges the waterline crosses and the edges at its parts' keels (within a fifth
    of the tolerance of their lowest points): the rest lies under the water and changes
    nothing the table keeps. Other stations need all their edges under the water. The top
    is as high again as the water is deep, or lower if that takes more than ``budget``
    edges.

    ``z`` and ``st`` are the break points' heights (m) and stations, sorted by station then
    height; ``heights`` their sorted unique heights, ``bp_key`` and ``bp_start`` as in
    :class:`WaterlineTable`.

    Returns ``(top, v_count, entry_v, entry_edge, crowded)`` (intervals per station; for
    each evaluated edge its interval and its index in the outline, sorted by interval then
    lower end; the intervals where a part meets the water in more than one piece), or None
    when not even a tenth of the water's depth above it fits.
    """
    o = outline
    s = o.n_stations
    finite = o.zmin[np.isfinite(o.zmin)]
    bottom = min(float(finite.min()), level) if len(finite) else level
    depth = max(level - bottom, 1e-3 * _span(o, tol))
    # each edge's ends as indices into its station's break points (its heights are some)
    i_lo = _under(heights, bp_key, o.station, o.zlo) - bp_start[o.station]
    i_hi = _under(heights, bp_key, o.station, np.maximum(o.za, o.zb)) - bp_start[o.station]
    # the keel edges of each part
    n_parts = len(o.part_area)
    part_low = np.full(n_parts, np.inf)
    np.minimum.at(part_low, o.contour, o.zlo)
    keel = o.zlo <= part_low[o.contour] + tol / 5
    for share in (1.0, 0.5, 0.25, 0.1):
        top = level + share * depth
        v_count = np.bincount(st[z < top], minlength=s) + 1
        last = v_count[o.station] - 1  # the station's highest interval
        first = i_lo + 1  # an edge is under the water from the interval above its lower end
        # crossings per part and interval: at most two makes a station simple
        cross_end = np.minimum(i_hi, last)
        n_cross = np.maximum(cross_end - first + 1, 0)
        cv = np.repeat(first, n_cross) + _ranges(n_cross)
        cp = np.repeat(o.contour, n_cross)
        simple = np.ones(s, dtype=bool)
        v_start = np.concatenate([[0], np.cumsum(v_count)])
        crowded = np.zeros(int(v_start[-1]), dtype=bool)  # a part in two pieces or more
        if len(cv):
            span = int(last.max()) + 2
            pair, count = np.unique(cp * span + cv, return_counts=True)
            many = pair[count > 2]
            simple[o.part_station[many // span]] = False
            crowded[v_start[o.part_station[many // span]] + many % span] = True
        end = np.where(simple[o.station] & ~keel, cross_end, last)
        n = np.maximum(end - first + 1, 0)
        if int(n.sum()) <= budget:
            break
    else:
        return None
    edge = np.repeat(np.arange(len(n)), n)
    entry_v = v_start[o.station[edge]] + np.repeat(first, n) + _ranges(n)
    order = np.lexsort((o.zlo[edge], entry_v))
    return top, v_count, entry_v[order], edge[order], crowded


def _ranges(n: np.ndarray) -> np.ndarray:
    """``0 .. n[i] - 1`` for every ``i``, concatenated."""
    total = int(n.sum())
    return np.arange(total) - np.repeat(np.cumsum(n) - n, n)


def _under(heights, bp_key, station, value) -> np.ndarray:
    """For each ``station`` and ``value``, the index of the station's first break point not
    below the value (its count of break points below it, plus the station's start): a
    search in the exact integer keys."""
    return np.searchsorted(
        bp_key, station * (len(heights) + 1) + np.searchsorted(heights, value), side="left"
    )


def _nearest(z, heights, bp_key, start, station, value) -> np.ndarray:
    """The break point of each ``station`` nearest to ``value``."""
    if len(z) == 0:
        return np.full(len(value), np.nan)
    lo = np.minimum(start[station], len(z) - 1)
    hi = np.maximum(start[station + 1] - 1, lo)
    above = np.clip(_under(heights, bp_key, station, value), lo, hi)
    below = np.clip(above - 1, lo, hi)
    return np.where(np.abs(z[below] - value) < np.abs(z[above] - value), z[below], z[above])


def _span(outline: Outline, tol: float) -> float:
    """A height larger than the sections', m."""
    finite = np.isfinite(outline.zmin)
    if not finite.any():
        return 1.0
    return float(np.ptp(np.concatenate([outline.za, outline.zb])) + 1.0 + tol)


def _virtual(outline: Outline, v_station, h, entry_v, entry_edge) -> Outline:
    """An outline with one station per interval, ``v_station`` the station of each: the
    edges :func:`_plan` chose for it, heights measured from ``h`` (one per interval)."""
    o = outline
    s = o.n_stations
    idx, ev = entry_edge, entry_v
    dz = h[ev]
    count = np.bincount(ev, minlength=len(v_station))
    # separate parts, renumbered per interval
    c_start = np.searchsorted(o.part_station, np.arange(s + 1))
    n_parts = np.diff(c_start)[v_station]
    p_idx = prefix_index(c_start[v_station], n_parts)
    p_base = np.concatenate([[0], np.cumsum(n_parts)])[:-1]
    pv = np.repeat(np.arange(len(v_station)), n_parts)
    contour = o.contour[idx] - c_start[v_station][ev] + p_base[ev]
    return Outline(
        station=ev,
        ya=o.ya[idx],
        za=o.za[idx] - dz,
        yb=o.yb[idx],
        zb=o.zb[idx] - dz,
        zlo=o.zlo[idx] - dz,
        start=np.concatenate([[0], np.cumsum(count)]),
        area=o.area[v_station],
        contour=contour,
        part_area=o.part_area[p_idx],
        part_station=pv,
        part_zmax=o.part_zmax[p_idx] - h[pv],
        part_ymin=o.part_ymin[p_idx],
        part_ymax=o.part_ymax[p_idx],
        zmin=o.zmin[v_station] - h,
        ymin=o.ymin[v_station],
        ymax=o.ymax[v_station],
        z_chine=o.z_chine[v_station] - h,
    )
