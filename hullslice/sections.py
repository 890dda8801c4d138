"""Cutting a hull into cross-sections at a pose: the 2D+t slices and their properties.

At a pose the wetted part of the hull (below ``z = 0``), of length ``DeltaL`` along ``x``, is
cut into ``n`` slices of thickness ``d = DeltaL / n`` (paper, Eq. 7); each slice is
represented by the hull's cross-section at its mid-station, cut by manifold3d. The result
is a :class:`Sections`: one array per property, one entry per station.

A cross-section in several separate parts (the two floats of a catamaran, any body made of
disjoint shells) gives one entry per part at that station, each a 2D section of its own with
its own penetration, half-beam, deadrise and mass per metre (the body's mass shared by
area); their forces add. A single part that meets the waterline in several separate spans
(twin keels joined above the water, a tunnel hull) is not one wedge: its entry reports the
number of spans in ``waterline_spans`` and the force is flagged outside the method's range.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from .constants import MAX_SLICES, TOL
from .errors import InputError
from .mesh import Hull
from .state import Pose

__all__ = ["DEADRISE_ESTIMATORS", "Sections", "cut", "split_parts", "wetted_extent"]

Polygons = tuple[np.ndarray, ...]


def _readonly(a: np.ndarray) -> np.ndarray:
    a = np.ascontiguousarray(a)
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class Sections:
    """Cross-sections of a hull at one pose, as arrays over stations.

    Attributes
    ----------
    x : (n,) float
        Station (mid-slice) positions along the body, in m (body frame ``x``).
    dx : (n,) float
        Slice thicknesses in m; the slices' thicknesses add up to the wetted length.
    penetration : (n,) float
        Depth of each section's lowest point below the water, in m (``>= 0``).
    half_beam : (n,) float
        Half the width of the wetted section at the waterline, in m.
    deadrise : (n,) float
        Local deadrise angle in rad, from the estimator named in ``deadrise_method``
        (NaN where the section is dry).
    area : (n,) float
        Area of the whole cross-section (not only its wetted part), in m^2.
    mass_per_metre : (n,) float
        Mass per metre of body length at each station, in kg/m (NaN without a hull mass).
    chine_wetted : (n,) bool
        True where the water has reached the section's widest point (its chine or deck):
        the wedge-entry model no longer describes the flow there.
    polygons : (n,) tuple of tuples of (k, 2) float
        The cross-section contours at each station in the earth frame ``(y, z)``, m; the
        waterline is ``z = 0``. Outer contours run counter-clockwise, holes clockwise.
    part : (n,) int
        Which separate part of the cross-section at its station the entry is: ``0`` for a
        section in one piece; ``0, 1, ...`` from starboard to port for a section in
        several (a catamaran's floats). Entries of one station are consecutive and share
        ``x`` and ``dx``.
    waterline_spans : (n,) int
        Number of separate spans of the waterline inside the part's outer contour: ``1`` for
        a wedge-like section, ``0`` when it is dry or under water, ``2`` or more for a part
        that meets the water in several places (twin keels joined above the water), which
        the equivalent wedge does not describe.
    deadrise_method : str
        Name of the deadrise estimator used (see :data:`DEADRISE_ESTIMATORS`).
    draft : float
        Depth of the body's lowest point below the water, m.
    wetted_length : float
        Length along ``x`` of the hull's part below the water, m.
    """

    x: np.ndarray
    dx: np.ndarray
    penetration: np.ndarray
    half_beam: np.ndarray
    deadrise: np.ndarray
    area: np.ndarray
    mass_per_metre: np.ndarray
    chine_wetted: np.ndarray
    polygons: tuple[Polygons, ...] = field(repr=False)
    deadrise_method: str = "wedge"
    draft: float = 0.0
    wetted_length: float = 0.0
    part: np.ndarray | None = None
    waterline_spans: np.ndarray | None = None

    _ARRAYS = (
        "x",
        "dx",
        "penetration",
        "half_beam",
        "deadrise",
        "area",
        "mass_per_metre",
        "chine_wetted",
        "part",
        "waterline_spans",
    )

    def __post_init__(self) -> None:
        n = len(self.x)
        if self.part is None:  # one part per station
            object.__setattr__(self, "part", np.zeros(n, dtype=np.int64))
        if self.waterline_spans is None:  # a wedge-like section wherever it is wetted
            spans = (np.asarray(self.penetration) > 0.0).astype(np.int64)
            object.__setattr__(self, "waterline_spans", spans)
        for name in self._ARRAYS:
            arr = np.asarray(getattr(self, name))
            if arr.shape != (n,):
                raise ValueError(f"Sections.{name} has shape {arr.shape}, expected ({n},)")
            object.__setattr__(self, name, _readonly(arr))
        if len(self.polygons) != n:
            raise ValueError(f"Sections.polygons has {len(self.polygons)} entries, expected {n}")

    def __len__(self) -> int:
        return len(self.x)

    @property
    def wetted(self) -> np.ndarray:
        """(n,) bool: sections with a positive penetration."""
        return self.penetration > 0.0

    @property
    def slice_index(self) -> np.ndarray:
        """(n,) int: the slice (station) of each entry, ``0, 1, ...`` along ``x``.

        The parts of one station are consecutive entries with the same ``x``.
        """
        new = np.ones(len(self.x), dtype=bool)
        new[1:] = self.x[1:] != self.x[:-1]
        return np.cumsum(new) - 1

    @property
    def slice_count(self) -> int:
        """Number of slices (stations); ``len()`` counts the entries, one per part."""
        return int(self.slice_index[-1]) + 1 if len(self.x) else 0

    @property
    def deadrise_deg(self) -> np.ndarray:
        """(n,) float: deadrise angles in degrees."""
        return np.degrees(self.deadrise)

    def subset(self, mask: np.ndarray) -> Sections:
        """The sections where ``mask`` is true, as a new :class:`Sections`.

        Each entry keeps its ``part`` and its ``x``, so ``slice_index`` counts the stations
        left in the subset.
        """
        mask = np.asarray(mask, dtype=bool)
        idx = np.flatnonzero(mask)
        kw = {name: getattr(self, name)[mask] for name in self._ARRAYS}
        return Sections(
            **kw,
            polygons=tuple(self.polygons[i] for i in idx),
            deadrise_method=self.deadrise_method,
            draft=self.draft,
            wetted_length=self.wetted_length,
        )

    def as_dict(self) -> dict[str, np.ndarray]:
        """The per-entry arrays by name (deadrise also in degrees as ``deadrise_deg``)."""
        d = {name: getattr(self, name) for name in self._ARRAYS}
        d["deadrise_deg"] = self.deadrise_deg
        return d


# -- deadrise estimators ----------------------------------------------------------------------


def _deadrise_wedge(penetration: np.ndarray, half_beam: np.ndarray) -> np.ndarray:
    """Equivalent wedge: ``tan(beta) = p / c`` (exact for a wedge), in rad."""
    with np.errstate(divide="ignore", invalid="ignore"):
        beta = np.arctan2(penetration, half_beam)
    return np.where((penetration > 0.0) & (half_beam > 0.0), beta, np.nan)


#: Deadrise estimators by name: ``f(penetration, half_beam) -> deadrise`` in rad.
DEADRISE_ESTIMATORS: dict[str, Callable[[np.ndarray, np.ndarray], np.ndarray]] = {
    "wedge": _deadrise_wedge,
}


# -- cutting ----------------------------------------------------------------------------------


def wetted_extent(hull: Hull, waterline: float) -> tuple[float, float]:
    """The ``x`` range of the part of a level hull below a waterline.

    Parameters
    ----------
    hull : Hull
    waterline : float
        Height of the water surface in the body frame, m.

    Returns
    -------
    (xmin, xmax) : tuple of float
        In m; equal values when nothing is below the waterline.
    """
    v = hull.vertices
    below = v[:, 2] < waterline
    if not below.any():
        lowest = float(v[np.argmin(v[:, 2]), 0])
        return lowest, lowest
    xs = [v[below, 0]]
    a, b = hull.edges.T
    cross = below[a] != below[b]
    if cross.any():
        va, vb = v[a[cross]], v[b[cross]]
        t = (waterline - va[:, 2]) / (vb[:, 2] - va[:, 2])
        xs.append(va[:, 0] + t * (vb[:, 0] - va[:, 0]))
    allx = np.concatenate(xs)
    return float(allx.min()), float(allx.max())


def _as_pose(pose: Pose | float) -> Pose:
    return pose if isinstance(pose, Pose) else Pose(draft=pose)


def _slice_count(slices: int) -> int:
    if isinstance(slices, bool) or not isinstance(slices, int | np.integer):
        raise InputError(f"slice count {slices!r} is not a whole number: give n >= 1")
    if slices < 1:
        raise InputError(f"slice count {slices!r} is not positive: give n >= 1 (e.g. 32)")
    if slices > MAX_SLICES:
        raise InputError(
            f"slice count {slices!r} is more than the {MAX_SLICES} hullslice allows: the "
            "force converges with far fewer (the paper uses 16 to 64)"
        )
    return int(slices)


def _check_deadrise(deadrise: str) -> str:
    if deadrise not in DEADRISE_ESTIMATORS:
        raise InputError(
            f"deadrise estimator {deadrise!r} is unknown; choose one of "
            f"{', '.join(DEADRISE_ESTIMATORS)}"
        )
    return deadrise


def cut(
    hull: Hull,
    pose: Pose | float,
    slices: int = 32,
    *,
    deadrise: str = "wedge",
    stations: Sequence[float] | None = None,
) -> Sections:
    """Cut a level hull at a pose into the slices of the 2D+t method.

    Parameters
    ----------
    hull : Hull
        The body.
    pose : Pose or float
        The pose, or the draft in m (depth of the lowest point below the water).
    slices : int
        Number of slices ``n`` over the wetted length (default 32); ignored when
        ``stations`` is given.
    deadrise : str
        Deadrise estimator, a key of :data:`DEADRISE_ESTIMATORS` (default ``"wedge"``).
    stations : sequence of float, optional
        Explicit station positions along ``x`` in m, instead of the mid-stations of ``n``
        equal slices; each station then stands for a slice reaching halfway to its
        neighbours (clipped to the wetted length).

    Returns
    -------
    Sections
    """
    pose = _as_pose(pose)
    _check_deadrise(deadrise)
    height = hull.extents[2]
    if pose.draft > height + TOL.coordinate * hull.size:
        raise InputError(
            f"draft {pose.draft:g} m is deeper than the body's height {height:.6g} m: the body "
            "would be under water; give a draft between 0 and the height"
        )
    if stations is None:
        return _level_sections(hull, pose.draft, _slice_count(slices), deadrise)
    waterline = hull.bounds[0, 2] + pose.draft
    x0, x1 = wetted_extent(hull, waterline)
    x = np.asarray(stations, dtype=np.float64).ravel()
    if not np.all(np.isfinite(x)) or np.any(np.diff(x) <= 0):
        raise InputError("stations must be finite and strictly increasing (in m)")
    edges = np.concatenate([[x0], 0.5 * (x[1:] + x[:-1]), [x1]])
    dx = np.diff(np.clip(edges, x0, x1))
    return _sections_at(hull, x, dx, waterline, deadrise, pose.draft, x1 - x0)


def _level_sections(hull: Hull, draft: float, n: int, deadrise: str) -> Sections:
    """The mid-stations of ``n`` equal slices over the wetted length (inputs checked)."""
    waterline = hull.bounds[0, 2] + draft  # body-frame height of the water surface
    x0, x1 = wetted_extent(hull, waterline)
    length = x1 - x0
    if length > 0.0:
        d = length / n
        x = x0 + (np.arange(n) + 0.5) * d
        dx = np.full(n, d)
    else:
        x, dx = np.empty(0), np.empty(0)
    return _sections_at(hull, x, dx, waterline, deadrise, draft, length)


def _cut_polygons(hull: Hull, x: np.ndarray, waterline: float) -> list[Polygons]:
    """Cross-section contours at stations ``x`` in the earth frame (y, z), z = 0 the water."""
    slicer, c, scale = hull._slicer
    out = []
    shift = np.array([c[1], c[2] - waterline])
    for xi in x:
        contours = slicer.slice(float((xi - c[0]) * scale)).to_polygons()
        out.append(tuple(np.asarray(p, dtype=np.float64) / scale + shift for p in contours))
    return out


def _signed_area(contour: np.ndarray) -> float:
    y, z = contour[:, 0], contour[:, 1]
    return 0.5 * float(np.dot(y, np.roll(z, -1)) - np.dot(np.roll(y, -1), z))


def _inside(point: np.ndarray, contour: np.ndarray) -> bool:
    """Whether a point is inside a closed contour (even-odd rule)."""
    y, z = contour[:, 0], contour[:, 1]
    yn, zn = np.roll(y, -1), np.roll(z, -1)
    straddle = (z > point[1]) != (zn > point[1])
    with np.errstate(divide="ignore", invalid="ignore"):
        yc = y + (point[1] - z) * (yn - y) / (zn - z)
    return bool(np.count_nonzero(straddle & (yc > point[0])) % 2)


def split_parts(contours: Polygons) -> list[Polygons]:
    """A cross-section's contours grouped into its separate parts, from starboard to port.

    Parameters
    ----------
    contours : sequence of (k, 2) float
        Outer contours (counter-clockwise) and holes (clockwise) of one section, ``(y, z)``.

    Returns
    -------
    list of tuples of (k, 2) float
        One entry per outer contour, with the holes inside it; a single entry (possibly
        empty) for a section in one part or with no contour.
    """
    if len(contours) <= 1:
        return [tuple(contours)]
    areas = [_signed_area(c) for c in contours]
    outers = [i for i, a in enumerate(areas) if a > 0.0]
    if len(outers) <= 1:
        return [tuple(contours)]
    groups: dict[int, list[int]] = {o: [o] for o in outers}
    for h, a in enumerate(areas):
        if a > 0.0:
            continue
        # a hole belongs to the smallest outer contour around it
        around = [o for o in outers if _inside(contours[h][0], contours[o])]
        owner = min(around, key=lambda o: areas[o]) if around else outers[0]
        groups[owner].append(h)
    order = sorted(outers, key=lambda o: float(contours[o][:, 0].min()))
    return [tuple(contours[i] for i in groups[o]) for o in order]


def _sections_at(
    hull: Hull,
    x: np.ndarray,
    dx: np.ndarray,
    waterline: float,
    deadrise: str,
    draft: float,
    wetted_length: float,
) -> Sections:
    station_polys = _cut_polygons(hull, x, waterline)
    polys: list[Polygons] = []
    station: list[int] = []
    part: list[int] = []
    for j, contours in enumerate(station_polys):
        parts = split_parts(contours)
        polys += parts
        station += [j] * len(parts)
        part += range(len(parts))
    idx = np.asarray(station, dtype=np.int64)
    props = polygon_properties(polys, tol=TOL.coordinate * hull.size)
    p = np.maximum(-props["zmin"], 0.0)
    if hull.mass is None:
        mpm = np.full(len(polys), np.nan)
    else:
        mpm = hull.mass * props["area"] / hull.volume
    c = props["half_beam"]
    return Sections(
        x=np.asarray(x, dtype=np.float64)[idx],
        dx=np.asarray(dx, dtype=np.float64)[idx],
        penetration=p,
        half_beam=c,
        deadrise=DEADRISE_ESTIMATORS[deadrise](p, c),
        area=props["area"],
        mass_per_metre=mpm,
        chine_wetted=props["chine_wetted"] & (p > 0.0),
        polygons=tuple(polys),
        deadrise_method=deadrise,
        draft=draft,
        wetted_length=wetted_length,
        part=np.asarray(part, dtype=np.int64),
        waterline_spans=np.where(p > 0.0, props["waterline_spans"], 0),
    )


def polygon_properties(polygons: Sequence[Polygons], tol: float) -> dict[str, np.ndarray]:
    """Properties of cross-sections in the earth frame, all stations at once.

    Parameters
    ----------
    polygons : (n,) sequence of sequences of (k, 2) float
        Contours of each section in ``(y, z)``, m, waterline at ``z = 0``.
    tol : float
        Coordinate tolerance in m: points closer than this to a level count as on it.

    Returns
    -------
    dict of (n,) arrays
        ``area`` (m^2), ``zmin`` (m, lowest point; ``+inf`` for an empty section),
        ``half_beam`` (m, half the width of the wetted section at the waterline, or of
        the whole section when it is under water), ``chine_wetted`` (bool, the waterline
        is at or above the section's widest point on either side), ``waterline_spans``
        (int, how many separate spans of the waterline lie inside the outer contours).
    """
    n = len(polygons)
    counts = [sum(len(c) for c in secs) for secs in polygons]
    area = np.zeros(n)
    zmin = np.full(n, np.inf)
    half_beam = np.zeros(n)
    chine = np.zeros(n, dtype=bool)
    spans = np.zeros(n, dtype=np.int64)
    if sum(counts) == 0:
        return {
            "area": area,
            "zmin": zmin,
            "half_beam": half_beam,
            "chine_wetted": chine,
            "waterline_spans": spans,
        }
    contours = [c for secs in polygons for c in secs]
    a = np.concatenate(contours)
    b = np.concatenate([np.roll(c, -1, axis=0) for c in contours])
    station = np.repeat(np.arange(n), counts)
    contour = np.repeat(np.arange(len(contours)), [len(c) for c in contours])
    nonempty = np.asarray(counts) > 0
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])[nonempty]

    ya, za, yb, zb = a[:, 0], a[:, 1], b[:, 0], b[:, 1]
    twice = ya * zb - yb * za
    area = np.bincount(station, weights=0.5 * twice, minlength=n)
    outer = (np.bincount(contour, weights=twice) > 0.0)[contour]  # counter-clockwise
    zmin[nonempty] = np.minimum.reduceat(za, starts)
    ymax = np.full(n, -np.inf)
    ymin = np.full(n, np.inf)
    ymax[nonempty] = np.maximum.reduceat(ya, starts)
    ymin[nonempty] = np.minimum.reduceat(ya, starts)

    # widest point on each side: the lowest vertex at the extreme y (a vertical side's
    # lower corner is the chine)
    z_port = np.full(n, np.inf)
    z_stbd = np.full(n, np.inf)
    at_port = ya >= ymax[station] - tol
    at_stbd = ya <= ymin[station] + tol
    np.minimum.at(z_port, station[at_port], za[at_port])
    np.minimum.at(z_stbd, station[at_stbd], za[at_stbd])
    chine = (z_port <= tol) | (z_stbd <= tol)

    # waterline crossings, half-open rule so that a vertex on the waterline counts once
    below_a, below_b = za < 0.0, zb < 0.0
    cross = below_a != below_b
    yc = ya[cross] + (0.0 - za[cross]) * (yb[cross] - ya[cross]) / (zb[cross] - za[cross])
    sc = station[cross]
    cmax = np.full(n, -np.inf)
    cmin = np.full(n, np.inf)
    np.maximum.at(cmax, sc, yc)
    np.minimum.at(cmin, sc, yc)
    crossed = np.isfinite(cmax)
    half_beam = np.where(crossed, 0.5 * (cmax - cmin), 0.0)
    submerged = ~crossed & (zmin < 0.0)
    half_beam[submerged] = 0.5 * (ymax - ymin)[submerged]
    # each span of the waterline inside an outer contour enters and leaves it once
    spans = np.bincount(station[cross & outer], minlength=n) // 2
    return {
        "area": area,
        "zmin": zmin,
        "half_beam": half_beam,
        "chine_wetted": chine,
        "waterline_spans": spans,
    }
