"""The keel line's loops, written for a compiler: numba's, when installed (compiled by
:func:`hullslice.planecut_loops.compiled`, which holds them by name).

:func:`side_view_loops` turns the silhouette edges to a pitch and finds the lowest of them
over every end abscissa and every interval's middle, as
:meth:`hullslice.kernel.envelope.lower_envelope` does with numpy: the same arithmetic per
pair, and a minimum, which does not depend on the order (but for the sign of a zero where
two segments tie at one: numpy keeps the last, the loops the first). :func:`envelope_loops`
does the same on edges already turned, :func:`lowest_loops` over given abscissae.
:func:`runs_loops` finds a keel line's runs. A new pitch's keel line in one call (the side
view's loops, the refinement of its lowest points, its runs) is
:func:`hullslice.frame_loops.frame_keel_loops`.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "abscissae_loops",
    "envelope_loops",
    "keel_arrays_loops",
    "keel_line_loops",
    "line_runs_loops",
    "lower_loops",
    "lowest_loops",
    "lowest_walk_loops",
    "row_loops",
    "run_ends_loops",
    "runs_loops",
    "search_loops",
    "segments_loops",
    "side_ends_loops",
    "side_heights_loops",
    "side_view_loops",
    "sorted_loops",
]


def search_loops(a, lo, hi, v, right):
    """``np.searchsorted`` of ``v`` in the sorted ``a[lo:hi]``, plus ``lo``: the first index
    whose value is not below ``v`` (``right``: above it), or ``hi``."""
    while lo < hi:
        m = (lo + hi) // 2
        if a[m] < v or (right and a[m] == v):
            lo = m + 1
        else:
            hi = m
    return lo


def lowest_loops(xs, xa, za, xb, zb):
    """The lowest height of the segments from ``(xa, za)`` to ``(xb, zb)`` over each of the
    sorted abscissae ``xs`` (``inf`` where none): a vertical segment's lower end, else the
    segment's height there, ``za + (x - xa) / (xb - xa) * (zb - za)``."""
    z = np.full(len(xs), np.inf)
    for j in range(len(xa)):
        dx = xb[j] - xa[j]
        dz = zb[j] - za[j]
        lo, hi = min(xa[j], xb[j]), max(xa[j], xb[j])
        for i in range(search_loops(xs, 0, len(xs), lo, False), len(xs)):
            if xs[i] > hi:
                break
            if dx == 0.0:
                zi = min(za[j], zb[j])
            else:
                zi = za[j] + (xs[i] - xa[j]) / dx * dz
            if zi < z[i] or zi != zi:  # np.minimum's: a NaN wins
                z[i] = zi
    return z


def envelope_loops(xa, za, xb, zb):
    """:func:`hullslice.kernel.envelope.lower_envelope`'s search by loops, on the segments
    from ``(xa, za)`` to ``(xb, zb)``: the end abscissae sorted, each once (NaNs, sorted
    last, as one), their interval middles, and the lowest height over each of both as
    :func:`lowest_loops` finds it. Returns ``(xs, mid, z, zm)``: numpy's very arrays."""
    e = len(xa)
    xs = np.empty(2 * e)
    xs[:e] = xa
    xs[e:] = xb
    xs.sort()
    xs, mid = abscissae_loops(xs)
    return xs, mid, lowest_loops(xs, xa, za, xb, zb), lowest_loops(mid, xa, za, xb, zb)


def side_ends_loops(a, b, gx, gz, c, s, order):
    """The silhouette edges from ``a`` to ``b`` ((e, 3) body points) turned nose up by a
    pitch (``c``, ``s``: its cosine and sine) about ``(gx, gz)``, as
    :func:`hullslice.geometry._turn` turns them, their end abscissae sorted by
    :func:`sorted_loops` from ``order`` (the ends' order at an earlier pitch, ``2 e``
    integers, updated), each once, with their middles (:func:`abscissae_loops`). Returns
    ``(xa, za, xb, zb, xs, mid, low, high)``: the turned ends, the abscissae and middles,
    and the turned ends' lowest and highest heights, ``min(za.min(), zb.min())``
    and ``max(za.max(), zb.max())`` as numpy and Python take them (each array's own with a
    NaN kept, then the first of the two unless the second is lower, or higher; NaN
    without an edge), found as the edges turn."""
    e = len(a)
    xa, za, xb, zb = np.empty(e), np.empty(e), np.empty(e), np.empty(e)
    ends = np.empty(2 * e)
    lo_a = hi_a = lo_b = hi_b = np.nan
    for i in range(e):
        rx, rz = a[i, 0] - gx, a[i, 2] - gz
        xa[i] = rx * c - rz * s
        va = rx * s + rz * c
        za[i] = va
        rx, rz = b[i, 0] - gx, b[i, 2] - gz
        xb[i] = rx * c - rz * s
        vb = rx * s + rz * c
        zb[i] = vb
        ends[i] = xa[i]
        ends[e + i] = xb[i]
        if i == 0:
            lo_a = hi_a = va
            lo_b = hi_b = vb
        else:  # numpy's minimum and maximum: a NaN kept, the first on a tie
            lo_a = lo_a if (lo_a <= va or lo_a != lo_a) else va
            hi_a = hi_a if (hi_a >= va or hi_a != hi_a) else va
            lo_b = lo_b if (lo_b <= vb or lo_b != lo_b) else vb
            hi_b = hi_b if (hi_b >= vb or hi_b != hi_b) else vb
    low = lo_b if lo_b < lo_a else lo_a  # Python's min and max of the two
    high = hi_b if hi_b > hi_a else hi_a
    xs, mid = abscissae_loops(sorted_loops(ends, order))
    return xa, za, xb, zb, xs, mid, low, high


def segments_loops(order, e):
    """The ``e`` segments in the order of their lower end abscissae (for
    :func:`lowest_walk_loops`), from ``order``, their ends' sorted order (``2 e``
    integers, :func:`sorted_loops`'): each at its first end in that order."""
    seg = np.empty(e, dtype=np.int64)
    seen = np.zeros(e, dtype=np.bool_)
    k = 0
    for i in range(2 * e):
        j = order[i]  # an end: the segment's first (j < e) or its second (j - e)
        if j >= e:  # not j % e: an integer division a value costs more than the loop
            j -= e
        if not seen[j]:
            seen[j] = True
            seg[k] = j
            k += 1
    return seg


def side_heights_loops(xs, mid, xa, za, xb, zb, seg):
    """The lowest heights of the turned segments (:func:`side_ends_loops`') over the sorted
    abscissae ``xs`` and their middles ``mid``: by :func:`lowest_walk_loops`, or with a
    NaN by the searches of :func:`lowest_loops`. Returns ``(z, zm)``."""
    finite = len(xs) == 0 or xs[len(xs) - 1] == xs[len(xs) - 1]
    if finite:
        return lowest_walk_loops(xs, mid, xa, za, xb, zb, seg)
    return lowest_loops(xs, xa, za, xb, zb), lowest_loops(mid, xa, za, xb, zb)


def side_view_loops(a, b, gx, gz, c, s, order):
    """The silhouette edges from ``a`` to ``b`` ((e, 3) body points) turned nose up by a
    pitch (``c``, ``s``: its cosine and sine) about ``(gx, gz)``, as
    :func:`hullslice.geometry._turn` turns them, and :func:`envelope_loops` on them, the
    end abscissae sorted by :func:`sorted_loops` from ``order`` (the ends' order at an
    earlier pitch, ``2 e`` integers, updated). Returns ``(xa, za, xb, zb, seg, xs, mid, z,
    zm, low, high)``: the turned ends, the segments in the order of their lower end
    abscissae (for :func:`lowest_walk_loops`), the envelope's arrays, and the turned ends'
    lowest and highest heights (see :func:`side_ends_loops`, :func:`segments_loops`, then
    :func:`side_heights_loops`)."""
    xa, za, xb, zb, xs, mid, low, high = side_ends_loops(a, b, gx, gz, c, s, order)
    seg = segments_loops(order, len(a))
    z, zm = side_heights_loops(xs, mid, xa, za, xb, zb, seg)
    return xa, za, xb, zb, seg, xs, mid, z, zm, low, high


def lowest_walk_loops(xs, mid, xa, za, xb, zb, seg):
    """:func:`lowest_loops` over the sorted abscissae ``xs`` and over ``mid`` at once, the
    segments taken in the order ``seg`` (ascending lower end abscissa; no NaN): each
    segment's first abscissa follows the one before it, found by walking on from it
    instead of searching (a search's every step is a guess the processor gets wrong half
    the time). The same heights as :func:`lowest_loops` (a minimum does not depend on the
    order). Returns ``(z, zm)``."""
    n, nm = len(xs), len(mid)
    z = np.full(n, np.inf)
    zm = np.full(nm, np.inf)
    i0 = 0
    k0 = 0
    for jj in range(len(seg)):
        j = seg[jj]
        x0, z0 = xa[j], za[j]
        dx = xb[j] - x0
        dz = zb[j] - z0
        lo, hi = min(x0, xb[j]), max(x0, xb[j])
        while i0 < n and xs[i0] < lo:
            i0 += 1
        while k0 < nm and mid[k0] < lo:
            k0 += 1
        flat = min(z0, zb[j])  # a vertical segment's lower end
        # no height the segment gives is below this (rounding is monotone: the fraction
        # of dx is within 0 .. 1, z0 plus its share of dz between z0 and z0 + dz)
        low = flat if dx == 0.0 else min(z0, z0 + dz)
        lower_loops(z, xs, i0, hi, x0, z0, dx, dz, flat, low)
        lower_loops(zm, mid, k0, hi, x0, z0, dx, dz, flat, low)
    return z, zm


def lower_loops(z, xs, i0, hi, x0, z0, dx, dz, flat, low):
    """``z`` lowered to the segment from ``x0`` (height ``z0``) by ``dx``, ``dz`` over the
    sorted abscissae ``xs`` from ``i0`` to its end ``hi`` (``flat`` where it is vertical),
    its height not computed where ``z`` is already at most ``low``, the lowest it gives
    (the division a height costs is most of the side view's time)."""
    for i in range(i0, len(xs)):
        if xs[i] > hi:
            break
        if not low < z[i]:
            continue
        zi = flat if dx == 0.0 else z0 + (xs[i] - x0) / dx * dz
        if zi < z[i]:
            z[i] = zi


def sorted_loops(v, order):
    """``v`` sorted ascending (NaNs last), from ``order``: the order of ``v``'s values at an
    earlier call (any permutation of ``0 .. len(v) - 1``), updated to their order now. Near
    the earlier order (the silhouette at a pitch close to the last one) an insertion sort
    takes a few moves per value; past :data:`SORT_MOVES` moves per value, and with a NaN,
    a full sort. The same values as ``np.sort(v)`` (equal as numbers: a zero's sign may
    follow the earlier order)."""
    n = len(v)
    out = np.empty(n)
    finite = True
    for i in range(n):
        out[i] = v[order[i]]
        if out[i] != out[i]:
            finite = False
    budget = SORT_MOVES * n
    moves = 0
    i = 1
    while finite and i < n and moves <= budget:
        x, k = out[i], order[i]
        j = i - 1
        while j >= 0 and out[j] > x:
            out[j + 1] = out[j]
            order[j + 1] = order[j]
            j -= 1
        moves += i - 1 - j
        out[j + 1] = x
        order[j + 1] = k
        i += 1
    if not finite or moves > budget:
        full = np.argsort(v, kind="mergesort")
        for i in range(n):
            order[i] = full[i]
            out[i] = v[full[i]]
    return out


#: Most moves per value of :func:`sorted_loops`'s insertion sort before a full sort.
SORT_MOVES = 8


def abscissae_loops(xs):
    """The sorted abscissae ``xs`` each once (NaNs, sorted last, as one) and their
    interval middles: ``(xs, mid)``."""
    n = 0
    for i in range(len(xs)):
        if i == 0 or (xs[i] != xs[i - 1] and not (xs[i] != xs[i] and xs[i - 1] != xs[i - 1])):
            xs[n] = xs[i]
            n += 1
    xs = xs[:n].copy()
    mid = np.empty(max(n - 1, 0))
    for i in range(n - 1):
        mid[i] = 0.5 * (xs[i + 1] + xs[i])
    return xs, mid


def runs_loops(x, z, end_face, steep_slope):
    """:meth:`hullslice.kernel.keel._Runs.of` of the break points ``x``, ``z`` by loops,
    with the same arithmetic in the same order (each sum a running one, as numpy's
    ``cumsum``): the same arrays, as rows of :func:`keel_line_loops`' (see
    :func:`line_runs_loops`). ``end_face`` and ``steep_slope`` are
    :data:`~hullslice.kernel.keel.END_FACE_SLOPE` and
    :data:`~hullslice.kernel.keel.STEEP_SLOPE`."""
    return line_runs_loops(keel_line_loops(x, z, end_face, steep_slope))


def line_runs_loops(line):
    """The runs of a keel line as :func:`keel_line_loops` gives them (``line``), as
    ``(ok, mid, cont, starts, offsets, steep, bend, bottom, height, lo, hi)``: rows of its
    arrays; ``ok`` False where no facet has a finite slope (numpy's path holds the slope at
    zero there; nothing else is meaningful), ``bottom`` whether a bottom facet exists (then
    ``(x, height, lo, hi)`` are the chords)."""
    nf, r, bottom, steep, _, runs, chords = line
    n = len(steep)
    if nf == 0:
        empty = np.empty(0)
        return False, empty, empty, empty, empty, steep, empty, False, empty, empty, empty
    return (
        True, runs[0, :nf], runs[1, :nf], runs[3, :r], runs[4, : r + 1], steep,
        runs[2, :nf], bottom, chords[0, : n + 1], chords[1, :n], chords[2, :n],
    )  # fmt: skip


def keel_line_loops(x, z, end_face, steep_slope):
    """The runs of the break points ``x``, ``z`` (:meth:`hullslice.kernel.keel._Runs.of`'s,
    with the same arithmetic in the same order, each sum a running one as numpy's
    ``cumsum``) written straight into the fused evaluation's arrays of the keel line, as
    :func:`keel_arrays_loops` lays them out: one pass over the facets finds each one's
    slope, its run (a finite slope after the last facet with one), the slope's running
    offset and bend, the bottom's rise and its runs' ends (written back where a run of
    bottom facets ends), and the lowest height from the first point; a pass back the
    lowest from the last. ``end_face`` and ``steep_slope`` are
    :data:`~hullslice.kernel.keel.END_FACE_SLOPE` and
    :data:`~hullslice.kernel.keel.STEEP_SLOPE`.

    Returns ``(nf, r, bottom, steep, keel, runs, chords)``: the facets with a finite slope
    (none: nothing else is meaningful), the runs after the first, whether a bottom facet
    exists, the facets' steep flags, and the arrays: ``keel`` (5, k) and ``chords``
    (3, k) as :func:`keel_arrays_loops` makes them (zeros without a bottom), ``runs``
    (5, k) its rows with NaN beyond their values (wider than its, by NaNs only)."""
    k = len(x)
    n = max(k - 1, 0)
    kk = max(k, 1)
    keel = np.empty((5, kk))
    runs = np.empty((5, kk))
    chords = np.empty((3, kk))
    steep = np.zeros(n, dtype=np.bool_)
    runs[4, 0] = 0.0  # the first run's offset
    chords[0, 0] = 0.0  # the rise at the first break point
    nf = 0  # facets with a finite slope so far
    r = 0  # runs after the first so far
    prev = -1  # the last facet with a finite slope, and its slope
    s_prev = 0.0
    offset = 0.0  # the slope's jumps between runs so far (a running sum from the first)
    total = 0.0  # the turns so far (a running sum from the second)
    turned = False
    bottom = False
    rise = 0.0
    run = -1  # the first facet of the current run of bottom facets
    low = 0.0  # the lowest height from the first point
    for i in range(n):
        dz = z[i + 1] - z[i]
        sl = dz / (x[i + 1] - x[i])
        flat = False  # a bottom facet: a finite slope, not steep
        if math.isfinite(sl):
            st = abs(sl) > end_face
            steep[i] = st
            flat = not st
            runs[0, nf] = 0.5 * (x[i + 1] + x[i])
            new = nf > 0 and (st != steep[prev] or i - prev > 1)
            jump = s_prev - sl if new else 0.0
            offset = jump if nf == 0 else offset + jump
            if new:
                runs[4, r + 1] = offset
                runs[3, r] = x[prev + 1] if i - prev > 1 else x[i]
                r += 1
            cont = sl + offset
            runs[1, nf] = cont
            turn = 0.0
            if nf > 0 and not new:
                if abs(sl) > steep_slope or abs(s_prev) > steep_slope:
                    turn = sl - s_prev
                    turned = turned or turn != 0.0
            if nf == 0:
                runs[2, 0] = cont - 0.0
            else:
                total = turn if nf == 1 else total + turn
                runs[2, nf] = cont - total
            s_prev = sl
            prev = i
            nf += 1
        # the chords of the bottom's runs: its rise from the first break point, and each
        # bottom facet's run's first and last break points (a facet's own first point else)
        bottom = bottom or flat
        step = dz if flat else 0.0
        rise = step if i == 0 else rise + step
        chords[0, i + 1] = rise
        if flat:
            if run < 0:
                run = i
        else:
            if run >= 0:
                run_ends_loops(chords, x, run, i)
                run = -1
            chords[1, i] = chords[2, i] = x[i]
        # the break point's own row: x, z, its facet's steepness, the lowest so far (a
        # running minimum as numpy's minimum.accumulate: a NaN kept, the new on a tie)
        keel[0, i] = x[i]
        keel[1, i] = z[i]
        keel[2, i] = 1.0 if steep[i] else 0.0
        b = z[i]
        low = b if (i == 0 or not (low < b or low != low)) else low
        keel[3, i] = low
    if run >= 0:
        run_ends_loops(chords, x, run, n)
    if k:  # the last break point: no facet of its own
        keel[0, n] = x[n]
        keel[1, n] = z[n]
        keel[2, n] = 0.0
        b = z[n]
        low = b if (n == 0 or not (low < b or low != low)) else low
        keel[3, n] = low
    for i in range(k - 1, -1, -1):
        b = z[i]
        low = b if (i == k - 1 or not (low < b or low != low)) else low
        keel[4, i] = low
    if k == 0:  # no break point: a column of zeros
        for j in range(5):
            keel[j, 0] = 0.0
    if not turned:  # no turn: the slopes as they are (the sign of a zero kept)
        for j in range(nf):
            runs[2, j] = runs[1, j]
    for j in range(nf, kk):
        runs[0, j] = runs[1, j] = runs[2, j] = np.nan
    for j in range(r, kk):
        runs[3, j] = np.nan
    for j in range(r + 1, kk):
        runs[4, j] = np.nan
    if not bottom:
        chords = np.zeros((3, k))
    else:  # a bottom facet: at least two break points
        for j in range(n, kk):
            chords[1, j] = chords[2, j] = np.nan
    return nf, r, bottom, steep, keel, runs, chords


def run_ends_loops(chords, x, i, j):
    """A run of bottom facets ``i`` to ``j - 1``: its first and last break points, into
    rows 1 and 2 of ``chords``."""
    for k in range(i, j):
        chords[1, k] = x[i]
        chords[2, k] = x[j]


def keel_arrays_loops(x, z, steep, mid, cont, bend, starts, offsets, height, lo, hi):
    """The fused evaluation's arrays of a keel line (see
    :func:`hullslice.forces.fused_arrays.keel_arrays`, which builds the same with numpy): the
    break points ``x``, ``z`` with the facets' ``steep`` flags and the lowest height from
    the first point and from the last, ``(5, k)``, zero beyond; the runs' ``mid``,
    ``cont``, ``bend``, ``starts`` and ``offsets``, ``(5, f)``, NaN beyond; the chords'
    ``height``, ``lo`` and ``hi`` (empty arrays where the line has none), ``(3, k)``, NaN
    beyond (zeros where none). A running minimum as numpy's ``minimum.accumulate`` takes
    it (a NaN kept, the new value on a tie). Each value is written once (the arrays are
    made empty, and what lies beyond the values filled)."""
    k = len(x)
    kk = max(k, 1)
    keel = np.empty((5, kk))
    n_steep = min(len(steep), k - 1)
    low = 0.0
    for i in range(k):
        keel[0, i] = x[i]
        keel[1, i] = z[i]
        keel[2, i] = 1.0 if (i < n_steep and steep[i]) else 0.0
        b = z[i]
        low = b if (i == 0 or not (low < b or low != low)) else low
        keel[3, i] = low
    for i in range(k - 1, -1, -1):
        b = z[i]
        low = b if (i == k - 1 or not (low < b or low != low)) else low
        keel[4, i] = low
    for r in range(k, kk):  # no break point: a row of zeros
        for j in range(5):
            keel[j, r] = 0.0
    f = max(len(mid), len(offsets))
    runs = np.empty((5, max(f, 1)))
    row_loops(runs, 0, mid)
    row_loops(runs, 1, cont)
    row_loops(runs, 2, bend)
    row_loops(runs, 3, starts)
    row_loops(runs, 4, offsets)
    if len(height) == 0:
        chords = np.zeros((3, k))
    else:
        chords = np.empty((3, kk))
        row_loops(chords, 0, height)
        row_loops(chords, 1, lo)
        row_loops(chords, 2, hi)
    return keel, runs, chords


def row_loops(out, row, values):
    """``values`` into the start of ``out``'s row ``row``, NaN beyond them."""
    n = len(values)
    for i in range(n):
        out[row, i] = values[i]
    for i in range(n, out.shape[1]):
        out[row, i] = np.nan
