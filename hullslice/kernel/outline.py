"""The contour edges of cross-sections, sorted for cutting at any waterline.

An :class:`Outline` holds the edges of the outer contours of a set of station sections
(``(y, z)`` in m), sorted by station and then by the height of their lower end, so that the
edges reaching below a waterline are a prefix of each station's; with them, what does not
depend on the water: areas, separate parts (outer contours with their holes), extents and
chines. Pure numpy.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

__all__ = [
    "ByStation",
    "Outline",
    "Polygons",
    "group_min",
    "grouped",
    "prefix_counts",
    "prefix_index",
]

#: The contours of one station's section: (k, 2) arrays of ``(y, z)``, m.
Polygons = tuple[np.ndarray, ...]


class ByStation(Sequence):
    """Stations' contours made as they are read: a subclass gives ``_station(i)`` for
    ``0 <= i < len(self)``; a negative index counts from the end, a slice gives a list,
    and an index past the end raises IndexError (which ends an iteration)."""

    def _station(self, i: int) -> Polygons:
        raise NotImplementedError

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[j] for j in range(*i.indices(len(self)))]
        n = len(self)
        if not -n <= i < n:
            raise IndexError(f"station {i} out of range for {n} stations")
        return self._station(int(i) % n)


@dataclass(frozen=True, eq=False)
class Outline:
    """The contour edges of a set of station sections, and what does not depend on the water.

    Only the edges of outer contours (counter-clockwise) are kept: the wetted geometry is
    theirs, holes being inside the body. Edges are sorted by station, then by their lower
    end's height, so that those reaching below a waterline are a prefix of each station's.

    Attributes
    ----------
    station : (e,) int
        Station of each edge.
    ya, za, yb, zb : (e,) float
        Start and end of each edge, m.
    zlo : (e,) float
        Height of the edge's lower end.
    start : (s + 1,) int
        Each station's first edge (and the end).
    area : (s,) float
        Area of each station's whole section, holes deducted, m^2.
    contour : (e,) int
        Outer contour (separate part of its section) of each edge.
    part_area : (c,) float
        Area of each outer contour, the holes inside it deducted, m^2.
    part_station, part_zmax, part_ymin, part_ymax : (c,) arrays
        Station, highest point and lateral extent of each outer contour.
    zmin, ymin, ymax : (s,) float
        Lowest point and lateral extent of each section (``inf``/``-inf`` when empty).
    z_chine : (s,) float
        Height of the lower of the section's widest points on the two sides (the chine: the
        lowest vertex at the extreme ``y``), m.
    top : float
        The height below which the edges' lower ends are (m, ``inf`` where every edge is
        kept): the outline serves waterlines up to it. The sections' own figures above
        (areas, extents, chines) are of all their edges.
    """

    station: np.ndarray
    ya: np.ndarray
    za: np.ndarray
    yb: np.ndarray
    zb: np.ndarray
    zlo: np.ndarray
    start: np.ndarray
    area: np.ndarray
    contour: np.ndarray
    part_area: np.ndarray
    part_station: np.ndarray
    part_zmax: np.ndarray
    part_ymin: np.ndarray
    part_ymax: np.ndarray
    zmin: np.ndarray
    ymin: np.ndarray
    ymax: np.ndarray
    z_chine: np.ndarray
    top: float = np.inf

    @property
    def n_stations(self) -> int:
        return len(self.area)

    @classmethod
    def of(
        cls,
        polygons: Sequence[Polygons],
        tol: float,
        origin: tuple[float, float] = (0.0, 0.0),
        scale: float = 1.0,
        loops: Callable | None = None,
        top: float = np.inf,
    ) -> Outline:
        """The outline of station sections given as contours (each station's outer
        contours counter-clockwise, holes clockwise, ``(y, z)`` in m), each point divided by
        ``scale`` and moved by ``origin``; of the edges, those whose lower end is below
        ``top`` (m, after the move; all where infinite): the edges that waterlines up to
        ``top`` read, in the same order as with all (see :attr:`top`).

        ``loops``, when given (:func:`hullslice.outline_loops.outline_loops`, compiled),
        builds it from the exact cut's own array where ``polygons`` carries one (its
        ``flat``) and no section has a hole: the same outline.
        """
        if not top < np.inf:  # no top (a NaN one too): every edge
            top = np.inf
        flat = getattr(polygons, "flat", None)
        if loops is not None and flat is not None:
            oy, oz = (float(v) for v in origin)
            cap = np.full(len(polygons), float(top))  # the edges kept, by station
            out = loops(*flat, len(polygons), float(tol), float(scale), oy, oz, cap,
                        np.full(1, -1, dtype=np.int64))  # fmt: skip
            if out[0]:
                return cls(*[*out[1:], float(top)])  # the loops give all but the top
        s = len(polygons)
        contours = [c for secs in polygons for c in secs]
        if contours:
            sizes = np.array([len(c) for c in contours])
            a = np.concatenate(contours)
            if scale != 1.0:
                a = a / scale
            if origin != (0.0, 0.0):
                if a.dtype == np.float64:  # a column at a time: a loop each, not one a point
                    a[:, 0] += origin[0]
                    a[:, 1] += origin[1]
                else:  # numpy's promotion (integer or single contours)
                    a = a + np.asarray(origin)
            ends = np.cumsum(sizes)
            b = np.empty_like(a)  # each point's next, each contour closing on its first
            b[:-1] = a[1:]
            b[ends - 1] = a[ends - sizes]
            contour = np.repeat(np.arange(len(contours)), sizes)
            per = [len(secs) for secs in polygons]
            # one contour a station (the usual sections): a station's edges are its contour's
            single = per.count(1) == s
            station = contour if single else np.repeat(np.repeat(np.arange(s), per), sizes)
        else:
            a = b = np.empty((0, 2))
            contour = station = np.empty(0, dtype=np.int64)
            single = False
        cross = a[:, 0] * b[:, 1] - b[:, 0] * a[:, 1]
        c_area = 0.5 * np.bincount(contour, weights=cross, minlength=len(contours))
        if single:  # the same sums (halving each term or the sum is exact)
            area = c_area
        else:  # float with no point too (numpy's bincount then counts, in integers)
            area = np.bincount(station, weights=0.5 * cross, minlength=s).astype(float, copy=False)
        outer = (c_area > 0.0)[contour] if len(a) else contour > 0
        part_area, renumber = _part_areas(contours, c_area, polygons)
        if outer.all():  # no holes (the usual case): nothing to drop
            contour = renumber[contour]
        else:
            station, a, b, contour = station[outer], a[outer], b[outer], renumber[contour[outer]]
            single = False
        ya, za, yb, zb = a[:, 0], a[:, 1], b[:, 0], b[:, 1]
        # per station and per contour, while both are still contiguous
        c = len(part_area)
        start = np.searchsorted(station, np.arange(s + 1))
        cstart = start if single else np.searchsorted(contour, np.arange(c + 1))
        zmin = grouped(np.minimum, za, start, np.inf)
        ymax = grouped(np.maximum, ya, start, -np.inf)
        ymin = grouped(np.minimum, ya, start, np.inf)
        wide = ya >= ymax[station] - tol  # the points at either side's extreme
        wide_port = ya <= ymin[station] + tol
        side = np.concatenate([station[wide], station[wide_port]])
        z_side = np.concatenate([za[wide], za[wide_port]])
        z_chine = group_min(side, z_side, s)
        part_station = station[cstart[:-1]] if c else np.empty(0, dtype=np.int64)
        part_zmax = grouped(np.maximum, za, cstart, -np.inf)
        if single:  # each part is its station's section
            part_ymin, part_ymax = ymin, ymax
        else:
            part_ymin = grouped(np.minimum, ya, cstart, np.inf)
            part_ymax = grouped(np.maximum, ya, cstart, -np.inf)
        # then each station's edges by the height of their lower end
        zlo = np.minimum(za, zb)
        # one sort of a combined key: the station, and the height scaled into [0, 1)
        # (heights closer than 1e-10 of the body's may swap; no result depends on it).
        # Stable: a contour's heights come in long sorted runs, which a merge sort takes
        # whole (several times faster than quicksort here), and equal keys keep their order
        if len(zlo):
            lo, span = zlo.min(), np.ptp(zlo)  # of every edge: the same keys
            if top < np.inf:  # the edges kept, before the sort (most of its cost)
                below = np.flatnonzero(zlo < top)
                station, ya, za, yb, zb, zlo, contour = (
                    v[below] for v in (station, ya, za, yb, zb, zlo, contour)
                )
                start = np.searchsorted(station, np.arange(s + 1))
            key = 2.0 * station + (zlo - lo) / (span * (1.0 + 1e-9) + 1e-300)
            order = np.argsort(key, kind="stable")
        else:
            order = np.empty(0, dtype=np.int64)
        station, ya, za, yb, zb, zlo, contour = (
            v[order] for v in (station, ya, za, yb, zb, zlo, contour)
        )
        return cls(
            station=station,
            ya=ya,
            za=za,
            yb=yb,
            zb=zb,
            zlo=zlo,
            start=start,
            area=area,
            contour=contour,
            part_area=part_area,
            part_station=part_station,
            part_zmax=part_zmax,
            part_ymin=part_ymin,
            part_ymax=part_ymax,
            zmin=zmin,
            ymin=ymin,
            ymax=ymax,
            z_chine=z_chine,
            top=float(top),
        )

    def window(self, k0: int, k1: int) -> Outline:
        """The outline of stations ``k0`` to ``k1 - 1`` alone (views, no copies)."""
        e0, e1 = int(self.start[k0]), int(self.start[k1])
        c0 = int(np.searchsorted(self.part_station, k0))
        c1 = int(np.searchsorted(self.part_station, k1))
        return Outline(
            station=self.station[e0:e1] - k0,
            ya=self.ya[e0:e1],
            za=self.za[e0:e1],
            yb=self.yb[e0:e1],
            zb=self.zb[e0:e1],
            zlo=self.zlo[e0:e1],
            start=self.start[k0 : k1 + 1] - e0,
            area=self.area[k0:k1],
            contour=self.contour[e0:e1] - c0,
            part_area=self.part_area[c0:c1],
            part_station=self.part_station[c0:c1] - k0,
            part_zmax=self.part_zmax[c0:c1],
            part_ymin=self.part_ymin[c0:c1],
            part_ymax=self.part_ymax[c0:c1],
            zmin=self.zmin[k0:k1],
            ymin=self.ymin[k0:k1],
            ymax=self.ymax[k0:k1],
            z_chine=self.z_chine[k0:k1],
            top=self.top,
        )

    def below(self, level: float | np.ndarray) -> tuple:
        """The edges reaching below ``level`` (a prefix of each station's), with heights
        measured from ``level`` (or from each station's, ``(s,)``): ``station, ya, za, yb,
        zb, contour``."""
        idx = prefix_index(self.start[:-1], prefix_counts(self, level))
        station = self.station[idx]
        at = level if np.isscalar(level) else np.asarray(level)[station]
        return (
            station,
            self.ya[idx],
            self.za[idx] - at,
            self.yb[idx],
            self.zb[idx] - at,
            self.contour[idx],
        )

    def take(self, stations: np.ndarray) -> Outline:
        """The outline of the given stations (indices, in this order, repeats allowed), as
        stations ``0 .. len(stations) - 1``: the same edges and values, copied."""
        k = np.asarray(stations, dtype=np.int64)
        counts = self.start[k + 1] - self.start[k]
        idx = prefix_index(self.start[k], counts)
        c0 = np.searchsorted(self.part_station, k, side="left")
        c_count = np.searchsorted(self.part_station, k, side="right") - c0
        parts = prefix_index(c0, c_count)
        new_c0 = np.cumsum(c_count) - c_count
        slot = np.repeat(np.arange(len(k)), counts)
        return Outline(
            station=slot,
            ya=self.ya[idx],
            za=self.za[idx],
            yb=self.yb[idx],
            zb=self.zb[idx],
            zlo=self.zlo[idx],
            start=np.concatenate([[0], np.cumsum(counts)]),
            area=self.area[k],
            contour=self.contour[idx] - c0[slot] + new_c0[slot],
            part_area=self.part_area[parts],
            part_station=np.repeat(np.arange(len(k)), c_count),
            part_zmax=self.part_zmax[parts],
            part_ymin=self.part_ymin[parts],
            part_ymax=self.part_ymax[parts],
            zmin=self.zmin[k],
            ymin=self.ymin[k],
            ymax=self.ymax[k],
            z_chine=self.z_chine[k],
            top=self.top,
        )


def _part_areas(contours, c_area: np.ndarray, polygons) -> tuple[np.ndarray, np.ndarray]:
    """Areas of the outer contours with their holes deducted, and the outer contours'
    numbers (``-1`` for a hole) for every contour.

    A hole belongs to the smallest outer contour of its station around it; a station with
    one outer contour (the usual case) needs no test.
    """
    outer = c_area > 0.0
    if outer.all():  # no holes (the usual case)
        return c_area.copy(), np.arange(len(c_area))
    renumber = np.where(outer, np.cumsum(outer) - 1, -1)
    part_area = c_area[outer].copy()
    first = 0
    for secs in polygons:
        idx = np.arange(first, first + len(secs))
        first += len(secs)
        outers = idx[outer[idx]]
        for h in idx[~outer[idx]]:
            if len(outers) == 1:
                around = list(outers)
            else:
                around = [o for o in outers if _inside(contours[h][0], contours[o])]
            if around:
                owner = min(around, key=lambda o: c_area[o])
                part_area[renumber[owner]] += c_area[h]
    return part_area, renumber


def _inside(point: np.ndarray, contour: np.ndarray) -> bool:
    """Whether a point is inside a closed contour (even-odd rule)."""
    y, z = contour[:, 0], contour[:, 1]
    yn, zn = np.roll(y, -1), np.roll(z, -1)
    straddle = (z > point[1]) != (zn > point[1])
    with np.errstate(divide="ignore", invalid="ignore"):
        yc = y + (point[1] - z) * (yn - y) / (zn - z)
    return bool(np.count_nonzero(straddle & (yc > point[0])) % 2)


def prefix_counts(outline: Outline, level: float | np.ndarray) -> np.ndarray:
    """For each station, how many of its edges (sorted by lower end) reach below ``level``
    (or below each station's, ``(s,)``)."""
    at = level if np.isscalar(level) else np.asarray(level)[outline.station]
    cum = np.concatenate([[0], np.cumsum(outline.zlo < at)])
    return cum[outline.start[1:]] - cum[outline.start[:-1]]


def prefix_index(starts: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """Indices ``starts[i] .. starts[i] + counts[i] - 1`` for all ``i``, concatenated."""
    total = int(counts.sum())
    if total == 0:
        return np.empty(0, dtype=np.int64)
    offsets = np.repeat(starts - (np.cumsum(counts) - counts), counts)
    return np.arange(total) + offsets


def grouped(ufunc, values: np.ndarray, start: np.ndarray, fill: float) -> np.ndarray:
    """``ufunc`` reduced over the contiguous groups ``start[i]:start[i + 1]``; ``fill`` for
    an empty group."""
    out = np.full(len(start) - 1, fill)
    full = start[1:] > start[:-1]
    if full.any():
        out[full] = ufunc.reduceat(values, start[:-1][full])
    return out


def group_min(keys: np.ndarray, values: np.ndarray, n: int) -> np.ndarray:
    out = np.full(n, np.inf)
    np.minimum.at(out, keys, values)
    return out
