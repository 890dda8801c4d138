"""The fused evaluation's slices, written for a compiler (see :mod:`hullslice.held_loops`):
the keel line's wetted range, the fixed slices over it and their sections (which station's,
moved how far), then each section's keel, velocity, the curve solver's force, its flags and
the sums, with numpy's arithmetic in numpy's order. Plain Python too (the tests run it)."""

from __future__ import annotations

import math

import numpy as np

from .loops_layout import (  # the layout's names, read from here too
    COLUMNS,
    ENTRY,
    I_CHINE,
    I_CODE,
    I_MOVED,
    I_ROWS,
    I_SLICE,
    I_SOURCE,
    OPTIONS,
    REASON_BITS,
    STATUS,
)

__all__ = ["COLUMNS", "ENTRY", "I_CHINE", "I_CODE", "I_MOVED", "I_ROWS", "I_SLICE", "I_SOURCE",
           "OPTIONS", "REASON_BITS", "STATUS", "finish_loops", "layout_loops",
           "wet_slices_loops", "window_loops"]  # fmt: skip


_X, _DX, _PEN, _HB, _HBP, _HBS, _DR, _DRP, _DRS, _AREA, _MPM, _SLOPE, _KZ, _YK, _PHB = range(15)
_CURV, _VEL, _FPM, _GAM, _ZT, _VT, _AT, _V0, _ACC, _FR, _LIFT = range(15, 26)


def interp_loops(x, xp, fp):
    """``np.interp(x, xp, fp)`` at one ``x``: numpy's own steps (the point's value where
    ``x`` is one, the other end's where a NaN arises)."""
    n = len(xp)
    if x != x:
        return x
    if x < xp[0]:
        return fp[0]
    if x > xp[n - 1]:
        return fp[n - 1]
    j = right_loops(xp, x) - 1  # the largest j with xp[j] <= x
    if j == n - 1 or xp[j] == x:
        return fp[j]
    slope = (fp[j + 1] - fp[j]) / (xp[j + 1] - xp[j])
    y = slope * (x - xp[j]) + fp[j]
    if y != y:
        y = slope * (x - xp[j + 1]) + fp[j + 1]
        if y != y and fp[j] == fp[j + 1]:
            y = fp[j]
    return y


def right_loops(a, x):
    """``np.searchsorted(a, x, side="right")`` for a finite ``x``."""
    lo, hi = 0, len(a)
    while lo < hi:
        mid = (lo + hi) >> 1
        if x >= a[mid]:
            lo = mid + 1
        else:
            hi = mid
    return lo


def left_loops(a, x, lo, hi):
    """``np.searchsorted(a[lo:hi], x, side="left") + lo`` for a finite ``x``."""
    while lo < hi:
        mid = (lo + hi) >> 1
        if a[mid] < x:
            lo = mid + 1
        else:
            hi = mid
    return lo


def left_loops_desc(a, x):
    """The first index of the non-increasing ``a`` whose value is below ``x`` (``len(a)``
    if none is)."""
    lo, hi = 0, len(a)
    while lo < hi:
        mid = (lo + hi) >> 1
        if a[mid] < x:
            hi = mid
        else:
            lo = mid + 1
    return lo


def div_loops(a, b):
    """``a / b`` as numpy divides (an infinity or NaN by zero), in plain Python too."""
    if b != 0.0:
        return a / b
    if a != a or a == 0.0:
        return math.nan
    return math.copysign(math.inf, a) * math.copysign(1.0, b)


def side_tan_loops(p, c):
    """The equivalent wedge's ``tan(beta) = p / c`` of one side (``p`` the penetration,
    ``c`` the side's half-beam from the keel, m), as :func:`hullslice.kernel.wetted.side_tan`
    gives it: a side whose waterline end lies at the keel or behind it (``c <= 0``, the
    keel under an overhang) rises as a wall, ``+inf``; else :func:`div_loops`."""
    if c <= 0.0 and p > 0.0:
        return math.inf
    return div_loops(p, c)


def slope_loops(x, mid, cont, starts, offsets):
    """The keel line's continuous slope at ``x`` (``_Runs.slope``)."""
    s = interp_loops(x, mid, cont)
    if len(starts):
        s = s - offsets[right_loops(starts, x)]
    return s


def runs_of_loops(runs):
    """The keel line's runs from their padded rows: the facet middles, ``C`` and ``B``
    there, the runs' starts and offsets."""
    nf = int(runs.shape[1])
    n_starts = 0
    while n_starts < nf and runs[3, n_starts] == runs[3, n_starts]:
        n_starts += 1
    n_mid = 0
    while n_mid < nf and runs[0, n_mid] == runs[0, n_mid]:
        n_mid += 1
    return (runs[0, :n_mid], runs[1, :n_mid], runs[2, :n_mid], runs[3, :n_starts],
            runs[4, : n_starts + 1])  # fmt: skip


def crossing_loops(kx, kz, i, level):
    """Where the keel line's segment ``i``, ``i + 1`` meets the level (``KeelLine.below``'s
    ``crossing``): an end of a gap's segment where the other is infinitely high."""
    if not math.isfinite(kz[i]):
        return kx[i + 1]
    if not math.isfinite(kz[i + 1]):
        return kx[i]
    t = (level - kz[i]) / (kz[i + 1] - kz[i])
    return kx[i] + t * (kx[i + 1] - kx[i])


def extent_loops(keel, level):
    """``KeelLine.bottom(level)``: ``(status, x0, x1)``, status 0, or 1 (dry) or 7 (the end
    faces walked out of the line)."""
    kx, kz, steep = keel[0], keel[1], keel[2]
    nk = len(kx)
    # the first and last break points under the level: where the keel line's running
    # minimum from either end (keel[3], keel[4]; non-increasing, non-decreasing) passes it
    first = left_loops_desc(keel[3], level)
    if first >= nk:
        return 1, 0.0, 0.0
    last = left_loops(keel[4], level, 0, nk) - 1
    lo = crossing_loops(kx, kz, first - 1, level) if first > 0 else kx[0]
    hi = crossing_loops(kx, kz, last, level) if last < nk - 1 else kx[nk - 1]
    lo = min(lo, kx[first])
    hi = max(hi, kx[last])
    b_lo, b_hi = lo, hi
    nst = nk - 1
    i = min(max(right_loops(kx, lo) - 1, 0), nst - 1)
    if kx[i] < lo:
        while steep[i] > 0.0 and kx[i + 1] < hi:
            lo, i = kx[i + 1], i + 1
            if i >= nst:
                return 7, 0.0, 0.0
    j = min(max(left_loops(kx, hi, 0, nk) - 1, 0), nst - 1)
    if hi < kx[j + 1]:
        while steep[j] > 0.0 and kx[j] > lo:
            hi, j = kx[j], j - 1
            if j < 0:
                return 7, 0.0, 0.0
    if not hi > lo:
        lo, hi = b_lo, b_hi
    return 0, lo, hi


def wet_slices_loops(keel, level, n):
    """The first and last of the ``n`` fixed slices the water wets at ``level`` (-1 for
    none): ``(status, k0, k1)``, status as :func:`extent_loops`'s."""
    status, x0, x1 = extent_loops(keel, level)
    if status != 0:
        return status, 0, 0
    kx = keel[0]
    xa = kx[0]
    d = (kx[len(kx) - 1] - xa) / n
    k_first = -1
    k_last = -1
    for k in range(min(max(int((x0 - xa) // d), 0), n - 1),
                   min(max(int((x1 - xa) // d), 0), n - 1) + 1):  # fmt: skip
        if min(xa + (k + 1) * d, x1) > max(xa + k * d, x0):
            if k_first < 0:
                k_first = k
            k_last = k
    return 0, k_first, k_last


def window_loops(keel, level, n):
    """The fixed stations an evaluation needs at the water's height ``level`` (``n``
    slices): ``(status, w0, w1)``, the wetted slices' and one on either side."""
    status, k_first, k_last = wet_slices_loops(keel, level, n)
    if status != 0:
        return status, 0, 0
    return 0, max(k_first - 1, 0), min(k_last + 2, n)


def layout_loops(fout, iout, opts, keel, runs, station_vals, e0, f0):
    """The slices of the wetted range (``fixed_sections``): each one's thickness, place,
    source station (of the kept cut) and lift, and whether it takes its source moved to
    its depth (``iout[I_MOVED]`` 1), or, with no wetted station near it (the first
    contact), is cut where it is: status 5, or with ``opts``' ``fresh`` marked 2 for the
    caller to cut (see :func:`hullslice.held_loops.pitch_loops`). ``e0`` holds the
    window's entries at the water's height, station ``s``'s from row ``f0[s]`` (see
    :func:`finish_loops`). Returns ``(status, m)``: 0 and the slice count, or a status of
    :data:`STATUS`."""
    level = opts[0]
    n, c0 = int(opts[6]), int(opts[7])
    end_face, steep_slope = opts[21], opts[22]
    status, x0, x1 = extent_loops(keel, level)
    if status != 0:
        return status, 0
    kx, kz = keel[0], keel[1]
    nk = len(kx)
    xa = kx[0]
    d = (kx[nk - 1] - xa) / n
    k_a = min(max(int((x0 - xa) // d), 0), n - 1)
    k_b = min(max(int((x1 - xa) // d), 0), n - 1)
    m = 0
    k_first = -1
    for k in range(k_a, k_b + 1):
        s_lo = max(xa + k * d, x0)
        s_hi = min(xa + (k + 1) * d, x1)
        if s_hi > s_lo:
            if k_first < 0:
                k_first = k
            fout[_DX, m] = s_hi - s_lo
            fout[_X, m] = 0.5 * (s_lo + s_hi)  # a partial slice's middle
            iout[I_SOURCE, m] = k
            m += 1
    mid, cont, _, starts, offsets = runs_of_loops(runs)
    for i in range(m):
        k = iout[I_SOURCE, i]
        width = fout[_DX, i]
        mid_k = xa + (k + 0.5) * d
        iout[I_MOVED, i] = 0
        fout[_LIFT, i] = 0.0
        if abs(width - d) <= 1e-12 * d:  # a full slice: its own station's section
            fout[_X, i] = mid_k
            continue
        x = fout[_X, i]
        inward = 1 if k == k_first else -1
        neighbour = min(max(k + inward, 0), n - 1)
        own = math.isfinite(station_vals[0, k - c0])
        if own:
            own = abs(slope_loops(mid_k, mid, cont, starts, offsets)) <= end_face
        source = k if own else neighbour
        depth = interp_loops(x, kx, kz) - station_vals[0, source - c0]
        # fresh: neither the slice's station nor its neighbour wetted at this level (no
        # entry of either with a penetration), or moved more steeply than 45 deg
        fresh = True
        for t in (k - c0, neighbour - c0):
            for j in range(f0[t], f0[t + 1]):
                fresh = fresh and not e0[j, 2] > 0.0
        if abs(depth) > steep_slope * abs(x - (xa + (source + 0.5) * d)):
            fresh = True
        if fresh:  # marked for the caller to cut where it is (opts' fresh), else numpy's
            if opts[24] > 0.0:
                iout[I_MOVED, i] = 2
                continue
            return 5, 0
        if not math.isfinite(level - depth):
            return 6, 0
        iout[I_SOURCE, i] = source
        iout[I_MOVED, i] = 1
        fout[_LIFT, i] = depth
    return 0, m


def finish_loops(fout, iout, scal, opts, keel, runs, chords, station_vals, e0, f0, e1, g1, m,
                 a_c, v_c):  # fmt: skip
    """From the slices' entries to the sections (``assemble``), their velocities, the curve
    solver's force, the flags and the sums (``evaluate``, ``ForceResult``): a slice's
    entries are its kept station's at the water's height, ``e0[f0[s]:f0[s + 1]]`` for
    station ``s`` (from the window's first), or, for a moved slice ``i`` or one cut
    afresh, its own, ``e1[g1[i]:g1[i + 1]]`` (one cut afresh, ``iout[I_MOVED]`` 2, takes
    its own section's area from ``fout``'s area column); one row each (a wetted piece of
    the section, or its dry
    entry), the rows of a slice one after another, the slices in order, as numpy's path
    lists them. Returns 0, 6 (a keel point faster than sound, a non-finite mass, a
    non-finite force or sum of forces: numpy's path names them in its errors) or 8 (more
    rows than ``fout`` has columns)."""
    level, w, u, q = opts[0], opts[1], opts[2], opts[3]
    x_cg, frame_x_cg = opts[4], opts[5]
    n, c0 = int(opts[6]), int(opts[7])
    density = opts[11]
    rho_ratio, rho_curves, g, froude_min = opts[12], opts[13], opts[14], opts[15]
    z_lo, z_hi, keel_window, sound = opts[16], opts[17], opts[18], opts[19]
    min_deadrise, end_face, steep_slope = opts[20], opts[21], opts[22]
    has_chords = opts[23] > 0.0
    kx, kz = keel[0], keel[1]
    nk = len(kx)
    mid, cont, bend, starts, offsets = runs_of_loops(runs)
    n_mid = len(mid)
    d = (kx[nk - 1] - kx[0]) / n
    n_rows = 0
    for i in range(m):
        s = iout[I_SOURCE, i] - c0
        n_rows += g1[i + 1] - g1[i] if iout[I_MOVED, i] > 0 else f0[s + 1] - f0[s]
    if n_rows > fout.shape[1] or n_rows > iout.shape[1]:
        return 8
    # the slices as layout_loops left them (their columns are written over by the rows)
    s_x, s_dx, s_lift = fout[_X, :m].copy(), fout[_DX, :m].copy(), fout[_LIFT, :m].copy()
    s_src, s_moved = iout[I_SOURCE, :m].copy(), iout[I_MOVED, :m].copy()
    s_area = fout[_AREA, :m].copy()  # a slice cut afresh: its own section's area (2 moved)
    total = 0.0
    total_x = 0.0
    moment = 0.0
    size = 0.0
    z_cg = -level
    r = 0
    for i in range(m):
        s = s_src[i] - c0
        moved = s_moved[i] > 0
        width = s_dx[i]
        x = s_x[i]
        lift = s_lift[i]
        keel_z = interp_loops(x, kx, kz)
        # assemble: the keel's chord and curvature, the mass per metre
        chord_w = max(width, 0.5 * d)
        slope = slope_loops(x, mid, cont, starts, offsets)
        if has_chords:
            jc = min(max(right_loops(kx, x) - 1, 0), nk - 2)
            h = min(0.5 * chord_w, x - chords[1, jc])
            h = min(h, chords[2, jc] - x)
            if h > 0.0:
                e_hi = interp_loops(x + h, kx, chords[0])
                e_lo = interp_loops(x - h, kx, chords[0])
                slope = (e_hi - e_lo) / (h + h)
        window = max(width, keel_window)
        curv = 0.0
        if n_mid >= 2:
            curv = (interp_loops(x + window / 2, mid, bend)
                    - interp_loops(x - window / 2, mid, bend)) / window  # fmt: skip
        if not math.isfinite(keel_z):
            keel_z = level
        area = s_area[i] if s_moved[i] == 2 else station_vals[2, s]
        keel_at = keel_z + z_cg
        x_earth = x + frame_x_cg
        # the section's penetration velocity (forces.kinematics.section_velocity)
        arm_x = x_earth - x_cg
        arm_z = keel_at - z_cg
        up = w + q * arm_x
        forward = u - q * arm_z
        vel = up - forward * slope
        if not math.hypot(up, forward) < sound:
            return 6
        if moved:
            entries, j0, j1 = e1, g1[i], g1[i + 1]
        else:
            entries, j0, j1 = e0, f0[s], f0[s + 1]
        for j in range(j0, j1):
            ent = entries[j]
            pen = ent[2]
            deadrise = ent[6]
            chine = ent[12] > 0.0
            mpm = density * area * ent[11]
            fout[_X, r] = x_earth
            fout[_DX, r] = width
            fout[_LIFT, r] = lift
            fout[_PEN, r] = pen
            fout[_HB, r] = ent[3]
            fout[_HBP, r] = ent[4]
            fout[_HBS, r] = ent[5]
            fout[_DR, r] = deadrise
            fout[_DRP, r] = ent[7]
            fout[_DRS, r] = ent[8]
            fout[_AREA, r] = area
            fout[_MPM, r] = mpm
            fout[_SLOPE, r] = slope
            fout[_KZ, r] = keel_at
            fout[_YK, r] = ent[9]
            fout[_PHB, r] = ent[10]
            fout[_CURV, r] = curv
            fout[_VEL, r] = vel
            iout[I_SOURCE, r] = s
            iout[I_MOVED, r] = 1 if moved else 0
            iout[I_SLICE, r] = i
            iout[I_CHINE, r] = 1 if chine else 0
            # evaluate(): which sections the solver is given, and the flags
            code = 0
            wet = pen > 0.0
            if wet and not math.isfinite(mpm):
                return 6
            massless = wet and mpm <= 0.0
            face = wet and abs(slope) > end_face
            solved = wet and not massless and not face
            flat = solved and not (deadrise >= min_deadrise)
            force = 0.0
            for c in range(_GAM, _FR + 1):
                fout[c, r] = np.nan
            if solved:
                beta = min_deadrise if flat else deadrise
                tb = math.tan(beta)
                gam = -0.0114 * (beta * (180.0 / math.pi)) + 1.5669
                m_eq = mpm * rho_ratio
                root_m = math.sqrt(m_eq)
                zt = div_loops(-pen * gam, root_m * tb)
                vt = v_c[len(v_c) - 1] + zt * 0.0
                for kc in range(len(v_c) - 2, -1, -1):
                    vt = v_c[kc] + vt * zt
                at_ = a_c[len(a_c) - 1] + zt * 0.0
                for kc in range(len(a_c) - 2, -1, -1):
                    at_ = a_c[kc] + at_ * zt
                v0 = div_loops(vel, vt)
                acc = div_loops(div_loops(at_ * (v0 * v0), root_m) * gam, tb)
                force = mpm * (acc + g) if vel < 0.0 else 0.0
                z_star = math.sqrt(2.0 * m_eq / (5.0 * math.pi * rho_curves * (gam * gam))) * tb
                froude = div_loops(abs(5.0 / 6.0 * v0), math.sqrt(g * z_star))
                fout[_GAM, r] = gam
                fout[_ZT, r] = zt
                fout[_VT, r] = vt
                fout[_AT, r] = at_
                fout[_V0, r] = v0
                fout[_ACC, r] = acc
                fout[_FR, r] = froude
                if zt < z_lo or zt > z_hi:
                    code |= 1
                if vt <= 0.0:
                    code |= 2
                if vel >= 0.0:
                    code |= 4
                if froude <= froude_min:
                    code |= 8
            if massless:
                code |= 16
            if face:
                code |= 32
            if flat:
                code |= 64
            if chine and not face:
                code |= 128
            if solved and abs(slope) > steep_slope:
                code |= 256
            iout[I_CODE, r] = code
            fout[_FPM, r] = force
            if not math.isfinite(force):  # numpy's path refuses the solver's output
                return 6
            # the sums of forces.result.ForceResult
            f = force * width
            size += abs(f)
            fx = -f * slope
            total += f
            total_x += fx
            moment += arm_x * f - (0.5 * keel_at - z_cg) * fx
            r += 1
    if not (math.isfinite(total) and math.isfinite(size)):  # numpy's path refuses them
        return 6
    # KeelLine.wet_length(level, x0, x1)
    _, x0, x1 = extent_loops(keel, level)
    length = 0.0  # facets outside [x0, x1] add nothing (clipped to no length)
    for i in range(max(right_loops(kx, x0) - 2, 0), min(left_loops(kx, x1, 0, nk) + 1, nk - 1)):
        a = min(max(kx[i], x0), x1)
        b = min(max(kx[i + 1], x0), x1)
        za, zb = kz[i], kz[i + 1]
        if not (math.isfinite(za) and math.isfinite(zb) and b > a):
            continue
        xl, xr = kx[i], kx[i + 1]
        t = 1.0 / (xr - xl) if xr > xl else 0.0
        ha = za + (zb - za) * (a - xl) * t
        hb = za + (zb - za) * (b - xl) * t
        under_a = ha < level
        under_b = hb < level
        cross = (level - ha) / (hb - ha) if hb != ha else 0.0
        span = b - a
        if under_a and under_b:
            wl = span
        elif under_a:
            wl = cross * span
        elif under_b:
            wl = (1.0 - cross) * span
        else:
            wl = 0.0
        length += min(max(wl, 0.0), span)
    scal[0] = n_rows
    scal[1] = length
    scal[2] = total
    scal[3] = total_x
    scal[4] = moment
    scal[5] = x0
    scal[6] = x1
    return 0
