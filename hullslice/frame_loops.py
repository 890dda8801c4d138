"""A new pitch's keel line by loops, written for a compiler: numba's, when installed
(compiled by :func:`hullslice.planecut_loops.compiled`, which holds them by name).

:func:`frame_keel_loops` makes it in one call: the side view's loops
(:func:`~hullslice.keel_loops.side_view_loops`), the refinement of their lowest points
(:func:`refine_loops`: :func:`hullslice.kernel.envelope.refined`, its gaps, jumps and
crossings, then the merge of close break points), the line's runs and arrays
(:func:`~hullslice.keel_loops.keel_line_loops`) and the turned ends' lowest and highest heights
(the side view's), with numpy's arithmetic in numpy's order: the same keel line.
"""

from __future__ import annotations

import math

import numpy as np

from .keel_loops import (
    keel_line_loops,
    line_runs_loops,
    search_loops,
    segments_loops,
    side_ends_loops,
    side_heights_loops,
)
from .side_loops import lower_side_loops

__all__ = [
    "FRAME_HELPERS_DIGEST",
    "above_chord_loops",
    "crossings_loops",
    "first_below_loops",
    "frame_keel_loops",
    "frame_points_loops",
    "last_below_loops",
    "lowest_at_loops",
    "merge_loops",
    "refine_loops",
    "segment_reach_loops",
    "window_line_loops",
]

#: The digest of the sources of the helpers these loops call (``keel_loops.py`` and
#: ``side_loops.py``). numba's cache of these loops goes stale when this file changes, not
#: when those do: a change of theirs changes this digest too
#: (``tests/test_frame_loops.py`` checks it), so that their cache is made again.
FRAME_HELPERS_DIGEST = "704598336c27e22d"

#: How many times the refinement halves an interval where two segments cross (as
#: :data:`hullslice.kernel.envelope.CROSSING_PASSES`, which a test holds equal).
CROSSING_PASSES = 8


def lowest_at_loops(q, lo, reach, xa, za, xb, zb, seg):
    """The lowest height of the turned silhouette segments (``xa`` to ``xb``; ``seg`` their
    order by lower end abscissa, ``lo`` those abscissae in that order and ``reach`` the
    running highest of their upper ends, as :func:`segment_reach_loops` gives them) at
    each of the finite abscissae ``q``: among the segments whose lower end is not past an
    abscissa, back from the last until none before reaches it, each one spanning it, as
    :func:`~hullslice.keel_loops.lower_loops` takes it (a vertical segment's lower end,
    else its height there; the lowest kept), so the heights numpy's ``lowest`` gives
    (a minimum over the segments spanning each abscissa, whatever their order)."""
    out = np.empty(len(q))
    for t in range(len(q)):
        x = q[t]
        z = np.inf
        j = search_loops(lo, 0, len(lo), x, True) - 1
        while j >= 0 and reach[j] >= x:
            k = seg[j]
            x0, z0 = xa[k], za[k]
            if x <= max(x0, xb[k]):
                dx = xb[k] - x0
                zi = min(z0, zb[k]) if dx == 0.0 else z0 + (x - x0) / dx * (zb[k] - z0)
                if zi < z:
                    z = zi
            j -= 1
        out[t] = z
    return out


def segment_reach_loops(xa, xb, seg):
    """The segments' lower end abscissae in the order ``seg`` (ascending) and the running
    highest of their upper ends: ``(lo, reach)``, for :func:`lowest_at_loops`."""
    lo, reach = np.empty(len(seg)), np.empty(len(seg))
    top = -np.inf
    for j in range(len(seg)):
        k = seg[j]
        lo[j] = min(xa[k], xb[k])
        top = max(top, max(xa[k], xb[k]))
        reach[j] = top
    return lo, reach


def crossings_loops(xa_c, za_c, xb_c, zb_c, xm, zm, lo, reach, xa, za, xb, zb, seg):
    """:func:`hullslice.kernel.envelope._crossings` by loops: the points of the lowest of
    segments crossing inside the intervals ``xa_c`` to ``xb_c`` (heights ``za_c``, ``zb_c``
    at their ends, ``zm`` at their middles ``xm``; the segments as
    :func:`lowest_at_loops` takes them): the middles, then the middles of the halves that
    peak above their chords, :data:`CROSSING_PASSES` times. Returns ``(x, z)``, in numpy's
    order."""
    out_x, out_z = xm.copy(), zm.copy()
    lx, lz = np.concatenate((xa_c, xm)), np.concatenate((za_c, zm))
    rx, rz = np.concatenate((xm, xb_c)), np.concatenate((zm, zb_c))
    for _ in range(CROSSING_PASSES):
        m = 0.5 * (lx + rx)
        z_mid = lowest_at_loops(m, lo, reach, xa, za, xb, zb, seg)
        above = np.zeros(len(m), dtype=np.bool_)
        k = 0
        for i in range(len(m)):
            v = z_mid[i]
            if math.isfinite(v) and v > 0.5 * (lz[i] + rz[i]) + 1e-12 * (1.0 + abs(v)):
                above[i] = True
                k += 1
        if k == 0:
            break
        m, z_mid = m[above], z_mid[above]
        out_x, out_z = np.concatenate((out_x, m)), np.concatenate((out_z, z_mid))
        lx, lz = np.concatenate((lx[above], m)), np.concatenate((lz[above], z_mid))
        rx, rz = np.concatenate((m, rx[above])), np.concatenate((z_mid, rz[above]))
    return out_x, out_z


def above_chord_loops(z, zm, i):
    """Whether the lowest height ``zm[i]`` over interval ``i``'s middle lies above the chord
    of its ends' ``z`` (``refined``'s test: a jump at an end, or two segments crossing)."""
    chord = 0.5 * (z[i + 1] + z[i])
    if not (math.isfinite(zm[i]) and math.isfinite(chord)):
        return False
    return zm[i] > chord + 1e-12 * (1.0 + abs(zm[i]))


def refine_loops(xs, mid, z, zm, merge, xa, za, xb, zb, seg):
    """:func:`hullslice.kernel.envelope.refined` of the lowest heights ``z`` over the
    sorted abscissae ``xs`` and ``zm`` over their middles ``mid`` (those of
    :func:`~hullslice.keel_loops.side_view_loops`, whose turned segments ``xa`` to ``zb``
    in the order ``seg`` give the heights it asks for), with numpy's arithmetic in numpy's
    order: the points of its gaps (``zm`` infinite), jumps and crossings (``zm`` above the
    chord) added, then the break points closer together than ``merge`` made one, at their
    mean abscissa (numpy's ``add.reduceat``: the first plus the running sum of the others)
    and their lowest height. Returns ``(ok, xs, z)``; ``ok`` False where an abscissa is not
    finite, or a group of points to merge is longer than 8 (numpy sums those pairwise):
    then numpy's path."""
    n = len(xs)
    if n and not math.isfinite(xs[n - 1]):  # NaNs sort last
        return False, xs, z
    n_gap = 0
    n_jump = 0
    for i in range(n - 1):
        n_gap += math.isinf(zm[i])
        n_jump += above_chord_loops(z, zm, i)
    if n_gap or n_jump:
        gap = np.empty(n_gap, dtype=np.int64)
        jump = np.empty(n_jump, dtype=np.int64)
        g = j = 0
        for i in range(n - 1):
            if math.isinf(zm[i]):
                gap[g] = i
                g += 1
            if above_chord_loops(z, zm, i):
                jump[j] = i
                j += 1
        # a jump: the heights a millionth of the interval inside its ends, added where one
        # differs from its end's by more than a thousandth of the interval; else a crossing
        inside = np.empty(2 * n_jump)
        width = np.empty(n_jump)
        for t in range(n_jump):
            i = jump[t]
            width[t] = xs[i + 1] - xs[i]
            inside[t] = xs[i] + 1e-6 * width[t]
            inside[n_jump + t] = xs[i + 1] - 1e-6 * width[t]
        lo, reach = segment_reach_loops(xa, xb, seg)
        z_in = lowest_at_loops(inside, lo, reach, xa, za, xb, zb, seg)
        steps = np.empty(2 * n_jump, dtype=np.bool_)
        for t in range(n_jump):
            i = jump[t]
            steps[t] = abs(z_in[t] - z[i]) > 1e-3 * width[t]
            steps[n_jump + t] = abs(z_in[n_jump + t] - z[i + 1]) > 1e-3 * width[t]
        cross = jump[~(steps[:n_jump] | steps[n_jump:])]  # neither end jumps: a crossing
        cx, cz = crossings_loops(
            xs[cross], z[cross], xs[cross + 1], z[cross + 1], mid[cross], zm[cross], lo,
            reach, xa, za, xb, zb, seg,
        )  # fmt: skip
        # numpy's stable sort of the points after the break points, which are sorted: the
        # added points sorted stably, then merged in after any break point they tie with
        add_x = np.concatenate((mid[gap], inside[steps], cx))
        add_z = np.concatenate((zm[gap], z_in[steps], cz))
        order = np.argsort(add_x, kind="mergesort")
        n_add = len(add_x)
        all_x, all_z = np.empty(n + n_add), np.empty(n + n_add)
        i = j = 0
        for k in range(n + n_add):
            if j < n_add and (i >= n or add_x[order[j]] < xs[i]):
                all_x[k], all_z[k] = add_x[order[j]], add_z[order[j]]
                j += 1
            else:
                all_x[k], all_z[k] = xs[i], z[i]
                i += 1
        xs, z = all_x, all_z
        n = len(xs)
    return merge_loops(xs, z, merge)


def merge_loops(xs, z, merge):
    """The break points ``xs`` (sorted), ``z`` closer together than ``merge`` made one, at
    their mean abscissa (numpy's ``add.reduceat``: the first plus the running sum of the
    others) and their lowest height, as :func:`hullslice.kernel.envelope.merged`. Returns
    ``(ok, xs, z)``; ``ok`` False where a group to merge is longer than 8 (numpy sums
    those pairwise)."""
    n = len(xs)
    if not (merge > 0.0 and n > 1):
        return True, xs, z
    close = False  # a pass the compiler turns into vector compares first: most have none
    for i in range(1, n):
        close = close | (xs[i] - xs[i - 1] <= merge)
    if not close:  # none closer than merge: numpy's path keeps the arrays
        return True, xs, z
    out_x = np.empty(n)
    out_z = np.empty(n)
    g = 0
    i = 0
    while i < n:
        j = i + 1
        while j < n and xs[j] - xs[j - 1] <= merge:
            j += 1
        if j - i > 8:
            return False, xs, z
        rest = 0.0
        low = z[i]
        for k in range(i + 1, j):
            rest += xs[k]
            low = low if (low < z[k] or low != low) else z[k]
        out_x[g] = (xs[i] + rest) / (j - i) if j - i > 1 else xs[i]  # numpy's: x / 1
        out_z[g] = low
        g += 1
        i = j
    if g == n:  # none closer than merge: numpy's path keeps the arrays
        return True, xs, z
    return True, out_x[:g], out_z[:g]


def frame_keel_loops(a, b, outline, whole, gx, gz, c, s, order, merge, end_face, steep_slope):
    """A new pitch's keel line in one call: :func:`~hullslice.keel_loops.side_view_loops`
    of the silhouette edges ``a`` to ``b`` (with ``gx`` to ``s`` and ``order``),
    :func:`refine_loops` of its lower envelope with ``merge`` and
    :func:`~hullslice.keel_loops.keel_line_loops` of the refined break points
    (``end_face`` and ``steep_slope`` as there), with the turned ends' lowest and highest
    heights (the side view's). Where the lower side of the body's side ``outline``
    (:func:`~hullslice.side_loops.lower_side_loops`; an empty outline never serves) runs
    forward from the first abscissa to the last, it is the envelope: its points are the
    break points, but for the merge (:func:`merge_loops`), and where the outline's points
    are all the edges' ends (``whole``) the edges are not turned. The break points are
    :func:`frame_points_loops`'.

    Returns ``(ok, side, low, high, x, z, runs, line)``: ``side`` the nine arrays and two
    heights of :func:`~hullslice.keel_loops.side_view_loops`, ``ok`` and the break points
    ``x``, ``z`` as :func:`refine_loops` gives them (where ``ok`` is False numpy's
    refinement must serve, and the rest is not meaningful), ``line`` what
    :func:`~hullslice.keel_loops.keel_line_loops` gives (the fused evaluation's arrays) and
    ``runs`` its eleven values of :func:`~hullslice.keel_loops.runs_loops`."""
    ok, side, low, high, x, z = frame_points_loops(a, b, outline, whole, gx, gz, c, s, order,
                                                   merge)  # fmt: skip
    line = keel_line_loops(x, z, end_face, steep_slope)
    return ok, side, low, high, x, z, line_runs_loops(line), line


def frame_points_loops(a, b, outline, whole, gx, gz, c, s, order, merge):
    """The break points of :func:`frame_keel_loops` (the same arguments but the line's
    ``end_face`` and ``steep_slope``), without its runs: ``(ok, side, low, high, x,
    z)``. Where the outline's lower side is the envelope, ``side``'s segments' order and
    middles (its fifth and seventh arrays) are empty and its abscissae and heights (the
    sixth and eighth) are that side's points: where ``ok`` is False there (a group of
    points to merge longer than :func:`merge_loops` takes), numpy's merge of them serves."""
    none, no_seg = np.empty(0), np.empty(0, dtype=np.int64)
    served, cx, cz, low, high = False, none, none, 0.0, 0.0
    if outline.shape[1] > 0:
        served, cx, cz, low, high = lower_side_loops(outline, gx, gz, c, s)
    if served and whole:  # the outline's points are the edges' ends: the edges not turned
        ok, x, zk = merge_loops(cx, cz, merge)
        side = (none, none, none, none, no_seg, cx, none, cz, none, low, high)
        return ok, side, low, high, x, zk
    xa, za, xb, zb, xs, mid, low, high = side_ends_loops(a, b, gx, gz, c, s, order)
    n = len(xs)
    if served and n and cx[0] == xs[0] and cx[len(cx) - 1] == xs[n - 1]:
        # the side runs forward over every abscissa: no gap, jump or crossing
        ok, x, zk = merge_loops(cx, cz, merge)
        side = (xa, za, xb, zb, no_seg, cx, none, cz, none, low, high)
        return ok, side, low, high, x, zk
    seg = segments_loops(order, len(a))
    z, zm = side_heights_loops(xs, mid, xa, za, xb, zb, seg)
    side = (xa, za, xb, zb, seg, xs, mid, z, zm, low, high)
    ok, x, z = refine_loops(xs, mid, z, zm, merge, xa, za, xb, zb, seg)
    return ok, side, low, high, x, z


#: Break points a window of the keel line keeps beyond the reach it needs, on either side
#: (see :func:`window_line_loops`).
WINDOW_SPARE = 2


#: How many heights :func:`first_below_loops` and :func:`last_below_loops` test at once.
BLOCK = 16


def first_below_loops(z, level):
    """The first index of ``z`` below ``level`` (``len(z)`` where none is: a NaN is not
    below), a block of :data:`BLOCK` tested at once (vector instructions), then the block
    point by point."""
    k = len(z)
    i = 0
    while i < k:
        block = z[i : min(i + BLOCK, k)]
        hit = False
        for t in range(len(block)):
            hit = hit | (block[t] < level)
        if hit:
            for t in range(len(block)):
                if block[t] < level:
                    return i + t
        i += BLOCK
    return k


def last_below_loops(z, level):
    """The last index of ``z`` below ``level`` (-1 where none is), as
    :func:`first_below_loops` from the end."""
    i = len(z)
    while i > 0:
        j = max(i - BLOCK, 0)
        block = z[j:i]
        hit = False
        for t in range(len(block)):
            hit = hit | (block[t] < level)
        if hit:
            for t in range(len(block) - 1, -1, -1):
                if block[t] < level:
                    return j + t
        i = j
    return -1


def window_line_loops(x, z, finite, level, n, reach, end_face, steep_slope):
    """:func:`~hullslice.keel_loops.keel_line_loops` of the break points ``x``, ``z`` that
    an evaluation at the water's height ``level`` reads (``n`` fixed slices), with the
    first and the last as they are: the line's ends, its length and its stations are the
    whole line's.

    The evaluation reads the line over the wetted extent, and from there at most ``reach``
    (m) further: a station's middle, a slice's chord and its keel's curvature (at least a
    slice's width, ``reach`` the larger of the station spacing and the curvature's
    window). The wetted extent lies within the break points before the first under the
    water and after the last. The window keeps the break points from ``reach`` before
    the one to ``reach`` after the other, and :data:`WINDOW_SPARE` more each side; every
    break point outside it is at the level or above, so the running lowest heights pass
    the level where the whole line's do. Within the window the slopes, the chords and the
    curvature are the whole line's; its running sums (the slope's offsets between runs,
    the bend, the bottom's rise) start at the line's first point and not at the window's,
    so that they differ by a constant and by rounding (a slope, a chord, a curvature:
    differences of them, the same but for rounding). Where ``finite`` is False (a gap's
    infinite heights may lie outside), no point is under the water, or the window holds
    nearly every point, the whole line is made."""
    k = len(x)
    first = first_below_loops(z, level)
    if not finite or first >= k or k < 8:
        return keel_line_loops(x, z, end_face, steep_slope)
    last = last_below_loops(z, level)
    reach = max(reach, (x[k - 1] - x[0]) / n)
    lo = x[max(first - 1, 0)] - reach
    hi = x[min(last + 1, k - 1)] + reach
    i0 = max(first - 1, 0)
    while i0 > 0 and x[i0] > lo:
        i0 -= 1
    i1 = min(last + 1, k - 1)
    while i1 < k - 1 and x[i1] < hi:
        i1 += 1
    i0 = max(i0 - WINDOW_SPARE, 1)  # the first point is kept as it is
    i1 = min(i1 + WINDOW_SPARE, k - 2)  # and the last
    m = i1 - i0 + 3
    if 2 * m > k:  # nearly every point: the whole line
        return keel_line_loops(x, z, end_face, steep_slope)
    xw, zw = np.empty(m), np.empty(m)
    xw[0], zw[0] = x[0], z[0]
    for i in range(i0, i1 + 1):
        xw[i - i0 + 1] = x[i]
        zw[i - i0 + 1] = z[i]
    xw[m - 1], zw[m - 1] = x[k - 1], z[k - 1]
    return keel_line_loops(xw, zw, end_face, steep_slope)
