"""The keel line from the body's side view: the lower envelope of the silhouette edges'
side views (:func:`lower_envelope`), exact at every end point, with its jumps at faces
vertical in the side view and its peaks where two edges cross (:func:`refined`). Pure
numpy; :mod:`hullslice.planecut_loops` gives the same searches compiled.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable

import numpy as np

from .keel import KeelLine

__all__ = [
    "CROSSING_PASSES",
    "lower_envelope",
    "lower_side",
    "lowest_segments",
    "merged",
    "refined",
    "side_envelope",
    "side_outline",
    "side_points",
]


def lower_envelope(
    a: np.ndarray,
    b: np.ndarray,
    loops: Callable | None = None,
    merge: float = 0.0,
    side: tuple[np.ndarray, np.ndarray] | None = None,
) -> KeelLine:
    """The lower envelope ``z(x)`` of segments from ``a`` to ``b`` ((e, 2) arrays of x, z).

    Evaluated exactly at every end point, with the jumps and crossings between them
    that :func:`refined` finds. ``loops``, when given, finds the
    abscissae and the lowest segment over each instead of numpy
    (``loops(xa, za, xb, zb) -> (xs, mid, z, zm)``, as
    :func:`hullslice.keel_loops.envelope_loops`, compiled: the same numbers).
    Break points closer than ``merge`` (m) are one (see :func:`refined`).

    ``side``, when given (without ``loops``), is the polygon whose inside the segments
    cover, turned as they are (``(x, z)``, counter-clockwise: a body's side outline,
    :func:`side_outline`): where its lower side (:func:`lower_side`) runs forward from the
    first end abscissa to the last, that side is the envelope (no gap, jump or crossing):
    the keel line is its points, close ones merged (:func:`merged`), instead of the
    segments' lowest heights over every end abscissa (the same line: the others' ends lie
    on its facets).
    """
    xs = None
    if side is not None and loops is None:
        chain = lower_side(*side)
        if chain is not None:
            xs = _abscissae(a, b)
            if len(xs) and chain[0][0] == xs[0] and chain[0][-1] == xs[-1]:
                return KeelLine(*merged(*chain, merge))
    if loops is not None:
        columns = (np.ascontiguousarray(v) for v in (a[:, 0], a[:, 1], b[:, 0], b[:, 1]))
        xs, mid, z, zm = loops(*columns)
        return refined(xs, mid, z, zm, merge, lowest_segments(a, b))
    if xs is None:
        xs = _abscissae(a, b)
    segments = _Segments(a, b)
    # the end abscissae and the middles in one sorted array (each middle lies between its
    # ends): each abscissa has the same pairs in the same order as on its own
    mid = 0.5 * (xs[1:] + xs[:-1])
    both = np.empty(len(xs) + len(mid))
    both[0::2], both[1::2] = xs, mid
    lowest = segments.lowest(both)
    return refined(xs, mid, lowest[0::2], lowest[1::2], merge, segments.lowest)


def side_envelope(
    x: np.ndarray, z: np.ndarray, merge: float = 0.0
) -> tuple[KeelLine, float, float] | None:
    """:func:`lower_envelope` of a body's silhouette edges with its ``side`` where the side
    outline's points (``x``, ``z``, turned as the edges are, counter-clockwise) are all the
    edges' ends (:func:`hullslice.geometry.side_outline_points`' ``whole``), read off the
    outline alone: the same keel line (the points of its lower side, from the leftmost to
    the rightmost, running forward; close ones merged), and the ends' lowest and highest
    heights (m). None where the lower side does not serve (:func:`lower_side`): then the
    edges' envelope must be found."""
    found = side_points(x, z, merge)
    if found is None:
        return None
    return KeelLine(*found[0]), found[1], found[2]


def side_points(
    x: np.ndarray, z: np.ndarray, merge: float = 0.0
) -> tuple[tuple[np.ndarray, np.ndarray], float, float] | None:
    """:func:`side_envelope`'s keel line as its break points ``(x, z)``, before the line
    is made of them, and the same lowest and highest heights; None where it gives None."""
    chain = lower_side(x, z)
    if chain is None:
        return None
    return merged(*chain, merge), float(z.min()), float(z.max())


def _abscissae(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The segments' end abscissae sorted, each once."""
    xs = np.concatenate([a[:, 0], b[:, 0]])
    xs.sort()
    if len(xs) > 1:  # np.unique's values, without its bookkeeping (NaNs, sorted last, as one)
        new = xs[1:] != xs[:-1]
        if np.isnan(xs[-1]):
            new &= ~np.isnan(xs[:-1])
        xs = xs[np.concatenate([[True], new])]
    return xs


def lower_side(x: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """The lower side of a polygon (its points ``x``, ``z``, counter-clockwise): its points
    from the leftmost to the rightmost, ``(x, z)``. None where that side does not run
    forward all the way (a face leaning over an end: the envelope jumps there), the
    leftmost or rightmost point is not one point (a face vertical in the side view), a
    point is not finite, or there are fewer than three."""
    m = len(x)
    if m < 3 or not (np.isfinite(x).all() and np.isfinite(z).all()):
        return None
    il, ir = int(np.argmin(x)), int(np.argmax(x))
    if np.count_nonzero(x == x[il]) != 1 or np.count_nonzero(x == x[ir]) != 1:
        return None
    lower = (il + np.arange((ir - il) % m + 1)) % m
    cx, cz = x[lower], z[lower]
    if not np.all(cx[1:] > cx[:-1]):
        return None
    return cx, cz


def refined(
    xs: np.ndarray,
    mid: np.ndarray,
    z: np.ndarray,
    zm: np.ndarray,
    merge: float = 0.0,
    lowest: Callable[[np.ndarray], np.ndarray] | None = None,
    runs: Callable | None = None,
) -> KeelLine:
    """The keel line through the lowest heights ``z`` over the abscissae ``xs``, refined
    where the heights at the middles ``mid``, ``zm``, lie off the straight line.

    Below it only where no segment spans the interval (``zm`` infinite: a gap between
    parts one behind the other). Above it (the lowest of segments over an interval with
    no end point inside is never below its chord), either two segments cross inside the
    interval, or the line jumps at an end: an end's height may be the foot of a segment
    vertical in the side view (a step's face or a part's end meshed in one plane, over
    another part's bottom), or where an outline folds back. With ``lowest`` (the lowest
    height of the segments at given abscissae) the heights a millionth of the interval
    inside its ends are taken, and where one differs from its end's by more than a
    thousandth of the interval (a slope of 1000), it is added: the jump becomes a facet
    steep enough to be a face, not a ramp across the interval. Where neither end jumps,
    the middle is added, and the middles of the halves that still peak above their
    chords, :data:`CROSSING_PASSES` times (the crossing itself is not found: the line
    lies low near it by at most its height over 2**CROSSING_PASSES of the interval).

    ``runs``, when given, finds the line's runs by loops (see :class:`KeelLine`).

    Break points closer together than ``merge`` (m; a rounding-size tie) are one
    point, at their mean abscissa and their lowest height: vertices that share a station
    at one pitch (a ring of a round body, port and starboard) part by ``height * pitch``
    at another, and without the merge the facets between them, narrower than any
    coordinate the mesh resolves, would stand in the slope's blend like real ones, so the
    keel's slope would jump as the pitch leaves zero."""
    chord = 0.5 * (z[1:] + z[:-1])
    # no segment over an interval: a gap between parts one behind the other, where the
    # line is infinitely high (not a straight line from one part's keel to the next's)
    lower = np.isinf(zm)
    add_x, add_z = [mid[lower]], [zm[lower]]
    if lowest is not None:
        jump = np.isfinite(zm) & np.isfinite(chord) & (zm > chord + 1e-12 * (1.0 + np.abs(zm)))
        if jump.any():
            i = np.flatnonzero(jump)
            width = xs[i + 1] - xs[i]
            inside = np.concatenate([xs[i] + 1e-6 * width, xs[i + 1] - 1e-6 * width])
            z_in = lowest(np.sort(inside))[np.argsort(np.argsort(inside))]
            ends = np.concatenate([z[i], z[i + 1]])
            steps = np.abs(z_in - ends) > 1e-3 * np.concatenate([width, width])
            # no jump: two segments cross inside the interval, the lowest of them peaking
            # between its ends above the straight line; the line goes through the middle
            cross = i[~(steps[: len(i)] | steps[len(i) :])]
            add_x.append(inside[steps])
            add_z.append(z_in[steps])
            if len(cross):
                cx, cz = _crossings(xs[cross], z[cross], xs[cross + 1], z[cross + 1],
                                    mid[cross], zm[cross], lowest)  # fmt: skip
                add_x.append(cx)
                add_z.append(cz)
    if len(add_x) > 1 or lower.any():
        xs = np.concatenate([xs, *add_x])
        z = np.concatenate([z, *add_z])
        order = np.argsort(xs, kind="stable")
        xs, z = xs[order], z[order]
    return KeelLine(*merged(xs, z, merge), runs)


def merged(xs: np.ndarray, z: np.ndarray, merge: float) -> tuple[np.ndarray, np.ndarray]:
    """The break points ``xs`` (sorted), ``z`` closer together than ``merge`` (m) made one,
    at their mean abscissa and their lowest height (see :func:`refined`)."""
    if merge > 0.0 and len(xs) > 1:
        close = np.diff(xs) <= merge
        if close.any():
            first = np.flatnonzero(np.concatenate([[True], ~close]))
            counts = np.diff(np.append(first, len(xs)))
            xs = np.add.reduceat(xs, first) / counts
            z = np.minimum.reduceat(z, first)
    return xs, z


#: How many times :func:`refined` halves an interval where two segments cross.
CROSSING_PASSES = 8


def _crossings(
    xa: np.ndarray,
    za: np.ndarray,
    xb: np.ndarray,
    zb: np.ndarray,
    xm: np.ndarray,
    zm: np.ndarray,
    lowest: Callable[[np.ndarray], np.ndarray],
) -> tuple[np.ndarray, np.ndarray]:
    """Points of the lowest of segments crossing inside the intervals ``xa``-``xb``
    (heights ``za``, ``zb`` at the ends, ``zm`` at the middles ``xm``, above the chords):
    the middles, then the middles of the halves peaking above their chords, and so on."""
    out_x, out_z = [xm], [zm]
    lx, lz = np.concatenate([xa, xm]), np.concatenate([za, zm])
    rx, rz = np.concatenate([xm, xb]), np.concatenate([zm, zb])
    for _ in range(CROSSING_PASSES):
        m = 0.5 * (lx + rx)
        order = np.argsort(m)
        zmid = np.empty_like(m)
        zmid[order] = lowest(m[order])
        above = np.isfinite(zmid) & (zmid > 0.5 * (lz + rz) + 1e-12 * (1.0 + np.abs(zmid)))
        if not above.any():
            break
        m, zmid = m[above], zmid[above]
        out_x.append(m)
        out_z.append(zmid)
        lx, lz, rx, rz = (
            np.concatenate([lx[above], m]), np.concatenate([lz[above], zmid]),
            np.concatenate([m, rx[above]]), np.concatenate([zmid, rz[above]]),
        )  # fmt: skip
    return np.concatenate(out_x), np.concatenate(out_z)


def lowest_segments(
    a: np.ndarray | None = None, b: np.ndarray | None = None, make: Callable | None = None
) -> Callable[[np.ndarray], np.ndarray]:
    """The lowest height of the segments from ``a`` to ``b`` ((e, 2) arrays of x, z), or
    of ``make() -> (a, b)`` (made on the first call only), over each of the sorted
    abscissae given to the function returned (``inf`` where none spans one)."""
    kept: list[_Segments] = []

    def lowest(xs: np.ndarray) -> np.ndarray:
        if not kept:
            ends = make() if make is not None else (a, b)
            kept.append(_Segments(*ends))
        return kept[0].lowest(xs)

    return lowest


#: Pairs of a segment and an abscissa that :meth:`_Segments.lowest` takes at a time (their
#: temporaries, 64 kB each, stay below the size the allocator maps afresh).
_PAIRS = 8192


class _Segments:
    """Segments from ``a`` to ``b`` ((e, 2) arrays of x, z), their columns apart."""

    def __init__(self, a: np.ndarray, b: np.ndarray) -> None:
        self.xa, self.za = np.ascontiguousarray(a[:, 0]), np.ascontiguousarray(a[:, 1])
        self.xb, self.zb = np.ascontiguousarray(b[:, 0]), np.ascontiguousarray(b[:, 1])
        self.lo = np.minimum(self.xa, self.xb)
        self.hi = np.maximum(self.xa, self.xb)
        self.dx = self.xb - self.xa
        self.dz = self.zb - self.za
        self.vertical = self.dx == 0.0
        self.z_vertical = np.minimum(self.za, self.zb)

    def lowest(self, xs: np.ndarray) -> np.ndarray:
        """Lowest height of the segments over each of the sorted abscissae ``xs``.

        Every pair of a segment and an abscissa within its span, in the order of the
        segments and of the abscissae along each, taken :data:`_PAIRS` pairs or so at a
        time: the same values and the same order of :func:`np.minimum.at`'s as all pairs at
        once (so the same result to the last bit, the sign of a zero included), with
        temporaries small enough to be served from the allocator's heap. A large mesh's
        silhouette has tens of thousands of pairs (an end cap's fan of edges, edge-on in the
        side view, spans a couple of hundred abscissae per edge), and arrays of that size
        are mapped afresh, page by page, at every call: that was most of the cost.
        """
        i0 = np.searchsorted(xs, self.lo, side="left")
        i1 = np.searchsorted(xs, self.hi, side="right")  # abscissae i0 .. i1-1 on a segment
        z = np.full(len(xs), np.inf)
        on = np.flatnonzero(i1 > i0)
        if not len(on):
            return z
        i0, count = i0[on], (i1 - i0)[on]
        xa, dx, za, dz = self.xa[on], self.dx[on], self.za[on], self.dz[on]
        vertical = self.vertical[on]
        end = np.cumsum(count)  # the pairs of segment k are first[k] .. end[k]-1
        first = end - count
        base = i0 - first  # a pair's abscissa is its rank among the pairs plus this
        cuts = np.searchsorted(end, np.arange(_PAIRS, int(end[-1]), _PAIRS), side="right")
        bounds = np.unique(np.concatenate([[0], cuts, [len(on)]])).tolist()
        with np.errstate(divide="ignore", invalid="ignore"):
            for a, b in itertools.pairwise(bounds):  # segments a .. b-1
                c = count[a:b]
                idx = np.repeat(base[a:b], c)
                idx += np.arange(first[a], end[b - 1])
                t = (xs[idx] - np.repeat(xa[a:b], c)) / np.repeat(dx[a:b], c)
                z_on = np.repeat(za[a:b], c) + t * np.repeat(dz[a:b], c)
                if vertical[a:b].any():
                    up = np.repeat(vertical[a:b], c)
                    z_on[up] = np.repeat(self.z_vertical[on[a:b]], c)[up]
                np.minimum.at(z, idx, z_on)
        return z


def side_outline(p: np.ndarray, edges: np.ndarray) -> np.ndarray | None:
    """The outer boundary of the straight-line graph of ``edges`` ((e, 2) indices into the
    points ``p``, (n, 2): a body's silhouette edges seen from the side, ``(x, z)``),
    counter-clockwise from its leftmost point (the lowest of ties): the indices of its
    points, each once (where points of ``p`` coincide, or lie within 1e-12 of the graph's
    size of one another, the first stands for them all; None where such a group of
    points spans more than twice that).

    Every point of the edge of the body's side view lies on a silhouette edge, and the
    graph's outer face lies outside the body: where the graph is plane (no two edges cross
    or overlap), the side view is this polygon and its inside, at every pitch (a pitch
    turns the whole view), and its lower side, where it runs forward, is the silhouette
    edges' lower envelope (see :func:`lower_envelope`'s ``side``). None where no such
    polygon is found: two edges cross, touch or overlap other than at a shared end (or
    come within 1e-12 of the graph's size of it), the graph is in several pieces, the
    boundary passes a point twice (parts that touch, an edge leading nowhere), or there
    are fewer than three edges."""
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    edges = edges[edges[:, 0] != edges[:, 1]]  # a vertex alone lies inside its flat face
    if len(edges) < 3:
        return None
    used = np.unique(edges.ravel())
    if not np.isfinite(p[used]).all():
        return None
    q, inverse = np.unique(p[used], axis=0, return_inverse=True)
    size = float(np.ptp(q, axis=0).max())
    if not size > 0.0:
        return None
    # points within 1e-12 of the graph's size are one (port and starboard seen from the
    # side, apart by rounding where the mesh's coordinates are doubles): the first stands
    group = _snapped(q, 1e-12 * size)
    if len(group) and group.max() < len(q) - 1:  # some joined: each group within 2e-12
        for axis in (0, 1):
            lo = np.full(group.max() + 1, np.inf)
            hi = np.full(group.max() + 1, -np.inf)
            np.minimum.at(lo, group, q[:, axis])
            np.maximum.at(hi, group, q[:, axis])
            if np.any(hi - lo > 2e-12 * size):  # a chain of close points: no outline
                return None
    node = group[inverse.ravel()]
    node_of = np.full(len(p), -1, dtype=np.int64)
    node_of[used] = node
    rep = np.full(int(node.max()) + 1, -1, dtype=np.int64)
    rep[node[::-1]] = used[::-1]  # each node's first point
    q = p[rep]
    e = node_of[edges]
    e = np.unique(np.sort(e[e[:, 0] != e[:, 1]], axis=1), axis=0)
    if len(e) < 3 or _crossed(q, e, 1e-12 * size) or not _connected(len(q), e):
        return None
    # the boundary's walk from the leftmost node: at each node the edge that turns least
    # to the left from the way back (the outside kept on the right), the way back last
    adj = np.concatenate([e, e[:, ::-1]])
    adj = adj[np.lexsort((adj[:, 1], adj[:, 0]))]
    start = np.searchsorted(adj[:, 0], np.arange(len(q) + 1))
    v0 = v = int(np.lexsort((q[:, 1], q[:, 0]))[0])

    def step(v: int, back: np.ndarray) -> int:
        nb = adj[start[v] : start[v + 1], 1]
        d = q[nb] - q[v]
        turn = np.mod(np.arctan2(d[:, 1], d[:, 0]) - np.arctan2(back[1], back[0]), 2.0 * np.pi)
        return int(nb[np.argmin(np.where(turn > 0.0, turn, 2.0 * np.pi))])

    first = step(v0, np.array([-1.0, 0.0]))  # as if come from the left
    out: list[int] = []
    seen = np.zeros(len(q), dtype=bool)
    w = first
    while not seen[v]:
        seen[v] = True
        out.append(v)
        v, w = w, step(w, q[v] - q[w])
    # back at the start, the boundary must go on as it began: else it passes the start
    # twice (an edge from it leading nowhere, or two parts meeting there)
    if v != v0 or w != first or len(out) < 3:
        return None
    return rep[np.asarray(out, dtype=np.int64)]


def _snapped(q: np.ndarray, tol: float) -> np.ndarray:
    """Each of the points ``q`` numbered by its group of points joined by steps no longer
    than ``tol``."""
    from scipy.spatial import cKDTree

    pairs = cKDTree(q).query_pairs(tol, output_type="ndarray")
    return _components(len(q), pairs) if len(pairs) else np.arange(len(q))


def _connected(n: int, e: np.ndarray) -> bool:
    """Whether the graph of ``n`` nodes and edges ``e`` is in one piece (a part apart from
    the polygon would be left out of it, inside or not)."""
    return bool(_components(n, e).max(initial=0) == 0)


def _components(n: int, e: np.ndarray) -> np.ndarray:
    """Each of the ``n`` nodes of the graph of edges ``e`` numbered by its piece."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    graph = coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n))
    return connected_components(graph, directed=False)[1]


#: Most pairs of edges side by side along ``x`` that :func:`side_outline` tests for a
#: crossing (some 150 MB of arrays; a 1M-face fuselage has 34,000): a graph with more is
#: taken as crossed (the keel line is then the edges' lower envelope, as without the
#: outline).
MAX_PAIRS = 2_000_000


def _crossed(q: np.ndarray, e: np.ndarray, tol: float) -> bool:
    """Whether two of the segments ``e`` ((k, 2) indices) of the points ``q`` cross, touch
    or overlap other than at an end they share, or come within ``tol`` of doing so (or
    more than :data:`MAX_PAIRS` pairs lie side by side along ``x``)."""
    a, b = q[e[:, 0]], q[e[:, 1]]
    lo_x = np.minimum(a[:, 0], b[:, 0])
    hi_x = np.maximum(a[:, 0], b[:, 0])
    order = np.argsort(lo_x, kind="stable")
    stop = np.searchsorted(lo_x[order], hi_x[order] + tol, side="right")
    count = np.maximum(stop - np.arange(len(order)) - 1, 0)  # later starts within reach
    if int(count.sum()) > MAX_PAIRS:  # edges stacked over one another: not worth testing
        return True
    first = np.repeat(np.arange(len(order)), count)
    offset = np.arange(len(first)) - np.repeat(np.cumsum(count) - count, count)
    i, j = order[first], order[first + 1 + offset]
    lo_z, hi_z = np.minimum(a[:, 1], b[:, 1]), np.maximum(a[:, 1], b[:, 1])
    near = (lo_z[i] <= hi_z[j] + tol) & (lo_z[j] <= hi_z[i] + tol)
    i, j = i[near], j[near]
    if len(i) == 0:
        return False
    for x, y in ((i, j), (j, i)):  # an end of one within tol of the other, not shared
        pa, ab = a[y], b[y] - a[y]
        for k in (0, 1):
            pt = q[e[x, k]]
            t = np.clip(((pt - pa) * ab).sum(axis=1) / (ab * ab).sum(axis=1), 0.0, 1.0)
            dist = np.hypot(*(pt - (pa + t[:, None] * ab)).T)
            own = (e[x, k] == e[y, 0]) | (e[x, k] == e[y, 1])
            if np.any((dist <= tol) & ~own):
                return True
    shared = (
        (e[i, 0] == e[j, 0]) | (e[i, 0] == e[j, 1]) | (e[i, 1] == e[j, 0]) | (e[i, 1] == e[j, 1])
    )
    cross_i = _turn_sign(a[i], b[i], a[j]) * _turn_sign(a[i], b[i], b[j])
    cross_j = _turn_sign(a[j], b[j], a[i]) * _turn_sign(a[j], b[j], b[i])
    return bool(np.any((cross_i < 0) & (cross_j < 0) & ~shared))


def _turn_sign(p: np.ndarray, q: np.ndarray, r: np.ndarray) -> np.ndarray:
    """The sign of the turn ``p -> q -> r`` of each row (1 left, -1 right, 0 straight)."""
    return np.sign(
        (q[:, 0] - p[:, 0]) * (r[:, 1] - p[:, 1]) - (q[:, 1] - p[:, 1]) * (r[:, 0] - p[:, 0])
    )
