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

__all__ = ["CROSSING_PASSES", "lower_envelope", "lowest_segments", "refined"]


def lower_envelope(
    a: np.ndarray, b: np.ndarray, loops: Callable | None = None, merge: float = 0.0
) -> KeelLine:
    """The lower envelope ``z(x)`` of segments from ``a`` to ``b`` ((e, 2) arrays of x, z).

    Evaluated exactly at every end point, with the jumps and crossings between them
    that :func:`refined` finds. ``loops``, when given, finds the
    abscissae and the lowest segment over each instead of numpy
    (``loops(xa, za, xb, zb) -> (xs, mid, z, zm)``, as
    :func:`hullslice.keel_loops.envelope_loops`, compiled: the same numbers).
    Break points closer than ``merge`` (m) are one (see :func:`refined`).
    """
    if loops is not None:
        columns = (np.ascontiguousarray(v) for v in (a[:, 0], a[:, 1], b[:, 0], b[:, 1]))
        xs, mid, z, zm = loops(*columns)
        return refined(xs, mid, z, zm, merge, lowest_segments(a, b))
    xs = np.concatenate([a[:, 0], b[:, 0]])
    xs.sort()
    if len(xs) > 1:  # np.unique's values, without its bookkeeping (NaNs, sorted last, as one)
        new = xs[1:] != xs[:-1]
        if np.isnan(xs[-1]):
            new &= ~np.isnan(xs[:-1])
        xs = xs[np.concatenate([[True], new])]
    segments = _Segments(a, b)
    # the end abscissae and the middles in one sorted array (each middle lies between its
    # ends): each abscissa has the same pairs in the same order as on its own
    mid = 0.5 * (xs[1:] + xs[:-1])
    both = np.empty(len(xs) + len(mid))
    both[0::2], both[1::2] = xs, mid
    lowest = segments.lowest(both)
    return refined(xs, mid, lowest[0::2], lowest[1::2], merge, segments.lowest)


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
    if merge > 0.0 and len(xs) > 1:
        close = np.diff(xs) <= merge
        if close.any():
            first = np.flatnonzero(np.concatenate([[True], ~close]))
            counts = np.diff(np.append(first, len(xs)))
            xs = np.add.reduceat(xs, first) / counts
            z = np.minimum.reduceat(z, first)
    return KeelLine(xs, z, runs)


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
