"""The exact plane cut's loops and the keel line's, written for a compiler: numba's, when
installed.

:func:`cut_loops` does in one pass over the candidate faces what
:meth:`hullslice.planecut.PlaneIndex.cut` does with numpy after choosing them: the sign
test, one crossing point per edge, the segments' successors and the contours' order, with
the very same arithmetic in the same order, so that both give the same points. It runs as
plain Python too (slowly: the tests compare it with numpy on small meshes); compiled by
numba (the ``fast`` extra, ``pip install hullslice[fast]``) it is the kernel's fast path.
numba is imported only when :func:`compiled` is first called, never by ``import
hullslice``; ``HULLSLICE_NUMBA=0`` in the environment keeps numpy's path.

:func:`stage_loops` chains these with the keel line's, the outline's and the fused
evaluation's loops: a free-fall solver's sums at a new pitch in one call.

The keel line's loops (the lowest of the side view's segments over each abscissa) are in
:mod:`hullslice.keel_loops`, and the outline's of the cut's contours (the same outline as
:meth:`hullslice.kernel.outline.Outline.of`) in :mod:`hullslice.outline_loops`: compiled
here by name with the others.
"""

from __future__ import annotations

import importlib.util
import math
import os
import threading
from collections.abc import Callable

import numpy as np

from .contour_loops import (
    match_loops,
    memo_cut_loops,
    points_loops,
    recipe_loops,
    same_sides_loops,
    shoelace_loops,
)
from .frame_loops import (
    above_chord_loops,
    crossings_loops,
    first_below_loops,
    frame_keel_loops,
    frame_points_loops,
    last_below_loops,
    lowest_at_loops,
    merge_loops,
    refine_loops,
    segment_reach_loops,
    window_line_loops,
)
from .held_loops import (
    fresh_count_loops,
    fresh_entries_loops,
    held_loops,
    pitch_entries_loops,
    pitch_loops,
    table_entry_loops,
    table_interval_loops,
)
from .index_loops import gallop_loops, near_loops, range_loops
from .keel_loops import (
    abscissae_loops,
    envelope_loops,
    keel_arrays_loops,
    keel_line_loops,
    line_runs_loops,
    lower_loops,
    lowest_loops,
    lowest_walk_loops,
    row_loops,
    run_ends_loops,
    runs_loops,
    search_loops,
    segments_loops,
    side_ends_loops,
    side_heights_loops,
    side_view_loops,
    sorted_loops,
)
from .outline_loops import (
    above_key_loops,
    below_key_loops,
    edge_order_loops,
    hinted_loops,
    key_loops,
    moved_loops,
    outline_cut_loops,
    outline_loops,
    stable_order_loops,
    unkey_loops,
)
from .side_loops import lower_side_loops, turned_outline_loops
from .slices_loops import (
    ENTRY,
    I_MOVED,
    crossing_loops,
    div_loops,
    extent_loops,
    finish_loops,
    interp_loops,
    layout_loops,
    left_loops,
    left_loops_desc,
    right_loops,
    runs_of_loops,
    side_tan_loops,
    slope_loops,
    wet_slices_loops,
    window_loops,
)
from .wetted_loops import wetted_loops

__all__ = [
    "available",
    "compiled",
    "cut_loops",
    "envelope_loops",
    "in_use",
    "lowest_loops",
    "outline_loops",
    "side_view_loops",
]

#: The digest of the sources of :func:`stage_loops`' helpers in other files
#: (``keel_loops.py``, ``side_loops.py``, ``frame_loops.py``, ``outline_loops.py``,
#: ``index_loops.py``, ``contour_loops.py`` and ``held_loops.py``, which
#: holds its own helpers' digest). numba's cache of the loops goes stale when this file
#: changes, not when those do: a change of theirs changes this digest too
#: (``tests/test_stage_loops.py`` checks it), so that the cache of :func:`stage_loops` is
#: made again.
STAGE_HELPERS_DIGEST = "34648eb3028e9171"

#: By a crossed face's code (bit k set for corner k ahead): the corner whose edge to the
#: next corner leaves the ahead side, and the one whose edge enters it.
K_OUT = np.array([0, 0, 1, 1, 2, 0, 2, 0], dtype=np.int64)
K_IN = np.array([0, 2, 0, 2, 1, 1, 0, 0], dtype=np.int64)


def cut_loops(
    first, last, corners, ends, x_rel, gx, gz, c, s, m, merge, slot, k_out_of, k_in_of,
):  # fmt: skip
    """The contours of the candidate faces of each station ``i``, the faces
    ``first[i, j] .. last[i, j] - 1`` of each bin ``j`` (as
    :meth:`hullslice.planecut.PlaneIndex.ranges` gives them), cut by the planes ``x_rel``
    at a pitch (``c``, ``s``: its cosine and sine) about ``(gx, gz)``, mapped by ``m``
    (2 x 4) to the cutter's ``(Y, Z)``. ``corners`` and ``ends`` are the index's records
    of the faces (:attr:`hullslice.planecut.PlaneIndex.corners`, ``x0 x1 x2 z0 z1 z2 y0
    y1 y2``, and :attr:`~hullslice.planecut.PlaneIndex.ends`, the vertices then the
    edges).

    Returns ``(points, ring_start, ring_station, status, ring_area)``: the kept contours'
    points one after another, each kept contour's first point (and the end), its station,
    0, or 1 where the mesh is not closed along a cut, and each kept contour's shoelace
    sum (twice its area in the cutter's frame). ``slot`` is scratch space, one integer per
    edge. The recipe of :func:`~hullslice.contour_loops.recipe_loops`, then its points by
    :func:`~hullslice.contour_loops.points_loops`.
    """
    none = np.empty(0)
    recipe = recipe_loops(first, last, corners, ends, x_rel, gx, gz, c, s, slot, k_out_of,
                          k_in_of, none, np.empty(0, dtype=np.int64), none, none, none)  # fmt: skip
    ends6, ring_len, st_p, st_q, status = recipe[0], recipe[1], recipe[2], recipe[3], recipe[10]
    points, ring_start, ring_station, ring_area = points_loops(
        ends6, ring_len, st_p, st_q, 0, x_rel, gx, gz, c, s, m, merge
    )
    return points, ring_start, ring_station, status, ring_area


def stage_loops(
    a, b, outline, whole, order, g, bounds, scale, keel_merge, end_face, steep_slope,
    key, bin_start, bin_zlo, bin_zhi, bin_reach, margin, span, x0, corners, ends, slot, guess,
    hint, k_out_of, k_in_of, merge, tol, n, xmin, reach_x, reach_z, c, s, z_cg, w, u, q, fout,
    iout, scal, extra, opts, a_c, v_c, memo,
):  # fmt: skip
    """A free-fall solver's sums at a new pitch in one call, as the fused evaluation
    (:mod:`hullslice.forces.fused`) makes them with a new frame: the keel line's break
    points (:func:`~hullslice.frame_loops.frame_points_loops` of the body's side
    ``outline`` (``whole`` where its points are all the edges' ends) and the silhouette
    edges ``a`` to ``b`` about the centre of gravity ``g``, ``order`` their ends' order,
    ``keel_merge`` as there); the draft of the centre of gravity at height ``z_cg`` (m)
    and the water's level; the line's runs and arrays over the break points the
    evaluation reads (:func:`~hullslice.frame_loops.window_line_loops`, ``end_face`` and
    ``steep_slope`` as there); the wetted slices'
    window; their fixed stations (``n`` slices over the keel line's length) cut by
    :func:`~hullslice.contour_loops.memo_cut_loops` (each from the thread's ``memo`` where
    its recipe serves, the others over the plane index's ranges,
    :func:`~hullslice.index_loops.range_loops`, from the thread's ``guess``; ``key`` to
    ``slot`` as :func:`cut_loops` takes them, ``merge`` the contours' merge distance,
    ``xmin`` the index's faces' lowest ``x``, ``reach_x`` and ``reach_z`` the body's reach
    from ``g``) with the cutter's map of :func:`hullslice.geometry._frame`
    (the body's ``bounds`` and ``scale``); their outline (``tol``, by
    :func:`~hullslice.outline_loops.outline_cut_loops`, from the thread's ``hint`` of its
    order at the last stage: the sections' areas from the cut's own sums, the same as the
    steps' but for rounding); and
    :func:`~hullslice.held_loops.pitch_loops` on them with
    the body's velocities ``w``, ``u`` and ``q`` (``fout`` to ``v_c`` as there). ``c`` and
    ``s`` are the pitch's cosine and sine. The same arithmetic in the same order as those
    steps made one by one, but for the keel line's running sums (below). Two things of
    those steps no slice reads are left out: the window's station before the wetted
    slices, and the order of the edges above the water, but for those an end slice's
    source may read (it takes it moved up by at most the steep slope times 1.5 station
    spacings, or the slice is cut afresh: the edges whose lower end is below the level
    plus the steep slope times 2 station spacings are kept, a margin of half a spacing's
    worth). A slice
    of the first contact (no wetted station near it) is cut where it is, its outline and
    wetted properties made, as numpy's path does (``slicing.fixed._with_fresh``). The
    keel line's running sums start at its first point within the window the evaluation
    reads, not the whole line's: the slopes, chords and curvatures it gives are the
    steps' but for rounding, so the sums are theirs within about 1e-13 of the force.

    Returns ``(status, points, ring_start, ring_station, memo)``: status 0 with the sums in
    ``scal`` and the cut's contours as :func:`cut_loops` gives them (their stations from
    the first station cut, then those of the first contact's slices), or a status where
    the steps one by one must serve:
    :data:`~hullslice.slices_loops.STATUS`'s, or 100 (the keel line needs numpy's
    refinement), 101 (it has no facet with a finite slope), 102 (a contour does not
    close) or 103 (a section has a hole). ``extra`` receives the first station cut and
    the count of sections (the first contact's too), the contours' origin ``(y, z)``, the
    water's level, the draft (clipped to the body's height), the draft unclipped, and the
    body's lowest point, m (all but the first two at status 1 too: a dry instant). The
    memo returned is that of the stations cut (the one given where none was)."""
    gx, gy, gz = g[0], g[1], g[2]
    none2, none1 = np.empty((0, 2)), np.empty(1, dtype=np.int64)
    ok, side, low, high, kx, kz = frame_points_loops(a, b, outline, whole, gx, gz, c, s, order,
                                                     keel_merge)  # fmt: skip
    if not ok:
        return 100, none2, none1, none1, memo
    draft = -(low + z_cg)  # ForceModel.draft's max(0.0, ...), _run's clip
    if not draft > 0.0:
        draft = 0.0
    extra[6], extra[7] = draft, low
    if draft > high - low:
        draft = high - low
    level = low + draft
    # the line's runs over the break points the evaluation reads (opts[18]: the keel's
    # curvature window; read off the side outline, every height is finite)
    line = window_line_loops(kx, kz, len(side[4]) == 0, level, n, opts[18], end_face,
                             steep_slope)  # fmt: skip
    nf, _, bottom, _, keel, runs_arr, chords = line  # the runs NaN-padded
    if nf == 0:
        return 101, none2, none1, none1, memo
    # the cutter's origin (geometry._frame): a dry instant's result has it too
    box0 = (bounds[0, 0] + bounds[1, 0]) * 0.5 - gx
    box1 = (bounds[0, 1] + bounds[1, 1]) * 0.5 - gy
    box2 = (bounds[0, 2] + bounds[1, 2]) * 0.5 - gz
    oz = box0 * s + box2 * c
    oy = box1 + gy
    extra[2], extra[3], extra[4], extra[5] = oy, oz, level, draft
    status, w0, w1 = window_loops(keel, level, n)
    if status != 0:
        return status, none2, none1, none1, memo
    _, k0, k1 = wet_slices_loops(keel, level, n)
    w0 = max(w0, k0)  # the window's station before the wetted slices: no slice's section
    xa, xb = kx[0], kx[len(kx) - 1]  # the fixed stations (Frame.fixed_stations)
    d = (xb - xa) / n
    n_cut = w1 - w0
    x_rel = np.empty(n_cut)
    for i in range(n_cut):
        x_rel[i] = xa + ((w0 + i) + 0.5) * d
    m = np.empty((2, 4))  # the cutter's map
    m[0, 0], m[0, 1], m[0, 2], m[0, 3] = scale * 0.0, scale * 1.0, scale * 0.0, scale * -oy
    m[1, 0], m[1, 1], m[1, 2] = scale * s, scale * 0.0, scale * c
    m[1, 3] = scale * (-(s * gx + c * gz) - oz)
    points, ring_start, ring_station, ring_area, closed, memo = memo_cut_loops(
        key, bin_start, bin_zlo, bin_zhi, bin_reach, margin, span, x0, xmin, corners, ends, x_rel,
        gx, gz, c, s, m, merge, slot, k_out_of, k_in_of, guess, w0, memo, reach_x, reach_z,
    )  # fmt: skip
    if closed != 0:
        return 102, none2, none1, none1, memo
    # edges above the water: read only by an end slice's own or inward source, moved up
    # to its depth (layout_loops): at most the steep slope (opts[22]) times its distance
    # from the source's middle, 1.5 stations, or it is cut afresh
    cap = np.full(n_cut, level)
    top = level + 2.0 * opts[22] * d
    if not top < math.inf:  # not finite: every edge
        top = math.inf
    for k in (k0, k0 + 1, k1 - 1, k1):
        if w0 <= k < w1:
            cap[k - w0] = top
    out = outline_cut_loops(points, ring_start, ring_station, ring_area, n_cut, tol, scale, oy,
                            oz, cap, hint)  # fmt: skip
    if not out[0]:
        return 103, none2, none1, none1, memo
    extra[0], extra[1] = w0, n_cut
    zmin, z_chine, area = out[15], out[18], out[8]
    stations = np.empty((3, n_cut))
    for i in range(n_cut):
        stations[0, i], stations[1, i], stations[2, i] = zmin[i], z_chine[i], area[i]
    arrays = (out[1], out[2], out[3], out[4], out[5], out[6], out[7], out[8], out[9],
              out[10], out[11], out[12], out[13], out[14], out[18])  # fmt: skip
    opts[0], opts[1], opts[2], opts[3] = level, w, u, q  # FusedEvaluation._options
    opts[5], opts[7], opts[8], opts[10] = gx, w0, n_cut, math.inf
    opts[23] = 1.0 if bottom else 0.0
    opts[24] = 1.0  # the first contact's slices cut here, where they are
    no_f = np.empty((0, len(ENTRY)))
    status = pitch_loops(fout, iout, scal, opts, keel, runs_arr, chords, stations, arrays,
                         a_c, v_c, no_f, np.zeros(1, dtype=np.int64), np.empty(0))  # fmt: skip
    if status != 9:
        return status, points, ring_start, ring_station, memo
    # slices with no wetted station near (the first contact): cut where they are, and their
    # outline and wetted properties, as numpy's path (slicing.fixed._with_fresh)
    n_f = fresh_count_loops(iout, int(scal[0]))
    x_f = np.empty(n_f)
    j = 0
    for i in range(int(scal[0])):
        if iout[I_MOVED, i] == 2:
            x_f[j] = fout[0, i]  # its relative x (layout_loops')
            j += 1
    first, last = range_loops(key, bin_start, bin_zlo, bin_zhi, bin_reach, x_f, gx, gz, c, s,
                              margin, span, x0, guess[:0], 0)  # fmt: skip
    p_f, rs_f, rst_f, closed, area_f = cut_loops(
        first, last, corners, ends, x_f, gx, gz, c, s, m, merge, slot, k_out_of, k_in_of
    )
    if closed != 0:
        return 102, none2, none1, none1, memo
    o = outline_cut_loops(p_f, rs_f, rst_f, area_f, n_f, tol, scale, oy, oz,
                          np.full(n_f, math.inf), np.full(1, -1, dtype=np.int64))  # fmt: skip
    if not o[0]:
        return 103, none2, none1, none1, memo
    e_f, f_f = pitch_entries_loops((o[1], o[2], o[3], o[4], o[5], o[6], o[7], o[8], o[9],
                                    o[10], o[11], o[12], o[13], o[14], o[18]),
                                   np.full(n_f, level), tol)  # fmt: skip
    status = pitch_loops(fout, iout, scal, opts, keel, runs_arr, chords, stations, arrays,
                         a_c, v_c, e_f, f_f, o[8])  # fmt: skip
    extra[1] = n_cut + n_f  # the sections: the window's stations', then these
    ring_start = np.concatenate((ring_start, rs_f[1:] + len(points)))
    ring_station = np.concatenate((ring_station, rst_f + n_cut))
    return status, np.concatenate((points, p_f)), ring_start, ring_station, memo


_LOCK = threading.Lock()
_COMPILED: dict[str, Callable | None] = {}
#: The loops compiled as others' helpers, by name (see :data:`CALLS`).
_HELPERS: dict[str, Callable] = {}


_FOUND: list[bool] = []
#: Holds True once a loop has been compiled in this process.
_IN_USE: list[bool] = []


def available() -> bool:
    """Whether the compiled path can serve: numba installed and not switched off by
    ``HULLSLICE_NUMBA=0`` (read at every call)."""
    if os.environ.get("HULLSLICE_NUMBA", "1") == "0":
        return False
    if not _FOUND:
        _FOUND.append(importlib.util.find_spec("numba") is not None)
    return _FOUND[0]


def in_use() -> bool:
    """Whether this process has compiled loops already (numba imported for them): then the
    keel line's are worth using too."""
    return bool(_IN_USE)


#: The loops :func:`compiled` compiles, by name.
LOOPS: dict[str, Callable] = {"cut": cut_loops, "lowest": lowest_loops}


def compiled(name: str = "cut") -> Callable | None:
    """The loops of :data:`LOOPS` by name (:func:`cut_loops` by default) compiled by numba
    (made on first call, cached on disk), or None without numba."""
    with _LOCK:
        if name not in _COMPILED:
            fn = None
            if available():
                import numba

                # IEEE division (an infinity or NaN by zero, as numpy's), no exception
                jit = numba.njit(cache=True, nogil=True, error_model="numpy")
                for callee in CALLS.get(name, ()):  # what the loops call: compiled first
                    _inject(callee, jit)
                fn = jit(LOOPS[name])
                _IN_USE.append(True)
            _COMPILED[name] = fn
        return _COMPILED[name]


def _inject(callee: str, jit: Callable) -> None:
    """The loops ``callee`` compiled (once), in place of its Python function in every module
    of :data:`LOOPS` holding it: numba reads a callee from the globals of each caller."""
    py = LOOPS[callee]
    if callee not in _HELPERS:
        _HELPERS[callee] = jit(py)
    spaces = {id(fn.__globals__): fn.__globals__ for fn in LOOPS.values()}
    for space in spaces.values():
        if space.get(py.__name__) is py:
            space[py.__name__] = _HELPERS[callee]


LOOPS.update(outline=outline_loops, order=stable_order_loops, hinted=hinted_loops,
    key=key_loops, unkey=unkey_loops, below_key=below_key_loops, above_key=above_key_loops,
    outline_cut=outline_cut_loops, moved=moved_loops, edge_order=edge_order_loops,
    envelope=envelope_loops,
    side=side_view_loops, ranges=range_loops, search=search_loops, gallop=gallop_loops,
    near=near_loops,
    sorted=sorted_loops, walk=lowest_walk_loops, lower=lower_loops, runs=runs_loops,
    run_ends=run_ends_loops, keel_line=keel_line_loops, line_runs=line_runs_loops,
    abscissae=abscissae_loops, keel_arrays=keel_arrays_loops, row=row_loops,
    reach=segment_reach_loops, above_chord=above_chord_loops, lowest_at=lowest_at_loops,
    crossings=crossings_loops, refine=refine_loops, side_ends=side_ends_loops,
    side_heights=side_heights_loops, lower_side=lower_side_loops,
    segments=segments_loops, merge=merge_loops,
    turned_outline=turned_outline_loops,
    frame_keel=frame_keel_loops, frame_points=frame_points_loops,
    window_line=window_line_loops, first_below=first_below_loops,
    last_below=last_below_loops, stage=stage_loops, recipe=recipe_loops, points=points_loops,
    match=match_loops, sides=same_sides_loops, memo_cut=memo_cut_loops, shoelace=shoelace_loops,
)  # fmt: skip
#: The loops that others call, by caller, their own helpers before them: compiled before
#: it, into every module's namespace that holds them (:func:`_inject`; numba calls compiled
#: functions only; :data:`LOOPS` keeps the Python ones, though once compiled their helpers
#: in those namespaces are numba's).
#: What the fused evaluation's loops call, helpers before callers.
_HELD = ("h_interp", "h_right", "h_left", "h_desc", "h_div", "h_sidetan", "h_slope", "h_runs",
         "h_cross", "h_extent", "h_wet", "h_window", "h_layout", "h_finish")  # fmt: skip
#: What the side view's loops call, helpers before callers.
_SIDE = ("search", "lowest", "sorted", "abscissae", "lower", "walk", "side_ends", "segments",
         "side_heights")  # fmt: skip
#: What the keel line's reading of the side outline calls, helpers before callers.
_CHAIN = ("turned_outline", "lower_side")
#: What the keel line's refinement calls, helpers before callers.
_REFINE = ("reach", "lowest_at", "crossings", "above_chord", "merge")
#: What the keel line's break points call, helpers before callers.
_FRAME_POINTS = (*_SIDE, *_CHAIN, *_REFINE, "refine")
#: What the keel line's one call calls, helpers before callers.
_FRAME_KEEL = (*_FRAME_POINTS, "frame_points", "run_ends", "keel_line", "line_runs")
#: What the stage loops call, helpers before callers.
_STAGE = (*_FRAME_POINTS, "frame_points", "run_ends", "keel_line", "first_below",
          "last_below", "window_line", "gallop",
          "near", "ranges", "recipe", "shoelace", "points", "match", "sides", "memo_cut", "cut",
          "order", "hinted", "moved", "edge_order", "outline", "key", "unkey", "below_key",
          "above_key", "outline_cut", *_HELD, "wetted", "h_entries", "h_fcount", "h_fentries",
          "pitch")  # fmt: skip
CALLS = {
    "cut": ("recipe", "shoelace", "points"),
    "points": ("shoelace",),
    "memo_cut": (
        "search",
        "gallop",
        "near",
        "ranges",
        "recipe",
        "shoelace",
        "points",
        "match",
        "sides",
    ),
    "held": (*_HELD, "h_interval", "h_table", "h_fcount", "h_fentries"),
    "pitch": (*_HELD, "wetted", "h_entries", "h_fcount", "h_fentries"),
    "window": ("h_right", "h_left", "h_desc", "h_cross", "h_extent", "h_wet"),
    "lowest": ("search",),
    "envelope": ("search", "lowest", "abscissae"),
    "walk": ("lower",),
    "side": _SIDE,
    "frame_keel": _FRAME_KEEL,
    "frame_points": _FRAME_POINTS,
    "window_line": ("run_ends", "keel_line", "first_below", "last_below"),
    "runs": ("run_ends", "keel_line", "line_runs"),
    "keel_line": ("run_ends",),
    "refine": ("search", *_REFINE),
    "crossings": ("search", "lowest_at"),
    "lowest_at": ("search",),
    "ranges": ("search", "gallop", "near"),
    "stage": _STAGE,
    "outline": ("order", "hinted", "moved", "edge_order"),
    "edge_order": ("order", "hinted"),
    "lower_side": ("turned_outline",),
    "below_key": ("key",),
    "above_key": ("key",),
    "outline_cut": (
        "order",
        "hinted",
        "moved",
        "edge_order",
        "outline",
        "key",
        "unkey",
        "below_key",
        "above_key",
    ),
    "keel_arrays": ("row",),
    "h_entries": ("h_div", "h_sidetan", "wetted"),
    "wetted": ("h_div", "h_sidetan"),
}
LOOPS.update(
    wetted=wetted_loops, held=held_loops, h_interp=interp_loops, h_right=right_loops,
    h_left=left_loops, h_div=div_loops, h_sidetan=side_tan_loops, h_desc=left_loops_desc,
    h_cross=crossing_loops,
    h_runs=runs_of_loops, h_extent=extent_loops, h_wet=wet_slices_loops,
    h_window=window_loops, h_layout=layout_loops,
    h_finish=finish_loops, h_interval=table_interval_loops,
    h_table=table_entry_loops, h_entries=pitch_entries_loops, pitch=pitch_loops,
    window=window_loops, h_slope=slope_loops, h_fcount=fresh_count_loops,
    h_fentries=fresh_entries_loops,
)  # fmt: skip
