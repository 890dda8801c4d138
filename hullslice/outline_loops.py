"""The outline of the exact cut's sections by loops, written for a compiler: numba's, when
installed (compiled by :func:`hullslice.planecut_loops.compiled`, which holds them by name).

:func:`outline_loops` is :meth:`hullslice.kernel.outline.Outline.of` on
:func:`~hullslice.planecut_loops.cut_loops`'s contours as they come (one array of points,
the rings' starts and stations), with the same sums in the same order and numpy's stable
order of the edges (:func:`stable_order_loops`): the same outline.
"""

from __future__ import annotations

import numpy as np

#: 1, unsigned: an index from memory unsigned is not tested for a negative value at each
#: use (see :data:`hullslice.contour_loops.U0`).
U1 = np.uint64(1)

__all__ = ["hinted_loops", "key_loops", "outline_cut_loops", "outline_loops",
           "stable_order_loops", "unkey_loops"]  # fmt: skip

#: Order keys: a double's bits as a signed integer, with its magnitude's bits flipped where
#: it is negative, compare as the double does (finite ones; -0.0 just below +0.0). The
#: compiler turns running minima and maxima of integers into vector instructions, of
#: doubles not (a third of the time of :func:`outline_loops`' one pass).
MAG = np.int64(0x7FFFFFFFFFFFFFFF)
#: An order key's exponent bits all set: the double is not finite.
EXP = np.int64(0x7FF0000000000000)
#: The lowest and highest order keys.
K_LO, K_HI = np.int64(-0x7FFFFFFFFFFFFFFF - 1), MAG


def outline_loops(points, ring_start, ring_station, n_st, tol, scale, oy, oz, cap, hint):
    """:meth:`hullslice.kernel.outline.Outline.of` of the exact cut's contours as
    :func:`~hullslice.planecut_loops.cut_loops` gives them (``points``, ``ring_start``,
    ``ring_station``; the rings grouped by station), each point divided by ``scale``
    (unless 1) and moved by ``(oy, oz)`` (unless both are 0): the same arithmetic in the
    same order, the same arrays. A station with a hole (a clockwise contour) needs the
    containment tests of numpy's path: then ``ok`` is False and nothing else is
    meaningful.

    ``cap`` (one height a station, m, after the move) keeps of a station's edges those
    whose lower end is below it, in their order (all where it is infinite): the edges
    the wetted properties read with the water at that height or lower, in the order they
    read them. The sections' own figures (areas, extremes, chines) are of all its edges.

    Returns ``(ok, station, ya, za, yb, zb, zlo, start, area, contour, part_area,
    part_station, part_zmax, part_ymin, part_ymax, zmin, ymin, ymax, z_chine)``, the
    edges in their final order (by station, then by the height of their lower end: the
    order of numpy's stable sort, found by :func:`stable_order_loops`).

    ``hint`` (integers, at least one) holds an order found before (an earlier pitch's of
    the same stations): its count ``hint[0]``, then the edges. Where it is this call's
    stable order (:func:`hinted_loops` checks it) it is taken instead of sorting. It is
    updated to this call's order where that fits (else ``hint[0]`` is -1); ``[-1]`` is
    no hint.
    """
    n = ring_start[-1]
    r = len(ring_station)
    a = moved_loops(points, n, scale, oy, oz)
    # the edges kept (below their station's cap), in their order, counted by station (the
    # outline's ``start``); the edges' arrays are written for those only (the rest reads no
    # other)
    b = np.empty((n, 2))
    station = np.empty(n, dtype=np.int64)
    contour = np.empty(n, dtype=np.int64)
    zlo = np.empty(n)
    area = np.zeros(n_st)
    c_area = np.zeros(r)
    zmin = np.full(n_st, np.inf)
    ymin = np.full(n_st, np.inf)
    ymax = np.full(n_st, -np.inf)
    part_station = np.empty(r, dtype=np.int64)
    part_zmax = np.full(r, -np.inf)
    part_ymin = np.full(r, np.inf)
    part_ymax = np.full(r, -np.inf)
    order = np.empty(n, dtype=np.int64)
    kept = np.zeros(n_st + 1, dtype=np.int64)
    m = 0
    # every edge's lower end's lowest and highest (numpy's min and max: NaN if one is)
    lo_all, hi_all, nan_seen = np.inf, -np.inf, False
    grouped = True  # the rings' stations ascending: each station's edges one run
    for j in range(r):
        st = ring_station[j]
        if j > 0 and st < ring_station[j - 1]:
            grouped = False
        sum_st = area[st]
        sum_c = c_area[j]
        top = cap[st]
        every = top == np.inf
        m0 = m
        # the minima and maxima ring by ring, as numpy's np.minimum and np.maximum take
        # them point by point (the second on a tie, a NaN kept)
        part_station[j] = st
        lo_z, lo_y, hi_y = zmin[st], ymin[st], ymax[st]
        p_z, p_lo, p_hi = part_zmax[j], part_ymin[j], part_ymax[j]
        i0, i1 = np.uint64(ring_start[j]), np.uint64(ring_start[j + 1])  # unsigned (U1)
        for i in range(i0, i1):
            k = i + U1 if i + U1 < i1 else i0
            y, z = a[i, 0], a[i, 1]
            yn, zn = a[k, 0], a[k, 1]
            cross = y * zn - yn * z
            sum_st += 0.5 * cross
            sum_c += cross
            zl = z if (z < zn or z != z) else zn
            if zl != zl:
                nan_seen = True
            else:
                lo_all = zl if zl < lo_all else lo_all
                hi_all = zl if zl > hi_all else hi_all
            if every or zl < top:
                order[m] = i
                m += 1
                b[i, 0] = yn
                b[i, 1] = zn
                station[i] = st
                contour[i] = j
                zlo[i] = zl
            if not (lo_z < z or lo_z != lo_z):
                lo_z = z
            if not (lo_y < y or lo_y != lo_y):
                lo_y = y
            if not (hi_y > y or hi_y != hi_y):
                hi_y = y
            if not (p_z > z or p_z != p_z):
                p_z = z
            if not (p_lo < y or p_lo != p_lo):
                p_lo = y
            if not (p_hi > y or p_hi != p_hi):
                p_hi = y
        area[st] = sum_st
        c_area[j] = sum_c
        zmin[st], ymin[st], ymax[st] = lo_z, lo_y, hi_y
        part_zmax[j], part_ymin[j], part_ymax[j] = p_z, p_lo, p_hi
        kept[st + 1] += m - m0
    ok = True
    for j in range(r):
        c_area[j] = 0.5 * c_area[j]
        if not c_area[j] > 0.0:
            ok = False
    z_chine = np.full(n_st, np.inf)
    for j in range(r):
        s = ring_station[j]
        low, y_lo, y_hi = z_chine[s], ymin[s] + tol, ymax[s] - tol
        for i in range(np.uint64(ring_start[j]), np.uint64(ring_start[j + 1])):
            if a[i, 0] >= y_hi or a[i, 0] <= y_lo:
                if not (low < a[i, 1] or low != low):
                    low = a[i, 1]
        z_chine[s] = low
    order = order[:m]
    for s in range(n_st):
        kept[s + 1] += kept[s]
    lo, hi = (np.nan, np.nan) if nan_seen else (lo_all, hi_all)
    order = edge_order_loops(order, station, zlo, kept, lo, hi, grouped, hint)
    n = m
    ya, za, yb, zb = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    o_station, o_zlo, o_contour = np.empty(n, np.int64), np.empty(n), np.empty(n, np.int64)
    for i in range(n):
        k = np.uint64(order[i])
        o_station[i] = station[k]
        ya[i], za[i], yb[i], zb[i] = a[k, 0], a[k, 1], b[k, 0], b[k, 1]
        o_zlo[i] = zlo[k]
        o_contour[i] = contour[k]
    return (
        ok, o_station, ya, za, yb, zb, o_zlo, kept, area, o_contour, c_area,
        part_station, part_zmax, part_ymin, part_ymax, zmin, ymin, ymax, z_chine,
    )  # fmt: skip


def moved_loops(points, n, scale, oy, oz):
    """The first ``n`` points divided by ``scale`` (unless 1) and moved by ``(oy, oz)``
    (unless both are 0), in loops over flat arrays that the compiler turns into vector
    instructions (a division a coordinate is most of their cost)."""
    a = np.empty((n, 2))
    flat_a = a.reshape(2 * n)
    flat_p = np.ascontiguousarray(points[:n]).reshape(2 * n)
    if scale != 1.0:
        for j in range(2 * n):
            flat_a[j] = flat_p[j] / scale
    else:
        for j in range(2 * n):
            flat_a[j] = flat_p[j]
    if oy != 0.0 or oz != 0.0:
        for i in range(n):
            a[i, 0] += oy
            a[i, 1] += oz
    return a


def edge_order_loops(order, station, zlo, kept, lo, hi, grouped, hint):
    """The kept edges ``order`` sorted by station, then by their lower end's height
    ``zlo`` (over the edges' lowest ``lo`` and highest ``hi``), as numpy's stable sort of
    one key orders them; ``kept`` counts them by station, ``grouped`` says each station's
    are one run. From ``hint`` where it holds that order, which is updated to it (see
    :func:`outline_loops`)."""
    m = len(order)
    if m:
        key = np.empty(len(zlo))  # the kept edges' keys (no other is read)
        scale_z = (hi - lo) * (1.0 + 1e-9) + 1e-300
        for j in range(m):
            i = order[j]
            key[i] = 2.0 * station[i] + (zlo[i] - lo) / scale_z
        if not (grouped and (hinted_loops(key, order, hint)
                             or stable_order_loops(key, kept, order))):  # fmt: skip
            sub = np.empty(m)
            for j in range(m):
                sub[j] = key[order[j]]
            order = order[np.argsort(sub, kind="mergesort")]
    hint[0] = m if len(hint) > m else -1  # this call's order, for the next
    if len(hint) > m:
        for j in range(m):
            hint[j + 1] = order[j]
    return order


def hinted_loops(key, order, hint):
    """Whether the order ``hint[1:]`` (of ``hint[0]`` edges) is numpy's stable sort by
    ``key`` of the edges ``order`` (ascending): the same edges, each once, their keys
    ascending and equal keys in ascending edge order (no NaN). Where it is, ``order``
    takes it."""
    m = len(order)
    if hint[0] != m or len(hint) <= m or m == 0:
        return False
    mark = np.zeros(len(key), dtype=np.bool_)
    for j in range(m):
        mark[order[j]] = True
    for j in range(m):
        i = hint[j + 1]
        if i < 0 or i >= len(key) or not mark[i]:
            return False
        mark[i] = False  # each edge once
    for j in range(1, m):
        a, b = hint[j], hint[j + 1]
        if not (key[a] < key[b] or (key[a] == key[b] and a < b)):
            return False
    for j in range(m):
        order[j] = hint[j + 1]
    return True


def stable_order_loops(key, start, order):
    """``order`` (indices into ``key``, ascending) sorted within each group ``start[g] ..
    start[g + 1] - 1`` by ``key``, ties in their first order: numpy's stable sort of the
    group. A natural merge sort: a section's edges come as a few runs of rising or falling
    height around its contours, so this takes a few passes where a full sort takes
    log2(n); the keys move with the indices (one load fewer on the merge's critical path).
    Returns False, leaving ``order`` unusable, where a key is NaN (numpy's sort puts those
    last)."""
    n = len(order)
    for i in range(n):
        if key[order[i]] != key[order[i]]:
            return False
    run = np.empty(n + 1, dtype=np.int64)  # the runs' starts (and the end)
    kv = np.empty(n)  # the keys in the order's order
    tmp = np.empty(n, dtype=np.int64)
    tk = np.empty(n)
    for g in range(len(start) - 1):
        lo, hi = start[g], start[g + 1]
        if hi - lo < 2:
            continue
        for i in range(lo, hi):
            kv[i] = key[order[i]]
        n_run = 0
        i = lo
        while i < hi:
            run[n_run] = i
            n_run += 1
            j = i + 1
            if j < hi and kv[j] < kv[j - 1]:  # strictly falling: reversed, still stable
                while j < hi and kv[j] < kv[j - 1]:
                    j += 1
                p, q = i, j - 1
                while p < q:
                    order[p], order[q] = order[q], order[p]
                    kv[p], kv[q] = kv[q], kv[p]
                    p += 1
                    q -= 1
            else:
                while j < hi and kv[j] >= kv[j - 1]:
                    j += 1
            i = j
        run[n_run] = hi
        while n_run > 1:  # merge neighbouring runs, the left one first on a tie
            m = 0
            for r in range(0, n_run, 2):
                if r + 1 >= n_run:
                    run[m] = run[r]
                    m += 1
                    continue
                p, mid, end = run[r], run[r + 1], run[r + 2]
                for t in range(p, mid):
                    tmp[t] = order[t]
                    tk[t] = kv[t]
                q, w, u = mid, p, p
                while u < mid and q < end:
                    if kv[q] < tk[u]:
                        order[w] = order[q]
                        kv[w] = kv[q]
                        q += 1
                    else:
                        order[w] = tmp[u]
                        kv[w] = tk[u]
                        u += 1
                    w += 1
                while u < mid:
                    order[w] = tmp[u]
                    kv[w] = tk[u]
                    u += 1
                    w += 1
                run[m] = p
                m += 1
            run[m] = hi
            n_run = m
    return True


def key_loops(v):
    """The order key of the double ``v`` (see :data:`MAG`)."""
    b = np.empty(1)
    b[0] = v
    k = b.view(np.int64)[0]
    return k ^ ((k >> 63) & MAG)


def unkey_loops(k):
    """The double of the order key ``k`` (the map is its own inverse)."""
    b = np.empty(1, dtype=np.int64)
    b[0] = k ^ ((k >> 63) & MAG)
    return b.view(np.float64)[0]


def below_key_loops(t):
    """The key a finite double's is below where it is below ``t`` (none for NaN)."""
    if t != t:
        return K_LO
    return np.int64(-1) if t == 0.0 else key_loops(t)  # -0.0's key where t is a zero


def above_key_loops(t):
    """The key a finite double's is at most where it is at most ``t`` (not NaN)."""
    return np.int64(0) if t == 0.0 else key_loops(t)  # +0.0's key where t is a zero


def outline_cut_loops(points, ring_start, ring_station, ring_area, n_st, tol, scale, oy, oz,
                      cap, hint):  # fmt: skip
    """:func:`outline_loops` of the exact cut's contours (the same arguments), with
    ``ring_area`` each contour's shoelace sum in the cutter's frame as
    :func:`~hullslice.contour_loops.points_loops` gives it: the same arrays, but for the
    areas, taken from those sums (a contour's half its sum over the scale squared, a
    station's the sum of its contours'), the same as :func:`outline_loops`' sums of the
    moved points but for rounding (within about 1e-15 of the area). The extremes, the
    chines and the edges kept are found by their order keys (:data:`MAG`), in passes the
    compiler turns into vector instructions: the same values (a zero's sign aside, which
    :func:`outline_loops` takes from the points' order: it serves where an extreme is a
    zero, and where a point is not finite)."""
    n = ring_start[-1]
    r = len(ring_station)
    a = moved_loops(points, n, scale, oy, oz)
    bits = a.reshape(2 * n).view(np.int64)
    ky, kz = np.empty(n, dtype=np.int64), np.empty(n, dtype=np.int64)
    bad = False
    for i in range(n):
        by, bz = bits[2 * i], bits[2 * i + 1]
        bad = bad | ((by & EXP) == EXP) | ((bz & EXP) == EXP)
        ky[i] = by ^ ((by >> 63) & MAG)
        kz[i] = bz ^ ((bz >> 63) & MAG)
    if bad:
        return outline_loops(points, ring_start, ring_station, n_st, tol, scale, oy, oz, cap,
                             hint)  # fmt: skip
    # each contour's extremes, and its edges' lower ends' highest (for the order's key)
    r_ext = np.empty((5, r), dtype=np.int64)  # y lowest, y highest, z lowest, z highest
    for j in range(r):
        i0, i1 = ring_start[j], ring_start[j + 1]
        last = i1 - 1
        y_lo, y_hi, z_lo, z_hi = ky[last], ky[last], kz[last], kz[last]
        e_hi = min(kz[last], kz[i0])  # the closing edge's lower end
        yy, zz, zn = ky[i0:last], kz[i0:last], kz[i0 + 1 : i1]
        for i in range(len(yy)):
            y, z = yy[i], zz[i]
            y_lo = min(y, y_lo)
            y_hi = max(y, y_hi)
            z_lo = min(z, z_lo)
            z_hi = max(z, z_hi)
            e_hi = max(min(z, zn[i]), e_hi)
        r_ext[0, j], r_ext[1, j], r_ext[2, j], r_ext[3, j], r_ext[4, j] = (y_lo, y_hi, z_lo,
                                                                           z_hi, e_hi)  # fmt: skip
    s_ext = np.empty((3, n_st), dtype=np.int64)  # by station: y lowest, y highest, z lowest
    for st in range(n_st):
        s_ext[0, st], s_ext[1, st], s_ext[2, st] = K_HI, K_LO, K_HI
    lo_k, hi_k = K_HI, K_LO  # every edge's lower end's lowest and highest
    zero = False
    part_station = np.empty(r, dtype=np.int64)
    part_zmax, part_ymin, part_ymax = np.empty(r), np.empty(r), np.empty(r)
    for j in range(r):
        st = ring_station[j]
        part_station[j] = st
        s_ext[0, st] = min(s_ext[0, st], r_ext[0, j])
        s_ext[1, st] = max(s_ext[1, st], r_ext[1, j])
        s_ext[2, st] = min(s_ext[2, st], r_ext[2, j])
        lo_k, hi_k = min(lo_k, r_ext[2, j]), max(hi_k, r_ext[4, j])
        part_zmax[j] = unkey_loops(r_ext[3, j])
        part_ymin[j] = unkey_loops(r_ext[0, j])
        part_ymax[j] = unkey_loops(r_ext[1, j])
        zero = zero or part_zmax[j] == 0.0 or part_ymin[j] == 0.0 or part_ymax[j] == 0.0
    zmin, ymin, ymax = np.full(n_st, np.inf), np.full(n_st, np.inf), np.full(n_st, -np.inf)
    for st in range(n_st):
        if s_ext[1, st] != K_LO:  # a station with a contour
            ymin[st], ymax[st] = unkey_loops(s_ext[0, st]), unkey_loops(s_ext[1, st])
            zmin[st] = unkey_loops(s_ext[2, st])
            zero = zero or zmin[st] == 0.0 or ymin[st] == 0.0 or ymax[st] == 0.0
    # the chines: the lowest of a station's points within tol of its widest
    inf_k = key_loops(np.inf)
    low = np.full(n_st, inf_k)
    for j in range(r):
        st = ring_station[j]
        k_hi = below_key_loops(ymax[st] - tol)  # y >= ymax - tol
        k_lo = above_key_loops(ymin[st] + tol)  # y <= ymin + tol
        lo = low[st]
        yy, zz = ky[ring_start[j] : ring_start[j + 1]], kz[ring_start[j] : ring_start[j + 1]]
        for i in range(len(yy)):
            y = yy[i]
            lo = min(lo, zz[i] if (y >= k_hi) | (y <= k_lo) else inf_k)
        low[st] = lo
    z_chine = np.empty(n_st)
    for st in range(n_st):
        z_chine[st] = unkey_loops(low[st])
        zero = zero or z_chine[st] == 0.0
    if zero:  # a zero's sign: the order of the points decides it
        return outline_loops(points, ring_start, ring_station, n_st, tol, scale, oy, oz, cap,
                             hint)  # fmt: skip
    c_area = np.empty(r)
    area = np.zeros(n_st)
    sq = scale * scale
    ok = True
    for j in range(r):
        c_area[j] = 0.5 * (ring_area[j] / sq)
        area[ring_station[j]] += c_area[j]
        if not c_area[j] > 0.0:
            ok = False
    # the edges kept (lower end below the cap), in their order, counted by station
    station = np.empty(n, dtype=np.int64)
    contour = np.empty(n, dtype=np.int64)
    zlo = np.empty(n)
    order = np.empty(n, dtype=np.int64)
    kept = np.zeros(n_st + 1, dtype=np.int64)
    m = 0
    grouped = True  # the rings' stations ascending: each station's edges one run
    for j in range(r):
        st = ring_station[j]
        if j > 0 and st < ring_station[j - 1]:
            grouped = False
        t_key = below_key_loops(cap[st])
        i0, i1 = ring_start[j], ring_start[j + 1]
        last = i1 - 1
        zz, zn, sel = kz[i0:last], kz[i0 + 1 : i1], order[m:]
        q = 0
        for i in range(len(zz)):  # each edge written, the count moved where it is kept
            sel[q] = i0 + i
            q += min(zz[i], zn[i]) < t_key
        sel[q] = last
        q += min(kz[last], kz[i0]) < t_key
        for p in range(m, m + q):
            i = order[p]
            k = i + 1 if i < last else i0
            station[i] = st
            contour[i] = j
            z, z_n = a[i, 1], a[k, 1]
            zlo[i] = z if (z < z_n or z != z) else z_n
        m += q
        kept[st + 1] += q
    order = order[:m]
    for st in range(n_st):
        kept[st + 1] += kept[st]
    lo, hi = unkey_loops(lo_k), unkey_loops(hi_k)
    order = edge_order_loops(order, station, zlo, kept, lo, hi, grouped, hint)
    ya, za, yb, zb = np.empty(m), np.empty(m), np.empty(m), np.empty(m)
    o_station, o_zlo, o_contour = np.empty(m, np.int64), np.empty(m), np.empty(m, np.int64)
    for p in range(m):
        i = order[p]
        j = contour[i]
        k = i + 1 if i + 1 < ring_start[j + 1] else ring_start[j]
        o_station[p] = station[i]
        ya[p], za[p], yb[p], zb[p] = a[i, 0], a[i, 1], a[k, 0], a[k, 1]
        o_zlo[p] = zlo[i]
        o_contour[p] = j
    return (
        ok, o_station, ya, za, yb, zb, o_zlo, kept, area, o_contour, c_area,
        part_station, part_zmax, part_ymin, part_ymax, zmin, ymin, ymax, z_chine,
    )  # fmt: skip
