"""A new pitch's keel line by the loops of :mod:`hullslice.frame_loops` (as Python, and
compiled where numba is installed) against numpy's: the refinement of the side view's
lowest points (:func:`refine_loops` against :func:`hullslice.kernel.envelope.refined`:
its gaps, jumps and crossings, then the merge of close break points) equal to the last bit
on a real aircraft, whose wings, nacelles and fairings cross the fuselage's keel in the side
view at every pitch (``meshes/airliner``), and on every catalogued body, at pitches from
-20 to 40 degrees."""

from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np
import pytest

import hullslice as hs
from hullslice import frame_loops, planecut_loops
from hullslice.constants import TOL
from hullslice.geometry import _turn, silhouette_edges
from hullslice.kernel import envelope
from hullslice.kernel.envelope import lowest_segments, refined
from hullslice.kernel.keel import END_FACE_SLOPE, STEEP_SLOPE

from .conftest import MESHES
from .test_planecut import BODIES, _same


def _refines():
    fns = [planecut_loops.LOOPS["refine"]]
    if planecut_loops.available():
        fns.append(planecut_loops.compiled("refine"))
    return fns


#: A real aircraft (its README), whose keel line the loops refine at every pitch.
AIRCRAFT = {"airliner": hs.load_hull(MESHES / "airliner" / "airliner.obj", length=37.6)}


@pytest.mark.parametrize("name", [*AIRCRAFT, *sorted(BODIES)])
def test_the_refinement_by_the_loops_equals_numpy(name):
    hull = AIRCRAFT[name] if name in AIRCRAFT else BODIES[name]
    a, b = silhouette_edges(hull)
    g = np.asarray(hull.cg)
    side = planecut_loops.side_view_loops
    refined_here = 0
    for pitch in np.radians([-20.0, -3.0, 0.0, 0.5, 4.0, 6.0, 9.0, 17.0, 40.0]):
        c, s = np.cos(pitch), np.sin(pitch)
        args = (float(g[0]), float(g[2]), float(c), float(s))
        xa, za, xb, zb, seg, xs, mid, z, zm, _, _ = side(a, b, *args, np.arange(2 * len(a)))
        ta, tb = _turn(a - g, c, s), _turn(b - g, c, s)
        for merge in TOL.keel_merge * hull.size * np.array([0.0, 1.0, 1e3]):
            want = refined(xs, mid, z, zm, merge, lowest_segments(ta, tb))
            for refine in _refines():
                ok, got_x, got_z = refine(xs, mid, z, zm, merge, xa, za, xb, zb, seg)
                assert ok
                assert _same(got_x, want.x) and _same(got_z, want.z), (pitch, merge)
                refined_here += len(want.x) > len(xs)
    if name in AIRCRAFT:  # points added at every pitch: crossings, jumps
        assert refined_here >= 9 * 3 * len(_refines()) - 6


def test_the_lowest_heights_by_a_search_equal_numpys():
    """:func:`lowest_at_loops` (the segments over an abscissa found by a search) gives
    numpy's lowest height of the silhouette segments at any abscissa: at 400 random ones
    and at every segment's ends, on the airliner at three pitches."""
    hull = AIRCRAFT["airliner"]
    a, b = silhouette_edges(hull)
    g = np.asarray(hull.cg)
    names = ("reach", "lowest_at")
    fns = [tuple(planecut_loops.LOOPS[n] for n in names)]
    if planecut_loops.available():
        fns.append(tuple(planecut_loops.compiled(n) for n in names))
    rng = np.random.default_rng(5)
    for pitch in np.radians([-3.0, 4.0, 17.0]):
        c, s = np.cos(pitch), np.sin(pitch)
        args = (float(g[0]), float(g[2]), float(c), float(s))
        xa, za, xb, zb, seg, xs, _, _, _, _, _ = planecut_loops.side_view_loops(
            a, b, *args, np.arange(2 * len(a))
        )
        q = np.concatenate([rng.uniform(xs[0] - 1.0, xs[-1] + 1.0, 400), xa, xb])
        want = lowest_segments(_turn(a - g, c, s), _turn(b - g, c, s))(np.sort(q))
        for reach, lowest_at in fns:
            lo, top = reach(xa, xb, seg)
            got = lowest_at(np.sort(q), lo, top, xa, za, xb, zb, seg)
            assert _same(got, want)


def test_what_the_refinement_leaves_to_numpy():
    """A group of nine close points to merge (numpy sums it pairwise) and an abscissa that
    is not a number: numpy's refinement."""
    xs = np.concatenate([np.arange(5.0), 5.0 + 1e-7 * np.arange(9)])
    z = np.zeros(len(xs))
    zm = np.full(len(xs) - 1, -1.0)
    none = np.empty(0)
    seg = np.empty(0, dtype=np.int64)
    for refine in _refines():
        assert not refine(xs, xs[:-1], z, zm, 1e-6, none, none, none, none, seg)[0]
        bad = xs.copy()
        bad[-1] = np.nan
        assert not refine(bad, xs[:-1], z, zm, 0.0, none, none, none, none, seg)[0]


def test_the_crossing_passes_are_numpys():
    assert frame_loops.CROSSING_PASSES == envelope.CROSSING_PASSES


def test_the_frame_loops_cache_sees_their_helpers():
    """numba's cache of these loops is stale when their own file changes; they call loops
    in another file, whose digest their file holds."""
    root = Path(frame_loops.__file__).parent
    names = ("keel_loops.py", "side_loops.py")
    digest = hashlib.sha256(b"".join((root / n).read_bytes() for n in names)).hexdigest()[:16]
    assert frame_loops.FRAME_HELPERS_DIGEST == digest, (
        f"set FRAME_HELPERS_DIGEST = {digest!r} in hullslice/frame_loops.py (its helpers changed)"
    )


@pytest.mark.parametrize("name", ["fuselage_model.obj", "fuselage_full.obj", "paper_prism.stl"])
def test_a_window_of_the_keel_line_reads_as_the_whole_line(name):
    # a new pitch's stage makes the keel line's runs over the break points its evaluation
    # reads (frame_loops.window_line_loops): over the wetted extent and a reach beyond it
    # (the station spacing or the curvature's window), the first and last points kept.
    # What the evaluation reads of it is the whole line's: the wetted extent and slices
    # (the same to the bit), the keel's height, its slope and its bend's change over the
    # curvature's window, and the chords' rise within 1e-12 (the running sums start at
    # the line's first point either way: they differ by a constant and rounding). Early
    # in an impact the window holds a fraction of the points.
    from hullslice import slices_loops as sl
    from hullslice.keel_loops import keel_line_loops

    hull = BODIES[name]
    a, b = silhouette_edges(hull)
    g = np.asarray(hull.cg)
    end_face, steep = END_FACE_SLOPE, STEEP_SLOPE
    window = planecut_loops.LOOPS["window_line"]
    n, reach = 32, 0.25 * hull.size / 4.0
    fewer = 0
    for pitch in np.radians([-3.0, 2.0, 6.0, 12.0]):
        c, s = np.cos(pitch), np.sin(pitch)
        line = envelope.lower_envelope(_turn(a - g, c, s), _turn(b - g, c, s),
                                       merge=TOL.keel_merge * hull.size)  # fmt: skip
        x, z = np.ascontiguousarray(line.x), np.ascontiguousarray(line.z)
        whole = keel_line_loops(x, z, end_face, steep)
        for share in (0.002, 0.02, 0.1, 0.4):
            level = z.min() + share * (z.max() - z.min())
            part = window(x, z, True, level, n, reach, end_face, steep)
            fewer += part[4].shape[1] < whole[4].shape[1]
            kw, kp = whole[4], part[4]
            assert kw[0, 0] == kp[0, 0] and kw[0, -1] == kp[0, -1]  # the ends: the stations
            assert sl.extent_loops(kw, level) == sl.extent_loops(kp, level)
            assert sl.window_loops(kw, level, n) == sl.window_loops(kp, level, n)
            _, x0, x1 = sl.extent_loops(kw, level)
            d = (x[-1] - x[0]) / n
            rw, rp = sl.runs_of_loops(whole[5]), sl.runs_of_loops(part[5])
            for q in np.linspace(x0 - d, x1 + d, 41):
                assert sl.interp_loops(q, kw[0], kw[1]) == sl.interp_loops(q, kp[0], kp[1])
                sw = sl.slope_loops(q, rw[0], rw[1], rw[3], rw[4])
                sp = sl.slope_loops(q, rp[0], rp[1], rp[3], rp[4])
                assert abs(sw - sp) <= 1e-12 * (1.0 + abs(sw)), (q, sw, sp)
                h = 0.5 * reach
                bw, bp = _change(q, h, rw[0], rw[2]), _change(q, h, rp[0], rp[2])
                assert abs(bw - bp) <= 1e-12 * (1.0 + abs(bw)), (q, bw, bp)
                if whole[2]:  # the chords' rise over half a station either side
                    ew = _change(q, d / 2, kw[0], whole[6][0])
                    ep = _change(q, d / 2, kp[0], part[6][0])
                    assert abs(ew - ep) <= 1e-12 * hull.size, (q, ew, ep)
    assert fewer >= 4, fewer


def _change(q: float, h: float, xp: np.ndarray, fp: np.ndarray) -> float:
    """The change of ``fp`` (interpolated over ``xp`` as the loops do) from ``q - h`` to
    ``q + h``."""
    from hullslice import slices_loops as sl

    return sl.interp_loops(q + h, xp, fp) - sl.interp_loops(q - h, xp, fp)


def test_the_first_and_last_heights_below_the_water_are_found_block_by_block():
    """The keel line's window starts from its first and last break point below the water:
    found a block of heights at a time, the same indices as a search point by point (a
    NaN not below; -1 and the length where none is), at lengths around the block's."""
    names = ("first_below", "last_below")
    fns = [tuple(planecut_loops.LOOPS[n] for n in names)]
    if planecut_loops.available():
        fns.append(tuple(planecut_loops.compiled(n) for n in names))
    rng = np.random.default_rng(4)
    for first, last in fns:
        for k in (0, 1, 15, 16, 17, 33, 200):
            z = rng.uniform(0.0, 1.0, k)
            z[rng.random(k) < 0.1] = np.nan
            for level in (-1.0, 0.02, 0.5, 2.0):
                below = np.flatnonzero(z < level)
                assert first(z, level) == (below[0] if len(below) else k)
                assert last(z, level) == (below[-1] if len(below) else -1)
