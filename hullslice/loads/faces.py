"""The sections' pressures mapped onto the faces of the hull's mesh.

At an instant every face of the mesh gets a pressure (Pa, gauge) from the 2D solutions of
the slices around it:

* **Where.** The face is placed in the earth frame by the instant's pose and cut at the
  stations it crosses and at the ends of the slices. On each piece the pressure is linear
  in earth ``X`` between the two stations around it (at the first and last slices, the
  slice's own pressure out to its outer edge), integrated exactly; a face outside the
  slices is dry. Where the slices are not of equal thickness (a fixed slicing's partial
  slices at the ends) each station's pressure is scaled by its slice's thickness over the
  integral of its interpolation weight, so that the loads still add up.
* **Which faces.** A section's pressure acts on the bottom it was computed for: faces
  whose outward normal points down, no higher above the keel than the section's loaded
  contour (with a margin of half the contour's height and the face's own height), so that
  a deck, the upper half of a round section or a wing above the water stays dry.
* **How much.** A section's pressure is given at the solver's points along each side,
  each standing for a width ``dy`` (its weight). It is taken as constant over that width,
  so that the pressure's integrals over the lateral coordinate ``s = y - y_keel`` (starboard
  negative) are exact: ``P0(s) = int p ds`` and ``P1(s) = int p s ds``. The face's vertical
  load is the integral of that pressure over its projection on the water plane: the
  projection's width along ``X`` is piecewise linear in ``s`` (a triangle), so the
  integral is exact from ``P0`` and ``P1`` at the face's three corners. The face's
  pressure is that load over its projected area: the **mean** of the section pressure
  over the face, so that a face's load (pressure times area, along its inward normal)
  has exactly the section's vertical load on the face's footprint. The faces' vertical
  loads add up to the slices' forces to rounding on any mesh whose bottom the faces
  tile; what remains is the faces' share of the wetted bottom (a face that does not face
  down, or lies above the loaded contour, takes none).
* **Hydrostatics.** Where the slices' forces hold the calm water's hydrostatic pressure
  (a solver's gravity option), every face below the calm water also gets ``rho g`` times
  its mean depth (exact for a plane face cut by the water line): their sum is the
  buoyancy of the submerged volume, as the slices' is of their submerged areas.

What the mapping leaves out: the pressure is the 2D solution's; the 3D flow at the bow and
the transom, and the pressure a 2D model does not give (the spray root's jet beyond the
loaded width, the sides past a separation), are not in it. A coarse face spreads a
pressure peak over its own area (its load is still right).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..caching import Entry, Once
from ..errors import InputError
from ..forces import ForceResult
from .record import SectionRecord
from .triangles import clip, mean_positive, split

__all__ = ["FaceGeometry", "FacePeak", "FacePressures", "face_geometry", "face_pressures"]

#: A face whose outward normal's vertical part is below ``-DOWN`` faces down.
DOWN = 1e-6
#: A face whose projection on the water plane is below this share of its area takes no
#: section pressure (a wall: the section's pressure is a vertical load per width).
STEEP = 1e-3
#: The margin above a section's loaded contour within which a face takes its pressure, as a
#: share of the contour's height (plus the face's own height).
HEIGHT_MARGIN = 0.5


@dataclass(frozen=True, eq=False)
class FaceGeometry:
    """The faces of a hull's mesh in its own frame, for the load mapping.

    Attributes
    ----------
    corners : (m, 3, 3) float
        Each face's corners, m.
    normal : (m, 3) float
        Unit outward normals.
    area : (m,) float
        Areas, m^2.
    centroid : (m, 3) float
        Centroids, m.
    cg : (3,) float
        The centre of gravity the body turns about, m.
    """

    corners: np.ndarray
    normal: np.ndarray
    area: np.ndarray
    centroid: np.ndarray
    cg: np.ndarray

    def __len__(self) -> int:
        return len(self.area)

    def earth(self, pitch: float, z_cg: float) -> tuple[np.ndarray, np.ndarray]:
        """The corners (m, 3, 3) and unit normals (m, 3) in the earth frame at a pitch
        (rad) and height of the centre of gravity (m); see :mod:`hullslice.geometry`."""
        c, s = np.cos(pitch), np.sin(pitch)
        r = self.corners - self.cg
        corners = np.empty_like(r)
        corners[..., 0] = self.cg[0] + r[..., 0] * c - r[..., 2] * s
        corners[..., 1] = r[..., 1] + self.cg[1]
        corners[..., 2] = z_cg + r[..., 0] * s + r[..., 2] * c
        n = self.normal
        normal = np.stack([n[:, 0] * c - n[:, 2] * s, n[:, 1], n[:, 0] * s + n[:, 2] * c], axis=1)
        return corners, normal


def _geometry(hull) -> FaceGeometry:
    corners = np.asarray(hull.vertices, dtype=np.float64)[np.asarray(hull.faces)]
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    double = np.linalg.norm(cross, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        normal = np.where(double[:, None] > 0, cross / double[:, None], 0.0)
    return FaceGeometry(
        corners=corners,
        normal=normal,
        area=0.5 * double,
        centroid=corners.mean(axis=1),
        cg=np.array(hull.cg, dtype=np.float64),
    )


#: A hull's face geometry about its centre of gravity, kept per hull.
GEOMETRY: Entry[Once[FaceGeometry]] = Entry("face geometry", Once)


def face_geometry(hull) -> FaceGeometry:
    """The :class:`FaceGeometry` of a hull (kept on it)."""
    return hull.cache[GEOMETRY].get(lambda: _geometry(hull))


@dataclass(frozen=True, eq=False)
class FacePressures:
    """The pressure on every face of the mesh at one instant.

    Attributes
    ----------
    t : float
        Time, s.
    pressure : (m,) float
        Gauge pressure on each face, Pa (zero on dry faces): the section pressure's mean
        over the face, and the hydrostatic pressure where the slices hold it.
    force : (m, 3) float
        Each face's load, ``pressure * area`` along its inward normal, in the earth frame
        ``(X, Y, Z)``, N.
    centroid : (m, 3) float
        Each face's centroid in the earth frame, m.
    x_cg, z_cg : float
        Earth ``X`` and ``Z`` of the centre of gravity, m.
    """

    t: float
    pressure: np.ndarray
    force: np.ndarray
    centroid: np.ndarray
    x_cg: float
    z_cg: float

    @property
    def wetted(self) -> np.ndarray:
        """(m,) bool: faces with a pressure."""
        return self.pressure != 0.0

    @property
    def total(self) -> float:
        """Vertical load of all faces, N, positive up."""
        return float(self.force[:, 2].sum())

    @property
    def total_x(self) -> float:
        """Horizontal load of all faces along the body, N, positive forward."""
        return float(self.force[:, 0].sum())

    @property
    def moment(self) -> float:
        """Pitch moment of the faces' loads about the centre of gravity, N m, nose up."""
        arm_x = self.centroid[:, 0] - self.x_cg
        arm_z = self.centroid[:, 2] - self.z_cg
        return float((arm_x * self.force[:, 2] - arm_z * self.force[:, 0]).sum())


class FacePeak:
    """Each face's largest pressure over the instants added (:meth:`add`) and its time.

    Attributes
    ----------
    pressure : (m,) float
        The largest pressure so far, Pa (0 on a face that stays dry).
    t : (m,) float
        Its time, s (NaN on a face that stays dry).
    """

    def __init__(self, faces: int) -> None:
        self.pressure = np.zeros(faces)
        self.t = np.full(faces, np.nan)

    def add(self, fp: FacePressures) -> None:
        """Take in one instant's face pressures."""
        higher = fp.pressure > self.pressure
        self.pressure = np.where(higher, fp.pressure, self.pressure)
        self.t = np.where(higher, fp.t, self.t)


def face_pressures(hull, state: SectionRecord | ForceResult, t: float = 0.0) -> FacePressures:
    """The pressure on every face of ``hull``'s mesh at one instant.

    Parameters
    ----------
    hull : Hull
        The body the instant was computed for.
    state : SectionRecord or ForceResult
        The instant: a record kept by a run (:attr:`History.sections
        <hullslice.History.sections>`) or a force result.
    t : float
        The time to label a force result with, s.

    Raises
    ------
    InputError
        The instant's solver gives no pressures along the sections.
    """
    rec = state if isinstance(state, SectionRecord) else SectionRecord.of(t, state)
    if not rec.has_pressures and np.any(rec.force):  # a dry instant asks no solver
        raise InputError(
            "the run's solver gives no pressures along the sections' contours, so none can "
            "be mapped onto the faces; use solver='mlm' (--solver mlm)"
        )
    geom = face_geometry(hull)
    corners, normal = geom.earth(rec.pitch, rec.z_cg)
    centroid = corners.mean(axis=1)
    area = geom.area
    pressure = np.zeros(len(geom))
    if rec.has_pressures:
        load = _dynamic_load(rec, corners, normal)  # vertical, N
        footprint = area * -normal[:, 2]
        steep = footprint <= STEEP * area
        pressure = np.where(steep, 0.0, load / np.where(steep, 1.0, footprint))
    if rec.hydrostatic > 0.0:
        inside = _in_slices(rec, centroid[:, 0])
        pressure = pressure + np.where(inside, rec.hydrostatic * mean_positive(-corners[..., 2]), 0)
    force = -(pressure * area)[:, None] * normal
    return FacePressures(rec.t, pressure, force, centroid, rec.x_cg, rec.z_cg)


# -- the mapping --------------------------------------------------------------------------------


def _in_slices(rec: SectionRecord, x: np.ndarray) -> np.ndarray:
    """Whether earth ``X`` lies within the instant's slices."""
    lo, hi = rec.x - 0.5 * rec.dx, rec.x + 0.5 * rec.dx
    order = np.argsort(lo)
    lo, hi = lo[order], np.maximum.accumulate(hi[order])
    i = np.searchsorted(lo, x, side="right") - 1
    return (i >= 0) & (x <= hi[np.clip(i, 0, None)])


def _stations(rec: SectionRecord):
    """Each station's position and first entry, sorted along ``X``."""
    stations, first = np.unique(rec.station, return_index=True)
    x = rec.x[first]
    order = np.argsort(x, kind="stable")
    return stations[order], x[order], first[order]


def _tables(rec: SectionRecord):
    """Per entry: the cells' edges along ``s`` (n, 2k+1), their pressures (n, 2k), the
    moments ``P0, P1, P2`` (``int p s^i ds`` from the starboard end) at the edges, and the
    contour's height above the keel in each cell."""
    assert rec.weight is not None and rec.pressure is not None and rec.z is not None
    w, p, z = rec.weight, rec.pressure, rec.z
    port, stbd = np.cumsum(w[:, 0], axis=1), np.cumsum(w[:, 1], axis=1)
    n = len(w)
    edges = np.concatenate([-stbd[:, ::-1], np.zeros((n, 1)), port], axis=1)
    cells = np.concatenate([p[:, 1, ::-1], p[:, 0]], axis=1)
    height = np.concatenate([z[:, 1, ::-1], z[:, 0]], axis=1)
    zero = np.zeros((n, 1))
    moments = [
        np.concatenate(
            [zero, np.cumsum(cells * np.diff(edges ** (i + 1), axis=1) / (i + 1), axis=1)], axis=1
        )
        for i in range(3)
    ]
    return edges, cells, moments, height


def _moments(tables, entry: np.ndarray, s: np.ndarray) -> list[np.ndarray]:
    """``P0, P1, P2`` of each face's entry at its lateral coordinates ``s`` (m, 3)."""
    edges, cells, moments, _ = tables
    e = edges[entry]  # (m, 2k+1)
    sc = np.clip(s, e[:, :1], e[:, -1:])
    i = np.empty(s.shape, dtype=np.int64)
    for j in range(s.shape[1]):  # the cell of each corner, row by row
        i[:, j] = _row_search(e, sc[:, j])
    i = np.clip(i, 0, cells.shape[1] - 1)
    rows = entry[:, None]
    lo = np.take_along_axis(e, i, axis=1)
    pc = cells[rows, i]
    return [
        m[rows, i] + pc * (sc ** (k + 1) - lo ** (k + 1)) / (k + 1) for k, m in enumerate(moments)
    ]


def _row_search(edges: np.ndarray, s: np.ndarray) -> np.ndarray:
    """For each row of ``edges`` (sorted), the cell holding ``s`` (index of its left
    edge), by bisection over the rows at once."""
    lo = np.zeros(len(s), dtype=np.int64)
    hi = np.full(len(s), edges.shape[1] - 1, dtype=np.int64)
    rows = np.arange(len(s))
    while np.any(hi - lo > 1):
        mid = (lo + hi) // 2
        right = edges[rows, mid] <= s
        lo = np.where(right, mid, lo)
        hi = np.where(right, hi, mid)
    return lo


def _footprint_integrals(tables, entry, y_keel, xs, ys) -> tuple[np.ndarray, np.ndarray]:
    """For each face, the integrals of its entry's pressure ``p`` and of ``p X`` over the
    face's projection on the water plane (corners ``xs``, ``ys``: (m, 3), earth ``X``
    relative to the face's station and ``Y``): N and N m.

    The projection's chord along ``X`` at a lateral position has a length ``D`` and a
    middle ``M`` linear in ``s`` on each of the triangle's two halves (below and above its
    middle corner), so both integrals are exact from ``P0, P1, P2``."""
    order = np.argsort(ys, axis=1)
    y = np.take_along_axis(ys, order, axis=1)
    x = np.take_along_axis(xs, order, axis=1)
    s = y - y_keel[entry][:, None]
    span = y[:, 2] - y[:, 0]
    with np.errstate(invalid="ignore", divide="ignore"):
        x_long = x[:, 0] + (x[:, 2] - x[:, 0]) * np.where(span > 0, (y[:, 1] - y[:, 0]) / span, 0)
    d_mid = np.abs(x_long - x[:, 1])  # the chord's length at the middle corner
    m_mid = 0.5 * (x_long + x[:, 1])
    q = _moments(tables, entry, s)
    tiny = 1e-9 * np.maximum(span, 1e-300)
    load = np.zeros(len(s))
    first = np.zeros(len(s))
    halves = ((0, 1, 0.0, d_mid, x[:, 0], m_mid), (1, 2, d_mid, 0.0, m_mid, x[:, 2]))
    for a, b, da, db, ma, mb in halves:
        u0, u1 = s[:, a], s[:, b]
        length = u1 - u0
        ok = length > tiny
        safe = np.where(ok, length, 1.0)
        d1 = (db - da) / safe
        d0 = da - d1 * u0
        m1 = (mb - ma) / safe
        m0 = ma - m1 * u0
        q0, q1, q2 = (qk[:, b] - qk[:, a] for qk in q)
        load += np.where(ok, d0 * q0 + d1 * q1, 0.0)
        first += np.where(ok, d0 * m0 * q0 + (d0 * m1 + d1 * m0) * q1 + d1 * m1 * q2, 0.0)
    return load, first


def _dynamic_load(rec: SectionRecord, corners: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """(m,) each face's vertical load from the sections' pressures, N."""
    m = len(corners)
    load = np.zeros(m)
    if m == 0 or len(rec.x) == 0:
        return load
    start = float((rec.x - 0.5 * rec.dx).min())
    stop = float((rec.x + 0.5 * rec.dx).max())
    X = corners[..., 0]
    down = (normal[:, 2] < -DOWN) & (X.max(axis=1) > start) & (X.min(axis=1) < stop)
    if not down.any():
        return load
    idx = np.nonzero(down)[0]
    sub = corners[idx]
    yc, zc = sub[..., 1].mean(axis=1), sub[..., 2].mean(axis=1)
    dz = np.ptp(sub[..., 2], axis=1)
    # the faces' projections, cut to the slices' extent along X
    xs_, ys_, parent = sub[..., 0], sub[..., 1], np.arange(len(idx))
    xs_, ys_, parent = clip(xs_, ys_, parent, stop, below=True)
    xs_, ys_, parent = clip(xs_, ys_, parent, start, below=False)
    stations, xs, first = _stations(rec)
    xs_, ys_, parent = split(xs_, ys_, parent, xs)  # pieces between stations: exact in X
    xc = xs_.mean(axis=1)
    j = np.clip(np.searchsorted(xs, xc, side="right") - 1, 0, len(xs) - 1)
    j1 = np.minimum(j + 1, len(xs) - 1)
    gap = xs[j1] - xs[j]
    tables = _tables(rec)
    # the weight of station j is 1 - (X - x_j) / gap, of station j + 1 (X - x_j) / gap
    # (linear in X over the piece, integrated exactly); past the ends, the end's own
    end = (gap <= 0) | (xc < xs[j]) | (xc > xs[j1])
    slope = np.where(end, 0.0, 1.0 / np.where(gap > 0, gap, 1.0))
    x_rel = xs_ - xs[j][:, None]
    scale = _scales(rec, xs, first, start, stop)
    total = np.zeros(len(parent))
    for st, level, sign in ((j, 1.0, -1.0), (j1, 0.0, 1.0)):
        entry = _entry_of(rec, stations[st], first[st], yc[parent])
        part, moment = _footprint_integrals(tables, entry, rec.y_keel, x_rel, ys_)
        on = _on_contour(tables, entry, rec, yc[parent], zc[parent], dz[parent])
        total += np.where(on, scale[st] * (level * part + sign * slope * moment), 0.0)
    load[idx] = np.bincount(parent, weights=total, minlength=len(idx))
    return load


def _scales(rec: SectionRecord, xs: np.ndarray, first: np.ndarray, start: float, stop: float):
    """Per station, its slice's thickness over the integral of its interpolation weight
    (1 for equal slices), so that the faces' loads add up to the slices' forces when the
    slices are not equal (a fixed slicing's partial slices at the ends)."""
    if len(xs) == 1:
        return np.array([rec.dx[first[0]] / (stop - start)]) if stop > start else np.ones(1)
    half = 0.5 * np.diff(xs)
    weight = np.concatenate([[0.0], half]) + np.concatenate([half, [0.0]])
    weight[0] += xs[0] - start
    weight[-1] += stop - xs[-1]
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(weight > 0, rec.dx[first] / weight, 1.0)


def _entry_of(rec: SectionRecord, station: np.ndarray, first: np.ndarray, y: np.ndarray):
    """The entry of each face's station that holds it laterally (a station with several
    wetted pieces, a catamaran's floats: the piece nearest across)."""
    counts = np.bincount(rec.station)
    if counts.max() <= 1:
        return first.copy()
    assert rec.weight is not None
    reach = rec.weight.sum(axis=2)  # (n, 2): port and starboard loaded widths
    lo, hi = rec.y_keel - reach[:, 1], rec.y_keel + reach[:, 0]
    order = np.argsort(rec.station, kind="stable")
    start = np.searchsorted(rec.station[order], station)
    best = first.copy()
    gap_best = np.full(len(y), np.inf)
    for k in range(int(counts.max())):  # the k-th piece of each face's station
        has = counts[station] > k
        e = order[np.minimum(start + k, len(order) - 1)]
        gap = np.maximum(lo[e] - y, 0.0) + np.maximum(y - hi[e], 0.0)
        gap = np.where(has, gap, np.inf)
        # inside two pieces' reach (it cannot be, they are apart): the nearer keel
        tie = np.where(has, np.abs(y - rec.y_keel[e]), np.inf)
        better = (gap < gap_best) | ((gap == gap_best) & (tie < np.abs(y - rec.y_keel[best])))
        best = np.where(better & has, e, best)
        gap_best = np.where(better & has, gap, gap_best)
    return best


def _on_contour(tables, entry, rec, y, z, dz) -> np.ndarray:
    """Whether each face is on its entry's loaded bottom: no higher above the keel than
    the contour there, with :data:`HEIGHT_MARGIN`."""
    edges, cells, _, height = tables
    e = edges[entry]
    s = np.clip(y - rec.y_keel[entry], e[:, 0], e[:, -1])
    i = np.clip(_row_search(e, s), 0, cells.shape[1] - 1)
    contour = height[entry, i]
    top = height[entry].max(axis=1)
    return z - rec.keel_z[entry] <= contour + HEIGHT_MARGIN * top + dz
