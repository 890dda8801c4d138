"""The keel line's loops of :mod:`hullslice.keel_loops` (as Python, and compiled where numba
is installed) against numpy: its runs (:func:`runs_loops` against :meth:`_Runs.of`, the
same arrays to the last bit, on every catalogued body's keel line at pitches from -20 to
40 degrees and on lines made to hold what a keel line can: gaps between parts, steps, end
faces, a fan of micro-facets, no bottom at all), the ends' sort from an earlier order,
the walk along the segments, and a new pitch's keel line made in one call."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from hullslice import planecut_loops
from hullslice.geometry import _turn, side_outline_points, silhouette_edges
from hullslice.kernel.envelope import lower_envelope
from hullslice.kernel.keel import END_FACE_SLOPE, STEEP_SLOPE, _Runs

from .test_planecut import BODIES, _same

FIELDS = ("mid", "cont", "starts", "offsets", "steep", "bend")


def _loops():
    paths = [planecut_loops.LOOPS["runs"]]
    if planecut_loops.available():
        paths.append(planecut_loops.compiled("runs"))
    return paths


def _assert_same_runs(x: np.ndarray, z: np.ndarray) -> None:
    want = _Runs.of(x, z)
    for loops in _loops():
        got = _Runs.of(x, z, loops)
        for name in FIELDS:
            assert _same(getattr(got, name), getattr(want, name)), name
        if want.chords is None:
            assert got.chords is None
        else:
            assert got.chords is not None
            for a, b in zip(got.chords, want.chords, strict=True):
                assert _same(a, b)


@pytest.mark.parametrize("name", sorted(BODIES))
def test_the_runs_by_loops_equal_numpy_on_every_body(name):
    hull = BODIES[name]
    a, b = silhouette_edges(hull)
    g = np.asarray(hull.cg)
    for pitch in np.radians([-20.0, -3.0, 0.0, 0.5, 6.0, 17.0, 40.0]):
        c, s = np.cos(pitch), np.sin(pitch)
        line = lower_envelope(_turn(a - g, c, s), _turn(b - g, c, s))
        _assert_same_runs(line.x, line.z)


def _fan() -> tuple[np.ndarray, np.ndarray]:
    xb = np.linspace(0.0, 1.0, 21)
    slopes = np.array([20.0, 80.0, 300.0, 800.0, 1300.0])
    xc = 1.0 + np.cumsum(np.full(len(slopes), 0.004))
    zc = 0.05 + np.cumsum(0.004 * slopes)
    return np.concatenate([xb, xc]), np.concatenate([0.05 * xb**2, zc])


LINES = {
    "straight": ([0.0, 1.0, 2.0], [0.0, 0.1, 0.2]),
    "one facet": ([0.0, 1.0], [0.3, -0.2]),
    "kink": ([0.0, 1.0, 2.0], [0.0, 0.1, 0.3]),
    "step": ([0.0, 0.5, 1.0, 1.01, 1.51, 2.01], [0.0, 0.05, 0.1, -0.1, -0.05, 0.0]),
    "gap between parts": ([0.0, 1.0, 1.5, 2.0, 3.0], [0.0, 0.1, np.inf, 0.2, 0.1]),
    "gap at the start": ([0.0, 0.5, 1.0, 2.0], [np.inf, 0.0, 0.1, 0.0]),
    "leaning steeply": ([0.0, 0.1, 0.2, 1.0, 1.1], [0.0, 0.3, 0.7, 0.8, 2.0]),
    "all steep": ([0.0, 0.001, 0.002], [0.0, 1.0, 3.0]),
    "no finite slope": ([0.0, 1.0, 2.0], [np.inf, np.inf, np.inf]),
    "signed zeros": ([0.0, 1.0, 2.0, 3.0], [-0.0, 0.0, -0.0, -0.0]),
    "fan of micro-facets": _fan(),
}


@pytest.mark.parametrize("name", sorted(LINES))
def test_the_runs_by_loops_equal_numpy_on_made_lines(name):
    x, z = (np.asarray(v, dtype=np.float64) for v in LINES[name])
    with np.errstate(invalid="ignore"):
        _assert_same_runs(x, z)


def test_one_run_of_bottom_facets_is_the_loops_runs_to_the_bit(monkeypatch):
    # lines whose every facet has a finite slope, none an end face's (a keel line's window
    # near the water, most often): numpy's shorter way (_Runs._one_run) gives the loops'
    # arrays, the chords too, on the drawn lines of no end face (140 of 300) with flats,
    # signed zeros, and facets leaning past the steep slope
    taken = []
    one_run = _Runs._one_run.__func__

    def spy(cls, *args):
        taken.append(1)
        return one_run(cls, *args)

    monkeypatch.setattr(_Runs, "_one_run", classmethod(spy))
    rng = np.random.default_rng(4)
    for _ in range(300):
        n = int(rng.integers(2, 40))
        x = np.cumsum(rng.uniform(0.001, 1.0, n))
        z = rng.normal(0.0, 0.4, n) * float(rng.choice([0.0, 0.3, 1.0, 3.0]))
        if rng.random() < 0.3:
            z = np.round(z, 1)
        z[rng.random(n) < 0.1] = -0.0
        if np.all(np.abs(np.diff(z) / np.diff(x)) <= END_FACE_SLOPE):
            _assert_same_runs(x, z)
    assert len(taken) >= 100


def _assert_arrays_in_the_runs_pass(x: np.ndarray, z: np.ndarray) -> None:
    """:func:`keel_line_loops`' arrays are :func:`keel_arrays_loops`' of :func:`runs_loops`'
    arrays to the last bit (the stage's own and the frames' fused arrays), its runs
    wider by NaNs only."""
    for made, runs, pack in zip(_keel_loops("keel_line"), _keel_loops("runs"),
                                _keel_loops("keel_arrays"), strict=True):  # fmt: skip
        nf, r, bottom, steep, keel, rows, chords = made(x, z, END_FACE_SLOPE, STEEP_SLOPE)
        ok, mid, cont, starts, offsets, steep_r, bend, bottom_r, height, lo, hi = runs(
            x, z, END_FACE_SLOPE, STEEP_SLOPE
        )
        assert (nf > 0) == ok and _same(steep, steep_r)
        if not ok:
            continue
        assert bottom == bottom_r and (nf, r) == (len(mid), len(starts))
        if not bottom:
            height, lo, hi = np.empty(0), np.empty(0), np.empty(0)
        want = pack(x, z, steep_r, mid, cont, bend, starts, offsets, height, lo, hi)
        assert _same(keel, want[0]) and _same(chords, want[2])
        f = want[1].shape[1]
        assert _same(rows[:, :f], want[1]) and np.isnan(rows[:, f:]).all()


@pytest.mark.parametrize("name", sorted(LINES))
def test_the_keel_arrays_in_the_runs_pass_equal_the_runs_arrays_on_made_lines(name):
    x, z = (np.asarray(v, dtype=np.float64) for v in LINES[name])
    with np.errstate(invalid="ignore"):
        _assert_arrays_in_the_runs_pass(x, z)


@pytest.mark.parametrize("name", sorted(BODIES))
def test_the_keel_arrays_in_the_runs_pass_equal_the_runs_arrays_on_every_body(name):
    hull = BODIES[name]
    a, b = silhouette_edges(hull)
    g = np.asarray(hull.cg)
    for pitch in np.radians([-20.0, 0.0, 6.0, 40.0]):
        c, s = np.cos(pitch), np.sin(pitch)
        line = lower_envelope(_turn(a - g, c, s), _turn(b - g, c, s))
        _assert_arrays_in_the_runs_pass(line.x, line.z)


def _keel_loops(name: str):
    paths = [planecut_loops.LOOPS[name]]
    if planecut_loops.available():
        paths.append(planecut_loops.compiled(name))
    return paths


def test_the_ends_sorted_from_an_earlier_order_are_numpys_sort():
    """:func:`sorted_loops` from any earlier order (the right one, one a few swaps off, a
    reversed one past its budget, a random one) gives ``np.sort``'s values, NaNs last, and
    leaves the order of the values it sorted."""
    rng = np.random.default_rng(7)
    v = np.round(rng.normal(size=300), 2)  # ties
    v[:3] = [0.0, -0.0, 0.0]
    near = np.argsort(v, kind="stable")
    near[10:12] = near[11:9:-1]  # two neighbours swapped
    hints = [np.argsort(v, kind="stable"), near, np.arange(300)[::-1], rng.permutation(300)]
    for fn in _keel_loops("sorted"):
        for hint in hints:
            order = hint.copy()
            got = fn(v, order)
            np.testing.assert_array_equal(got, np.sort(v))
            assert sorted(order.tolist()) == list(range(300))
            np.testing.assert_array_equal(v[order], got)
        with_nan = v.copy()
        with_nan[[5, 50]] = np.nan
        order = np.arange(300)
        got = fn(with_nan, order)
        np.testing.assert_array_equal(got, np.sort(with_nan))  # NaNs last, as numpy's
        np.testing.assert_array_equal(with_nan[order], got)


def test_the_walk_along_the_segments_equals_the_searches():
    """:func:`lowest_walk_loops`, the segments in the order of their lower ends, gives
    :func:`lowest_loops`'s heights to the last bit over the ends and over the intervals'
    middles: random segments, vertical ones, segments sharing ends, abscissae outside
    every segment."""
    rng = np.random.default_rng(11)
    e = 200
    xa, xb = np.round(rng.uniform(0, 10, e), 1), np.round(rng.uniform(0, 10, e), 1)
    xb[:20] = xa[:20]  # vertical in the side view
    za, zb = rng.normal(size=e), rng.normal(size=e)
    xs = np.unique(np.concatenate([xa, xb, [-1.0, 11.0]]))
    mid = 0.5 * (xs[1:] + xs[:-1])
    seg = np.argsort(np.minimum(xa, xb), kind="stable")
    lowest = planecut_loops.LOOPS["lowest"]
    want = lowest(xs, xa, za, xb, zb), lowest(mid, xa, za, xb, zb)
    for walk in _keel_loops("walk"):
        z, zm = walk(xs, mid, xa, za, xb, zb, seg)
        assert _same(z, want[0]) and _same(zm, want[1])


@pytest.mark.parametrize("name", sorted(BODIES))
def test_a_new_pitchs_keel_line_in_one_call_equals_numpys(name):
    """:func:`frame_keel_loops` (as Python, and compiled where numba is installed), the
    keel line of a new pitch in one call, gives what numpy's path makes to the last bit,
    at pitches from -20 to 40 degrees: the keel line's break points (where only close ones
    merge; elsewhere it says so, and numpy's refinement takes over), its runs, and the
    body's lowest and highest points in the side view."""
    hull = BODIES[name]
    a, b = silhouette_edges(hull)
    g = np.asarray(hull.cg)
    merge = 1e-12 * hull.size
    outline, whole = side_outline_points(hull)
    ok_seen = 0
    # the silhouette edges alone (the walk), with the side outline's lower side, and from
    # the outline alone where its points are all the ends
    for made, (shape, full) in itertools.product(
        _keel_loops("frame_keel"), [(np.empty((2, 0)), False), (outline, False), (outline, whole)]
    ):
        order = np.arange(2 * len(a))
        for pitch in np.radians([-20.0, -3.0, 0.0, 0.5, 6.0, 17.0, 40.0]):
            c, s = np.cos(pitch), np.sin(pitch)
            ta, tb = _turn(a - g, c, s), _turn(b - g, c, s)
            args = (float(g[0]), float(g[2]), float(c), float(s))
            ok, side, low, high, x, z, runs, _ = made(
                a, b, shape, full, *args, order, merge, END_FACE_SLOPE, STEEP_SLOPE
            )
            if len(side[1]):  # empty where the outline alone served
                assert _same(side[1], ta[:, 1]) and _same(side[3], tb[:, 1])
            assert low == min(ta[:, 1].min(), tb[:, 1].min())
            assert high == max(ta[:, 1].max(), tb[:, 1].max())
            if not ok:
                continue
            ok_seen += 1
            rx, rz = shape[0] - g[0], shape[1] - g[2]
            turned = (rx * c - rz * s, rx * s + rz * c) if shape.shape[1] else None
            want = lower_envelope(ta, tb, merge=merge, side=turned)
            assert _same(x, want.x) and _same(z, want.z)
            got = _Runs.from_loops(x, runs)
            assert got is not None
            for field in FIELDS:
                assert _same(getattr(got, field), getattr(want._runs, field)), field
    assert ok_seen > 0  # most pitches only merge


def test_the_side_views_extremes_are_numpys_then_pythons():
    """:func:`side_view_loops` gives the turned ends' ``min(za.min(), zb.min())`` and
    ``max(za.max(), zb.max())``: numpy's minimum and maximum of each (a NaN kept), Python's
    of the two (the first unless the second is lower, or higher; a NaN first stays), NaN
    without an edge. Edges at no pitch: the heights turn to themselves."""
    rng = np.random.default_rng(3)
    cases = [(rng.normal(size=50), rng.normal(size=50)), (np.array([1.0]), np.array([2.0]))]
    for where in ("a", "b", "both"):
        za, zb = rng.normal(size=30), rng.normal(size=30)
        if where in ("a", "both"):
            za[7] = np.nan
        if where in ("b", "both"):
            zb[0] = np.nan
        cases.append((za, zb))
    for side in _keel_loops("side"):
        for za, zb in cases:
            e = len(za)
            a = np.stack([np.arange(e) * 1.0, np.zeros(e), za], axis=1)
            b = np.stack([np.arange(e) + 0.5, np.zeros(e), zb], axis=1)
            lo, hi = side(a, b, 0.0, 0.0, 1.0, 0.0, np.arange(2 * e))[9:]
            want_lo, want_hi = min(za.min(), zb.min()), max(za.max(), zb.max())
            assert _same(np.float64(lo), np.float64(want_lo))
            assert _same(np.float64(hi), np.float64(want_hi))
        none = np.empty((0, 3))
        lo, hi = side(none, none, 0.0, 0.0, 1.0, 0.0, np.empty(0, dtype=np.int64))[9:]
        assert np.isnan(lo) and np.isnan(hi)


def test_a_height_of_minus_zero_read_off_the_outline_is_numpys():
    # a point of the outline's lower side at a height of -0.0 (the level of the centre of
    # gravity): the keel line's break point there has the point's own height, -0.0,
    # read off the outline alone or with the edges turned, as numpy's path reads it, to
    # the sign of the zero
    points = np.array([[-2.0, 0.0, 1.0], [-1.0, 0.0, -0.0], [2.0, 0.0, 0.5], [1.5, 0.0, 2.0]])
    edges = np.array([[0, 1], [1, 2], [2, 3], [3, 0]])
    outline = np.ascontiguousarray(points[:, [0, 2]].T)
    a, b = points[edges[:, 0]], points[edges[:, 1]]
    turned = _turn(a, 1.0, 0.0), _turn(b, 1.0, 0.0)
    want = lower_envelope(*turned, merge=1e-6, side=(outline[0], outline[1]))
    assert np.copysign(1.0, want.z[1]) == -1.0
    for made in _keel_loops("frame_keel"):
        for whole in (True, False):
            ok, _, _, _, x, z, _, _ = made(
                a, b, outline, whole, 0.0, 0.0, 1.0, 0.0, np.arange(8), 1e-6, END_FACE_SLOPE,
                STEEP_SLOPE,
            )  # fmt: skip
            assert ok and _same(x, want.x) and _same(z, want.z), whole


def test_the_turned_outlines_extremes_are_the_first_of_each():
    # the side outline turned: its leftmost and rightmost points are the first of the
    # lowest and highest abscissa (one each, or the outline does not serve), and its lowest
    # and highest heights the first of each, to the sign of a zero (found by order keys,
    # in which -0.0 lies below +0.0: the doubles' own comparison picks the point)
    loops = [planecut_loops.LOOPS["turned_outline"]]
    if planecut_loops.available():
        loops.append(planecut_loops.compiled("turned_outline"))
    cases = [  # (x, z), at no pitch about the origin: turned to themselves
        ([-2.0, -1.0, 1.0, 2.0, 0.0], [1.0, -0.0, 0.0, 1.0, 2.0], (True, 0, 3, -0.0, 2.0)),
        ([-2.0, 1.0, -1.0, 2.0, 0.0], [1.0, 0.0, -0.0, 1.0, 2.0], (True, 0, 3, 0.0, 2.0)),
        ([-2.0, -2.0, 1.0, 2.0], [1.0, 0.5, -1.0, 1.0], (False, 0, 3, -1.0, 1.0)),  # a tie
        ([-2.0, 1.0, 2.0, 2.0], [1.0, 0.5, -1.0, 3.0], (False, 0, 2, -1.0, 3.0)),
        ([0.0, 1.0], [0.0, 1.0], (False, 0, 1, 0.0, 1.0)),  # fewer than three
    ]
    for turned in loops:
        for x, z, (ok, il, ir, low, high) in cases:
            outline = np.array([x, z])
            got = turned(outline, 0.0, 0.0, 1.0, 0.0)
            assert (got[0], got[3], got[4]) == (ok, il, ir), (x, z, got)
            assert np.copysign(1.0, got[5]) == np.copysign(1.0, low) and got[5] == low
            assert got[6] == high
            assert np.array_equal(got[1], outline[0]) and np.array_equal(got[2], outline[1])
        bad = np.array([[0.0, 1.0, np.inf], [0.0, 1.0, 0.5]])
        assert not turned(bad, 0.0, 0.0, 1.0, 0.0)[0]
