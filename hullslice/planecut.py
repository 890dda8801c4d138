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
* the segments chained into closed contours (pointer jumping, no loop per point), repeated
  points (vertices on the plane) dropped and contours left with no area discarded.

The contours come out as :meth:`hullslice.geometry.Frame.cut` gives manifold3d's: ``(k,
2)`` arrays of the cutter's ``(Y, Z)`` (scaled and moved, see
:attr:`~hullslice.geometry.Frame.scale`). Pure numpy.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from . import planecut_loops
from .caching import Entry, Once
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

    def _ends(self, cx, cz, face, rows, at, matrix) -> np.ndarray:
        """The cutter's ``(Y, Z)``, ``(n, 2)``, of the corners ``at`` (flat indices into the
        candidates' ``(q, 3)`` corners ``cx``, ``cz``) of the crossed faces ``face`` (the
        candidates' ``rows``)."""
        k = at - 3 * rows
        x, y, z = cx.ravel()[at], self.corners[face, 6 + k], cz.ravel()[at]
        m = matrix
        return np.stack(
            [m[0, 0] * x + m[0, 1] * y + m[0, 2] * z + m[0, 3],
             m[1, 0] * x + m[1, 1] * y + m[1, 2] * z + m[1, 3]], axis=1
        )  # fmt: skip

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
        )

    def candidates(
        self, x_rel: np.ndarray, pitch: float, cg: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """The faces that the planes at relative stations ``x_rel`` (m) may cross at a pitch
        (rad): ``(station, face)`` pairs, grouped by station (a superset of the crossed
        faces)."""
        first, last = self.ranges(x_rel, pitch, cg)
        count = np.maximum(last - first, 0).ravel()
        total = int(count.sum())
        if total == 0:
            return np.empty(0, dtype=np.int64), np.empty(0, dtype=np.int64)
        offsets = np.repeat(first.ravel() - (np.cumsum(count) - count), count)
        face = np.arange(total) + offsets
        station = np.repeat(np.arange(len(x_rel)), count.reshape(first.shape).sum(axis=1))
        return station, face

    def ranges(
        self, x_rel: np.ndarray, pitch: float, cg: np.ndarray, compiled: bool = False
    ) -> tuple[np.ndarray, np.ndarray]:
        """The candidate faces of :meth:`candidates` as ranges: ``(first, last)``, (s, b)
        arrays, the faces ``first[i, j] .. last[i, j] - 1`` of bin ``j`` for station ``i``
        (none where ``last <= first``); ``compiled``: searched by numba's loops where numba
        serves (:func:`~hullslice.planecut_loops.range_loops`: the same indices)."""
        c, s = np.cos(pitch), np.sin(pitch)
        x_rel = np.asarray(x_rel, dtype=np.float64)
        search = planecut_loops.compiled("ranges") if compiled else None
        if search is not None:  # the same arithmetic and indices by loops
            return search(
                self.key, self.bin_start, self.bin_zlo, self.bin_zhi, self.bin_reach, x_rel,
                float(cg[0]), float(cg[2]), float(c), float(s), self.margin, self.key_span,
                self.key_x0, np.empty((0, len(self.bin_zlo), 2), dtype=np.int64), 0,
            )  # fmt: skip
        # body x of each plane at a bin's lowest and highest z: r_x = (x_rel + r_z s) / c
        za = (self.bin_zlo - cg[2]) * s
        zb = (self.bin_zhi - cg[2]) * s
        xa = cg[0] + (x_rel[:, None] + za[None, :]) / c
        xb = cg[0] + (x_rel[:, None] + zb[None, :]) / c
        lo = np.minimum(xa, xb) - self.bin_reach - self.margin
        hi = np.maximum(xa, xb) + self.margin
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
        n_st = len(x_rel)
        c, s = np.cos(pitch), np.sin(pitch)
        loops = _loops(path)
        if loops is not None:
            compiled = loops is not planecut_loops.LOOPS["cut"]
            first, last = self.ranges(x_rel, pitch, cg, compiled=compiled)
            return self._cut_by_loops(loops, first, last, x_rel, c, s, cg, matrix, merge)
        station, face = self.candidates(x_rel, pitch, cg)
        corner = self.ends[face, 0:3]  # (q, 3): the vertices
        cx, cz = self.corners[face, 0:3], self.corners[face, 3:6]
        # each vertex's distance ahead of its station's plane, the same for all its faces
        d = (cx - cg[0]) * c - (cz - cg[2]) * s
        d -= x_rel[station][:, None]
        ahead = d >= 0.0
        code = ahead[:, 0] + 2 * ahead[:, 1].astype(np.int64) + 4 * ahead[:, 2]
        rows = np.flatnonzero((code > 0) & (code < 7))
        station, face, code = station[rows], face[rows], code[rows]
        # the segment runs from the edge that leaves the ahead side (corner k ahead, k + 1
        # not) to the one that enters it: counter-clockwise around the section seen along X
        k_out, k_in = _K_OUT[code], _K_IN[code]
        e_out = self.ends[face, 3 + k_out].astype(np.int64)
        e_in = self.ends[face, 3 + k_in].astype(np.int64)
        # the crossing point of each segment's first edge (every crossed edge is the first
        # edge of exactly one segment of its station): from the edge's canonical ends
        at_a = rows * 3 + k_out
        at_b = rows * 3 + _NEXT[k_out]
        swap = corner.ravel()[at_a] > corner.ravel()[at_b]
        at_a, at_b = np.where(swap, at_b, at_a), np.where(swap, at_a, at_b)
        da, db = d.ravel()[at_a], d.ravel()[at_b]
        # the ends' coordinates from the faces' own corners (the vertices', exactly)
        pa, pb = (
            self._ends(cx, cz, face, rows, at_a, matrix),
            self._ends(cx, cz, face, rows, at_b, matrix),
        )
        near_a = (np.abs(da) <= np.abs(db))[:, None]
        ta = (da / (da - db))[:, None]
        tb = (db / (db - da))[:, None]
        point = np.where(near_a, pa + ta * (pb - pa), pb + tb * (pa - pb))
        succ = _successors(station, e_out, e_in, self.n_edges)
        return _contours(point, station, succ, n_st, merge)

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
        points, start, ring_station, status = loops(
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


#: By a crossed face's code (bit k set for corner k ahead): the corner whose edge to the
#: next corner leaves the ahead side, and the one whose edge enters it.
_K_OUT = planecut_loops.K_OUT
_K_IN = planecut_loops.K_IN
_NEXT = np.array([1, 2, 0])

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


def _successors(station: np.ndarray, e_out: np.ndarray, e_in: np.ndarray, n_edges: int):
    """Each segment's successor: the segment of its station leaving from the edge it
    enters."""
    n = len(e_out)
    # most crossed edges are crossed at one station only: a scatter by edge finds their
    # segments; the edges of several stations (long faces) are matched by a sort
    slot = np.empty(n_edges, dtype=np.int64)
    slot[e_out] = np.arange(n)
    succ = np.clip(slot[e_in], 0, max(n - 1, 0))
    wrong = np.flatnonzero((e_out[succ] != e_in) | (station[succ] != station))
    if len(wrong):
        key_out = station * n_edges + e_out
        order = np.argsort(key_out, kind="stable")
        key_in = station[wrong] * n_edges + e_in[wrong]
        at = np.minimum(np.searchsorted(key_out[order], key_in), n - 1)
        succ[wrong] = order[at]
        if not np.array_equal(key_out[succ[wrong]], key_in):
            raise ValueError("the mesh is not closed along a cut: a contour does not close")
    return succ


def _contours(
    point: np.ndarray, station: np.ndarray, succ: np.ndarray, n_st: int, merge: float
) -> list[tuple[np.ndarray, ...]]:
    """The closed contours of the segments' chains, one tuple per station."""
    n = len(succ)
    out: list[list[np.ndarray]] = [[] for _ in range(n_st)]
    if n == 0:
        return [tuple(c) for c in out]
    walked = _walk(succ)
    if walked is not None:  # the rings' own order, in one depth-first walk
        ordered, first = point[walked[0]], walked[1]
        length = np.diff(np.append(first, n))
        roots = walked[0][first]
    else:
        ordered, roots, length = _jump(point, succ)
    ring = np.repeat(np.arange(len(roots)), length)
    first = np.cumsum(length) - length
    prev = np.arange(n) - 1
    prev[first] = first + length - 1
    # repeated points dropped: a vertex on the plane (reached from several edges), or
    # points closer than ``merge`` along both axes (a plane through a ring of vertices up
    # to rounding; manifold3d's grid joins them too)
    far = np.abs(ordered - ordered[prev]) > merge
    keep = far[:, 0] | far[:, 1]
    ordered, ring = ordered[keep], ring[keep]
    length = np.bincount(ring, minlength=len(roots))
    first = np.cumsum(length) - length
    nxt = np.arange(len(ring)) + 1
    full = length > 0
    nxt[(first + length - 1)[full]] = first[full]
    cross = ordered[:, 0] * ordered[nxt, 1] - ordered[nxt, 0] * ordered[:, 1]
    area = np.bincount(ring, weights=cross, minlength=len(roots))
    root_station = station[roots]
    bounds = np.concatenate([[0], np.cumsum(length)])
    for i in np.flatnonzero((length >= 3) & (area != 0.0)):  # contours with an area
        out[int(root_station[i])].append(ordered[bounds[i] : bounds[i + 1]])
    return [tuple(c) for c in out]


def _walk(succ: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """The segments ring by ring, each ring from its lowest segment number along ``succ``,
    the rings by that number: ``(order, first)``, the order and each ring's first place in
    it; None where that is not what a depth-first walk gave (checked: then
    :func:`_jump` orders them).

    The walk is scipy's, from a root joined to every segment in turn: it follows the
    first segment's ring to its end, returns to the root, and the next segment it has not
    seen is the lowest of the next ring.
    """
    from scipy.sparse import csr_array
    from scipy.sparse.csgraph import depth_first_order

    n = len(succ)
    indptr = np.append(np.arange(n + 1), 2 * n)
    graph = csr_array(
        (np.ones(2 * n), np.concatenate((succ, np.arange(n))), indptr), shape=(n + 1, n + 1)
    )
    order = depth_first_order(graph, n, directed=True, return_predecessors=False)[1:]
    if len(order) != n:
        return None
    first = np.flatnonzero(np.append(True, order[1:] != succ[order[:-1]]))
    last = np.append(first[1:], n) - 1
    heads = order[first]
    closed = np.array_equal(succ[order[last]], heads)
    if not (closed and np.all(np.diff(heads) > 0)):
        return None
    if not np.array_equal(np.minimum.reduceat(order, first), heads):
        return None
    return order, first


def _jump(point: np.ndarray, succ: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The points ring by ring as :func:`_walk` orders them, by pointer jumping (windows
    of 1, 2, 4, ... segments): ``(ordered, roots, length)``, the points, each ring's
    lowest segment and its length."""
    n = len(succ)
    # each chain's lowest segment number and each segment's distance ahead to it
    label = np.arange(n)
    dist = np.zeros(n, dtype=np.int64)
    jump, width = succ, 1
    while True:
        lab2 = label[jump]
        if width >= 2 and np.array_equal(lab2, label) and np.array_equal(label[succ], label):
            break
        better = lab2 < label
        label = np.where(better, lab2, label)
        dist = np.where(better, dist[jump] + width, dist)
        jump, width = jump[jump], 2 * width
    roots = np.flatnonzero(label == np.arange(n))  # ascending: grouped by station
    size = np.bincount(label, minlength=n)
    length = size[roots]
    offset = np.zeros(n, dtype=np.int64)
    offset[roots] = np.cumsum(length) - length
    ring_size = size[label]
    where = offset[label] + (ring_size - dist) % ring_size
    ordered = np.empty_like(point)
    ordered[where] = point
    return ordered, roots, length


#: A hull's plane index (geometry alone).
PLANE_INDEX: Entry[Once[PlaneIndex]] = Entry("plane index", Once, geometry=True)


def plane_index(hull) -> PlaneIndex:
    """The :class:`PlaneIndex` of a hull, built once and kept on it."""
    return hull.cache[PLANE_INDEX].get(lambda: PlaneIndex.of(hull.vertices, hull.faces))
