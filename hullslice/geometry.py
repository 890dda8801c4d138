"""Placing the hull in the earth frame at a pitch, and what depends only on the pitch.

The body turns about its centre of gravity ``g``. A body point ``r = v - g`` (``x``, ``z``
components; ``y`` is unchanged) is at

    X = x_g + r_x cos(theta) - r_z sin(theta)
    Z = Z_g + r_x sin(theta) + r_z cos(theta)

with ``theta`` the pitch, positive nose up. ``Z_g`` follows from the draft: the lowest point
of the body is ``draft`` below the water ``Z = 0``. Earth ``X`` is measured so that a level
body has ``X = x``: stations are reported in a frame moving horizontally with the body.

For one pitch, three things do not depend on the draft and are computed once
(:class:`Frame`): the lowest point, the keel line (the lower edge of the body's side view,
``Z_k(X)``, exact as a polyline) and the manifold3d object that cuts the body along earth
planes ``X = const``.

A large hull is turned for manifold3d through a region of it (:mod:`hullslice.regions`).
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, cast

import numpy as np

from . import planecut_loops
from .caching import LRU, Cache, Entry, Once
from .constants import TOL
from .errors import InputError
from .kernel.envelope import (
    lower_envelope,
    lowest_segments,
    merged,
    refined,
    side_outline,
    side_points,
)
from .kernel.keel import END_FACE_SLOPE, STEEP_SLOPE, KeelLine, window_points
from .planecut import plane_index
from .reduce import row_max, row_min
from .regions import REGION_CACHE, region

__all__ = ["CUTTERS", "Frame", "KeelLine", "check_cutter", "frame"]

#: How the stations of a pitch are cut, by name (the ``cutter`` option).
CUTTERS: dict[str, str] = {
    "exact": "an exact kernel on the body-frame mesh, without turning it "
    "(hullslice.planecut); free-pitch runs' default",
    "manifold3d": "manifold3d on the mesh (or a region of it) turned to the pitch; the "
    "default elsewhere",
}


def check_cutter(cutter: str) -> str:
    """``cutter`` if it names one of :data:`CUTTERS`."""
    if cutter not in CUTTERS:
        raise InputError(f"cutter {cutter!r} is unknown; choose one of {', '.join(CUTTERS)}")
    return cutter


@dataclass(frozen=True, eq=False)
class Frame:
    """What depends on the pitch only: placement, keel line and the cutter.

    Attributes
    ----------
    pitch : float
        Pitch in rad, positive nose up.
    cg : (3,) float
        Centre of gravity in the body frame, m (the centre of rotation).
    lowest, highest : float
        Heights of the body's lowest and highest points above the centre of gravity in the
        pitched frame, m.
    keel : KeelLine
        The keel line, relative to the centre of gravity (made when first read where the
        frame was made with its break points only).
    """

    pitch: float
    cg: np.ndarray
    lowest: float
    highest: float
    _keel: KeelLine | None = field(repr=False)
    _hull: Any = field(repr=False)
    _matrix: np.ndarray = field(repr=False)  # body point -> cutter (Y, Z, X), 3 x 4
    _offset: np.ndarray = field(repr=False)  # (Y, Z, X) of the cutter's origin, rel. cg
    _scale: float = 1.0  # the cutter's coordinates are metres times this
    #: The keel line's break points ``(x, z)`` where the line is made when first read.
    _points: tuple[np.ndarray, np.ndarray] | None = field(default=None, repr=False)
    _slicers: LRU[tuple[float, float] | None, Any] = field(
        default_factory=lambda: LRU(REGION_CACHE), repr=False
    )
    #: What the layers above keep for this pitch (see :mod:`hullslice.caching`).
    cache: Cache = field(default_factory=Cache, repr=False)

    @property
    def keel(self) -> KeelLine:
        """The keel line, relative to the centre of gravity."""
        line = self._keel
        if line is None:  # made of its break points when first read (frozen: set once)
            assert self._points is not None
            line = KeelLine(*self._points)
            object.__setattr__(self, "_keel", line)
        return line

    def _line_ends(self) -> tuple[float, float]:
        """The keel line's first and last break points' ``x`` (m, relative)."""
        x = self._keel.x if self._keel is not None else cast(tuple, self._points)[0]
        return float(x[0]), float(x[-1])

    def keel_for(self, level: float, n: int, reach: float) -> KeelLine:
        """The keel line an evaluation with the water at ``level`` (m, relative) and ``n``
        fixed slices reads at a pitch met for the first time: where the frame holds its
        line's break points only (numpy's lower side of the body's side view), the line of
        those :func:`~hullslice.kernel.keel.window_points` keeps around the water (within
        ``reach``, m), which the compiled stage reads at such a pitch. What the evaluation
        reads of it is the whole line's but for rounding (the running sums of its runs
        start at its first point within the window). Else the whole line."""
        if self._keel is not None or self._points is None:
            return self.keel
        window = window_points(*self._points, level, n, reach)
        return self.keel if window is None else KeelLine(*window)

    def fixed_stations(self, n: int) -> tuple[float, np.ndarray]:
        """Thickness and mid-stations (relative to the cg) of ``n`` equal slices over the
        body's length at this pitch."""
        xa, xb = self._line_ends()
        d = (xb - xa) / n
        return d, xa + (np.arange(n) + 0.5) * d

    def z_cg(self, draft: float) -> float:
        """Earth height of the centre of gravity for a draft (m)."""
        return -self.lowest - draft

    def cut(self, x_rel: np.ndarray, cutter: str = "manifold3d") -> list[tuple[np.ndarray, ...]]:
        """Cross-sections at relative stations ``x_rel = X - x_g`` (m), as manifold3d gives
        them: one tuple of ``(k, 2)`` contours per station (outer ones counter-clockwise),
        in the cutter's coordinates: divide by :attr:`scale` and add :attr:`origin` (and
        ``Z_g``) for earth coordinates in m.

        ``cutter="exact"`` cuts by :mod:`hullslice.planecut`'s kernel on the body-frame
        mesh (the same contours to manifold3d's grid, without turning the mesh; manifold3d
        cuts pitches steeper than :data:`KERNEL_MAX_PITCH`); ``"manifold3d"`` by
        manifold3d on the mesh turned to the pitch (see :data:`CUTTERS`).
        """
        x_rel = np.asarray(x_rel, dtype=np.float64)
        if len(x_rel) == 0:
            return []
        if cutter == "exact" and abs(self.pitch) < KERNEL_MAX_PITCH:
            index = plane_index(self._hull)
            return index.cut(x_rel, self.pitch, self.cg, self._matrix, MERGE * CUTTER_SIZE)
        slicer = self._slicer(*self._reach(x_rel))
        ox, k = self._offset[2], self._scale
        return [tuple(slicer.slice(float((xi - ox) * k)).to_polygons()) for xi in x_rel]

    def _reach(self, x_rel: np.ndarray) -> tuple[float, float]:
        """The body's ``x`` range (m) that the planes at ``x_rel`` cross."""
        c, s = np.cos(self.pitch), np.sin(self.pitch)
        bounds = self._hull.bounds
        rz = bounds[:, 2] - self.cg[2]
        # a plane X = x_rel holds the body points with r_x c - r_z s = x_rel
        rx = (np.array([x_rel.min(), x_rel.max()])[:, None] + rz[None, :] * s) / c
        return float(self.cg[0] + rx.min()), float(self.cg[0] + rx.max())

    def _slicer(self, lo: float, hi: float):
        """The cutter turned to this pitch, through a region of the hull holding the faces
        between body ``x = lo`` and ``hi``.

        The whole hull while it has been cut at one pitch only: a region costs more to make
        than turning the whole once, and pays off only over several pitches.
        """
        body: Any
        if len(self._hull.cache[FRAMES]) > 1:
            key, body = region(self._hull, lo, hi)
        else:
            key, body = None, self._hull.manifold
        slicer = self._slicers.get(key)
        if slicer is None:
            slicer = body.transform(self._matrix)
            self._slicers.put(key, slicer)
        return slicer

    @property
    def scale(self) -> float:
        """The cutter's coordinates are metres times this (the body brought to
        :data:`CUTTER_SIZE`)."""
        return self._scale

    @property
    def origin(self) -> tuple[float, float]:
        """``(Y, Z - Z_g)`` of the origin of :meth:`cut`'s contours, m."""
        return float(self._offset[0]), float(self._offset[1])

    def body_to_earth(self, v: np.ndarray, z_cg: float) -> np.ndarray:
        """Earth coordinates ``(X, Y, Z)`` (m) of body points ``v`` (n, 3)."""
        c, s = np.cos(self.pitch), np.sin(self.pitch)
        r = np.asarray(v, dtype=np.float64) - self.cg
        X = self.cg[0] + r[:, 0] * c - r[:, 2] * s
        Z = z_cg + r[:, 0] * s + r[:, 2] * c
        return np.stack([X, r[:, 1] + self.cg[1], Z], axis=1)


#: The size of the body in the cutter's coordinates. manifold3d rounds its sections to a
#: grid of 1e-8 of these units (Clipper2's precision), so its sections are exact to about
#: 1e-12 of the body's size: at unit size the rounding moved the force on a barely wetted
#: body by some 1e-6, and jumped as the pitch crossed grid lines.
CUTTER_SIZE = 1e4
#: Consecutive points of a kernel's contour closer than this (m, of a body of unit size;
#: along both of the cutter's axes) are one: manifold3d's grid joins them too.
MERGE = 1e-12
#: The kernel cuts pitches up to this (rad); manifold3d cuts steeper ones.
KERNEL_MAX_PITCH = 1.2
#: How many pitches' frames a hull keeps.
FRAME_CACHE = 4


#: A hull's frames by pitch (rad): they depend on its centre of gravity.
FRAMES: Entry[LRU[float, Frame]] = Entry("frames", lambda: LRU(FRAME_CACHE))
#: The silhouette edges' end points (see :func:`silhouette_edges`).
SILHOUETTE: Entry[Once[tuple[np.ndarray, np.ndarray]]] = Entry("silhouette", Once, geometry=True)
#: The silhouette edges' end vertices (see :func:`silhouette_ends`).
SILHOUETTE_ENDS: Entry[Once[np.ndarray]] = Entry("silhouette ends", Once, geometry=True)
#: The body's side outline (see :func:`side_outline_points`).
SIDE_OUTLINE: Entry[Once[tuple[np.ndarray, bool]]] = Entry("side outline", Once, geometry=True)
#: Per thread, the silhouette edges' ends in their order along the side view at the last
#: pitch (see :func:`_side_order`).
SIDE_ORDER: Entry[threading.local] = Entry("side order", threading.local, geometry=True)


def frame(hull, pitch: float) -> Frame:
    """The :class:`Frame` of a hull at a pitch (rad), kept on the hull for reuse."""
    pitch = float(pitch)
    frames = hull.cache[FRAMES]
    fr = frames.get(pitch)
    if fr is None:
        fr = _frame(hull, pitch)
        frames.put(pitch, fr)
    return fr


def _frame(hull, pitch: float) -> Frame:
    g = np.asarray(hull.cg, dtype=np.float64)
    c, s = np.cos(pitch), np.sin(pitch)
    # side view: the silhouette edges turned by the pitch, in (X, Z) relative to the cg;
    # the lowest and highest points at any pitch are on them
    # (where numpy's lower side of the side outline serves, the line's break points: the
    # line is made when first read)
    line, lowest, highest = _side_keel(
        hull, *silhouette_edges(hull), side_outline_points(hull), pitch, _side_order, lazy=True
    )
    keel, points = (None, line) if isinstance(line, tuple) else (line, None)
    # centre the cutter's coordinates on the body (its sections are rounded to a fixed
    # grid): the bounding-box centre, in the pitched frame relative to the cg
    bounds = hull.bounds
    box = (bounds[0] + bounds[1]) * 0.5 - g  # numpy's mean of the two, to the bit
    ox = box[0] * c - box[2] * s
    oz = box[0] * s + box[2] * c
    oy = box[1] + g[1]
    # rows map a body point to (Y, Z, X) relative to that centre; manifold3d cuts at Z = X.
    # Scaled to a fixed size too: manifold3d rounds its sections to a fixed grid (Clipper2,
    # 1e-8), so a tiny body would be cut into nothing and a huge one coarsely
    scale = CUTTER_SIZE / hull.size
    cut_matrix = scale * np.array(
        [
            [0.0, 1.0, 0.0, -oy],
            [s, 0.0, c, -(s * g[0] + c * g[2]) - oz],
            [c, 0.0, -s, -(c * g[0] - s * g[2]) - ox],
        ]
    )
    return Frame(
        pitch=pitch,
        cg=g,
        lowest=lowest,
        highest=highest,
        _keel=keel,
        _hull=hull,
        _matrix=cut_matrix,
        _offset=np.array([oy, oz, ox]),
        _scale=scale,
        _points=points,
    )


def _side_keel(
    hull,
    a: np.ndarray,
    b: np.ndarray,
    outline: tuple[np.ndarray, bool],
    pitch: float,
    order_of: Callable,
    lazy: bool = False,
) -> tuple[KeelLine | tuple[np.ndarray, np.ndarray], float, float]:
    """The keel line at ``pitch`` of the silhouette edges ``a`` to ``b`` (end points, m),
    and their ends' lowest and highest heights (m): by the compiled loops where they are
    in use (from the order ``order_of(hull, 2 * len(a))`` gives), else by numpy's lower
    envelope; where the lower side of the body's side ``outline``
    (:func:`side_outline_points`' pair; an empty one never serves) runs forward, that
    side's points are its break points (``lazy``: given as ``(x, z)``, the line not
    made)."""
    g = np.asarray(hull.cg, dtype=np.float64)
    c, s = np.cos(pitch), np.sin(pitch)
    merge = TOL.keel_merge * hull.size  # break points of the keel line this close are one
    made = loops_in_use("frame_keel")
    if made is None:
        side = None
        if outline[0].shape[1]:  # turned as the edges' ends are
            rx, rz = outline[0][0] - g[0], outline[0][1] - g[2]
            side = (rx * c - rz * s, rx * s + rz * c)
            if outline[1]:  # its points are all the edges' ends: the edges not turned
                found = side_points(*side, merge)
                if found is not None:
                    return (found[0] if lazy else KeelLine(*found[0])), found[1], found[2]
                side = None  # its lower side does not serve: the edges' envelope must
        ta, tb = _turn(a - g, c, s), _turn(b - g, c, s)
        za, zb = ta[:, 1], tb[:, 1]
        keel = lower_envelope(ta, tb, merge=merge, side=side)
        return keel, float(min(za.min(), zb.min())), float(max(za.max(), zb.max()))
    # the turn, the keel line's search, the merge of its close break points and its runs
    # in one compiled call (the loops are in use: the others too)
    order = order_of(hull, 2 * len(a))
    ok, side, low, high, xr, zr, runs, _ = made(
        a, b, *outline, float(g[0]), float(g[2]), float(c), float(s), order, merge,
        END_FACE_SLOPE, STEEP_SLOPE,
    )  # fmt: skip
    compiled = planecut_loops.compiled
    if ok:  # most pitches: only close break points to merge
        return KeelLine(xr, zr, compiled("runs"), runs), float(low), float(high)
    xa, za, xb, zb, seg, xs, mid, z, zm, _, _ = side
    if len(xs) and not len(seg):  # the side outline's lower side: a long group to merge
        return KeelLine(*merged(xs, z, merge), compiled("runs")), float(low), float(high)
    walk, none = compiled("walk"), np.empty(0)
    if walk is not None and np.isfinite(xs[-1:]).all():  # the refinement's by the loops
        heights = lambda q: walk(q, none, xa, za, xb, zb, seg)[0]  # noqa: E731
    else:
        turned = lambda: (_turn(a - g, c, s), _turn(b - g, c, s))  # noqa: E731
        heights = lowest_segments(make=turned)
    return refined(xs, mid, z, zm, merge, heights, compiled("runs")), float(low), float(high)


def _side_order(hull, n: int, piece: int | None = None) -> np.ndarray:
    """This thread's order of the silhouette edges' ends (of the whole body, or of one
    ``piece``'s) along the side view at the last pitch it turned them to (``n`` integers,
    updated by the loops: a new pitch's ends are then nearly in order, and sorted in a few
    moves each); kept on the hull."""
    local = hull.cache[SIDE_ORDER]
    if piece is None:
        order = getattr(local, "order", None)
        if order is None or len(order) != n:
            order = local.order = np.arange(n, dtype=np.int64)
        return order
    pieces = local.__dict__.setdefault("pieces", {})
    order = pieces.get(piece)
    if order is None or len(order) != n:
        order = pieces[piece] = np.arange(n, dtype=np.int64)
    return order


def loops_in_use(name: str) -> Callable | None:
    """The compiled loops ``name`` of :data:`hullslice.planecut_loops.LOOPS` (``"frame_keel"``,
    ``"walk"`` and ``"runs"`` for the keel line, ``"outline"``, ``"wetted"``) where
    :func:`keel_loops` holds, else None (numpy's path): a new pitch's keel line, outline
    and wetted properties by the compiler once its cut is."""
    return planecut_loops.compiled(name) if keel_loops() else None


def keel_loops() -> bool:
    """Whether the keel line at a new pitch is found by the compiled loops: once the exact
    cut's are in use in this process (numba installed, not switched off, and imported
    for the cut: a run at a held pitch does not import it for its few frames), see
    :mod:`hullslice.planecut_loops`. The same keel line as numpy's."""
    return planecut_loops.available() and planecut_loops.in_use()


def _turn(r: np.ndarray, c: float, s: float) -> np.ndarray:
    """(X, Z) of body offsets ``r`` (n, 3) turned nose up by the pitch (cos, sin)."""
    return np.stack([r[:, 0] * c - r[:, 2] * s, r[:, 0] * s + r[:, 2] * c], axis=1)


def silhouette_edges(hull) -> tuple[np.ndarray, np.ndarray]:
    """The edges of the body's outline seen from the side, as end points (e, 3) in m.

    An edge is on the outline seen along ``y`` when one of its two faces faces port and the
    other starboard (or either is edge-on). Turning the body about ``y`` (its pitch) does not
    change which faces face which way, so these edges serve every pitch: the keel line at
    any pitch is the lower envelope of their side views, and the body's lowest and highest
    points are among their ends. An edge between two edge-on faces is left out: both lie
    in one plane through ``y`` (a flat end cap's fan, a flat side), or the edge runs along
    ``y`` and is a point in the side view; either way the edges around that faces' region
    cover its side view at every pitch (a flat cap's fan is a vertical line in the side
    view at pitch 0 only, and at any other pitch spreads over the cap's height, each pair
    of its edges an overlap). A vertex that only such edges reach stays, as an edge from
    the vertex to itself: the keel line keeps its break points, and so its refinement
    between them. Kept on the hull.
    """
    return hull.cache[SILHOUETTE].get(lambda: _silhouette_edges(hull))


def _silhouette_edges(hull) -> tuple[np.ndarray, np.ndarray]:
    ends = silhouette_ends(hull)
    return hull.vertices[ends[:, 0]], hull.vertices[ends[:, 1]]


def silhouette_ends(hull) -> np.ndarray:
    """(e, 2) int: the vertices at the ends of :func:`silhouette_edges`. Kept on the hull."""
    return hull.cache[SILHOUETTE_ENDS].get(lambda: _silhouette_ends(hull))


def side_outline_points(hull) -> tuple[np.ndarray, bool]:
    """``(points, whole)``: the body's side view as a polygon, (2, m), the ``x`` and ``z``
    (m, body frame) of :func:`~hullslice.kernel.envelope.side_outline` of its silhouette
    edges, counter-clockwise, (2, 0) where that finds none (the keel line is then the
    silhouette edges' lower envelope at every pitch); and whether its points are all the
    silhouette edges' ends (seen from the side: none inside the polygon). Kept on the
    hull."""
    return hull.cache[SIDE_OUTLINE].get(lambda: _side_outline_points(hull))


def _side_outline_points(hull) -> tuple[np.ndarray, bool]:
    v = np.asarray(hull.vertices, dtype=np.float64)
    ends = silhouette_ends(hull)
    ring = side_outline(v[:, [0, 2]], ends)
    if ring is None:
        return np.empty((2, 0)), False
    seen = np.unique(v[np.unique(ends.ravel())][:, [0, 2]], axis=0)
    return np.ascontiguousarray(v[ring][:, [0, 2]].T), len(seen) == len(ring)


def keel_line_of(hull, pitch: float, edges: np.ndarray, piece: int) -> KeelLine:
    """The keel line at ``pitch`` (relative to the centre of gravity, as
    :attr:`Frame.keel`) of the silhouette edges ``edges`` only (indices into
    :func:`silhouette_edges`): that of a body's ``piece``, made as the body's is."""
    a, b = silhouette_edges(hull)
    order_of = lambda h, n: _side_order(h, n, piece)  # noqa: E731
    line = _side_keel(hull, a[edges], b[edges], (np.empty((2, 0)), False), pitch, order_of)[0]
    return cast(KeelLine, line)  # not lazy: a line


def _silhouette_ends(hull) -> np.ndarray:
    v, f = hull.vertices, hull.faces
    e1, e2 = v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]
    ny = e1[:, 2] * e2[:, 0] - e1[:, 0] * e2[:, 2]  # the normals' y components
    # both ends of an outline edge touch a face facing port (or edge-on) and one facing
    # starboard (or edge-on): only the edges between such vertices are matched
    port, stbd = np.zeros(len(v), dtype=bool), np.zeros(len(v), dtype=bool)
    port[f[ny >= 0.0].ravel()] = True
    stbd[f[ny <= 0.0].ravel()] = True
    both = port & stbd
    directed = f[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    use = np.flatnonzero(both[directed[:, 0]] & both[directed[:, 1]])
    directed = directed[use]
    lo, hi = row_min(directed), row_max(directed)
    order = np.argsort(lo.astype(np.int64) * len(v) + hi)
    face = (use // 3)[order]
    # a closed manifold uses each edge twice: the two uses are neighbours once sorted
    n0, n1 = ny[face[0::2]], ny[face[1::2]]
    outline = (np.sign(n0) * np.sign(n1)) <= 0
    side = outline & ((n0 != 0.0) | (n1 != 0.0))
    ends = directed[order[0::2][side]]
    # a vertex that only edges between edge-on faces reach (a fan's centre inside a flat
    # cap or bottom) stays a break point of the keel line: a point of its own
    dropped = directed[order[0::2][outline & ~side]].ravel()
    alone = np.setdiff1d(dropped, ends.ravel())
    return np.concatenate([ends, np.stack([alone, alone], axis=1)])
