"""A held pitch's force evaluation in one pass, written for a compiler: numba's, when
installed (:mod:`hullslice.planecut_loops` compiles it by the name ``"held"``).

At a held pitch with fixed slicing the stations are cut once and their wetted properties
come from a waterline table (:mod:`hullslice.slicing.fixed`); what is left at each
evaluation is some 150 small numpy operations over the slices: the keel line's wetted
range, the slices and their entries in the table, the keel's height, chord and curvature,
each section's penetration velocity, the curve solver's force (:mod:`hullslice.solvers.karman`)
and the checks that flag a section, the force's sums. :func:`held_loops` does them all in
one loop over the slices, with the same arithmetic in the same order as numpy's path, so
that both give the same numbers (the tests compare them to 1e-12); compiled, an evaluation
costs a few microseconds. Wherever numpy's path would take a turn that is not written here
(a slice that is cut afresh at the first contact, a station the kept cut or the table does
not hold, an interval of the table marked inexact, a keel moving faster than sound,
dry water), it returns a status that sends the evaluation back to that path.

The glue that chooses it and builds the results is :mod:`hullslice.forces.fused`.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["COLUMNS", "OPTIONS", "REASON_BITS", "STATUS", "held_loops"]

#: The float columns of the per-slice output ``fout``, by name.
COLUMNS = (
    "x", "dx", "penetration", "half_beam", "half_beam_port", "half_beam_stbd", "deadrise",
    "deadrise_port", "deadrise_stbd", "area", "mass_per_metre", "keel_slope", "keel_z",
    "y_keel", "part_half_beam", "keel_curvature", "velocity", "force_per_metre", "gamma",
    "z_tilde", "v_tilde", "a_tilde", "v_z0", "acceleration", "froude", "lift",
)  # fmt: skip
#: The integer columns of ``iout``: each slice's source station (of the kept cut), its
#: chine flag (0 or 1) and its reason code (bits of :data:`REASON_BITS`).
I_SOURCE, I_CHINE, I_CODE = 0, 1, 2
#: The entries of the options array ``opts``, by name.
OPTIONS = (
    "level", "w", "u", "q", "x_cg", "frame_x_cg", "n", "c0", "n_cut", "tol", "top",
    "density", "rho_ratio", "rho_curves", "g", "froude_min", "z_lo", "z_hi", "keel_window",
    "sound", "min_deadrise", "end_face", "steep", "has_chords",
)  # fmt: skip
#: Why a section is flagged, as bits in the order the reasons are joined: the curve
#: solver's own four checks, then a section without mass, then the checks of
#: :func:`hullslice.forces.evaluate.evaluate` (a face, a flat bottom, the chine, steep).
REASON_BITS = ("z_range", "v_tilde", "not_down", "froude", "massless", "face", "flat",
               "chine", "steep")  # fmt: skip
#: What :func:`held_loops` returns: 0 when it did the evaluation, else why numpy's path must.
STATUS = {
    0: "done",
    1: "dry: the keel is nowhere under the water",
    2: "a station outside the kept cut",
    3: "the water above the table's top (or a moved slice's)",
    4: "an inexact interval of the table",
    5: "a slice cut afresh (the first contact)",
    6: "a keel point faster than sound, or a non-finite value",
    7: "the keel line's end faces walk out of its range",
}

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
    lo, hi = 0, n  # the largest j with xp[j] <= x
    while lo < hi:
        mid = (lo + hi) >> 1
        if x >= xp[mid]:
            lo = mid + 1
        else:
            hi = mid
    j = lo - 1
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


def slope_loops(x, mid, cont, starts, offsets):
    """The keel line's continuous slope at ``x`` (``_Runs.slope``)."""
    s = interp_loops(x, mid, cont)
    if len(starts):
        s = s - offsets[right_loops(starts, x)]
    return s


def held_loops(fout, iout, scal, opts, keel, runs, chords, heights, tkey, tvals, station_vals,
               a_c, v_c):  # fmt: skip
    """Evaluate the force of a held pitch's fixed slices at the water's height ``level``.

    ``opts`` holds the scalars of :data:`OPTIONS`. ``keel`` is the keel line (5, k): its
    break points ``x``, heights ``z``, its steep facets (1 or 0, the first k - 1), and the
    running minimum of ``z`` from the first point and from the last (``inf`` in a gap);
    ``runs`` its runs (5, f): the facet middles, the continuous slope ``C`` and the
    bottom's turn ``B`` there, then the runs' starts and offsets (padded with NaN);
    ``chords`` (3, k) the bottom's rise and each facet's run's ends (when ``has_chords``).
    The waterline table: ``heights`` its heights (sorted), ``tkey`` (4, ...) its break
    points' keys, each station's first break point and first interval and each interval's
    first entry (padded); ``tvals`` (e, 12) each entry's wet flag, keel height, the three
    affine quantities' intercepts and slopes, the three constant ones (``y_keel``,
    ``part_half_beam``, ``mass_share``) and whether its interval is exact;
    ``station_vals`` (3, s) the kept stations' lowest point, chine height and area;
    ``a_c``, ``v_c`` the curves' coefficients (ascending).

    Writes each slice's columns (:data:`COLUMNS`) into ``fout`` (26, n) and ``iout`` (3, n),
    and ``scal``: the slice count, the wetted length, the vertical force (N), the
    horizontal force (N), the moment (N m) and the wetted range's ends ``x0``, ``x1``;
    with status 3, the height the table must reach (``scal[7]``).
    Returns 0, or a status of :data:`STATUS` for numpy's path.
    """
    level, w, u, q = opts[0], opts[1], opts[2], opts[3]
    x_cg, frame_x_cg = opts[4], opts[5]
    n, c0, n_cut = int(opts[6]), int(opts[7]), int(opts[8])
    tol, top, density = opts[9], opts[10], opts[11]
    rho_ratio, rho_curves, g, froude_min = opts[12], opts[13], opts[14], opts[15]
    z_lo, z_hi, keel_window, sound = opts[16], opts[17], opts[18], opts[19]
    min_deadrise, end_face, steep_slope = opts[20], opts[21], opts[22]
    has_chords = opts[23] > 0.0
    kx, kz = keel[0], keel[1]
    nk = len(kx)
    nf = int(runs.shape[1])
    mid, cont, bend = runs[0], runs[1], runs[2]
    steep = keel[2]
    n_starts = 0
    while n_starts < nf and runs[3, n_starts] == runs[3, n_starts]:
        n_starts += 1
    starts = runs[3, :n_starts]
    offsets = runs[4, : n_starts + 1]
    n_mid = 0
    while n_mid < nf and mid[n_mid] == mid[n_mid]:
        n_mid += 1
    mid, cont, bend = mid[:n_mid], cont[:n_mid], bend[:n_mid]
    # -- KeelLine.below(level), then bottom(): the wetted range without end faces
    # the first and last break points under the level: where the keel line's running
    # minimum from either end (keel[3], keel[4]; non-increasing, non-decreasing) passes it
    first = left_loops_desc(keel[3], level)
    if first >= nk:
        return 1
    last = left_loops(keel[4], level, 0, nk) - 1
    if first > 0:
        i = first - 1
        if not math.isfinite(kz[i]):
            lo = kx[i + 1]
        elif not math.isfinite(kz[i + 1]):
            lo = kx[i]
        else:
            t = (level - kz[i]) / (kz[i + 1] - kz[i])
            lo = kx[i] + t * (kx[i + 1] - kx[i])
    else:
        lo = kx[0]
    if last < nk - 1:
        i = last
        if not math.isfinite(kz[i]):
            hi = kx[i + 1]
        elif not math.isfinite(kz[i + 1]):
            hi = kx[i]
        else:
            t = (level - kz[i]) / (kz[i + 1] - kz[i])
            hi = kx[i] + t * (kx[i + 1] - kx[i])
    else:
        hi = kx[nk - 1]
    lo = min(lo, kx[first])
    hi = max(hi, kx[last])
    b_lo, b_hi = lo, hi
    nst = nk - 1
    i = min(max(right_loops(kx, lo) - 1, 0), nst - 1)
    if kx[i] < lo:
        while steep[i] > 0.0 and kx[i + 1] < hi:
            lo, i = kx[i + 1], i + 1
            if i >= nst:
                return 7
    j = min(max(left_loops(kx, hi, 0, nk) - 1, 0), nst - 1)
    if hi < kx[j + 1]:
        while steep[j] > 0.0 and kx[j] > lo:
            hi, j = kx[j], j - 1
            if j < 0:
                return 7
    if not hi > lo:
        lo, hi = b_lo, b_hi
    x0, x1 = lo, hi
    # -- fixed_sections: the slices of the wetted range
    xa = kx[0]
    d = (kx[nk - 1] - xa) / n
    k_a = min(max(int((x0 - xa) // d), 0), n - 1)
    k_b = min(max(int((x1 - xa) // d), 0), n - 1)
    m = 0
    k_first = -1
    k_last = -1
    for k in range(k_a, k_b + 1):
        s_lo = max(xa + k * d, x0)
        s_hi = min(xa + (k + 1) * d, x1)
        if s_hi > s_lo:
            if k_first < 0:
                k_first = k
            k_last = k
            fout[_DX, m] = s_hi - s_lo
            fout[_X, m] = 0.5 * (s_lo + s_hi)  # a partial slice's middle, for now
            iout[I_SOURCE, m] = k
            m += 1
    w0 = max(k_first - 1, 0)
    w1 = min(k_last + 2, n)
    if w0 < c0 or w1 > c0 + n_cut:
        return 2
    if level > top:
        scal[7] = level
        return 3
    n_h = len(heights)
    rank = left_loops(heights, level, 0, n_h)
    bp_key, bp_start, v_start, e_start = tkey[0], tkey[1], tkey[2], tkey[3]
    # each window station's table entry at this level; stations are the kept cut's
    for k in range(w0, w1):
        s = k - c0
        key = s * (n_h + 1) + rank
        jv = left_loops(bp_key, key, bp_start[s], bp_start[s + 1]) - bp_start[s]
        e = e_start[v_start[s] + jv]
        if tvals[e, 11] <= 0.0:
            return 4
    total = 0.0
    total_x = 0.0
    moment = 0.0
    z_cg = -level
    need = -math.inf  # the highest water a moved slice needs above the table's top
    for i in range(m):
        k = iout[I_SOURCE, i]
        width = fout[_DX, i]
        full = abs(width - d) <= 1e-12 * d
        mid_k = xa + (k + 0.5) * d
        x = mid_k if full else fout[_X, i]
        keel_z = interp_loops(x, kx, kz)
        source = k
        depth = 0.0
        lift = 0.0
        if not full:
            inward = 1 if k == k_first else -1
            neighbour = min(max(k + inward, 0), n - 1)
            own = math.isfinite(station_vals[0, k - c0])
            if own:
                own = abs(slope_loops(mid_k, mid, cont, starts, offsets)) <= end_face
            source = k if own else neighbour
            depth = keel_z - station_vals[0, source - c0]
            # fresh: neither the slice's station nor its neighbour wetted at this level
            wet_k = False
            wet_n = False
            for kk in (k, neighbour):
                s = kk - c0
                key = s * (n_h + 1) + rank
                jv = left_loops(bp_key, key, bp_start[s], bp_start[s + 1]) - bp_start[s]
                e = e_start[v_start[s] + jv]
                p_kk = max(-(tvals[e, 1] - level), 0.0)
                if kk == k:
                    wet_k = p_kk > 0.0
                else:
                    wet_n = p_kk > 0.0
            fresh = not wet_k and not wet_n
            mid_src = xa + (source + 0.5) * d
            if abs(depth) > steep_slope * abs(x - mid_src):
                fresh = True
            if fresh:
                return 5
            lift = depth
        at = level - lift
        if not math.isfinite(at):
            return 6
        if at > top:
            need = max(need, at)
            continue
        s = source - c0
        r_at = left_loops(heights, at, 0, n_h)
        key = s * (n_h + 1) + r_at
        jv = left_loops(bp_key, key, bp_start[s], bp_start[s + 1]) - bp_start[s]
        e = e_start[v_start[s] + jv]
        if tvals[e, 11] <= 0.0:
            return 4
        hb = tvals[e, 2] + tvals[e, 5] * at
        hbp = tvals[e, 3] + tvals[e, 6] * at
        hbs = tvals[e, 4] + tvals[e, 7] * at
        pen = max(-(tvals[e, 1] - at), 0.0)
        t_port = div_loops(pen, hbp)
        t_stbd = div_loops(pen, hbs)
        t_mean = div_loops(2.0, div_loops(1.0, t_port) + div_loops(1.0, t_stbd))
        chine = (station_vals[1, s] - at <= tol) and tvals[e, 0] > 0.0
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
        area = station_vals[2, s]
        mpm = density * area * tvals[e, 10]
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
        deadrise = math.atan(t_mean)
        fout[_X, i] = x_earth
        fout[_PEN, i] = pen
        fout[_HB, i] = hb
        fout[_HBP, i] = hbp
        fout[_HBS, i] = hbs
        fout[_DR, i] = deadrise
        fout[_DRP, i] = math.atan(t_port)
        fout[_DRS, i] = math.atan(t_stbd)
        fout[_AREA, i] = area
        fout[_MPM, i] = mpm
        fout[_SLOPE, i] = slope
        fout[_KZ, i] = keel_at
        fout[_YK, i] = tvals[e, 8]
        fout[_PHB, i] = tvals[e, 9]
        fout[_CURV, i] = curv
        fout[_VEL, i] = vel
        fout[_LIFT, i] = lift
        iout[I_SOURCE, i] = source - c0
        iout[I_CHINE, i] = 1 if chine else 0
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
            fout[c, i] = np.nan
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
            fout[_GAM, i] = gam
            fout[_ZT, i] = zt
            fout[_VT, i] = vt
            fout[_AT, i] = at_
            fout[_V0, i] = v0
            fout[_ACC, i] = acc
            fout[_FR, i] = froude
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
        iout[I_CODE, i] = code
        fout[_FPM, i] = force
        # the sums of forces.result.ForceResult
        f = force * width
        fx = -f * slope
        total += f
        total_x += fx
        moment += arm_x * f - (0.5 * keel_at - z_cg) * fx
    if need > top:
        scal[7] = need
        return 3
    # KeelLine.wet_length(level, x0, x1)
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
        hb2 = za + (zb - za) * (b - xl) * t
        under_a = ha < level
        under_b = hb2 < level
        cross = (level - ha) / (hb2 - ha) if hb2 != ha else 0.0
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
    scal[0] = m
    scal[1] = length
    scal[2] = total
    scal[3] = total_x
    scal[4] = moment
    scal[5] = x0
    scal[6] = x1
    return 0
