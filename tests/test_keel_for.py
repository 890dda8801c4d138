"""The keel line a new pitch's evaluation reads by numpy's path
(:meth:`hullslice.geometry.Frame.keel_for`): the break points from a reach before the first
under the water to a reach after the last, the line's ends as they are, as the compiled
stage reads them (:func:`hullslice.frame_loops.window_line_loops`); everything an
evaluation reads of it the whole line's but for rounding; and the free-pitch stages that
read it (:meth:`hullslice.motion.ForceModel.result_at` and ``totals_at`` by numpy's path)."""

from __future__ import annotations

import numpy as np
import pytest

from hullslice import frame_loops
from hullslice.constants import TOL
from hullslice.frame_loops import window_line_loops
from hullslice.geometry import FRAMES, _frame, frame, side_outline_points
from hullslice.kernel.envelope import side_envelope
from hullslice.kernel.keel import END_FACE_SLOPE, STEEP_SLOPE, WINDOW_SPARE, KeelLine
from hullslice.motion import ForceModel
from hullslice.slicing.assemble import keel_window
from hullslice.state import Motion, Pose

from .test_planecut import BODIES
from .test_stage_loops import _massive, assert_same_sums

N = 48  # fixed slices


@pytest.fixture(autouse=True)
def numpys_path(monkeypatch):
    monkeypatch.setenv("HULLSLICE_NUMBA", "0")


def _poses(hull, count: int, seed: int):
    """Pitches from -0.1 to 0.35 rad with a frame made afresh each, and drafts from a
    touch (0.1 %) to most of the body's height there, as many in each decade."""
    rng = np.random.default_rng(seed)
    for pitch in rng.uniform(-0.1, 0.35, count):
        fr = _frame(hull, float(pitch))
        draft = 10.0 ** float(rng.uniform(-3.0, -0.05)) * (fr.highest - fr.lowest)
        yield fr, fr.lowest + draft


@pytest.mark.parametrize("name", sorted(BODIES))
def test_a_frames_keel_line_is_made_when_first_read(name):
    # numpy's path: the frame holds the line's break points, its stations read off them;
    # the line, made when first read, is the side envelope's to the bit
    hull = BODIES[name]
    made = 0
    for fr, _ in _poses(hull, 6, 1):
        if fr._points is None:  # the side outline's lower side does not serve this body
            assert fr._keel is not None
            continue
        made += 1
        d, mids = fr.fixed_stations(N)
        assert fr._keel is None
        line = fr.keel
        assert fr._keel is line and fr.keel is line
        assert fr.fixed_stations(N)[0] == d
        np.testing.assert_array_equal(fr.fixed_stations(N)[1], mids)
        want = side_envelope(*_side(hull, fr.pitch))
        assert want is not None
        np.testing.assert_array_equal(line.x, want[0].x)
        np.testing.assert_array_equal(line.z, want[0].z)
        assert (fr.lowest, fr.highest) == want[1:]
    # a side outline of all the silhouette edges' ends: its lower side serves (else the
    # edges' envelope, refined, makes the line with the frame)
    assert made or not side_outline_points(hull)[1], name


def _read(line: KeelLine, fr, level: float, reach: float) -> dict[str, np.ndarray]:
    """What a fixed-slice evaluation reads of a keel line at ``level``: the wetted extent
    and length, and the heights, slopes, chords and curvatures at the wetted slices'
    middles and their mid-stations (over a slice and over ``reach``)."""
    extent = line.bottom(level)
    if extent is None:
        return {"extent": np.array([np.nan])}
    x0, x1 = extent
    d, mids = fr.fixed_stations(N)
    xa = float(line.x[0])
    k = np.arange(max(int((x0 - xa) // d), 0), min(int((x1 - xa) // d), N - 1) + 1)
    lo, hi = np.maximum(xa + k * d, x0), np.minimum(xa + (k + 1) * d, x1)
    keep = hi > lo
    x = np.concatenate([0.5 * (lo + hi)[keep], mids[k]])
    width = np.concatenate([np.maximum(hi - lo, 0.5 * d)[keep], np.full(len(k), d)])
    z, slope = line.at(x)
    return {
        "extent": np.array(extent),
        "length": np.array([line.wet_length(level, x0, x1)]),
        "height": z,
        "slope": slope,
        "chord": line.mean_slope(x, width),
        "curvature": line.mean_curvature(x, np.maximum(width, reach)),
    }


@pytest.mark.parametrize("name", sorted(BODIES))
def test_the_window_reads_as_the_whole_line_but_for_rounding(name):
    """At 25 new pitches and drafts a body: the window's break points are those the
    compiled stage reads (the same loops, run by Python), and what an evaluation reads of
    them equals the whole line's: the wetted extent and heights to the bit, the length
    within 1e-13 of the body's size, slopes and chords within 1e-12 of the largest, the
    curvatures within 1e-12 of the largest over the size (running sums that start at
    another point). On a body of a hundred side points or more, a window serves at least
    5 of the poses."""
    hull = BODIES[name]
    reach = keel_window(hull)
    windows = 0
    for fr, level in _poses(hull, 25, 2):
        if fr._points is None:
            continue
        x, z = fr._points
        line = fr.keel_for(level, N, reach)
        ok, *rest = window_line_loops(x, z, True, level, N, reach, END_FACE_SLOPE, STEEP_SLOPE)
        if ok:  # the loops' break points: the keel arrays' first two rows
            keel = rest[3]
            np.testing.assert_array_equal(line.x, keel[0, : len(line.x)])
            np.testing.assert_array_equal(line.z, keel[1, : len(line.x)])
            assert keel.shape[1] == max(len(line.x), 1)
        whole = fr.keel
        if line is whole:
            continue
        assert fr.keel_for(level, N, reach) is whole  # made since: the whole line serves
        windows += 1
        got, want = _read(line, fr, level, reach), _read(whole, fr, level, reach)
        np.testing.assert_array_equal(got["extent"], want["extent"])
        if "height" not in want:
            continue
        np.testing.assert_array_equal(got["height"], want["height"])
        assert abs(got["length"][0] - want["length"][0]) <= 1e-13 * hull.size
        for key in ("slope", "chord"):
            scale = max(float(np.abs(want[key]).max(initial=0.0)), 1.0)
            np.testing.assert_allclose(got[key], want[key], rtol=0, atol=1e-12 * scale)
        scale = max(float(np.abs(want["curvature"]).max(initial=0.0)), 1.0 / hull.size)
        np.testing.assert_allclose(got["curvature"], want["curvature"], rtol=0,
                                   atol=1e-12 * scale)  # fmt: skip
    side, whole_side = side_outline_points(hull)
    if whole_side and side.shape[1] >= 100:  # a line of many points: often a window
        assert windows >= 5, windows


def test_the_windows_spare_points_are_the_compiled_stages():
    assert WINDOW_SPARE == frame_loops.WINDOW_SPARE


def test_a_line_read_already_or_dry_water_is_the_whole_line():
    hull = BODIES["fuselage_model.obj"]
    fr = _frame(hull, 0.05)
    reach = keel_window(hull)
    assert fr.keel_for(fr.lowest - 0.01, N, reach) is fr.keel  # nothing under the water
    fr = _frame(hull, 0.05)
    assert fr.keel_for(fr.highest, N, reach) is fr.keel  # every point: the whole line
    fr = _frame(hull, 0.05)
    line = fr.keel_for(fr.lowest + 0.01, N, reach)
    assert line is not fr.keel and len(line.x) < len(fr.keel.x) / 2
    assert fr.keel_for(fr.lowest + 0.01, N, reach) is fr.keel  # read: the whole line
    np.testing.assert_array_equal(side_envelope(*_side(hull, 0.05))[0].x, fr.keel.x)


def _side(hull, pitch: float):
    pts = side_outline_points(hull)[0]
    g = hull.cg
    c, s = np.cos(pitch), np.sin(pitch)
    rx, rz = pts[0] - g[0], pts[1] - g[2]
    return rx * c - rz * s, rx * s + rz * c, TOL.keel_merge * hull.size


@pytest.mark.parametrize("name", ["fuselage_model.obj", "fuselage_full.obj", "paper_prism.stl"])
def test_numpys_stage_at_a_new_pitch_reads_the_window(name):
    """By numpy's path, a free-pitch stage at a pitch the hull has no frame for reads the
    window (the frame's whole line is not made; at least 5 of 12 shallow poses) and sums
    what the same pose sums with the whole line, within 1e-12 of the force's scale; at a
    pitch with a frame, the steps as they are (the whole line)."""
    hull = _massive(BODIES[name])
    twin = hull.with_mass(hull.mass)
    one = ForceModel(hull, slices=N, slicing="fixed", cutter="exact")
    whole = ForceModel(twin, slices=N, slicing="fixed", cutter="exact")
    assert one.fused is None
    rng = np.random.default_rng(7)
    read = 0
    for pitch in rng.uniform(-0.05, 0.3, 12):
        pitch = float(pitch)
        fr = frame(twin, pitch)
        fr.keel  # noqa: B018  (the twin's whole line, made)
        draft = 10.0 ** float(rng.uniform(-3.0, -0.5)) * (fr.highest - fr.lowest)
        z_cg = -(fr.lowest + draft)
        w, u, q = -float(rng.uniform(0.3, 3.0)), float(rng.uniform(0.0, 20.0)), 0.1
        got = one.result_at(z_cg, pitch, w, u, q)
        assert got is not None
        r, pose = got
        assert pose == Pose(one.draft(z_cg, pitch), pitch)
        mine = hull.cache[FRAMES].get(pitch)
        read += mine._keel is None  # the window served: the whole line not made
        want = whole(Pose(min(draft, fr.highest - fr.lowest), pitch), Motion(w, u, q))
        assert_same_sums((r.total, r.moment, r.total_x),
                         (want.total, want.moment, want.total_x), hull.size)  # fmt: skip
        assert one.result_at(z_cg, pitch, w, u, q) is None  # met again: it has a frame
        totals = one.totals_at(z_cg, pitch, w, u, q)  # the steps: the whole line
        assert_same_sums(totals, (want.total, want.moment, want.total_x), hull.size)
    assert read >= 5, read
