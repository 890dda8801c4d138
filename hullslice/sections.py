"""Cutting a hull into cross-sections at a pose: the 2D+t slices and their properties.

At a pose the wetted part of the hull (below ``Z = 0``), of length ``DeltaL`` along the
earth's ``X``, is cut into ``n`` slices of thickness ``d = DeltaL / n`` (paper, Eq. 7); each
slice is represented by the hull's cross-section at its mid-station, cut by manifold3d along
the earth-fixed plane ``X = const`` (for a pitched body a tilted plane in its own frame).

A section may have several wetted pieces (two floats, a catamaran): each piece is an
**entry** of :class:`Sections` with its own keel, penetration and deadrise, and its share of
the section's mass per metre. A section with one piece (the usual case) is one entry. The
mass is shared first between the section's separate parts (disjoint outer contours, such as
a catamaran's floats) by their areas, each carrying its own; then between the wetted pieces
of one part (twin keels joined above the water) by their widths at the waterline.

Local deadrise estimators (each per side, port and starboard, of each piece):

``wedge`` (default)
    The equivalent wedge of the wetted piece: ``tan(beta) = p / c``, ``p`` the depth of its
    keel below the water, ``c`` the horizontal distance from the keel to the waterline on
    that side. Exact for a wedge.
``waterline-slope``
    The slope of the contour where it meets the water: ``tan(beta) = |dz/dy|`` there.
``keel-fit``
    A least-squares line through the keel fitted to the wetted contour of that side,
    ``z - z_k = tan(beta) |y - y_k|``, integrated exactly over the contour's segments.

The two sides combine into the section's deadrise by the harmonic mean of ``tan(beta)``
(for ``wedge``: ``tan(beta) = p / c`` with ``c`` the half-width of the piece).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from .constants import TOL
from .errors import InputError
from .geometry import frame
from .limits import check_slice_count
from .mesh import Hull
from .state import Pose

__all__ = [
    "DEADRISE_ESTIMATORS",
    "SLICINGS",
    "Outline",
    "Sections",
    "area_curve",
    "cut",
    "section_properties",
]

Polygons = tuple[np.ndarray, ...]

#: Deadrise estimators by name, with a one-line description.
DEADRISE_ESTIMATORS: dict[str, str] = {
    "wedge": "equivalent wedge of the wetted piece, tan(beta) = p / c",
    "waterline-slope": "slope of the contour where it meets the water",
    "keel-fit": "least-squares line through the keel fitted to the wetted contour",
}


class ShiftedPolygons(Sequence):
    """Station contours scaled and moved when they are read (no copy until then).

    Parameters
    ----------
    polygons : sequence of sequences of (k, 2) float
        Contours per station.
    shift : (float, float)
        Offset added to every point, m.
    scale : float
        Every point is divided by it before the shift.
    """

    def __init__(
        self, polygons: Sequence[Polygons], shift: tuple[float, float], scale: float = 1.0
    ) -> None:
        self._polygons = polygons
        self._shift = np.asarray(shift, dtype=np.float64)
        self._scale = float(scale)

    def __len__(self) -> int:
        return len(self._polygons)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[j] for j in range(*i.indices(len(self)))]
        return tuple(np.asarray(c) / self._scale + self._shift for c in self._polygons[i])


def _readonly(a) -> np.ndarray:
    a = np.ascontiguousarray(a)
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class Sections:
    """Cross-sections of a hull at one pose, as arrays over entries (wetted pieces).

    Every array has one value per entry; ``station`` says which station (slice) an entry
    belongs to. A dry station has one entry with zero penetration.

    Attributes
    ----------
    station : (n,) int
        Index of the entry's station, into ``polygons`` and the station arrays.
    x : (n,) float
        Station position along the earth's ``X`` in m (equal to the body's ``x`` when level).
    dx : (n,) float
        Thickness of the entry's slice in m.
    penetration : (n,) float
        Depth of the piece's lowest point below the water, m (``>= 0``).
    half_beam : (n,) float
        Half the width of the wetted piece at the waterline, m.
    half_beam_port, half_beam_stbd : (n,) float
        Horizontal distance from the keel to the waterline on each side, m.
    deadrise : (n,) float
        Local deadrise in rad (both sides combined; NaN for a dry entry).
    deadrise_port, deadrise_stbd : (n,) float
        Deadrise of each side in rad.
    area : (n,) float
        Area of the station's whole cross-section (not only its wetted part), m^2.
    mass_per_metre : (n,) float
        Mass per metre carried by the piece, kg/m (NaN without a hull mass).
    chine_wetted : (n,) bool
        The water has reached the station's widest point (chine or deck) on either side.
    keel_slope : (n,) float
        Slope ``dZ/dX`` of the body's keel line at the station (earth frame).
    keel_z : (n,) float
        Earth height of the station's lowest point, m.
    y_keel : (n,) float
        Lateral position ``y`` of the piece's keel, m.
    part_half_beam : (n,) float
        Half the largest width of the separate part of the section that the piece belongs
        to (its float, for a catamaran), m; NaN for a dry entry.
    polygons : sequence of tuples of (k, 2) float
        Contours of each **station** in the earth ``(Y, Z)`` plane, m; the waterline is
        ``Z = 0``; outer contours counter-clockwise.
    deadrise_method : str
        The estimator used, a key of :data:`DEADRISE_ESTIMATORS`.
    draft, pitch, wetted_length : float
        The pose (m, rad) and the length of the wetted part along ``X`` (m).
    z_cg : float
        Earth height of the centre of gravity, m.
    keel_curvature : (n,) float
        The keel line's ``d^2 Z_k / dX^2`` averaged over the entry's slice, 1/m (zeros when
        not given).
    """

    station: np.ndarray
    x: np.ndarray
    dx: np.ndarray
    penetration: np.ndarray
    half_beam: np.ndarray
    half_beam_port: np.ndarray
    half_beam_stbd: np.ndarray
    deadrise: np.ndarray
    deadrise_port: np.ndarray
    deadrise_stbd: np.ndarray
    area: np.ndarray
    mass_per_metre: np.ndarray
    chine_wetted: np.ndarray
    keel_slope: np.ndarray
    keel_z: np.ndarray
    y_keel: np.ndarray
    part_half_beam: np.ndarray
    polygons: Sequence[Polygons] = field(repr=False, default=())
    deadrise_method: str = "wedge"
    draft: float = 0.0
    pitch: float = 0.0
    wetted_length: float = 0.0
    z_cg: float = 0.0
    keel_curvature: np.ndarray | None = field(repr=False, default=None)

    _ARRAYS = (
        "station",
        "x",
        "dx",
        "penetration",
        "half_beam",
        "half_beam_port",
        "half_beam_stbd",
        "deadrise",
        "deadrise_port",
        "deadrise_stbd",
        "area",
        "mass_per_metre",
        "chine_wetted",
        "keel_slope",
        "keel_z",
        "y_keel",
        "part_half_beam",
        "keel_curvature",
    )

    def __post_init__(self) -> None:
        fields = self.__dict__  # frozen: set once here, read-only arrays
        n = len(fields["x"])
        if fields["keel_curvature"] is None:
            fields["keel_curvature"] = np.zeros(n)
        for name in self._ARRAYS:
            arr = fields[name]
            if not (type(arr) is np.ndarray and arr.shape == (n,) and arr.flags.c_contiguous):
                arr = np.ascontiguousarray(arr)
                if arr.shape != (n,):
                    raise ValueError(f"Sections.{name} has shape {arr.shape}, expected ({n},)")
            arr.flags.writeable = False
            fields[name] = arr

    def __len__(self) -> int:
        return len(self.x)

    @property
    def n_stations(self) -> int:
        """Number of stations (slices)."""
        return len(self.polygons)

    @property
    def wetted(self) -> np.ndarray:
        """(n,) bool: entries with a positive penetration."""
        return self.penetration > 0.0

    @property
    def deadrise_deg(self) -> np.ndarray:
        """(n,) float: deadrise angles in degrees."""
        return np.degrees(self.deadrise)

    def subset(self, mask: np.ndarray) -> Sections:
        """The entries where ``mask`` is true, as a new :class:`Sections` (same stations)."""
        mask = np.asarray(mask, dtype=bool)
        kw = {name: getattr(self, name)[mask] for name in self._ARRAYS}
        return Sections(
            **kw,
            polygons=self.polygons,
            deadrise_method=self.deadrise_method,
            draft=self.draft,
            pitch=self.pitch,
            wetted_length=self.wetted_length,
            z_cg=self.z_cg,
        )

    def to_xarray(self):
        """The entries as an ``xarray.Dataset`` with units (needs xarray)."""
        from .xarray_io import sections_to_xarray

        return sections_to_xarray(self)

    def to_dataframe(self):
        """The entries as a ``pandas.DataFrame``, units in ``attrs``."""
        from .xarray_io import sections_to_dataframe

        return sections_to_dataframe(self)

    def as_dict(self) -> dict[str, np.ndarray]:
        """The per-entry arrays by name, deadrise also in degrees (``*_deg``)."""
        d = {name: getattr(self, name) for name in self._ARRAYS}
        d["deadrise_deg"] = self.deadrise_deg
        d["deadrise_port_deg"] = np.degrees(self.deadrise_port)
        d["deadrise_stbd_deg"] = np.degrees(self.deadrise_stbd)
        return d


# -- inputs ------------------------------------------------------------------------------------


def _as_pose(pose: Pose | float) -> Pose:
    return pose if isinstance(pose, Pose) else Pose(draft=pose)


_slice_count = check_slice_count


def _check_deadrise(deadrise: str) -> str:
    if deadrise not in DEADRISE_ESTIMATORS:
        raise InputError(
            f"deadrise estimator {deadrise!r} is unknown; choose one of "
            f"{', '.join(DEADRISE_ESTIMATORS)}"
        )
    return deadrise


def _height_at(hull: Hull, pitch: float) -> float:
    """Vertical extent of the body at a pitch, m."""
    fr = frame(hull, pitch)
    return fr.highest - fr.lowest


# -- cutting -----------------------------------------------------------------------------------


def cut(
    hull: Hull,
    pose: Pose | float,
    slices: int = 32,
    *,
    deadrise: str = "wedge",
    stations: Sequence[float] | None = None,
    slicing: str = "wetted",
) -> Sections:
    """Cut a hull at a pose into the slices of the 2D+t method.

    Parameters
    ----------
    hull : Hull
        The body.
    pose : Pose or float
        The pose (draft in m, pitch in rad), or the draft alone (level body).
    slices : int
        Number of slices ``n`` over the wetted length (default 32); ignored when
        ``stations`` is given.
    deadrise : str
        Deadrise estimator, a key of :data:`DEADRISE_ESTIMATORS` (default ``"wedge"``).
    stations : sequence of float, optional
        Explicit station positions along ``X`` in m, instead of the mid-stations of ``n``
        equal slices; each then stands for a slice reaching halfway to its neighbours
        (clipped to the wetted length).
    slicing : str
        ``"wetted"`` (default, the paper's: ``n`` slices over the wetted length) or
        ``"fixed"`` (``n`` slices over the body's length, cut once per pitch), see
        :data:`SLICINGS`.

    Returns
    -------
    Sections
    """
    pose = _as_pose(pose)
    _check_deadrise(deadrise)
    _check_slicing(slicing)
    height = _height_at(hull, pose.pitch)
    if pose.draft > height + TOL.coordinate * hull.size:
        raise InputError(
            f"draft {pose.draft:g} m is deeper than the body's height {height:.6g} m: the body "
            "would be under water; give a draft between 0 and the height"
        )
    if stations is None:
        return sections_at(hull, pose, _slice_count(slices), deadrise, slicing=slicing)
    x = np.asarray(stations, dtype=np.float64).ravel()
    if not np.all(np.isfinite(x)) or np.any(np.diff(x) <= 0):
        raise InputError("stations must be finite and strictly increasing (in m)")
    return sections_at(hull, pose, len(x), deadrise, stations=x)


#: How the slices are placed, by name.
SLICINGS: dict[str, str] = {
    "wetted": "n equal slices over the wetted length at each instant (the paper's)",
    "fixed": "n equal slices over the body's length, cut once per pitch; the slices at the "
    "ends of the wetted part count their wetted length only",
}


def _check_slicing(slicing: str) -> str:
    if slicing not in SLICINGS:
        raise InputError(f"slicing {slicing!r} is unknown; choose one of {', '.join(SLICINGS)}")
    return slicing


def sections_at(
    hull: Hull,
    pose: Pose,
    n: int,
    deadrise: str,
    stations: np.ndarray | None = None,
    slicing: str = "wetted",
    cache: bool = True,
) -> Sections:
    """The sections at a pose, inputs already checked (see :func:`cut`).

    ``slicing="fixed"`` places the slices over the body's length (see :data:`SLICINGS`);
    ``cache=False`` cuts its stations afresh instead of reusing the pitch's cut (the same
    numbers, for checking).
    """
    fr = frame(hull, pose.pitch)
    level = fr.lowest + pose.draft  # the water surface, relative to the cg
    extent = fr.keel.below(level)
    tol = TOL.coordinate * hull.size
    if slicing == "fixed" and stations is None:
        return _fixed_sections(hull, fr, pose, n, deadrise, level, extent, tol, cache)
    if extent is None:
        x0 = x1 = float(fr.keel.x[np.argmin(fr.keel.z)])
    else:
        x0, x1 = extent
    length = x1 - x0
    if stations is None:
        if length > 0.0:
            d = length / n
            rel = x0 + (np.arange(n) + 0.5) * d
            dx = np.full(n, d)
        else:
            rel, dx = np.empty(0), np.empty(0)
    else:
        rel = np.asarray(stations, dtype=np.float64) - fr.cg[0]
        bounds = np.concatenate([[x0], 0.5 * (rel[1:] + rel[:-1]), [x1]])
        dx = np.diff(np.clip(bounds, x0, x1))
    polys = fr.cut(rel)
    props = wetted_properties(Outline.of(polys, tol, fr.origin, fr.scale), level, tol, deadrise)
    return _assemble(hull, fr, pose, level, length, rel, dx, props, polys, deadrise)


def area_curve(hull: Hull, stations: int = 40) -> tuple[np.ndarray, np.ndarray]:
    """The sectional area curve of a level hull.

    Parameters
    ----------
    hull : Hull
    stations : int
        Number of stations, the mid-points of equal parts of the body's length (default 40).

    Returns
    -------
    x : (stations,) float
        Stations along the body, m.
    area : (stations,) float
        Area of the cross-section at each, m^2. ``sum(area) * length / stations`` is the
        volume by the midpoint rule.
    """
    n = _slice_count(stations)
    fr = frame(hull, 0.0)
    _, rel = fr.fixed_stations(n)
    outline = Outline.of(fr.cut(rel), TOL.coordinate * hull.size, fr.origin, fr.scale)
    return rel + fr.cg[0], outline.area.copy()


def _station_mass(hull: Hull, fr, area: np.ndarray, rel: np.ndarray) -> np.ndarray:
    """Mass per metre of the stations at ``rel`` (relative X) with section ``area``."""
    if hull.mass is None:
        return np.full(len(rel), np.nan)
    if hull.mass_distribution is None:
        return hull.mass / hull.volume * area
    # the distribution's parts, each at its own height, crossed by the tilted planes
    return hull.mass_distribution.on_planes(
        rel, fr.pitch, (fr.cg[0], fr.cg[2]), float(hull.centroid[2])
    )


def _assemble(
    hull, fr, pose, level, length, rel, dx, props, polys, deadrise, scale=None, keel=None
):
    """:class:`Sections` from per-station positions and per-entry properties; ``keel`` is
    the keel line's height and slope at the stations when already known."""
    st = props["station"]
    keel_z, slope = fr.keel.at(rel) if keel is None else keel
    if scale is None:
        penetration, half_beam = props["penetration"], props["half_beam"]
        port, stbd = props["half_beam_port"], props["half_beam_stbd"]
    else:
        r = scale[st]
        penetration, half_beam = props["penetration"] * r, props["half_beam"] * r
        port, stbd = props["half_beam_port"] * r, props["half_beam_stbd"] * r
    z_cg = -level
    shift = (fr.origin[0], fr.origin[1] + z_cg)
    m_station = _station_mass(hull, fr, props["area"], rel)
    return Sections(
        station=st,
        x=(rel + fr.cg[0])[st],
        dx=dx[st],
        penetration=penetration,
        half_beam=half_beam,
        half_beam_port=port,
        half_beam_stbd=stbd,
        deadrise=props["deadrise"],
        deadrise_port=props["deadrise_port"],
        deadrise_stbd=props["deadrise_stbd"],
        area=props["area"][st],
        mass_per_metre=m_station[st] * props["mass_share"],
        chine_wetted=props["chine_wetted"],
        keel_slope=slope[st],
        keel_z=(keel_z + z_cg)[st],
        y_keel=props["y_keel"],
        part_half_beam=props["part_half_beam"],
        polygons=ShiftedPolygons(polys, shift, fr.scale),
        deadrise_method=deadrise,
        draft=pose.draft,
        pitch=pose.pitch,
        wetted_length=length,
        z_cg=z_cg,
        keel_curvature=fr.keel.mean_curvature(rel, dx)[st],
    )


def _fixed_sections(hull, fr, pose, n, deadrise, level, extent, tol, cache) -> Sections:
    """Fixed slices over the body's length; the wetted ones at this waterline.

    Interior slices use their mid-station's section. A slice only partly wetted counts its
    wetted length and stands at that part's middle, with the section of its own
    mid-station (or, when that is dry, of its wetted neighbour's) made similar to the
    section there: penetration and half-beams scaled by the keel line's depth ratio, the
    deadrise kept. Its force then grows from zero as the water reaches it.
    """
    xa = float(fr.keel.x[0])
    d, mids = fr.fixed_stations(n)
    if extent is None:
        return _assemble(
            hull,
            fr,
            pose,
            level,
            0.0,
            np.empty(0),
            np.empty(0),
            wetted_properties(Outline.of([], tol), level, tol, deadrise),
            [],
            deadrise,
        )
    x0, x1 = extent
    k = np.arange(
        min(max(int((x0 - xa) // d), 0), n - 1), min(max(int((x1 - xa) // d), 0), n - 1) + 1
    )
    lo = np.maximum(xa + k * d, x0)
    hi = np.minimum(xa + (k + 1) * d, x1)
    keep = hi > lo
    k, lo, hi = k[keep], lo[keep], hi[keep]
    # only the stations of the wetted slices and their neighbours matter
    w0, w1 = max(int(k[0]) - 1, 0), min(int(k[-1]) + 2, n)
    props = None
    if cache:
        outline, polys, c0 = fr.fixed_outline(n, tol, w0, w1)
        props = _tabulated(fr._fixed[(n, tol)], outline, level, tol, deadrise, w0 - c0, w1 - c0)
    else:
        (outline, polys), c0 = _outline_of(fr, mids, tol), 0
    if props is None:
        props = wetted_properties(outline.window(w0 - c0, w1 - c0), level, tol, deadrise)
    props["station"] = props["station"] + w0
    wet_mid = np.zeros(n, dtype=bool)
    wet_mid[props["station"][props["penetration"] > 0]] = True
    full = np.abs(hi - lo - d) <= 1e-12 * d
    x = np.where(full, mids[k], 0.5 * (lo + hi))
    source = k.copy()
    # a partial slice whose own mid-station is dry borrows its wetted neighbour's section;
    # so does one whose mid-station is wetted less than half as deep as the slice's own
    # middle: scaling a barely wetted section up by the depth ratio would stretch the few
    # facets at its keel into a flat bottom
    keel = fr.keel.at(x)
    pen_mid = np.zeros(n)
    np.maximum.at(pen_mid, props["station"], props["penetration"])
    inward = np.where(k == k.min(), 1, -1)
    neighbour = np.minimum(np.maximum(k + inward, 0), n - 1)
    weak = wet_mid[k] & (2.0 * pen_mid[k] < level - keel[0]) & (pen_mid[neighbour] > pen_mid[k])
    borrow = ~full & (~wet_mid[k] | weak)
    source[borrow] = neighbour[borrow]
    fresh = ~full & ~wet_mid[source]
    ratio = np.ones(len(x))
    part = ~full & ~fresh
    if part.any():
        kz_src = np.interp(mids[source[part]], fr.keel.x, fr.keel.z)
        ratio[part] = (level - keel[0][part]) / (level - kz_src)
    # entries of the chosen sources, one slice after another (entries sorted by station)
    first = np.searchsorted(props["station"], source, side="left")
    count = np.searchsorted(props["station"], source, side="right") - first
    take = _prefix_index(first, count)
    slot = np.repeat(np.arange(len(source)), count)
    sel = {key: val[take] for key, val in props.items() if key != "area"}
    sel["station"] = slot
    sel["area"] = props["area"][source - w0]
    slice_polys = [polys[src - c0] for src in source]
    if fresh.any():  # no wetted section nearby (the first contact): cut where the slice is
        sel, slice_polys = _with_fresh(fr, sel, slice_polys, fresh, x, level, tol, deadrise)
    return _assemble(
        hull,
        fr,
        pose,
        level,
        x1 - x0,
        x,
        hi - lo,
        sel,
        slice_polys,
        deadrise,
        scale=ratio,
        keel=keel,
    )


#: A kept outline gets a waterline table from its this many-th evaluation on (a table
#: costs some evaluations' time to make: it pays off over a time history, not at once).
TABLE_AFTER = 8


def _tabulated(store, outline, level, tol, deadrise, k0, k1):
    """The properties of stations ``k0 .. k1 - 1`` of a kept outline from its waterline
    table (made, or made higher, when needed); None where a table does not serve."""
    from .waterline import TABULATED, WaterlineTable

    store["evaluations"] = count = store.get("evaluations", 0) + 1
    if deadrise not in TABULATED or count < TABLE_AFTER:
        return None
    tables = store.setdefault("tables", {})
    table = tables.get(deadrise)
    if table is None or table.outline is not outline or level > table.top:
        # none where one was too costly for this outline at a lower water
        too_high = store.setdefault("too_high", {}).get(deadrise)
        if too_high is not None and too_high[0] is outline and level >= too_high[1]:
            return None
        table = WaterlineTable.of(outline, level, tol, deadrise)
        if table is None:
            store["too_high"][deadrise] = (outline, level)
            tables.pop(deadrise, None)
            return None
        tables[deadrise] = table
    return table.at(level, k0, k1)


def _outline_of(fr, rel: np.ndarray, tol: float):
    polys = fr.cut(rel)
    return Outline.of(polys, tol, fr.origin, fr.scale), polys


def _with_fresh(fr, sel, slice_polys, fresh, x, level, tol, deadrise):
    """Replace the entries of the slices marked ``fresh`` by a cut at their position."""
    idx = np.flatnonzero(fresh)
    outline, polys = _outline_of(fr, x[idx], tol)
    new = wetted_properties(outline, level, tol, deadrise)
    keep = ~np.isin(sel["station"], idx)
    out = {}
    for key in sel:
        if key == "area":
            area = sel["area"].copy()
            area[idx] = new["area"]
            out["area"] = area
        elif key == "station":
            out["station"] = np.concatenate([sel["station"][keep], idx[new["station"]]])
        else:
            out[key] = np.concatenate([sel[key][keep], new[key]])
    order = np.argsort(out["station"], kind="stable")
    out = {key: (val if key == "area" else val[order]) for key, val in out.items()}
    for j, i in enumerate(idx):
        slice_polys[i] = polys[j]
    return out, slice_polys


# -- properties of cross-sections ---------------------------------------------------------------


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
    ) -> Outline:
        """The outline of station sections given as contours (see :func:`section_properties`),
        each point divided by ``scale`` and moved by ``origin``."""
        s = len(polygons)
        contours = [c for secs in polygons for c in secs]
        if contours:
            sizes = np.array([len(c) for c in contours])
            a = np.concatenate(contours)
            if scale != 1.0:
                a = a / scale
            if origin != (0.0, 0.0):
                a = a + np.asarray(origin)
            nxt = np.arange(len(a)) + 1
            nxt[np.cumsum(sizes) - 1] = np.cumsum(sizes) - sizes  # each contour closes
            b = a[nxt]
            contour = np.repeat(np.arange(len(contours)), sizes)
            station = np.repeat(np.repeat(np.arange(s), [len(secs) for secs in polygons]), sizes)
        else:
            a = b = np.empty((0, 2))
            contour = station = np.empty(0, dtype=np.int64)
        cross = a[:, 0] * b[:, 1] - b[:, 0] * a[:, 1]
        area = np.bincount(station, weights=0.5 * cross, minlength=s)
        c_area = 0.5 * np.bincount(contour, weights=cross, minlength=len(contours))
        outer = (c_area > 0.0)[contour] if len(a) else contour > 0
        part_area, renumber = _part_areas(contours, c_area, polygons)
        if outer.all():  # no holes (the usual case): nothing to drop
            contour = renumber[contour]
        else:
            station, a, b, contour = station[outer], a[outer], b[outer], renumber[contour[outer]]
        ya, za, yb, zb = a[:, 0], a[:, 1], b[:, 0], b[:, 1]
        # per station and per contour, while both are still contiguous
        c = len(part_area)
        start = np.searchsorted(station, np.arange(s + 1))
        cstart = np.searchsorted(contour, np.arange(c + 1))
        zmin = _grouped(np.minimum, za, start, np.inf)
        ymax = _grouped(np.maximum, ya, start, -np.inf)
        ymin = _grouped(np.minimum, ya, start, np.inf)
        side = np.concatenate([station[ya >= ymax[station] - tol],
                               station[ya <= ymin[station] + tol]])  # fmt: skip
        z_side = np.concatenate([za[ya >= ymax[station] - tol], za[ya <= ymin[station] + tol]])
        z_chine = _group_min(side, z_side, s)
        part_station = station[cstart[:-1]] if c else np.empty(0, dtype=np.int64)
        part = (
            _grouped(np.maximum, za, cstart, -np.inf),
            _grouped(np.minimum, ya, cstart, np.inf),
            _grouped(np.maximum, ya, cstart, -np.inf),
        )
        # then each station's edges by the height of their lower end
        zlo = np.minimum(za, zb)
        # one sort of a combined key: the station, and the height scaled into [0, 1)
        # (heights closer than 1e-10 of the body's may swap; no result depends on it)
        if len(zlo):
            lo, span = zlo.min(), np.ptp(zlo)
            key = 2.0 * station + (zlo - lo) / (span * (1.0 + 1e-9) + 1e-300)
            order = np.argsort(key)
        else:
            order = np.empty(0, dtype=np.int64)
        station, ya, za, yb, zb, zlo, contour = (
            v[order] for v in (station, ya, za, yb, zb, zlo, contour)
        )
        return cls(
            station, ya, za, yb, zb, zlo, start, area, contour, part_area, part_station, *part,
            zmin, ymin, ymax, z_chine,
        )  # fmt: skip

    def window(self, k0: int, k1: int) -> Outline:
        """The outline of stations ``k0`` to ``k1 - 1`` alone (views, no copies)."""
        e0, e1 = int(self.start[k0]), int(self.start[k1])
        c0 = int(np.searchsorted(self.part_station, k0))
        c1 = int(np.searchsorted(self.part_station, k1))
        return Outline(
            self.station[e0:e1] - k0, self.ya[e0:e1], self.za[e0:e1], self.yb[e0:e1],
            self.zb[e0:e1], self.zlo[e0:e1], self.start[k0 : k1 + 1] - e0, self.area[k0:k1],
            self.contour[e0:e1] - c0, self.part_area[c0:c1], self.part_station[c0:c1] - k0,
            self.part_zmax[c0:c1], self.part_ymin[c0:c1], self.part_ymax[c0:c1],
            self.zmin[k0:k1], self.ymin[k0:k1], self.ymax[k0:k1], self.z_chine[k0:k1],
        )  # fmt: skip

    def below(self, level: float) -> tuple:
        """The edges reaching below ``level`` (a prefix of each station's), with heights
        measured from ``level``: ``station, ya, za, yb, zb, contour``."""
        idx = _prefix_index(self.start[:-1], _prefix_counts(self, level))
        return (
            self.station[idx],
            self.ya[idx],
            self.za[idx] - level,
            self.yb[idx],
            self.zb[idx] - level,
            self.contour[idx],
        )


def _part_areas(contours, c_area: np.ndarray, polygons) -> tuple[np.ndarray, np.ndarray]:
    """Areas of the outer contours with their holes deducted, and the outer contours'
    numbers (``-1`` for a hole) for every contour.

    A hole belongs to the smallest outer contour of its station around it; a station with
    one outer contour (the usual case) needs no test.
    """
    outer = c_area > 0.0
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


def _prefix_counts(outline: Outline, level: float) -> np.ndarray:
    """For each station, how many of its edges (sorted by lower end) reach below ``level``."""
    cum = np.concatenate([[0], np.cumsum(outline.zlo < level)])
    return cum[outline.start[1:]] - cum[outline.start[:-1]]


def _prefix_index(starts: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """Indices ``starts[i] .. starts[i] + counts[i] - 1`` for all ``i``, concatenated."""
    total = int(counts.sum())
    if total == 0:
        return np.empty(0, dtype=np.int64)
    offsets = np.repeat(starts - (np.cumsum(counts) - counts), counts)
    return np.arange(total) + offsets


def _grouped(ufunc, values: np.ndarray, start: np.ndarray, fill: float) -> np.ndarray:
    """``ufunc`` reduced over the contiguous groups ``start[i]:start[i + 1]``; ``fill`` for
    an empty group."""
    out = np.full(len(start) - 1, fill)
    full = start[1:] > start[:-1]
    if full.any():
        out[full] = ufunc.reduceat(values, start[:-1][full])
    return out


def _group_min(keys: np.ndarray, values: np.ndarray, n: int) -> np.ndarray:
    out = np.full(n, np.inf)
    np.minimum.at(out, keys, values)
    return out


def section_properties(
    polygons: Sequence[Polygons], tol: float, deadrise: str = "wedge"
) -> dict[str, np.ndarray]:
    """Properties of cross-sections in the earth frame, all stations and pieces at once.

    Parameters
    ----------
    polygons : (s,) sequence of sequences of (k, 2) float
        Contours of each station in ``(y, z)``, m, waterline at ``z = 0``; outer contours
        counter-clockwise, holes clockwise.
    tol : float
        Coordinate tolerance in m.
    deadrise : str
        Deadrise estimator (see :data:`DEADRISE_ESTIMATORS`).

    Returns
    -------
    dict of arrays
        Per station: ``area`` (s,). Per entry (wetted piece, or one per dry station):
        ``station``, ``penetration``, ``half_beam``, ``half_beam_port``,
        ``half_beam_stbd``, ``deadrise``, ``deadrise_port``, ``deadrise_stbd`` (rad),
        ``y_keel``, ``mass_share`` (the piece's share of its station's mass: its part's by
        area, shared between the pieces of one part by waterline width), ``chine_wetted``.
    """
    outline = Outline.of(polygons, tol)
    return wetted_properties(outline, 0.0, tol, deadrise)


def wetted_properties(
    outline: Outline, level: float, tol: float, deadrise: str = "wedge"
) -> dict[str, np.ndarray]:
    """Properties of the sections of an :class:`Outline` with the water at height ``level``.

    See :func:`section_properties` for the result.
    """
    s = outline.n_stations
    station, ya, za, yb, zb, contour = outline.below(level)
    chine_station = outline.z_chine - level <= tol

    pieces = _wetted_pieces(station, ya, za, yb, zb, contour, outline, level)
    ps, yl, yr, tan_l, tan_r, part = pieces
    m = len(ps)
    # underwater parts of the segments, assigned to the piece above them
    za_c, zb_c = np.minimum(za, 0.0), np.minimum(zb, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        yc = ya + (0.0 - za) * (yb - ya) / (zb - za)
        ya_c = np.where(za < 0.0, ya, yc)
        yb_c = np.where(zb < 0.0, yb, yc)
    seg_piece = _assign(station, 0.5 * (ya_c + yb_c), ps, yl, yr)
    # a part with a single wetted piece owns all its underwater edges, also those outside
    # its waterline interval (a section under water beyond its widest point, whose keel
    # may lie outside the interval)
    if m:
        count = np.bincount(part, minlength=len(outline.part_area))
        only = np.full(len(outline.part_area), -1)
        single = count[part] == 1
        only[part[single]] = np.flatnonzero(single)
        own = only[contour]
        seg_piece = np.where(own >= 0, own, seg_piece)
    sel = np.flatnonzero(seg_piece >= 0)
    seg_piece = seg_piece[sel]
    y1, z1, y2, z2 = ya_c[sel], za_c[sel], yb_c[sel], zb_c[sel]
    # keel of each piece: its lowest underwater point
    zk = _group_min(seg_piece, np.minimum(z1, z2), m) if m else np.empty(0)
    pts_piece = np.concatenate([seg_piece, seg_piece])
    pts_y = np.concatenate([y1, y2])
    pts_z = np.concatenate([z1, z2])
    # the keel: where the lowest point of each piece is; on a flat bottom, its middle (the
    # points level with it to manifold3d's single precision, a fifth of the tolerance: a
    # finely faceted round bottom must not count as flat)
    at_keel = pts_z <= zk[pts_piece] + tol / 5
    keel_piece, keel_y = pts_piece[at_keel], pts_y[at_keel]
    yk = 0.5 * (_group_min(keel_piece, keel_y, m) - _group_min(keel_piece, -keel_y, m))
    p = np.maximum(-zk, 0.0)
    c_port = yr - yk
    c_stbd = yk - yl
    if deadrise == "wedge":
        with np.errstate(divide="ignore", invalid="ignore"):
            t_port, t_stbd = p / c_port, p / c_stbd
    elif deadrise == "waterline-slope":
        t_port, t_stbd = tan_r, tan_l
    else:  # keel-fit
        t_port, t_stbd = _keel_fit(
            seg_piece,
            y1 - yk[seg_piece],
            z1 - zk[seg_piece],
            y2 - yk[seg_piece],
            z2 - zk[seg_piece],
            m,
        )
    with np.errstate(divide="ignore", invalid="ignore"):
        t_mean = 2.0 / (1.0 / t_port + 1.0 / t_stbd)
    width = yr - yl
    share = _mass_share(outline, ps, part, width)

    # one dry entry for each station without a wetted piece
    has_piece = np.zeros(s, dtype=bool)
    has_piece[ps] = True
    dry = np.flatnonzero(~has_piece)
    nd = len(dry)
    entry_station = np.concatenate([ps, dry])
    order = np.argsort(entry_station, kind="stable")
    nan_d = np.full(nd, np.nan)

    def col(wet, fill):
        return np.concatenate([wet, np.full(nd, fill) if np.isscalar(fill) else fill])[order]

    return {
        "area": outline.area,
        "station": entry_station[order],
        "penetration": col(p, 0.0),
        "half_beam": col(0.5 * width, 0.0),
        "half_beam_port": col(c_port, 0.0),
        "half_beam_stbd": col(c_stbd, 0.0),
        "deadrise": col(np.arctan(t_mean), nan_d),
        "deadrise_port": col(np.arctan(t_port), nan_d),
        "deadrise_stbd": col(np.arctan(t_stbd), nan_d),
        "y_keel": col(yk, nan_d),
        "part_half_beam": col(0.5 * (outline.part_ymax - outline.part_ymin)[part], nan_d),
        "mass_share": col(share, 1.0),
        "chine_wetted": col(chine_station[ps], False).astype(bool),
    }


def _mass_share(outline, ps, part, width) -> np.ndarray:
    """Each wetted piece's share of its station's mass per metre.

    A separate part of the section (an outer contour with its holes: one float of a
    catamaran) carries its own mass, by area; the wetted pieces of one part share its mass
    by their widths at the waterline.
    """
    part_width = np.bincount(part, weights=width, minlength=len(outline.part_area))
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.where(part_width[part] > 0.0, width / part_width[part], 1.0)
        return outline.part_area[part] / outline.area[ps] * frac


def _wetted_pieces(station, ya, za, yb, zb, contour, outline, level):
    """The wetted pieces of each station: the intervals of the waterline inside the body.

    Along the waterline, a contour going down (into the water) opens an interval inside
    the body to its right, one going up closes it (outer contours run counter-clockwise,
    holes clockwise), so a running winding count finds the intervals. A separate part of a
    section under water altogether (no crossing) is one piece over its whole width.

    Returns
    -------
    station, y_left, y_right, tan_left, tan_right, part : (m,) arrays
        For each piece its station, the ends of its waterline interval (m), the slope
        ``|dz/dy|`` of the contour where it meets the water at each end, and the outer
        contour (separate part of the section, see :class:`Outline`) it belongs to.
    """
    down = (za >= 0.0) & (zb < 0.0)
    up = (za < 0.0) & (zb >= 0.0)
    cross = down | up
    with np.errstate(divide="ignore", invalid="ignore"):
        yc = ya[cross] + (0.0 - za[cross]) * (yb[cross] - ya[cross]) / (zb[cross] - za[cross])
        slope = np.abs((zb - za) / (yb - ya))[cross]
    sc, cc = station[cross], contour[cross]
    step = np.where(down[cross], 1, -1)
    order = np.lexsort((yc, sc))
    sc, yc, step, slope, cc = sc[order], yc[order], step[order], slope[order], cc[order]
    winding = np.cumsum(step)
    # the count restarts at each station (every station's crossings add up to zero)
    opens = (winding == 1) & (step == 1)
    closes = (winding == 0) & (step == -1)
    ps, part = sc[opens], cc[opens]
    yl, yr = yc[opens], yc[closes]
    tl, tr = slope[opens], slope[closes]
    crossed = np.zeros(len(outline.part_area), dtype=bool)
    crossed[cc] = True
    submerged = np.flatnonzero(~crossed & (outline.part_zmax - level < 0.0))
    if len(submerged):
        ps = np.concatenate([ps, outline.part_station[submerged]])
        yl = np.concatenate([yl, outline.part_ymin[submerged]])
        yr = np.concatenate([yr, outline.part_ymax[submerged]])
        tl = np.concatenate([tl, np.full(len(submerged), np.inf)])
        tr = np.concatenate([tr, np.full(len(submerged), np.inf)])
        part = np.concatenate([part, submerged])
        o = np.lexsort((yl, ps))
        ps, yl, yr, tl, tr, part = ps[o], yl[o], yr[o], tl[o], tr[o], part[o]
    return ps, yl, yr, tl, tr, part


def _assign(seg_station, seg_y, ps, yl, yr) -> np.ndarray:
    """Index of the piece whose waterline interval holds each point, or -1."""
    if len(ps) == 0:
        return np.full(len(seg_y), -1)
    # pieces are sorted by (station, y_left): search in a combined key
    span = max(float(np.max(np.abs(np.concatenate([yl, yr, seg_y])))), 1.0) * 4.0
    key_p = ps * span + yl
    key_s = seg_station * span + seg_y
    i = np.searchsorted(key_p, key_s, side="right") - 1
    ok = (i >= 0) & (ps[np.clip(i, 0, None)] == seg_station) & (seg_y <= yr[np.clip(i, 0, None)])
    return np.where(ok, i, -1)


def _keel_fit(piece, y1, z1, y2, z2, m):
    """Least-squares slopes through the keel, per side: integrals over the contour."""
    # split each segment at the keel's y so that each part lies on one side
    straddle = (y1 < 0.0) != (y2 < 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        zc = np.where(straddle, z1 + (0.0 - y1) * (z2 - z1) / (y2 - y1), 0.0)
    parts = [
        (piece[~straddle], y1[~straddle], z1[~straddle], y2[~straddle], z2[~straddle]),
        (piece[straddle], y1[straddle], z1[straddle], np.zeros(straddle.sum()), zc[straddle]),
        (piece[straddle], np.zeros(straddle.sum()), zc[straddle], y2[straddle], z2[straddle]),
    ]
    pc, a1, b1, a2, b2 = (np.concatenate(v) for v in zip(*parts, strict=True))
    # exact for z linear in y along a segment: int y z dy and int y^2 dy
    iyz = (a2 - a1) * (2 * a1 * b1 + a1 * b2 + a2 * b1 + 2 * a2 * b2) / 6.0
    iyy = (a2**3 - a1**3) / 3.0
    port = (a1 + a2) > 0.0
    num_p = np.bincount(pc[port], weights=iyz[port], minlength=m)
    den_p = np.bincount(pc[port], weights=iyy[port], minlength=m)
    num_s = np.bincount(pc[~port], weights=iyz[~port], minlength=m)
    den_s = np.bincount(pc[~port], weights=iyy[~port], minlength=m)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.abs(num_p / den_p), np.abs(num_s / den_s)
