"""The exact plane cut's loops, written for a compiler (numba's, compiled by
:mod:`hullslice.planecut_loops`), and its memo of crossed edges.

A cut is made in two passes. :func:`recipe_loops` finds what a station's plane crosses:
the sign test on the candidate faces, the segments' successors and each contour's order,
kept as each contour point's edge (its two ends, in the edge's canonical order, as body
coordinates), the *recipe*. :func:`points_loops` computes the points from a recipe at a
pitch and stations: one crossing point per edge, from the end nearer the plane, repeated
points dropped and contours with no area discarded. :func:`cut_loops
<hullslice.planecut_loops.cut_loops>` is the two in turn.

Where no vertex has changed side of a station's plane since its recipe was made, the
plane crosses the same edges in the same order, and the recipe gives the points of a
fresh cut, to the last bit (the same arithmetic on the same numbers).
:func:`memo_cut_loops` serves each station so where that is shown, and cuts the others
afresh. Between two pitches a vertex's distance to a plane changes by at most
``|dc| |r_x| + |ds| |r_z| + |dx|`` (the change of the pitch's cosine and sine, and of the
station's place). It is shown:

* for the faces outside the station's candidate ranges, by their distance when the recipe
  was made: at least the *gap* along ``x`` from the index's sorted faces to the plane;
* for the candidate faces, by their nearest vertex's distance when that is larger than
  the change anywhere on the body, or else face by face: by the face's own nearest
  vertex's distance where that is larger, and by the sign test on the face again (its
  side code compared with the recipe's) where not. On a fine mesh a station's nearest
  vertex is nearly always close to its plane, a face's seldom: on the 1M-face fuselage of
  the benchmark, one candidate in 140 is tested again.
"""

from __future__ import annotations

import math

import numpy as np

from .index_loops import range_loops

#: Unsigned index constants: numba tests a signed index from memory for a negative value at
#: each use (to count from the end), an unsigned one not (an eighth of the cut's time).
U0, U1, U2, U3, U6 = (np.uint64(v) for v in (0, 1, 2, 3, 6))
#: How far :func:`memo_cut_loops` widens a fresh station's candidate ranges, as a share of
#: the index's key span (four times the body's size): a thousandth of the size, so that the
#: faces out of them are that far from the plane, and the recipe serves while no vertex
#: has moved by as much.
MEMO_WIDTH = 2.5e-4


def recipe_loops(
    first, last, corners, ends, x_rel, gx, gz, c, s, slot, k_out_of, k_in_of, xmin, bin_start,
    bin_zlo, bin_zhi, bin_reach,
):  # fmt: skip
    """The recipe of the contours of the candidate faces of each station ``i``, the faces
    ``first[i, j] .. last[i, j] - 1`` of each bin ``j``, cut by the planes ``x_rel`` at a
    pitch (``c``, ``s``: its cosine and sine) about ``(gx, gz)`` (see
    :func:`~hullslice.planecut_loops.cut_loops` for the other arguments).

    Returns ``(ends6, ring_len, st_p, st_q, near, gap, reach, codes, code_near, code_p,
    status)``:
    each contour point's edge ends, ``x y z`` of its canonical first end then of its second
    (``(6, p)``, a row a coordinate, contour by contour, each from its lowest segment),
    each contour's length, each station's first point and first contour (and the ends);
    each station's nearest candidate vertex's distance to its plane (m), the gap along
    ``x`` from its plane to the faces out of its ranges (m; -inf where ``xmin``, the
    index's faces' lowest ``x``, is empty) and the largest ``|x - gx|`` of its plane over
    the bins' heights (m); each candidate face's side code (bit ``k`` set for corner ``k``
    ahead), station by station in range order, and its nearest corner's distance to the
    plane (m), each station's first code (and the end); and 0, or 1 where the mesh is not
    closed along a cut.
    """
    n_st, n_bins = first.shape
    q = 0
    for i in range(n_st):
        for j in range(n_bins):
            q += max(last[i, j] - first[i, j], 0)
    seg_station = np.empty(q, dtype=np.int64)
    seg_face = np.empty(q, dtype=np.int64)
    seg_ab = np.empty(q, dtype=np.int64)
    e_out = np.empty(q, dtype=np.int64)
    e_in = np.empty(q, dtype=np.int64)
    near_d = np.empty(n_st)
    codes = np.empty(q, dtype=np.int8)
    code_near = np.empty(q)
    code_p = np.zeros(n_st + 1, dtype=np.int64)
    n = 0
    n_c = 0
    for st in range(n_st):
        xs = x_rel[st]
        near = math.inf
        for b in range(n_bins):
            for f in range(np.uint64(first[st, b]), np.uint64(last[st, b])):
                d0 = (corners[f, 0] - gx) * c - (corners[f, 3] - gz) * s - xs
                d1 = (corners[f, 1] - gx) * c - (corners[f, 4] - gz) * s - xs
                d2 = (corners[f, 2] - gx) * c - (corners[f, 5] - gz) * s - xs
                dm = min(abs(d0), abs(d1), abs(d2))
                near = min(near, dm)
                code = (d0 >= 0.0) + 2 * (d1 >= 0.0) + 4 * (d2 >= 0.0)
                codes[n_c] = code
                code_near[n_c] = dm
                n_c += 1
                if code == 0 or code == 7:
                    continue
                ko = np.uint64(k_out_of[code])  # unsigned, as the face (see U0)
                kn = ko + U1 if ko != U2 else U0
                e_out[n] = ends[f, U3 + ko]
                e_in[n] = ends[f, U3 + np.uint64(k_in_of[code])]
                if ends[f, ko] > ends[f, kn]:  # the edge's canonical order: by vertex number
                    seg_ab[n] = 3 * kn + ko
                else:
                    seg_ab[n] = 3 * ko + kn
                seg_face[n] = f
                seg_station[n] = st
                n += 1
        near_d[st] = near
        code_p[st + 1] = n_c
    gaps = np.full(n_st, -math.inf)
    reach = np.zeros(n_st)
    if len(xmin) > 0:  # every face out of the ranges: as far as the bin's sorted lowest x allow
        for st in range(n_st):
            xs = x_rel[st]
            gap = math.inf
            far = 0.0
            for b in range(n_bins):
                xa = gx + (xs + (bin_zlo[b] - gz) * s) / c
                xb = gx + (xs + (bin_zhi[b] - gz) * s) / c
                far = max(far, abs(xa - gx), abs(xb - gx))
                if last[st, b] < bin_start[b + 1]:  # the faces after: all ahead
                    gap = min(gap, xmin[last[st, b]] - max(xa, xb))
                if first[st, b] > bin_start[b]:  # the faces before: all behind
                    gap = min(gap, min(xa, xb) - bin_reach[b] - xmin[first[st, b] - 1])
            gaps[st] = gap
            reach[st] = far
    # successors, station by station: the segment leaving from the edge each one enters
    succ = np.empty(n, dtype=np.int64)
    status = 0
    a = 0
    while a < n:
        b = a
        while b < n and seg_station[b] == seg_station[a]:
            b += 1
        for j in range(a, b):
            slot[e_out[j]] = j
        for j in range(a, b):
            k = slot[e_in[j]]
            if k < a or k >= b or e_out[k] != e_in[j]:
                status = 1
                k = j
            succ[j] = k
        a = b
    # the contours, each from its lowest segment (grouped by station, as the segments)
    ends6 = np.empty((6, n))  # a row a coordinate: the points' loops run along them
    ring_len = np.empty(n, dtype=np.int64)
    st_p = np.zeros(n_st + 1, dtype=np.int64)
    st_q = np.zeros(n_st + 1, dtype=np.int64)
    seen = np.zeros(n, dtype=np.bool_)
    n_p = 0
    n_ring = 0
    for j0 in range(n):
        if seen[j0]:
            continue
        j = j0
        length = 0
        while not seen[j]:
            seen[j] = True
            f = np.uint64(seg_face[j])
            ka = np.uint64(seg_ab[j] // 3)
            kb = np.uint64(seg_ab[j] - 3 * (seg_ab[j] // 3))
            ends6[0, n_p] = corners[f, ka]
            ends6[1, n_p] = corners[f, U6 + ka]
            ends6[2, n_p] = corners[f, U3 + ka]
            ends6[3, n_p] = corners[f, kb]
            ends6[4, n_p] = corners[f, U6 + kb]
            ends6[5, n_p] = corners[f, U3 + kb]
            n_p += 1
            length += 1
            j = succ[j]
        ring_len[n_ring] = length
        n_ring += 1
        st = seg_station[j0]
        st_p[st + 1] += length
        st_q[st + 1] += 1
    for st in range(n_st):
        st_p[st + 1] += st_p[st]
        st_q[st + 1] += st_q[st]
    return (ends6, ring_len[:n_ring].copy(), st_p, st_q, near_d, gaps, reach, codes[:n_c].copy(),
            code_near[:n_c].copy(), code_p, status)  # fmt: skip


def points_loops(ends6, ring_len, st_p, st_q, k0, x_rel, gx, gz, c, s, m, merge):
    """The contours of the recipe's stations ``k0``, ``k0 + 1``, ... cut by the planes
    ``x_rel`` at a pitch (``c``, ``s``) about ``(gx, gz)``, mapped by ``m`` (2 x 4) to the
    cutter's ``(Y, Z)``: each point from its edge's end nearer the plane, consecutive points
    closer than ``merge`` along both axes one, contours of fewer than three points or no
    area left out. Returns ``(points, ring_start, ring_station, ring_area)`` as
    :func:`~hullslice.planecut_loops.cut_loops` (stations counted from ``k0``):
    ``ring_area`` each kept contour's shoelace sum (twice its area in the cutter's
    frame), the sum its test of an area takes."""
    n_st = len(x_rel)
    p0, p1 = st_p[k0], st_p[k0 + n_st]
    q0 = st_q[k0]
    n_rings = st_q[k0 + n_st] - q0
    m00, m01, m02, m03 = m[0, 0], m[0, 1], m[0, 2], m[0, 3]
    m10, m11, m12, m13 = m[1, 0], m[1, 1], m[1, 2], m[1, 3]
    # each point's y and z, in loops the compiler turns into vector instructions: the
    # recipe's ends a row a coordinate, a station's points slices of them, the nearer end
    # chosen by selects, not branches
    py, pz = np.empty(p1 - p0), np.empty(p1 - p0)
    for i in range(n_st):
        xs = x_rel[i]
        a, b = st_p[k0 + i], st_p[k0 + i + 1]
        xa_, wa_, ha_ = ends6[0, a:b], ends6[1, a:b], ends6[2, a:b]
        xb_, wb_, hb_ = ends6[3, a:b], ends6[4, a:b], ends6[5, a:b]
        out_y, out_z = py[a - p0 : b - p0], pz[a - p0 : b - p0]
        for q in range(b - a):
            xa, wa, ha = xa_[q], wa_[q], ha_[q]
            xb, wb, hb = xb_[q], wb_[q], hb_[q]
            da = (xa - gx) * c - (ha - gz) * s - xs
            db = (xb - gx) * c - (hb - gz) * s - xs
            ya = m00 * xa + m01 * wa + m02 * ha + m03
            za = m10 * xa + m11 * wa + m12 * ha + m13
            yb = m00 * xb + m01 * wb + m02 * hb + m03
            zb = m10 * xb + m11 * wb + m12 * hb + m13
            near = abs(da) <= abs(db)  # from the nearer end: t = d0 / (d0 - d1)
            d0 = da if near else db
            d1 = db if near else da
            y0 = ya if near else yb
            y1 = yb if near else ya
            z0 = za if near else zb
            z1 = zb if near else za
            t = d0 / (d0 - d1)
            out_y[q] = y0 + t * (y1 - y0)
            out_z[q] = z0 + t * (z1 - z0)
    out = np.empty((p1 - p0, 2))
    ring_start = np.empty(n_rings + 1, dtype=np.int64)
    ring_station = np.empty(n_rings, dtype=np.int64)
    ring_area = np.empty(n_rings)
    kept_at = np.empty(p1 - p0, dtype=np.bool_)  # a contour's points kept
    n_out = 0
    n_ring = 0
    ring_start[0] = 0
    r = q0
    at = 0
    for i in range(n_st):
        for _ in range(st_q[k0 + i + 1] - st_q[k0 + i]):
            length = ring_len[r]
            r += 1
            first = n_out
            if length == 0:
                continue
            # the points kept: each farther than merge from the one before along an axis
            # (the first from the last)
            ys, zs, keep = py[at : at + length], pz[at : at + length], kept_at[:length]
            last = length - 1
            keep[0] = (abs(ys[0] - ys[last]) > merge) | (abs(zs[0] - zs[last]) > merge)
            n_kept = 1 if keep[0] else 0
            y1, y0, z1, z0, keep1 = ys[1:], ys[:last], zs[1:], zs[:last], keep[1:]
            for k in range(last):  # flags and a count first: most contours keep every point
                keep1[k] = (abs(y1[k] - y0[k]) > merge) | (abs(z1[k] - z0[k]) > merge)
                n_kept += keep1[k]
            dest = out[n_out : n_out + n_kept]
            if n_kept == length:  # a copy with no branch
                for k in range(length):
                    dest[k, 0] = ys[k]
                    dest[k, 1] = zs[k]
            else:
                j = 0
                for k in range(length):
                    if keep[k]:
                        dest[j, 0] = ys[k]
                        dest[j, 1] = zs[k]
                        j += 1
            n_out += n_kept
            at += length
            area = shoelace_loops(dest) if n_kept >= 3 else 0.0
            if n_kept >= 3 and area != 0.0:
                ring_station[n_ring] = i
                ring_area[n_ring] = area
                n_ring += 1
                ring_start[n_ring] = n_out
            else:
                n_out = first
    return out[:n_out], ring_start[: n_ring + 1], ring_station[:n_ring], ring_area[:n_ring]


def shoelace_loops(pts):
    """A contour's shoelace sum (twice its area, ``pts`` its (k, 2) points, k >= 3): four
    running sums of its terms, the compiler's vector instructions, where their sum's
    rounding cannot have changed its sign or made it zero; else the sum term by term in
    the points' order, closing last (numpy's ``bincount``), whose zero is what the cut
    tests."""
    y, z = pts[:, 0], pts[:, 1]
    n = len(y) - 1
    y0, y1, z0, z1 = y[:n], y[1:], z[:n], z[1:]
    s0 = s1 = s2 = s3 = 0.0
    a0 = a1 = a2 = a3 = 0.0
    for q in range(n // 4):
        k = 4 * q
        t0 = y0[k] * z1[k] - y1[k] * z0[k]
        t1 = y0[k + 1] * z1[k + 1] - y1[k + 1] * z0[k + 1]
        t2 = y0[k + 2] * z1[k + 2] - y1[k + 2] * z0[k + 2]
        t3 = y0[k + 3] * z1[k + 3] - y1[k + 3] * z0[k + 3]
        s0, s1, s2, s3 = s0 + t0, s1 + t1, s2 + t2, s3 + t3
        a0, a1, a2, a3 = a0 + abs(t0), a1 + abs(t1), a2 + abs(t2), a3 + abs(t3)
    for k in range(n - n % 4, n):
        t0 = y0[k] * z1[k] - y1[k] * z0[k]
        s0, a0 = s0 + t0, a0 + abs(t0)
    close = y[n] * z[0] - y[0] * z[n]
    total = ((s0 + s1) + (s2 + s3)) + close
    size = ((a0 + a1) + (a2 + a3)) + abs(close)
    # each sum within (n + 1) * 2**-53 * size of the terms' exact sum: 1e-15 covers both
    if abs(total) > 1e-15 * (n + 1) * size:
        return total
    total = 0.0
    for k in range(n):
        total += y0[k] * z1[k] - y1[k] * z0[k]
    return total + close


def match_loops(x_rel, c, s, memo, reach_x, reach_z, eps):
    """For each station ``x_rel`` (ascending) at a pitch (``c``, ``s``), the station of the
    ``memo`` (see :func:`memo_cut_loops`; its places ascending) nearest it, where its
    recipe may serve: ``k`` where it serves as it is (no vertex within the body's reach,
    ``reach_x`` and ``reach_z`` from the centre of gravity along ``x`` and ``z``, m, can
    have crossed the plane), ``-2 - k`` where it serves if its candidates' side codes are
    unchanged (the faces out of its ranges cannot have crossed), else -1. ``eps`` (m) is
    rounding's room."""
    st = memo[0]  # a row a figure: place, cosine, sine, nearest vertex, gap, reach
    mx, mc, ms, m_near, m_gap, m_reach = st[0], st[1], st[2], st[3], st[4], st[5]
    n = len(x_rel)
    kn = len(mx)
    src = np.full(n, -1, dtype=np.int64)
    k = 0
    for i in range(n):
        if kn == 0:
            break
        x = x_rel[i]
        while k + 1 < kn and abs(mx[k + 1] - x) <= abs(mx[k] - x):
            k += 1
        dc, ds, dx = abs(c - mc[k]), abs(s - ms[k]), abs(x - mx[k])
        if (mc[k] - dc) * m_gap[k] - dc * m_reach[k] - ds * reach_z - dx <= eps:
            continue
        if dc * reach_x + ds * reach_z + dx < m_near[k] - eps:
            src[i] = k
        else:
            src[i] = -2 - k
    return src


def same_sides_loops(ranges, codes, code_near, at, corners, x, gx, gz, c, s, move, eps):
    """Whether each candidate face of the ranges ``ranges`` (``(bins, 2)``: first, last)
    has the side ``codes[at], codes[at + 1], ...`` of the plane ``x`` at a pitch (``c``,
    ``s``) about ``(gx, gz)``: a face whose nearest corner was farther from the recipe's
    plane (``code_near[at], ...``, m) than ``move`` (the most a vertex's distance to it
    can have changed, m) by more than ``eps`` (rounding's room) has it (as
    :func:`match_loops` shows for a station); the others by the same sign test as
    :func:`recipe_loops`."""
    for b in range(ranges.shape[0]):
        for f in range(np.uint64(ranges[b, 0]), np.uint64(ranges[b, 1])):
            if move < code_near[at] - eps:
                at += 1
                continue
            d0 = (corners[f, 0] - gx) * c - (corners[f, 3] - gz) * s - x
            d1 = (corners[f, 1] - gx) * c - (corners[f, 4] - gz) * s - x
            d2 = (corners[f, 2] - gx) * c - (corners[f, 5] - gz) * s - x
            if (d0 >= 0.0) + 2 * (d1 >= 0.0) + 4 * (d2 >= 0.0) != codes[at]:
                return False
            at += 1
    return True


def memo_cut_loops(
    key, bin_start, bin_zlo, bin_zhi, bin_reach, margin, span, x0, xmin, corners, ends, x_rel,
    gx, gz, c, s, m, merge, slot, k_out_of, k_in_of, guess, g0, memo, reach_x, reach_z,
):  # fmt: skip
    """:func:`~hullslice.planecut_loops.cut_loops` of the stations ``x_rel`` (ascending) at
    a pitch, each station from the thread's ``memo`` where its recipe serves
    (:func:`match_loops`, :func:`same_sides_loops`), the others cut afresh over the plane
    index's ranges (:func:`~hullslice.index_loops.range_loops`; from the ``guess`` of the
    stations ``g0``, ... where all are), widened by :data:`MEMO_WIDTH`. The same points.

    ``memo`` holds seven arrays, by station (ascending, ``n`` of them): ``(6, n)`` its
    place, the cosine and sine of its pitch, its nearest candidate vertex's distance, its
    gap and its plane's reach (see :func:`recipe_loops`); its ranges ``(n, bins, 2)``;
    ``(3, n + 1)`` its first side code, first point and first contour (and the ends); the
    codes; its recipe's edge ends ``(6, p)`` and contour lengths; and each code's face's
    nearest corner's distance. (Seven arrays, not fourteen: each one the call returns
    costs about a third of a microsecond.) Returns
    ``(points, ring_start, ring_station, ring_area, status, memo)`` (the first four as
    :func:`points_loops` gives them), the memo of these stations (the
    one given where it served them all in its order, or the status is not 0). ``margin``
    (m) is rounding's room too."""
    n = len(x_rel)
    src = match_loops(x_rel, c, s, memo, reach_x, reach_z, margin)
    m_st, m_ranges, m_codes, m_ends6, m_ring_len = memo[0], memo[1], memo[3], memo[4], memo[5]
    m_code_p, m_st_p, m_st_q, m_near = memo[2][0], memo[2][1], memo[2][2], memo[6]
    for i in range(n):
        if src[i] <= -2:
            k = -2 - src[i]
            dc, ds, dx = abs(c - m_st[1, k]), abs(s - m_st[2, k]), abs(x_rel[i] - m_st[0, k])
            move = dc * reach_x + ds * reach_z + dx  # as match_loops makes it
            same = same_sides_loops(m_ranges[k], m_codes, m_near, m_code_p[k], corners, x_rel[i],
                                    gx, gz, c, s, move, margin)  # fmt: skip
            src[i] = k if same else -1
    k0 = src[0] if n > 0 else -1
    kept = k0 >= 0
    for i in range(n):
        if src[i] != k0 + i:
            kept = False
            break
    if kept:  # every station from the memo, in its order: the memo as it is
        pts, ring_start, ring_station, ring_area = points_loops(
            m_ends6, m_ring_len, m_st_p, m_st_q, k0, x_rel, gx, gz, c, s, m, merge
        )
        return pts, ring_start, ring_station, ring_area, 0, memo
    n_f = 0
    for i in range(n):
        if src[i] < 0:
            n_f += 1
    x_f = np.empty(n_f)
    j = 0
    for i in range(n):
        if src[i] < 0:
            x_f[j] = x_rel[i]
            j += 1
    wide = margin + MEMO_WIDTH * span
    if n_f == n:
        first, last = range_loops(key, bin_start, bin_zlo, bin_zhi, bin_reach, x_f, gx, gz, c, s,
                                  wide, span, x0, guess, g0)  # fmt: skip
    else:
        first, last = range_loops(key, bin_start, bin_zlo, bin_zhi, bin_reach, x_f, gx, gz, c, s,
                                  wide, span, x0, guess[:0], 0)  # fmt: skip
    fresh = recipe_loops(first, last, corners, ends, x_f, gx, gz, c, s, slot, k_out_of, k_in_of,
                         xmin, bin_start, bin_zlo, bin_zhi, bin_reach)  # fmt: skip
    (f_ends6, f_ring_len, f_st_p, f_st_q, f_near, f_gap, f_reach, f_codes, f_code_near, f_code_p,
     status) = fresh  # fmt: skip
    if status != 0:
        none = np.empty(0, dtype=np.int64)
        return np.empty((0, 2)), none, none, np.empty(0), status, memo
    # the memo of these stations: each one's from the old memo or from the fresh cut
    nb = len(bin_zlo)
    stations = np.empty((6, n))
    place, cos_, sin_ = stations[0], stations[1], stations[2]
    near, gap, reach = stations[3], stations[4], stations[5]
    ranges = np.empty((n, nb, 2), dtype=np.int64)
    offsets = np.zeros((3, n + 1), dtype=np.int64)
    code_p, st_p, st_q = offsets[0], offsets[1], offsets[2]
    j = 0
    for i in range(n):
        k = src[i]
        if k >= 0:
            for row in range(6):
                stations[row, i] = m_st[row, k]
            ranges[i] = m_ranges[k]
            code_p[i + 1] = code_p[i] + m_code_p[k + 1] - m_code_p[k]
            st_p[i + 1] = st_p[i] + m_st_p[k + 1] - m_st_p[k]
            st_q[i + 1] = st_q[i] + m_st_q[k + 1] - m_st_q[k]
        else:
            place[i], cos_[i], sin_[i] = x_f[j], c, s
            near[i], gap[i], reach[i] = f_near[j], f_gap[j], f_reach[j]
            for b in range(nb):
                ranges[i, b, 0], ranges[i, b, 1] = first[j, b], last[j, b]
            code_p[i + 1] = code_p[i] + f_code_p[j + 1] - f_code_p[j]
            st_p[i + 1] = st_p[i] + f_st_p[j + 1] - f_st_p[j]
            st_q[i + 1] = st_q[i] + f_st_q[j + 1] - f_st_q[j]
            j += 1
    codes = np.empty(code_p[n], dtype=np.int8)
    code_near = np.empty(code_p[n])
    ends6 = np.empty((6, st_p[n]))
    ring_len = np.empty(st_q[n], dtype=np.int64)
    j = 0
    for i in range(n):
        k = src[i]
        if k >= 0:
            e6, rl, cd, cn = m_ends6, m_ring_len, m_codes, m_near
            p_a, q_a, c_a = m_st_p[k], m_st_q[k], m_code_p[k]
        else:
            e6, rl, cd, cn = f_ends6, f_ring_len, f_codes, f_code_near
            p_a, q_a, c_a = f_st_p[j], f_st_q[j], f_code_p[j]
            j += 1
        for col in range(6):
            for p in range(st_p[i + 1] - st_p[i]):
                ends6[col, st_p[i] + p] = e6[col, p_a + p]
        for r in range(st_q[i + 1] - st_q[i]):
            ring_len[st_q[i] + r] = rl[q_a + r]
        for r in range(code_p[i + 1] - code_p[i]):
            codes[code_p[i] + r] = cd[c_a + r]
            code_near[code_p[i] + r] = cn[c_a + r]
    pts, ring_start, ring_station, ring_area = points_loops(
        ends6, ring_len, st_p, st_q, 0, x_rel, gx, gz, c, s, m, merge
    )
    new = (stations, ranges, offsets, codes, ends6, ring_len, code_near)
    return pts, ring_start, ring_station, ring_area, 0, new


def empty_memo(bins: int) -> tuple:
    """A memo of no station for an index of ``bins`` height bins (see
    :func:`memo_cut_loops`)."""
    return (np.empty((6, 0)), np.empty((0, bins, 2), dtype=np.int64),
            np.zeros((3, 1), dtype=np.int64), np.empty(0, dtype=np.int8), np.empty((6, 0)),
            np.empty(0, dtype=np.int64), np.empty(0))  # fmt: skip
