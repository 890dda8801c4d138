"""A fixed slicing's force evaluation in one pass, written for a compiler: numba's, when
installed (:mod:`hullslice.planecut_loops` compiles these by the names ``"held"`` and
``"pitch"``).

With fixed slicing the stations of a pitch are cut once and kept, and after a few
evaluations their wetted properties come from a waterline table
(:mod:`hullslice.slicing.fixed`); what is left at each evaluation is some 150 small numpy
operations over the slices: the keel line's wetted range, the slices and their sections,
the keel's height, chord and curvature, each section's penetration velocity, the curve
solver's force (:mod:`hullslice.solvers.karman`), the checks that flag a section, the
force's sums. :func:`held_loops` does them all in one pass, its sections' properties read
from the table; :func:`pitch_loops` does the same at a pitch without a table (every stage
of a free-pitch run), its sections' properties computed afresh by
:func:`hullslice.wetted_loops.wetted_loops` as numpy's path computes them. The slices and
what follows are :mod:`hullslice.slices_loops`'. Each step has numpy's arithmetic in
numpy's order, so that both paths give the same numbers (the tests compare them to
1e-12); compiled, an evaluation costs some microseconds. Wherever numpy's path would take
a turn that is not written here (a slice that is cut afresh at the first contact, a
station the kept cut or the table does not hold, an interval of the table marked
inexact, a section in two wetted pieces, a keel moving faster than sound, dry water),
they return a status that sends the evaluation back to that path.

The glue that chooses them and builds the results is :mod:`hullslice.forces.fused`.
"""

from __future__ import annotations

import math

import numpy as np

from .slices_loops import (
    _AREA,
    _LIFT,
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
    div_loops,
    finish_loops,
    layout_loops,
    left_loops,
    side_tan_loops,
    wet_slices_loops,
    window_loops,
)
from .wetted_loops import wetted_loops

#: The digest of the helpers' sources (``slices_loops.py``, ``wetted_loops.py``, and
#: ``loops_layout.py``, whose tuples the loops read as constants). numba's
#: cache of these loops goes stale when this file changes, not when the helpers' files
#: do: a change of theirs changes this digest too (``tests/test_fused.py`` checks it), so
#: that the cache of :func:`held_loops` and :func:`pitch_loops` is made again.
HELPERS_DIGEST = "1489a7f22ee5a7e3"

__all__ = [
    "COLUMNS",
    "ENTRY",
    "I_CHINE",
    "I_CODE",
    "I_MOVED",
    "I_ROWS",
    "I_SLICE",
    "I_SOURCE",
    "OPTIONS",
    "REASON_BITS",
    "STATUS",
    "held_loops",
    "pitch_entries_loops",
    "pitch_loops",
    "table_entry_loops",
    "table_interval_loops",
]


def table_interval_loops(at, s, heights, tkey):
    """The waterline table's interval of kept station ``s`` with the water at ``at``:
    ``(first, count)``, its first entry and how many it has (``WaterlineTable._evaluate``)."""
    n_h = len(heights)
    bp_key, bp_start, v_start, e_start = tkey[0], tkey[1], tkey[2], tkey[3]
    key = s * (n_h + 1) + left_loops(heights, at, 0, n_h)
    jv = left_loops(bp_key, key, bp_start[s], bp_start[s + 1]) - bp_start[s]
    v = v_start[s] + jv
    return e_start[v], e_start[v + 1] - e_start[v]


def table_entry_loops(e, k, first, count, at, s, tvals, station_vals, tol):
    """The waterline table's entries ``first`` to ``first + count - 1`` (kept station
    ``s``'s interval with the water at ``at``, :func:`table_interval_loops`) in the columns
    of :data:`ENTRY`, into the rows of ``e`` from ``k`` (``WaterlineTable._evaluate``: those
    of a section in several wetted pieces in order along the waterline, stably, as a fresh
    evaluation orders them)."""
    order = np.empty(count if count > 1 else 0)  # the keys along the waterline (0: dry)
    for j in range(count):
        ent = first + j
        row = e[k + j]
        pen = max(-(tvals[ent, 1] - at), 0.0)
        hbp = tvals[ent, 3] + tvals[ent, 6] * at
        hbs = tvals[ent, 4] + tvals[ent, 7] * at
        t_port = side_tan_loops(pen, hbp)
        t_stbd = side_tan_loops(pen, hbs)
        row[0] = tvals[ent, 11]
        row[1] = tvals[ent, 0]
        row[2] = pen
        row[3] = tvals[ent, 2] + tvals[ent, 5] * at
        row[4] = hbp
        row[5] = hbs
        row[6] = math.atan(div_loops(2.0, div_loops(1.0, t_port) + div_loops(1.0, t_stbd)))
        row[7] = math.atan(t_port)
        row[8] = math.atan(t_stbd)
        row[9] = tvals[ent, 8]
        row[10] = tvals[ent, 9]
        row[11] = tvals[ent, 10]
        row[12] = 1.0 if (station_vals[1, s] - at <= tol and tvals[ent, 0] > 0.0) else 0.0
        if count > 1:
            order[j] = row[9] - hbs if tvals[ent, 0] > 0.0 else 0.0
    for j in range(1, count):  # numpy's lexsort of the rows by their keys: stable, NaN last
        key_j = order[j]
        row_j = e[k + j].copy()
        i = j
        while i > 0:
            prev = order[i - 1]
            if not (key_j < prev or (prev != prev and key_j == key_j)):
                break
            order[i] = prev
            e[k + i] = e[k + i - 1]
            i -= 1
        order[i] = key_j
        e[k + i] = row_j


def held_loops(fout, iout, scal, opts, keel, runs, chords, station_vals, heights, tkey,
               tvals, a_c, v_c, e_f, f_f, area_f):  # fmt: skip
    """Evaluate the force of a held pitch's fixed slices at the water's height ``level``,
    their wetted properties from the kept cut's waterline table.

    ``opts`` holds the scalars of :data:`OPTIONS`. ``keel`` is the keel line (5, k): its
    break points ``x``, heights ``z``, its steep facets (1 or 0, the first k - 1), and the
    running minimum of ``z`` from the first point and from the last (``inf`` in a gap);
    ``runs`` its runs (5, f): the facet middles, the continuous slope ``C`` and the
    bottom's turn ``B`` there, then the runs' starts and offsets (padded with NaN);
    ``chords`` (3, k) the bottom's rise and each facet's run's ends (when ``has_chords``);
    ``station_vals`` (3, s) the kept stations' lowest point, chine height and area.
    The waterline table: ``heights`` its heights (sorted), ``tkey`` (4, ...) its break
    points' keys, each station's first break point and first interval and each interval's
    first entry (padded); ``tvals`` (e, 12) each entry's wet flag, keel height, the three
    affine quantities' intercepts and slopes, the three constant ones (``y_keel``,
    ``part_half_beam``, ``mass_share``) and whether its interval is exact. ``a_c``,
    ``v_c``: the curves' coefficients (ascending).

    Writes each slice's columns (:data:`COLUMNS`) into ``fout`` (26, n) and ``iout`` (4, n),
    and ``scal``: the slice count, the wetted length, the vertical force (N), the
    horizontal force (N), the moment (N m) and the wetted range's ends ``x0``, ``x1``;
    with status 3, the height the table must reach (``scal[7]``). The first contact's
    slices (cut where they are) as :func:`pitch_loops` takes them (``e_f``, ``f_f``,
    ``area_f``; status 9 asks for them, with ``opts``' ``fresh``).
    Returns 0, or a status of :data:`STATUS` for numpy's path.
    """
    level, n, c0, n_cut = opts[0], int(opts[6]), int(opts[7]), int(opts[8])
    tol, top = opts[9], opts[10]
    status, w0, w1 = window_loops(keel, level, n)
    if status != 0:
        return status
    if w0 < c0 or w1 > c0 + n_cut:
        return 2
    if level > top:
        scal[7] = level
        return 3
    # each window station's table entries at this level
    f0 = np.zeros(n_cut + 1, dtype=np.int64)
    first0 = np.zeros(n_cut, dtype=np.int64)  # each one's first entry in the table
    for k in range(n_cut):
        f0[k + 1] = f0[k]
        if w0 - c0 <= k < w1 - c0:
            first0[k], count = table_interval_loops(level, k, heights, tkey)
            f0[k + 1] += count
    e0 = np.empty((f0[n_cut], len(ENTRY)))
    for k in range(w0 - c0, w1 - c0):
        table_entry_loops(e0, f0[k], first0[k], f0[k + 1] - f0[k], level, k, tvals, station_vals,
                          tol)  # fmt: skip
    for j in range(f0[n_cut]):
        if e0[j, 0] <= 0.0:
            return 4
    status, m = layout_loops(fout, iout, opts, keel, runs, station_vals, e0, f0)
    if status != 0:
        return status
    if fresh_count_loops(iout, m) != len(area_f):
        scal[0] = m
        return 9
    # each moved slice's entries at its own depth
    need = -math.inf  # the highest water a moved slice needs above the table's top
    g1 = np.zeros(m + 1, dtype=np.int64)
    first1 = np.zeros(m, dtype=np.int64)
    j = 0
    for i in range(m):
        g1[i + 1] = g1[i]
        if iout[I_MOVED, i] == 2:
            g1[i + 1] += f_f[j + 1] - f_f[j]
            j += 1
        elif iout[I_MOVED, i] == 1:
            at = level - fout[_LIFT, i]
            if at > top:
                need = max(need, at)
                continue
            first1[i], count = table_interval_loops(at, iout[I_SOURCE, i] - c0, heights, tkey)
            if tvals[first1[i], 11] <= 0.0:  # an inexact interval (its entries' "ok")
                return 4
            g1[i + 1] += count
    if need > top:
        scal[7] = need
        return 3
    e1 = np.empty((g1[m], len(ENTRY)))
    for i in range(m):
        if iout[I_MOVED, i] == 1:
            at = level - fout[_LIFT, i]
            s = iout[I_SOURCE, i] - c0
            table_entry_loops(e1, g1[i], first1[i], g1[i + 1] - g1[i], at, s, tvals, station_vals,
                              tol)  # fmt: skip
    fresh_entries_loops(fout, iout, e1, g1, m, e_f, f_f, area_f, c0 + n_cut)
    return finish_loops(fout, iout, scal, opts, keel, runs, chords, station_vals, e0, f0, e1,
                        g1, m, a_c, v_c)  # fmt: skip


def pitch_entries_loops(outline_arrays, levels, tol):
    """The wetted properties (:func:`hullslice.wetted_loops.wetted_loops`, the ``wedge``
    estimator) of the kept cut's stations with the water at their ``levels`` (``-inf``:
    dry), in the columns of :data:`ENTRY`: ``(entries, first)``, station ``s``'s from row
    ``first[s]`` (one per wetted piece of its section, in order along the waterline, or
    its one dry entry)."""
    (station, ya, za, yb, zb, zlo, start, area, contour, part_area, part_station, part_zmax,
     part_ymin, part_ymax, z_chine) = outline_arrays  # fmt: skip
    st, wet, p, hb, port, stbd, tm, tp, ts, yk, phb, share, chine = wetted_loops(
        station, ya, za, yb, zb, zlo, start, area, contour, part_area, part_station,
        part_zmax, part_ymin, part_ymax, z_chine, levels, tol, False,
    )  # fmt: skip
    n_e = len(st)
    first = np.zeros(len(area) + 1, dtype=np.int64)
    for j in range(n_e):
        first[st[j] + 1] += 1
    for s in range(len(area)):
        first[s + 1] += first[s]
    e = np.empty((n_e, len(ENTRY)))
    for j in range(n_e):  # the entries come by station
        row = e[j]
        row[0] = 1.0
        row[1] = 1.0 if wet[j] else 0.0
        row[2] = p[j]
        row[3] = hb[j]
        row[4] = port[j]
        row[5] = stbd[j]
        row[6] = math.atan(tm[j]) if wet[j] else math.nan
        row[7] = math.atan(tp[j]) if wet[j] else math.nan
        row[8] = math.atan(ts[j]) if wet[j] else math.nan
        row[9] = yk[j]
        row[10] = phb[j]
        row[11] = share[j]
        row[12] = 1.0 if chine[j] else 0.0
    return e, first


def pitch_loops(fout, iout, scal, opts, keel, runs, chords, station_vals, outline_arrays,
                a_c, v_c, e_f, f_f, area_f):  # fmt: skip
    """:func:`held_loops` at a pitch without a waterline table (a new pitch): the wetted
    properties of the kept cut's stations computed afresh by
    :func:`hullslice.wetted_loops.wetted_loops`, as numpy's path computes them, from
    ``outline_arrays``, the kept cut's outline (its arrays as
    :class:`~hullslice.kernel.outline.Outline` holds them, to ``z_chine``). Returns 0, or
    a status of :data:`STATUS` (4: two slices taking one station's section at two
    heights). The stations may start at the first wetted slice's: no slice takes the
    section of the window's station before it.

    With ``opts``' ``fresh`` set, the slices to cut where they are (the first contact) are
    the caller's: status 9 where ``area_f`` holds no area for each of them (``scal[0]``
    then holds the slice count, and each such slice is marked 2 in ``iout[I_MOVED]``, its
    relative ``x`` in ``fout``'s first row); with their sections' entries at the water's
    height (``e_f``, from row ``f_f[j]`` for the ``j``-th, as :func:`pitch_entries_loops`
    gives them) and areas, the evaluation, the ``j``-th taking the source ``n_cut + j``."""
    level, n, c0, n_cut = opts[0], int(opts[6]), int(opts[7]), int(opts[8])
    tol = opts[9]
    status, w0, w1 = window_loops(keel, level, n)
    if status != 0:
        return status
    k0 = wet_slices_loops(keel, level, n)[1]  # -1 where none: then the window's first
    if max(w0, k0) < c0 or w1 > c0 + n_cut:  # the first station a slice reads, as the stage's
        return 2
    levels = np.full(n_cut, -math.inf)
    for s in range(max(w0, c0) - c0, w1 - c0):
        levels[s] = level
    e0, f0 = pitch_entries_loops(outline_arrays, levels, tol)
    status, m = layout_loops(fout, iout, opts, keel, runs, station_vals, e0, f0)
    if status != 0:
        return status
    n_fresh = fresh_count_loops(iout, m)
    if n_fresh != len(area_f):
        scal[0] = m
        return 9
    n_moved = 0
    for i in range(m):
        n_moved += 1 if iout[I_MOVED, i] == 1 else 0
    g1 = np.zeros(m + 1, dtype=np.int64)
    if n_moved + n_fresh == 0:
        return finish_loops(fout, iout, scal, opts, keel, runs, chords, station_vals, e0, f0,
                            e0[:0], g1, m, a_c, v_c)  # fmt: skip
    levels[:] = -math.inf
    for i in range(m):
        if iout[I_MOVED, i] == 1:
            s = iout[I_SOURCE, i] - c0
            at = level - fout[_LIFT, i]
            if levels[s] != -math.inf and levels[s] != at:
                return 4
            levels[s] = at
    e_moved, f_moved = pitch_entries_loops(outline_arrays, levels, tol)
    j = 0
    for i in range(m):
        g1[i + 1] = g1[i]
        if iout[I_MOVED, i] == 1:
            s = iout[I_SOURCE, i] - c0
            g1[i + 1] += f_moved[s + 1] - f_moved[s]
        elif iout[I_MOVED, i] == 2:
            g1[i + 1] += f_f[j + 1] - f_f[j]
            j += 1
    e1 = np.empty((g1[m], len(ENTRY)))
    for i in range(m):
        if iout[I_MOVED, i] == 1:
            s = iout[I_SOURCE, i] - c0
            for t in range(f_moved[s + 1] - f_moved[s]):
                e1[g1[i] + t] = e_moved[f_moved[s] + t]
    fresh_entries_loops(fout, iout, e1, g1, m, e_f, f_f, area_f, c0 + n_cut)
    return finish_loops(fout, iout, scal, opts, keel, runs, chords, station_vals, e0, f0, e1,
                        g1, m, a_c, v_c)  # fmt: skip


def fresh_count_loops(iout, m):
    """How many of the ``m`` slices are to be cut where they are (marked 2 in
    ``iout[I_MOVED]`` by :func:`~hullslice.slices_loops.layout_loops`)."""
    n = 0
    for i in range(m):
        n += 1 if iout[I_MOVED, i] == 2 else 0
    return n


def fresh_entries_loops(fout, iout, e1, g1, m, e_f, f_f, area_f, first):
    """The slices cut where they are (marked 2), the ``j``-th of them taking its own
    section: its entries ``e_f[f_f[j]:f_f[j + 1]]`` into ``e1`` from row ``g1`` of its
    slice, its area into ``fout``'s area column (read by
    :func:`~hullslice.slices_loops.finish_loops`) and the source station ``first + j``."""
    j = 0
    for i in range(m):
        if iout[I_MOVED, i] == 2:
            for t in range(f_f[j + 1] - f_f[j]):
                e1[g1[i] + t] = e_f[f_f[j] + t]
            fout[_AREA, i] = area_f[j]
            iout[I_SOURCE, i] = first + j
            j += 1
