"""numpy's path of the exact plane cut (:mod:`hullslice.planecut`): each station's recipe
(the edges its plane crosses, contour by contour) from a fresh cut, the thread's memo of
the stations cut last, and the contours from a recipe at a pitch.

The same scheme as the compiled loops of :mod:`hullslice.contour_loops` (whose text gives
the reasoning), with the same memo, in numpy's arithmetic: a station is served from the
memo where no vertex can have changed side of its plane since its recipe was made, and
its points are then a fresh cut's to the last bit.
"""

from __future__ import annotations

import numpy as np

from .contour_loops import MEMO_WIDTH, empty_memo
from .planecut_loops import K_IN, K_OUT

#: Each corner's next around its face.
_NEXT = np.array([1, 2, 0])


def memo_cut(index, memo, x_rel, pitch, cg, matrix, merge) -> tuple[list, tuple]:
    """The sections at relative stations ``x_rel`` (m, ascending) at a pitch (rad), as
    :meth:`hullslice.planecut.PlaneIndex.cut` gives them, each station from the ``memo``
    where its recipe serves and the others cut afresh, and the memo of these stations."""
    c, s = np.cos(pitch), np.sin(pitch)
    src = served(index, memo, x_rel, c, s, cg)
    fresh = np.flatnonzero(src < 0)
    k0 = int(src[0]) if len(src) else 0
    if len(fresh) or not np.array_equal(src, k0 + np.arange(len(src))):
        new = recipe(index, x_rel[fresh], pitch, cg) if len(fresh) else None
        memo, k0 = _combined(memo, src, new), 0
    return contours(memo, k0, x_rel, c, s, cg, matrix, merge), memo


def served(index, memo, x_rel, c, s, cg) -> np.ndarray:
    """:func:`hullslice.contour_loops.match_loops` and, where it asks for it,
    :func:`~hullslice.contour_loops.same_sides_loops`, by numpy: each station's source in
    the memo, or -1."""
    mx, mc, ms, m_near, m_gap, m_reach = memo[0]  # a row a figure
    n = len(x_rel)
    if len(mx) == 0 or n == 0:
        return np.full(n, -1, dtype=np.int64)
    top = len(mx) - 1
    j = np.searchsorted(mx, x_rel)
    lo, hi = np.minimum(np.maximum(j - 1, 0), top), np.minimum(j, top)  # j >= 0
    k = np.where(np.abs(mx[lo] - x_rel) < np.abs(mx[hi] - x_rel), lo, hi)  # the nearest
    dc, ds, dx = np.abs(c - mc[k]), np.abs(s - ms[k]), np.abs(x_rel - mx[k])
    reach_x, reach_z = index.reach(cg)
    eps = index.margin
    far_ok = (mc[k] - dc) * m_gap[k] - dc * m_reach[k] - ds * reach_z - dx > eps
    move = dc * reach_x + ds * reach_z + dx
    quiet = move < m_near[k] - eps
    src = np.where(far_ok, k, -1)
    check = np.flatnonzero(far_ok & ~quiet)
    if len(check):  # the sign test again on each candidate whose nearest corner was near
        kk = k[check]
        code_p = memo[2][0]
        count = code_p[kk + 1] - code_p[kk]
        at = _spans(code_p[kk], count)
        station = np.repeat(np.arange(len(check)), count)
        test = np.flatnonzero(~(move[check][station] < memo[6][at] - eps))
        # the faces of those candidates alone: each one's place among its station's
        # ranges, bin by bin, in the order the recipe listed them (range_faces')
        ranges = memo[1][kk]
        first = ranges[:, :, 0].ravel()
        sizes = np.maximum(ranges[:, :, 1].ravel() - first, 0)
        ends = np.cumsum(sizes)
        slot = np.searchsorted(ends, test, side="right")
        face = first[slot] + (test - (ends[slot] - sizes[slot]))
        station = station[test]
        _, code = _sides(index, station, face, x_rel[check], c, s, cg)
        wrong = np.bincount(station[code != memo[3][at[test]]], minlength=len(check))
        src[check[wrong > 0]] = -1
    return src


def recipe(index, x_rel: np.ndarray, pitch: float, cg: np.ndarray) -> tuple:
    """The memo of stations ``x_rel`` cut afresh at a pitch (rad): their places, pitch,
    nearest candidate vertex, gap and reach, ranges (widened by :data:`MEMO_WIDTH`), side
    codes, recipe and each candidate's nearest corner's distance to its plane, as
    :func:`hullslice.contour_loops.memo_cut_loops` keeps them."""
    c, s = np.cos(pitch), np.sin(pitch)
    n_st = len(x_rel)
    wide = index.margin + MEMO_WIDTH * index.key_span
    first, last, xa, xb = index.ranges(x_rel, pitch, cg, margin=wide, ends=True)
    station, face = range_faces(first, last)
    d, codes = _sides(index, station, face, x_rel, c, s, cg)
    code_near = np.abs(d).min(axis=1) if len(face) else np.empty(0)
    per = np.bincount(station, minlength=n_st)
    code_p = np.concatenate(([0], np.cumsum(per)))
    near = np.full(n_st, np.inf)
    if len(face):
        has = per > 0
        near[has] = np.minimum.reduceat(code_near, code_p[:-1][has])
    gap, reach = _gaps(index, first, last, xa, xb, cg)
    rows = np.flatnonzero((codes > 0) & (codes < 7))
    station, face, code = station[rows], face[rows], codes[rows]
    # the segment runs from the edge that leaves the ahead side (corner k ahead, k + 1
    # not) to the one that enters it: counter-clockwise around the section seen along X
    k_out = K_OUT[code]
    e_out = index.ends[face, 3 + k_out].astype(np.int64)
    e_in = index.ends[face, 3 + K_IN[code]].astype(np.int64)
    # each segment's first edge (every crossed edge is the first edge of exactly one
    # segment of its station), its ends in canonical order (lower vertex number first)
    ka, kb = k_out, _NEXT[k_out]
    swap = index.ends[face, ka] > index.ends[face, kb]
    ka, kb = np.where(swap, kb, ka), np.where(swap, ka, kb)
    perm, roots, length = _rings(_successors(station, e_out, e_in, index.n_edges))
    f, a, b = face[perm], ka[perm], kb[perm]
    co = index.corners
    ends6 = np.stack([co[f, a], co[f, 6 + a], co[f, 3 + a], co[f, b], co[f, 6 + b],
                      co[f, 3 + b]])  # fmt: skip
    ring_station = station[roots]
    st_q = np.concatenate(([0], np.cumsum(np.bincount(ring_station, minlength=n_st))))
    points = np.bincount(ring_station, weights=length, minlength=n_st).astype(np.int64)
    st_p = np.concatenate(([0], np.cumsum(points)))
    stations = np.stack([np.asarray(x_rel, dtype=np.float64), np.full(n_st, c),
                         np.full(n_st, s), near, gap, reach])  # fmt: skip
    return (stations, np.stack([first, last], axis=2), np.stack([code_p, st_p, st_q]),
            codes.astype(np.int8), ends6, length.astype(np.int64), code_near)  # fmt: skip


def contours(memo, k0, x_rel, c, s, cg, matrix, merge) -> list[tuple[np.ndarray, ...]]:
    """The closed contours of the memo's stations ``k0``, ``k0 + 1``, ... cut by the planes
    ``x_rel`` at a pitch (``c``, ``s``), one tuple per station: each point from its edge's
    end nearer the plane, mapped by the first two rows of ``matrix`` to the cutter's
    ``(Y, Z)``; repeated points (closer than ``merge`` along both axes) dropped and
    contours with no area left out."""
    n_st = len(x_rel)
    ends6, ring_len, st_p, st_q = memo[4], memo[5], memo[2][1], memo[2][2]
    p0, p1 = st_p[k0], st_p[k0 + n_st]
    xa, ya, za, xb, yb, zb = ends6[:, p0:p1]  # each point's edge
    xs = np.repeat(x_rel, np.diff(st_p[k0 : k0 + n_st + 1]))
    # both ends' distances ahead of the plane and their (Y, Z), as a fresh cut takes them
    da = (xa - cg[0]) * c - (za - cg[2]) * s
    da -= xs
    db = (xb - cg[0]) * c - (zb - cg[2]) * s
    db -= xs
    y_a, y_b = _mapped(matrix[0], xa, ya, za), _mapped(matrix[0], xb, yb, zb)
    z_a, z_b = _mapped(matrix[1], xa, ya, za), _mapped(matrix[1], xb, yb, zb)
    near_a = np.abs(da) <= np.abs(db)
    y = _between(near_a, da, db, y_a, y_b)
    z = _between(near_a, da, db, z_a, z_b)
    length = ring_len[st_q[k0] : st_q[k0 + n_st]]
    root_station = np.repeat(np.arange(n_st), np.diff(st_q[k0 : k0 + n_st + 1]))
    return _finish(y, z, length, root_station, n_st, merge)


def _between(near_a, da, db, va, vb) -> np.ndarray:
    """Each point's value from its edge's end values ``va``, ``vb`` at the ends' distances
    ``da``, ``db`` ahead of the plane, from the nearer end (``near_a``):
    ``va + ta * (vb - va)`` with ``ta = da / (da - db)``, else ``vb + tb * (va - vb)`` with
    ``tb = db / (db - da)``; written with the differences' signs turned (exact), in fewer
    passes."""
    w = da - db  # -(db - da)
    u = vb - va  # -(va - vb)
    a = da / w
    a *= u
    a += va
    u *= db / w  # tb * (va - vb)
    u += vb
    return np.where(near_a, a, u)


def _mapped(row: np.ndarray, x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
    """``row[0] * x + row[1] * y + row[2] * z + row[3]``, summed in that order, the terms
    of a zero coefficient left out: the same values for finite points (a term of zero adds
    nothing), and the cutter's map has two zeros a row."""
    out = None
    for coef, v in ((row[0], x), (row[1], y), (row[2], z)):
        if coef != 0.0:
            if out is None:
                out = coef * v
            else:
                out += coef * v
    if out is None:
        return np.full(len(x), float(row[3]))
    out += row[3]
    return out


def _combined(memo, src, fresh) -> tuple:
    """The memo of a call's stations: each one's from ``memo`` (``src[i] >= 0``) or, in
    turn, from the ``fresh`` stations' memo (None where there is none)."""
    if fresh is None:
        fresh = empty_memo(memo[1].shape[1])
    n = len(src)
    take = src >= 0
    j = np.cumsum(~take) - 1  # each fresh station's row in ``fresh``
    stations = np.empty((6, n))  # a column a station
    stations[:, take] = memo[0][:, src[take]]
    stations[:, ~take] = fresh[0][:, j[~take]]
    ranges = np.empty((n, *memo[1].shape[1:]), dtype=memo[1].dtype)  # a row a station
    ranges[take] = memo[1][src[take]]
    ranges[~take] = fresh[1][j[~take]]
    offsets = np.empty((3, n + 1), dtype=np.int64)
    data = []
    for row, at in ((0, 3), (1, 4), (2, 5), (0, 6)):  # each station's run of the codes,
        old, new = memo[2][row], fresh[2][row]  # ends, rings, and the codes' distances
        axis = 1 if at == 4 else 0  # the edge ends: a row a coordinate
        count = np.empty(n, dtype=np.int64)
        base = np.empty(n, dtype=np.int64)
        k, f = src[take], j[~take]
        count[take], base[take] = old[k + 1] - old[k], old[k]
        count[~take], base[~take] = new[f + 1] - new[f], memo[at].shape[axis] + new[f]
        pieces = np.concatenate((memo[at], fresh[at]), axis=axis)
        offsets[row] = np.concatenate(([0], np.cumsum(count)))
        data.append(pieces.take(_spans(base, count), axis=axis))
    codes, ends6, ring_len, code_near = data
    return (stations, ranges, offsets, codes, ends6, ring_len, code_near)


def _gaps(index, first, last, xa, xb, cg) -> tuple[np.ndarray, np.ndarray]:
    """Each station's gap along ``x`` from its plane to the faces out of its ranges, m, and
    its plane's largest ``|x - gx|`` over the bins' heights (see
    :func:`hullslice.contour_loops.recipe_loops`)."""
    lo, hi = np.minimum(xa, xb), np.maximum(xa, xb)
    end, start = index.bin_start[1:], index.bin_start[:-1]
    after = np.where(last < end, index.xmin[np.minimum(last, len(index.xmin) - 1)] - hi, np.inf)
    before = np.where(first > start, lo - index.bin_reach - index.xmin[np.maximum(first - 1, 0)],
                      np.inf)  # fmt: skip
    gap = np.minimum(after, before).min(axis=1, initial=np.inf)
    reach = np.maximum(np.abs(xa - cg[0]), np.abs(xb - cg[0])).max(axis=1, initial=0.0)
    return gap, reach


def _spans(start: np.ndarray, count: np.ndarray) -> np.ndarray:
    """The indices ``start[i] .. start[i] + count[i] - 1`` for each ``i``, one after another."""
    count = np.asarray(count, dtype=np.int64)
    total = int(count.sum())
    if total == 0:
        return np.empty(0, dtype=np.int64)
    return np.arange(total) + np.repeat(np.asarray(start) - (np.cumsum(count) - count), count)


def range_faces(first: np.ndarray, last: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The candidate faces of ranges ``(first, last)`` ((s, b) arrays): ``(station, face)``
    pairs, station by station, bin by bin."""
    count = np.maximum(last - first, 0)
    face = _spans(first.ravel(), count.ravel())
    return np.repeat(np.arange(len(first)), count.sum(axis=1)), face


def _sides(index, station, face, x_rel, c, s, cg) -> tuple[np.ndarray, np.ndarray]:
    """Each candidate's corners' distances ahead of its station's plane, ``(q, 3)``, and
    its side code (bit ``k`` set for corner ``k`` ahead: a vertex on the plane counts as
    ahead, the same for all its faces)."""
    cx, cz = index.corners[face, 0:3], index.corners[face, 3:6]
    d = (cx - cg[0]) * c - (cz - cg[2]) * s
    d -= x_rel[station][:, None]
    ahead = d >= 0.0
    return d, ahead[:, 0] + 2 * ahead[:, 1].astype(np.int64) + 4 * ahead[:, 2]


def _successors(station: np.ndarray, e_out: np.ndarray, e_in: np.ndarray, n_edges: int):
    """Each segment's successor: the segment of its station leaving from the edge it
    enters."""
    n = len(e_out)
    # most crossed edges are crossed at one station only: a scatter by edge finds their
    # segments; the edges of several stations (long faces) are matched by a sort
    slot = np.empty(n_edges, dtype=np.int64)
    slot[e_out] = np.arange(n)
    succ = np.minimum(np.maximum(slot[e_in], 0), max(n - 1, 0))
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


def _rings(succ: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The segments' chains as rings, each from its lowest segment, the rings by it:
    ``(perm, roots, length)``, the segments in ring order, each ring's first segment and
    its length."""
    n = len(succ)
    if n == 0:
        none = np.empty(0, dtype=np.int64)
        return none, none, none
    walked = _walk(succ)
    if walked is not None:  # the rings' own order, in one depth-first walk
        perm, first = walked
        return perm, perm[first], np.diff(np.append(first, n))
    return _jump(np.arange(n), succ)


def _finish(
    y: np.ndarray,
    z: np.ndarray,
    length: np.ndarray,
    root_station: np.ndarray,
    n_st: int,
    merge: float,
) -> list[tuple[np.ndarray, ...]]:
    """The closed contours of the points ``(y, z)`` ring by ring (each ring's ``length``
    and station), one tuple per station."""
    out: list[list[np.ndarray]] = [[] for _ in range(n_st)]
    n = len(y)
    if n == 0:
        return [tuple(c) for c in out]
    rings = len(length)
    ring = np.repeat(np.arange(rings), length)
    first = np.cumsum(length) - length
    # repeated points dropped: a vertex on the plane (reached from several edges), or
    # points closer than ``merge`` along both axes (a plane through a ring of vertices up
    # to rounding; manifold3d's grid joins them too)
    full = length > 0
    keep = _apart(y, first, length, full, merge, -1)
    keep |= _apart(z, first, length, full, merge, -1)
    if not keep.all():
        y, z, ring = y[keep], z[keep], ring[keep]
        length = np.bincount(ring, minlength=rings)
        first = np.cumsum(length) - length
        full = length > 0
    cross = y * _shifted(z, first, length, full, 1)  # y z_next - y_next z
    y_next = _shifted(y, first, length, full, 1)
    y_next *= z
    cross -= y_next
    area = np.bincount(ring, weights=cross, minlength=rings)
    bounds = np.concatenate([[0], np.cumsum(length)])
    ordered = np.stack([y, z], axis=1)
    for i in np.flatnonzero((length >= 3) & (area != 0.0)):  # contours with an area
        out[int(root_station[i])].append(ordered[bounds[i] : bounds[i + 1]])
    return [tuple(c) for c in out]


def _shifted(v, first, length, full, step: int) -> np.ndarray:
    """Each point's neighbour around its ring (rings of ``length`` points from ``first``,
    one after another; ``full``: the rings with a point): the next one for ``step`` 1 (the
    first after the last), the one before for -1."""
    out = np.empty_like(v)
    if step > 0:
        out[:-1] = v[1:]
        out[(first + length - 1)[full]] = v[first[full]]
    else:
        out[1:] = v[:-1]
        out[first[full]] = v[(first + length - 1)[full]]
    return out


def _apart(v, first, length, full, merge: float, step: int) -> np.ndarray:
    """Whether each point's ``v`` is farther than ``merge`` from its neighbour's
    (:func:`_shifted`)."""
    d = _shifted(v, first, length, full, step)
    np.subtract(v, d, out=d)
    np.abs(d, out=d)
    return d > merge


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
