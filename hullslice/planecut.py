"""The exact cut of a body along earth planes at any pitch, without turning the mesh.

manifold3d cuts only planes of constant height in its own frame, so a pitch of its own
costs turning the whole body (or a region of it) first. This kernel cuts the body-frame
mesh directly: in body coordinates relative to the centre of gravity ``g``, the earth plane
``X - x_g = x_rel`` at pitch ``theta`` is

    r_x cos(theta) - r_z sin(theta) = x_rel,   r = v - g.

A :class:`PlaneIndex` is built once per hull: the faces binned by body height and, in each
bin, sorted along the body's ``x``, and each face's three undirected edges. At any pitch a
station's candidate faces are then a few contiguous ranges (one per bin: the plane's reach
along ``x`` over the bin's heights, widened by the bin's longest face). On the candidates:

* the exact sign test of each vertex's distance ``d`` to the plane (a vertex on the plane
  counts as ahead, ``d >= 0``, the same for every face that holds it, so that a face is
  crossed on exactly two edges or none);
* each crossing point computed once per mesh edge, from the edge's ends in their canonical
  order (lower vertex number first) and from the end nearer the plane, so that the two
  faces of an edge meet at the same point and a vertex on the plane is kept exactly;
* each crossed face's segment oriented by its winding (from the edge it leaves the plane's
  far side on to the one it enters it by), so that a section's outer contours run
  counter-clockwise seen along the earth ``X``;
* the segments chained into closed contours, repeated points (vertices on the plane)
  dropped and contours left with no area discarded.

Each thread keeps the edges its last stations' planes crossed, contour by contour, and a
station takes them again at a new pitch where no vertex can have changed side of its
plane (:mod:`hullslice.contour_loops`). The loops are numpy's
(:mod:`hullslice.planecut_numpy`) or, with numba, compiled (:mod:`hullslice.planecut_loops`).

The contours come out as :meth:`hullslice.geometry.Frame.cut` gives manifold3d's: ``(k,
2)`` arrays of the cutter's ``(Y, Z)`` (scaled and moved, see
:attr:`~hullslice.geometry.Frame.scale`).
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from . import planecut_loops, planecut_numpy
from .caching import Entry, Once
from .contour_loops import empty_memo
from .kernel.outline import ByStation
from .reduce import row_max, row_min

__all__ = ["PLANE_INDEX", "PlaneIndex", "plane_index"]

#: Faces per height bin of the index (at least one bin, at most :data:`MAX_BINS`).
FACES_PER_BIN = 2000
#: Most height bins of the index.
MAX_BINS = 48


@dataclass(frozen=True, eq=False)
class PlaneIndex:
    """The faces of a closed mesh indexed for cutting planes of any pitch.

    Attributes
    ----------
    vertices : (n, 3) float
        Vertex coordinates, m, body frame.
    corners : (m, 9) float
        Each face's corners' ``x``, ``z`` and ``y`` (``x0 x1 x2 z0 z1 z2 y0 y1 y2``), m, in
        index order: one record per face, so that a station's candidate faces (a few
        short runs of the index per height bin) are read as a few runs of memory, the
        sign test's ``x`` and ``z`` first (the loops read a crossed edge's ends here, next
        to the face, not from the vertices).
    ends : (m, 6) int32 (int64 for a mesh of 2**31 vertices or edges)
        Each face's vertices, then its edges (corner ``k`` to ``k + 1``) as undirected
        edge numbers, in index order (bin by bin, each bin's by lowest ``x``).
    xmin : (m,) float
        Each face's lowest ``x``, m (sorted within each bin).
    bin_start : (b + 1,) int
        Each bin's first face (and the end).
    bin_zlo, bin_zhi : (b,) float
        The lowest and highest ``z`` of each bin's faces, m.
    bin_reach : (b,) float
        The longest extent along ``x`` of each bin's faces, m.
    margin : float
        Widening of the candidate ranges, m (rounding's room; the sign test decides).
    n_edges : int
        How many undirected edges the mesh has.
    key : (m,) float
        The faces' search keys, ascending: ``bin * key_span + xmin - key_x0``.
    key_span, key_x0 : float
        The keys' span per bin (twice the body's length and more) and their ``x`` origin, m.
    box : (2, 3) float
        The vertices' lowest and highest coordinates, m.
    """

    vertices: np.ndarray
    corners: np.ndarray
    ends: np.ndarray
    xmin: np.ndarray
    bin_start: np.ndarray
    bin_zlo: np.ndarray
    bin_zhi: np.ndarray
    bin_reach: np.ndarray
    margin: float
    n_edges: int
    key: np.ndarray
    key_span: float
    key_x0: float
    box: np.ndarray
    #: Per thread, the compiled loops' scratch (one integer per edge), kept: a fresh one
    #: at every cut is mapped anew and faulted in page by page.
    _scratch: threading.local = field(default_factory=threading.local, repr=False)

    def scratch(self) -> np.ndarray:
        """This thread's scratch array of one integer per edge (a value left by an earlier
        cut is never trusted: the loops check each one against their own segments)."""
        slot = getattr(self._scratch, "slot", None)
        if slot is None:
            slot = self._scratch.slot = np.empty(max(self.n_edges, 1), dtype=np.int64)
        return slot

    def reach(self, cg: np.ndarray) -> tuple[float, float]:
        """The body's largest ``|x - x_g|`` and ``|z - z_g|`` from a centre of gravity, m."""
        box = self.box
        return (float(max(box[1, 0] - cg[0], cg[0] - box[0, 0])),
                float(max(box[1, 2] - cg[2], cg[2] - box[0, 2])))  # fmt: skip

    @classmethod
    def of(cls, vertices: np.ndarray, faces: np.ndarray) -> PlaneIndex:
        """The index of a closed, consistently wound triangle mesh."""
        v = np.ascontiguousarray(vertices, dtype=np.float64)
        f = np.asarray(faces, dtype=np.int64)
        m = len(f)
        corner = v[f]  # (m, 3, 3)
        x, z = corner[:, :, 0], corner[:, :, 2]
        fx0, fx1 = row_min(x), row_max(x)
        fz0, fz1 = row_min(z), row_max(z)
        nb = int(min(MAX_BINS, max(1, m // FACES_PER_BIN)))
        zc = 0.5 * (fz0 + fz1)
        lo, hi = float(zc.min()), float(zc.max())
        b = np.minimum(((zc - lo) / ((hi - lo) or 1.0) * nb).astype(np.int64), nb - 1)
        order = np.lexsort((fx0, b))
        b = b[order]
        start = np.searchsorted(b, np.arange(nb + 1))
        fx0, fx1, fz0, fz1 = fx0[order], fx1[order], fz0[order], fz1[order]
        f = f[order]
        # the undirected edges: corner k to k + 1, numbered by (low, high) vertex
        directed = f[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
        key = row_min(directed) * len(v) + row_max(directed)
        _, edge = np.unique(key, return_inverse=True)
        # numbered in order of first use by the faces (bin by bin, along x), so that the
        # edges of a station's faces lie near each other in the loops' scratch
        n_edges = int(edge.max()) + 1 if m else 0
        first = np.full(n_edges, len(edge))
        np.minimum.at(first, edge, np.arange(len(edge)))
        renumber = np.empty(n_edges, dtype=np.int64)
        renumber[np.argsort(first)] = np.arange(n_edges)
        edge = renumber[edge]
        full = start[1:] > start[:-1]
        zlo, zhi, reach = np.zeros(nb), np.zeros(nb), np.zeros(nb)
        at = start[:-1][full]
        zlo[full] = np.minimum.reduceat(fz0, at)
        zhi[full] = np.maximum.reduceat(fz1, at)
        reach[full] = np.maximum.reduceat(fx1 - fx0, at)
        size = float(np.linalg.norm(np.ptp(v, axis=0))) if len(v) else 1.0
        x0 = float(fx0.min()) - size
        key_span = 4.0 * size
        key = b * key_span + (fx0 - x0)
        wide = max(len(v), n_edges) >= 2**31
        return cls(
            vertices=v,
            corners=np.ascontiguousarray(np.concatenate([v[f, 0], v[f, 2], v[f, 1]], axis=1)),
            ends=np.concatenate([f, edge.reshape(m, 3)], axis=1).astype(
                np.int64 if wide else np.int32
            ),
            xmin=fx0,
            bin_start=start,
            bin_zlo=zlo,
            bin_zhi=zhi,
            bin_reach=reach,
            margin=1e-9 * size,
            n_edges=n_edges,
            key=key,
            key_span=key_span,
            key_x0=x0,
            box=np.stack([v.min(axis=0), v.max(axis=0)]) if len(v) else np.zeros((2, 3)),
        )

    def candidates(
        self, x_rel: np.ndarray, pitch: float, cg: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """The faces that the planes at relative stations ``x_rel`` (m) may cross at a pitch
        (rad): ``(station, face)`` pairs, grouped by station (a superset of the crossed
        faces)."""
        return planecut_numpy.range_faces(*self.ranges(x_rel, pitch, cg))

    def ranges(
        self,
        x_rel: np.ndarray,
        pitch: float,
        cg: np.ndarray,
        compiled: bool = False,
        margin: float | None = None,
        ends: bool = False,
    ) -> tuple[np.ndarray, ...]:
        """The candidate faces of :meth:`candidates` as ranges: ``(first, last)``, (s, b)
        arrays, the faces ``first[i, j] .. last[i, j] - 1`` of bin ``j`` for station ``i``
        (none where ``last <= first``); ``compiled``: searched by numba's loops where numba
        serves (:func:`~hullslice.planecut_loops.range_loops`: the same indices);
        ``margin`` (m) widens them instead of :attr:`margin`; ``ends``: the plane's body
        ``x`` at each bin's lowest and highest ``z`` too, ``(first, last, xa, xb)`` (by
        numpy)."""
        margin = self.margin if margin is None else margin
        c, s = np.cos(pitch), np.sin(pitch)
        x_rel = np.asarray(x_rel, dtype=np.float64)
        search = planecut_loops.compiled("ranges") if compiled else None
        if search is not None and not ends:  # the same arithmetic and indices by loops
            return search(
                self.key, self.bin_start, self.bin_zlo, self.bin_zhi, self.bin_reach, x_rel,
                float(cg[0]), float(cg[2]), float(c), float(s), margin, self.key_span,
                self.key_x0, np.empty((0, len(self.bin_zlo), 2), dtype=np.int64), 0,
            )  # fmt: skip
        # body x of each plane at a bin's lowest and highest z: r_x = (x_rel + r_z s) / c
        za = (self.bin_zlo - cg[2]) * s
        zb = (self.bin_zhi - cg[2]) * s
        xa = cg[0] + (x_rel[:, None] + za[None, :]) / c
        xb = cg[0] + (x_rel[:, None] + zb[None, :]) / c
        lo = np.minimum(xa, xb) - self.bin_reach - margin
        hi = np.maximum(xa, xb) + margin
        nb = len(self.bin_zlo)
        # one search of the faces' keys (bin number times a span beyond the body's length,
        # plus the lowest x): each bin's faces are a contiguous, sorted run of them
        span, x0 = self.key_span, self.key_x0
        base = np.arange(nb) * span
        # searched bin by bin (the bounds then ascend where the stations do, and each
        # search starts from the one before), the results back in station order
        lo = (base[:, None] + np.clip(lo.T - x0, 0.0, 0.5 * span)).ravel()
        hi = (base[:, None] + np.clip(hi.T - x0, 0.0, 0.5 * span)).ravel()
        first = np.searchsorted(self.key, lo, side="left").reshape(nb, -1).T
        last = np.searchsorted(self.key, hi, side="right").reshape(nb, -1).T
        if ends:
            return np.ascontiguousarray(first), np.ascontiguousarray(last), xa, xb
        return np.ascontiguousarray(first), np.ascontiguousarray(last)

    def cut(
        self,
        x_rel: np.ndarray,
        pitch: float,
        cg: np.ndarray,
        matrix: np.ndarray,
        merge: float = 0.0,
        path: str = "auto",
    ) -> list[tuple[np.ndarray, ...]]:
        """The sections at relative stations ``x_rel`` (m) at a pitch (rad), about the
        centre of gravity ``cg``: one tuple of closed ``(k, 2)`` contours per station (outer
        ones counter-clockwise), each point mapped by the first two rows of ``matrix`` (a
        body point to the cutter's ``(Y, Z)``, 2 x 4); consecutive points of a contour
        closer than ``merge`` along both of the cutter's axes are one.

        ``path`` chooses the loops: ``"numpy"``, ``"numba"`` (the compiled loops of
        :mod:`hullslice.planecut_loops`), ``"python"`` (those loops uncompiled, slow: for
        checking), or ``"auto"`` (numba's where installed, else numpy's).
        """
        x_rel = np.asarray(x_rel, dtype=np.float64)
        c, s = np.cos(pitch), np.sin(pitch)
        loops = _loops(path)
        if loops is planecut_loops.LOOPS["cut"]:  # the Python loops, afresh
            first, last = self.ranges(x_rel, pitch, cg)
            return self._cut_by_loops(loops, first, last, x_rel, c, s, cg, matrix, merge)
        # each station from this thread's memo where its recipe serves (the same memo for
        # the compiled loops and numpy's)
        memo = getattr(self._scratch, "memo", None)
        if memo is None or not np.array_equal(memo[0], cg):
            memo = (np.array(cg, dtype=np.float64), empty_memo(len(self.bin_zlo)))
        fn = None if loops is None else planecut_loops.compiled("memo_cut")
        if fn is None:
            cuts, kept = planecut_numpy.memo_cut(self, memo[1], x_rel, pitch, cg, matrix, merge)
        else:
            cuts, kept = self._cut_by_memo(fn, memo[1], x_rel, c, s, cg, matrix, merge)
        self._scratch.memo = (memo[0], kept)
        return cuts

    def _cut_by_memo(self, fn, memo, x_rel, c, s, cg, matrix, merge) -> tuple[Rings, tuple]:
        """:meth:`cut` by ``fn``, the compiled :func:`~hullslice.contour_loops.memo_cut_loops`,
        from ``memo``: the sections and the memo of these stations."""
        nb = len(self.bin_zlo)
        m = np.ascontiguousarray(matrix[:2], dtype=np.float64)
        points, start, ring_station, _, status, kept = fn(
            self.key, self.bin_start, self.bin_zlo, self.bin_zhi, self.bin_reach, self.margin,
            self.key_span, self.key_x0, self.xmin, self.corners, self.ends, x_rel,
            float(cg[0]), float(cg[2]), float(c), float(s), m, float(merge), self.scratch(),
            planecut_loops.K_OUT, planecut_loops.K_IN, np.empty((0, nb, 2), dtype=np.int64), 0,
            memo, *self.reach(cg),
        )  # fmt: skip
        if status:
            raise ValueError("the mesh is not closed along a cut: a contour does not close")
        return Rings.of(points, start, ring_station, len(x_rel)), kept

    def _cut_by_loops(
        self,
        loops: Callable,
        first: np.ndarray,
        last: np.ndarray,
        x_rel: np.ndarray,
        c: float,
        s: float,
        cg: np.ndarray,
        matrix: np.ndarray,
        merge: float,
    ) -> list[tuple[np.ndarray, ...]]:
        """:meth:`cut` over the candidates' ranges ``first`` .. ``last`` (see
        :meth:`ranges`), by :func:`~hullslice.planecut_loops.cut_loops` (compiled or not):
        the same points."""
        slot = self.scratch()
        m = np.ascontiguousarray(matrix[:2], dtype=np.float64)
        points, start, ring_station, status, _ = loops(
            first, last, self.corners, self.ends, x_rel, float(cg[0]), float(cg[2]),
            float(c), float(s),
            m, float(merge), slot, planecut_loops.K_OUT, planecut_loops.K_IN,
        )  # fmt: skip
        if status:
            raise ValueError("the mesh is not closed along a cut: a contour does not close")
        return Rings.of(points, start, ring_station, len(x_rel))


class Rings(list):
    """The sections of :meth:`PlaneIndex.cut` by the loops (a list of one tuple of
    contours per station, the contours views of one array), with that array as the loops
    gave it: ``flat = (points, ring_start, ring_station)`` (see
    :func:`~hullslice.planecut_loops.cut_loops`), for
    :func:`~hullslice.outline_loops.outline_loops`."""

    def __init__(self, sections: list, flat: tuple[np.ndarray, np.ndarray, np.ndarray]):
        super().__init__(sections)
        self.flat = flat

    @classmethod
    def of(cls, points: np.ndarray, start: np.ndarray, ring_station: np.ndarray, n: int) -> Rings:
        """The sections of ``n`` stations from the loops' contours (``points``, each ring's
        first point ``start`` and its ``ring_station``)."""
        out: list[list[np.ndarray]] = [[] for _ in range(n)]
        for i, st in enumerate(ring_station.tolist()):
            out[st].append(points[start[i] : start[i + 1]])
        return cls([tuple(ring) for ring in out], (points, start, ring_station))


class StationRings(ByStation):
    """:class:`Rings` of the loops' contours made station by station as they are read
    (a result whose sections are seldom drawn need not split them all, nor sort its rings
    by station until one is read): station ``i``'s contours, a tuple of views of
    ``points``, in the rings' order."""

    def __init__(self, points: np.ndarray, start: np.ndarray, ring_station: np.ndarray, n: int):
        self.flat = (points, start, ring_station)
        self._n = n
        self._by_station: tuple[np.ndarray, np.ndarray] | None = None

    def __len__(self) -> int:
        return self._n

    def _station(self, i: int) -> tuple[np.ndarray, ...]:
        points, start, ring_station = self.flat
        if self._by_station is None:  # the rings by station, and each station's first
            order = np.argsort(ring_station, kind="stable")
            first = np.searchsorted(ring_station[order], np.arange(self._n + 1))
            self._by_station = (order, first)
        order, first = self._by_station
        rings = order[first[i] : first[i + 1]].tolist()
        return tuple(points[start[k] : start[k + 1]] for k in rings)


#: The loops' paths (see :meth:`PlaneIndex.cut`).
PATHS = ("auto", "numpy", "numba", "python")


def _loops(path: str) -> Callable | None:
    """The loops :meth:`PlaneIndex.cut` runs on a ``path``: None for numpy's."""
    if path == "numpy":
        return None
    if path == "python":  # the Python function (once compiled for the stage loops, the
        return planecut_loops.LOOPS["cut"]  # module's name holds numba's)
    if path not in PATHS:
        raise ValueError(f"path {path!r} is unknown; choose one of {', '.join(PATHS)}")
    fn = planecut_loops.compiled() if path == "numba" or planecut_loops.available() else None
    if fn is None and path == "numba":
        raise ImportError("the compiled path needs numba: pip install hullslice[fast]")
    return fn


#: A hull's plane index (geometry alone).
PLANE_INDEX: Entry[Once[PlaneIndex]] = Entry("plane index", Once, geometry=True)


def plane_index(hull) -> PlaneIndex:
    """The :class:`PlaneIndex` of a hull, built once and kept on it."""
    return hull.cache[PLANE_INDEX].get(lambda: PlaneIndex.of(hull.vertices, hull.faces))
