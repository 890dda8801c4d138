"""The wetted properties of an outline's sections, written for a compiler: numba's, when
installed (see :mod:`hullslice.planecut_loops`, which compiles them).

:func:`wetted_loops` does in one pass per station what
:func:`hullslice.kernel.wetted.wetted_properties` does with numpy for the ``wedge`` and
``waterline-slope`` estimators: the edges below each station's water, the wetted pieces
(the waterline's intervals inside the body, by a running winding count over the crossings
sorted along the waterline, stably), the parts under water altogether, each edge's piece,
each piece's keel, half-beams, slopes and share of the mass. The arithmetic is the same,
operation by operation and in the same order (sums in the same sequence, stable sorts),
so the results are the same (a division by zero gives numpy's infinity or NaN: numba
compiles it with ``error_model="numpy"``; a minimum or a maximum is numpy's, the second
value on a tie and a NaN kept); the deadrise's arctangent is left to numpy. It runs as
plain Python too on numpy's scalars (slowly: the tests compare it with numpy).
"""

from __future__ import annotations

import numpy as np

from .slices_loops import side_tan_loops

__all__ = ["wetted_loops"]


def wetted_loops(
    station, ya, za, yb, zb, zlo, start, area, contour, part_area, part_station, part_zmax,
    part_ymin, part_ymax, z_chine, level, tol, slope_estimator,
):  # fmt: skip
    """The wetted properties of an outline's sections (its arrays, as
    :class:`~hullslice.kernel.outline.Outline` holds them), each station ``s`` with the
    water at ``level[s]``; ``slope_estimator``: the deadrise by the waterline's slope
    (``waterline-slope``), else by the equivalent wedge.

    Returns the entries (one per wetted piece, or one per dry station, by station):
    ``(station, wet, penetration, half_beam, half_beam_port, half_beam_stbd, tan_mean,
    tan_port, tan_stbd, y_keel, part_half_beam, mass_share, chine_wetted)``; the
    tangents, the keel and the part's half-beam NaN for a dry station.
    """
    n_st = len(area)
    n_parts = len(part_area)
    # the edges reaching below each station's water: a prefix of its edges
    n_below = 0
    count = np.zeros(n_st, dtype=np.int64)
    for s in range(n_st):
        for i in range(start[s], start[s + 1]):
            if zlo[i] < level[s]:
                count[s] += 1
        n_below += count[s]
    # arrays of one length and type as rows of one block: one allocation each
    e_ints = np.empty((2, n_below), dtype=np.int64)
    e_idx, e_st = e_ints[0], e_ints[1]
    k = 0
    for s in range(n_st):
        for i in range(start[s], start[s] + count[s]):
            e_idx[k] = i
            e_st[k] = s
            k += 1
    e_flt = np.empty((2, n_below))
    ea, eb = e_flt[0], e_flt[1]
    for k in range(n_below):
        ea[k] = za[e_idx[k]] - level[e_st[k]]
        eb[k] = zb[e_idx[k]] - level[e_st[k]]
    # the crossings of the waterline, station by station (the edges are by station)
    n_cross = 0
    for k in range(n_below):
        if (ea[k] >= 0.0 and eb[k] < 0.0) or (ea[k] < 0.0 and eb[k] >= 0.0):
            n_cross += 1
    c_ints = np.empty((3, n_cross), dtype=np.int64)
    c_st, c_step, c_part = c_ints[0], c_ints[1], c_ints[2]
    c_flt = np.empty((2, n_cross))
    c_y, c_slope = c_flt[0], c_flt[1]
    j = 0
    for k in range(n_below):
        down = ea[k] >= 0.0 and eb[k] < 0.0
        up = ea[k] < 0.0 and eb[k] >= 0.0
        if down or up:
            i = e_idx[k]
            c_y[j] = ya[i] + (0.0 - ea[k]) * (yb[i] - ya[i]) / (eb[k] - ea[k])
            c_slope[j] = abs((eb[k] - ea[k]) / (yb[i] - ya[i]))
            c_st[j] = e_st[k]
            c_step[j] = 1 if down else -1
            c_part[j] = contour[i]
            j += 1
    # sorted by station, then along the waterline (stably: np.lexsort's order)
    order = np.empty(n_cross, dtype=np.int64)
    a = 0
    while a < n_cross:
        b = a
        while b < n_cross and c_st[b] == c_st[a]:
            b += 1
        sub = np.argsort(c_y[a:b], kind="mergesort")
        for t in range(b - a):
            order[a + t] = a + sub[t]
        a = b
    # the pieces: at most one per crossing and one per part under water altogether
    room = n_cross + n_parts
    p_ints = np.empty((2, room), dtype=np.int64)
    ps, part = p_ints[0], p_ints[1]
    p_flt = np.empty((4, room))
    yl, yr, tl, tr = p_flt[0], p_flt[1], p_flt[2], p_flt[3]
    n_o = 0
    n_c = 0
    winding = 0
    for t in range(n_cross):
        o = order[t]
        winding += c_step[o]
        if winding == 1 and c_step[o] == 1:
            ps[n_o] = c_st[o]
            part[n_o] = c_part[o]
            yl[n_o] = c_y[o]
            tl[n_o] = c_slope[o]
            n_o += 1
        elif winding == 0 and c_step[o] == -1:
            if n_c < room:
                yr[n_c] = c_y[o]
                tr[n_c] = c_slope[o]
            n_c += 1
    crossed = np.zeros(n_parts, dtype=np.bool_)
    for t in range(n_cross):
        crossed[c_part[t]] = True
    m = n_o
    for c in range(n_parts):  # parts under water altogether: one piece each
        if not crossed[c] and part_zmax[c] - level[part_station[c]] < 0.0:
            ps[m] = part_station[c]
            yl[m] = part_ymin[c]
            yr[m] = part_ymax[c]
            tl[m] = np.inf
            tr[m] = np.inf
            part[m] = c
            m += 1
    ps, yl, yr, tl, tr, part = ps[:m], yl[:m], yr[:m], tl[:m], tr[:m], part[:m]
    if m > n_o:  # then all by (station, y_left), stably
        o2 = np.argsort(ps, kind="mergesort")
        a = 0
        while a < m:  # within a station, by y_left, stably
            b = a
            while b < m and ps[o2[b]] == ps[o2[a]]:
                b += 1
            key = np.empty(b - a)
            for t in range(b - a):
                key[t] = yl[o2[a + t]]
            sub = np.argsort(key, kind="mergesort")
            grp = o2[a:b].copy()
            for t in range(b - a):
                o2[a + t] = grp[sub[t]]
            a = b
        ps, yl, yr, tl, tr, part = ps[o2], yl[o2], yr[o2], tl[o2], tr[o2], part[o2]
    # each edge's underwater part, and the piece above it
    first = np.zeros(n_st + 1, dtype=np.int64)
    for q in range(m):
        first[ps[q] + 1] += 1
    for s in range(n_st):
        first[s + 1] += first[s]
    n_of_part = np.zeros(n_parts, dtype=np.int64)
    for q in range(m):
        n_of_part[part[q]] += 1
    only = np.full(n_parts, -1, dtype=np.int64)
    for q in range(m):
        if n_of_part[part[q]] == 1:
            only[part[q]] = q
    seg_piece = np.empty(n_below, dtype=np.int64)
    s_flt = np.empty((4, n_below))
    y1, z1, y2, z2 = s_flt[0], s_flt[1], s_flt[2], s_flt[3]
    for k in range(n_below):
        i = e_idx[k]
        s = e_st[k]
        za_c = ea[k] if (ea[k] < 0.0 or ea[k] != ea[k]) else 0.0
        zb_c = eb[k] if (eb[k] < 0.0 or eb[k] != eb[k]) else 0.0
        ya_c, yb_c = ya[i], yb[i]
        if not ea[k] < 0.0 or not eb[k] < 0.0:
            yc = ya[i] + (0.0 - ea[k]) * (yb[i] - ya[i]) / (eb[k] - ea[k])
            if not ea[k] < 0.0:
                ya_c = yc
            if not eb[k] < 0.0:
                yb_c = yc
        y_mid = 0.5 * (ya_c + yb_c)
        piece = first[s] - 1
        for q in range(first[s], first[s + 1]):
            if yl[q] <= y_mid:
                piece = q
        if not (piece >= first[s] and y_mid <= yr[max(piece, 0)]):
            piece = -1
        if m and only[contour[i]] >= 0:
            piece = only[contour[i]]
        seg_piece[k] = piece
        y1[k], z1[k], y2[k], z2[k] = ya_c, za_c, yb_c, zb_c
    # each piece's keel (its lowest point; on a flat bottom the middle of its points there)
    k_flt = np.full((3, m), np.inf)
    zk, lo_y, lo_neg = k_flt[0], k_flt[1], k_flt[2]
    for k in range(n_below):
        q = seg_piece[k]
        if q >= 0:
            lowest = z1[k] if (z1[k] < z2[k] or z1[k] != z1[k]) else z2[k]
            if not (zk[q] < lowest or zk[q] != zk[q]):
                zk[q] = lowest
    for end in range(2):
        for k in range(n_below):
            q = seg_piece[k]
            if q < 0:
                continue
            y, z = (y1[k], z1[k]) if end == 0 else (y2[k], z2[k])
            if z <= zk[q] + tol / 5:
                if not (lo_y[q] < y or lo_y[q] != lo_y[q]):
                    lo_y[q] = y
                if not (lo_neg[q] < -y or lo_neg[q] != lo_neg[q]):
                    lo_neg[q] = -y
    part_width = np.zeros(n_parts)
    for q in range(m):
        part_width[part[q]] += yr[q] - yl[q]
    # the entries: a station's pieces in order, or one dry entry
    n_dry = 0
    for s in range(n_st):
        if first[s + 1] == first[s]:
            n_dry += 1
    n_e = m + n_dry
    o_st = np.empty(n_e, dtype=np.int64)
    o_flags = np.zeros((2, n_e), dtype=np.bool_)
    o_wet, o_chine = o_flags[0], o_flags[1]
    o_flt = np.empty((10, n_e))  # the dry entries' values: 0, 0, 0, 0, NaN x 5, 1
    for r in range(4):
        for j in range(n_e):
            o_flt[r, j] = 0.0
    for r in range(4, 9):
        for j in range(n_e):
            o_flt[r, j] = np.nan
    for j in range(n_e):
        o_flt[9, j] = 1.0
    o_p, o_hb, o_port, o_stbd = o_flt[0], o_flt[1], o_flt[2], o_flt[3]
    o_tm, o_tp, o_ts, o_yk, o_phb = o_flt[4], o_flt[5], o_flt[6], o_flt[7], o_flt[8]
    o_share = o_flt[9]
    e = 0
    for s in range(n_st):
        if first[s + 1] == first[s]:
            o_st[e] = s
            e += 1
            continue
        for q in range(first[s], first[s + 1]):
            yk = 0.5 * (lo_y[q] - lo_neg[q])
            p = -zk[q] if (-zk[q] > 0.0 or zk[q] != zk[q]) else 0.0
            c_port = yr[q] - yk
            c_stbd = yk - yl[q]
            if slope_estimator:
                t_port, t_stbd = tr[q], tl[q]
            else:
                t_port, t_stbd = side_tan_loops(p, c_port), side_tan_loops(p, c_stbd)
            width = yr[q] - yl[q]
            pw = part_width[part[q]]
            frac = width / pw if pw > 0.0 else 1.0
            o_st[e] = s
            o_wet[e] = True
            o_p[e] = p
            o_hb[e] = 0.5 * width
            o_port[e] = c_port
            o_stbd[e] = c_stbd
            o_tm[e] = 2.0 / (1.0 / t_port + 1.0 / t_stbd)
            o_tp[e] = t_port
            o_ts[e] = t_stbd
            o_yk[e] = yk
            o_phb[e] = 0.5 * (part_ymax[part[q]] - part_ymin[part[q]])
            o_share[e] = part_area[part[q]] / area[s] * frac
            o_chine[e] = z_chine[s] - level[s] <= tol
            e += 1
    return (o_st, o_wet, o_p, o_hb, o_port, o_stbd, o_tm, o_tp, o_ts, o_yk, o_phb, o_share, o_chine)
