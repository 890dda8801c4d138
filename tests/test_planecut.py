"""The exact cut of a new pitch (hullslice.planecut) against manifold3d's own cut.

manifold3d is the reference: it cuts the body turned to the pitch, its sections rounded to a
grid of 1e-8 of the cutter's units (1e-12 of the body's size), so the kernel's contours
must have its edge counts and its areas to 1e-12 of the size squared.
"""

from __future__ import annotations

import itertools
import subprocess
import sys

import numpy as np
import pytest

import hullslice as hs
from hullslice import planecut_loops, shapes
from hullslice.errors import InputError
from hullslice.geometry import CUTTER_SIZE, MERGE, check_cutter, frame
from hullslice.kernel.waterline_table import WaterlineTable
from hullslice.planecut import PlaneIndex, plane_index

from .conftest import MESHES

#: Areas to this share of the size squared (manifold3d's grid is 1e-12 of the size).
AREA_TOL = 1e-12
PITCHES = (-0.35, -0.05, 0.08, 0.3, 0.7)
#: No order found before, for the outline's loops.
NO_HINT = np.full(1, -1, dtype=np.int64)


def _area(c: np.ndarray) -> float:
    y, z = c[:, 0], c[:, 1]
    return 0.5 * float(y @ np.roll(z, -1) - np.roll(y, -1) @ z)


def _bodies():
    yield "paper_prism.stl", hs.load_hull(MESHES / "paper_prism.stl", mass=1.0)
    yield "wedge_prism.stl", hs.load_hull(MESHES / "wedge_prism.stl", mass=1.0)
    yield "fuselage_model.obj", hs.load_hull(MESHES / "fuselage_model.obj", mass=60.0)
    yield "fuselage_full.obj", hs.load_hull(MESHES / "fuselage_full.obj", mass=6e4)
    shaped = {
        "wedge": shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0),
        "fuselage": shapes.fuselage(stations=40, points=24),
        "cylinder": shapes.circular_cylinder(),
        "asymmetric wedge": shapes.asymmetric_wedge_prism(),
        "paper prism, flipped diagonals": shapes.paper_prism(stations=41, flip_diagonals=True),
    }
    for name, (v, f) in shaped.items():
        yield name, hs.Hull.from_arrays(v, f, name=name)


BODIES = dict(_bodies())


def _compare(ref, got) -> float:
    """The largest area difference of two cuts (cutter units squared), their contours'
    point counts and orientations asserted equal."""
    worst = 0.0
    assert len(ref) == len(got)
    for a, b in zip(ref, got, strict=True):
        assert sorted(len(c) for c in a) == sorted(len(c) for c in b)
        assert sorted(_area(c) > 0 for c in a) == sorted(_area(c) > 0 for c in b)
        worst = max(worst, abs(sum(map(_area, a)) - sum(map(_area, b))))
        for c in b:  # closed rings of distinct consecutive points
            step = np.abs(c - np.roll(c, 1, axis=0)).max(axis=1)
            assert step.min() > MERGE * CUTTER_SIZE
    return worst


@pytest.mark.parametrize("name", sorted(BODIES))
def test_kernel_contours_equal_manifold3d_on_every_body(name):
    hull = BODIES[name]
    index = plane_index(hull)
    for pitch in PITCHES:
        fr = frame(hull, pitch)
        x = np.linspace(fr.keel.x[0], fr.keel.x[-1], 33)
        x[0] -= 1e-3 * hull.size  # a plane missing the body: no contour
        ref = fr.cut(x, "manifold3d")
        got = index.cut(x, fr.pitch, fr.cg, fr._matrix, MERGE * CUTTER_SIZE)
        assert got[0] == () and ref[0] == ()
        assert _compare(ref, got) <= AREA_TOL * CUTTER_SIZE**2


def test_the_frame_cuts_by_either_cutter():
    hull = hs.load_hull(MESHES / "fuselage_model.obj", mass=60.0)
    fr = frame(hull, 0.1)
    x = np.linspace(fr.keel.x[0], fr.keel.x[-1], 9)[1:-1]
    # manifold3d's by default; the kernel's by cutter="exact", equal to it to its grid
    a, b = fr.cut(x), hull.manifold.transform(fr._matrix)
    ref = [tuple(b.slice(float((xi - fr._offset[2]) * fr.scale)).to_polygons()) for xi in x]
    assert all(np.array_equal(p, q) for sa, sb in zip(a, ref, strict=True)
               for p, q in zip(sa, sb, strict=True))  # fmt: skip
    kernel = plane_index(hull).cut(x, fr.pitch, fr.cg, fr._matrix, MERGE * CUTTER_SIZE)
    got = fr.cut(x, "exact")
    assert all(np.array_equal(p, q) for sa, sb in zip(got, kernel, strict=True)
               for p, q in zip(sa, sb, strict=True))  # fmt: skip
    assert _compare(a, got) <= AREA_TOL * CUTTER_SIZE**2


def test_vertices_exactly_on_the_plane():
    """A level fuselage cut through its rings of vertices (every ring's distance to the
    plane exactly zero): the kernel keeps the vertices themselves, each once."""
    v, f = shapes.fuselage(stations=30, points=20)
    hull = hs.Hull.from_arrays(v, f, name="rings")
    fr = frame(hull, 0.0)
    ring_x, count = np.unique(hull.vertices[:, 0], return_counts=True)
    ring_x = ring_x[count >= 20]  # the rings of 20 points
    x = ring_x[3:-3:4] - fr.cg[0]
    assert len(x) >= 4
    got = plane_index(hull).cut(x, 0.0, fr.cg, fr._matrix, MERGE * CUTTER_SIZE)
    ref = fr.cut(x, "manifold3d")
    assert _compare(ref, got) <= AREA_TOL * CUTTER_SIZE**2
    for xi, sec in zip(x, got, strict=True):
        ring = hull.vertices[hull.vertices[:, 0] - fr.cg[0] == xi]  # d = 0 exactly
        assert len(sec) == 1 and len(sec[0]) == len(ring)


def test_a_plane_through_a_box_face_and_its_corner():
    """Degenerate planes: through a box's end face, through its edge only (at a pitch of
    45 degrees, the plane touching the lower aft edge), and beyond the body."""
    v = np.array([[x, y, z] for x in (0.0, 2.0) for y in (-0.5, 0.5) for z in (0.0, 1.0)])
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])  # fmt: skip
    hull = hs.Hull.from_arrays(v, f, mass=500.0, name="box")
    index = PlaneIndex.of(hull.vertices, hull.faces)
    fr = frame(hull, 0.0)
    g = fr.cg
    m = fr._matrix
    # the end faces and the middle: the section is the 1 x 1 square wherever it is cut
    x = np.array([0.0, 1.0, 2.0]) - g[0]
    got = index.cut(x, 0.0, g, m, MERGE * CUTTER_SIZE)
    ref = fr.cut(x[1:2], "manifold3d")
    assert _compare(ref, got[1:2]) <= AREA_TOL * CUTTER_SIZE**2
    square = (fr.scale * 1.0) ** 2
    assert abs(sum(map(_area, got[1])) - square) <= AREA_TOL * CUTTER_SIZE**2
    # x = 2: the far end face is ahead (d = 0 counts as ahead) and so is cut as the square
    assert abs(sum(map(_area, got[2])) - square) <= AREA_TOL * CUTTER_SIZE**2
    # at 45 degrees, the plane through the corner edge (x = 2, z = 0) only: no area
    pitch = np.pi / 4
    c, s = np.cos(pitch), np.sin(pitch)
    edge = (2.0 - g[0]) * c - (0.0 - g[2]) * s
    far = (2.0 - g[0]) * c - (1.0 - g[2]) * s  # the lowest plane reaching the aft face top
    got = index.cut(np.array([edge, edge + 1.0]), pitch, g, m, MERGE * CUTTER_SIZE)
    assert got[0] == () and got[1] == ()
    assert edge > far


def test_the_waterline_table_builds_from_the_kernel_outline():
    hull = hs.load_hull(MESHES / "fuselage_model.obj", mass=60.0)
    frame(hull, 0.05)
    fr = frame(hull, 0.06)
    _, mids = fr.fixed_stations(32)
    tol = 1e-9 * hull.size
    for cutter in ("exact", "manifold3d"):
        outline = hs.kernel.Outline.of(fr.cut(mids, cutter), tol, fr.origin, fr.scale)
        level = float(np.nanmin(np.where(np.isfinite(outline.zmin), outline.zmin, np.nan)))
        table = WaterlineTable.of(outline, level + 0.3, tol, "wedge")
        assert table is not None
    exact = hs.kernel.Outline.of(fr.cut(mids, "exact"), tol, fr.origin, fr.scale)
    ref = hs.kernel.Outline.of(fr.cut(mids, "manifold3d"), tol, fr.origin, fr.scale)
    np.testing.assert_allclose(exact.area, ref.area, rtol=0, atol=AREA_TOL * hull.size**2)


def test_free_pitch_history_equals_a_manifold3d_only_run():
    runs = {}
    for cutter in ("manifold3d", "exact", None):  # None: the kernel's, free pitch's default
        hull = hs.load_hull(MESHES / "fuselage_model.obj", mass=60.0)
        runs[cutter] = hs.simulate(
            hull, -1.0, 0.04, dt=5e-4, pitch_rad=0.1, forward_speed=19.0, slices=32,
            slicing="fixed", stop_on=(), free_pitch=True, cutter=cutter,
        )  # fmt: skip
    a, b = runs["manifold3d"], runs["exact"]
    assert len(a) == len(b) == 81
    np.testing.assert_array_equal(runs[None].force, b.force)
    peak = np.max(np.abs(a.force))
    assert np.max(np.abs(np.asarray(b.force) - a.force)) <= 1e-9 * peak
    assert np.max(np.abs(np.asarray(b.moment) - a.moment)) <= 1e-9 * np.max(np.abs(a.moment))
    assert np.max(np.abs(np.asarray(b.pitch) - a.pitch)) <= 1e-12


def test_wetted_slicing_at_a_new_pitch_equals_manifold3d():
    hull = hs.load_hull(MESHES / "fuselage_model.obj", mass=60.0)
    motion = hs.Motion(-1.0, 19.0)
    exact = hs.ForceModel(hull, slices=40, cutter="exact")
    ref = hs.ForceModel(hull, slices=40)  # manifold3d's, the default
    for pitch in (0.04, 0.05, 0.1):
        for draft in (0.01, 0.05):
            a, b = exact(hs.Pose(draft, pitch), motion), ref(hs.Pose(draft, pitch), motion)
            assert abs(float(a.total - b.total)) <= 1e-9 * abs(float(b.total))


def test_an_unknown_cutter_is_refused():
    assert check_cutter("manifold3d") == "manifold3d"
    with pytest.raises(InputError, match="cutter 'clipper' is unknown"):
        hs.ForceModel(BODIES["wedge_prism.stl"], cutter="clipper")


def _kernel_cuts(hull, path: str):
    index = plane_index(hull)
    out = []
    for pitch in (-0.2, 0.1, 0.45):
        fr = frame(hull, pitch)
        x = np.linspace(fr.keel.x[0], fr.keel.x[-1], 21)
        out.append(index.cut(x, fr.pitch, fr.cg, fr._matrix, MERGE * CUTTER_SIZE, path=path))
    return out


def _largest_difference(a, b) -> float:
    """The largest coordinate difference of two kernels' cuts (cutter units), their
    contours' counts and point counts asserted equal."""
    worst = 0.0
    for cut_a, cut_b in zip(a, b, strict=True):
        for sa, sb in zip(cut_a, cut_b, strict=True):
            assert [len(c) for c in sa] == [len(c) for c in sb]
            for p, q in zip(sa, sb, strict=True):
                worst = max(worst, float(np.abs(p - q).max()))
    return worst


@pytest.mark.parametrize("name", ["fuselage_model.obj", "paper_prism.stl", "cylinder"])
def test_the_loops_for_a_compiler_equal_numpy(name):
    """The loops of hullslice.planecut_loops, run uncompiled (numba's input), against
    numpy's path: the same points to 1e-12 of the body's size."""
    hull = BODIES[name]
    diff = _largest_difference(_kernel_cuts(hull, "python"), _kernel_cuts(hull, "numpy"))
    assert diff <= 1e-12 * CUTTER_SIZE


@pytest.mark.parametrize("name", ["fuselage_model.obj", "paper_prism.stl", "cylinder"])
def test_the_compiled_path_equals_numpy(name):
    if not planecut_loops.available():
        pytest.skip("numba is not installed (.[fast]) or HULLSLICE_NUMBA=0")
    hull = BODIES[name]
    diff = _largest_difference(_kernel_cuts(hull, "numba"), _kernel_cuts(hull, "numpy"))
    assert diff <= 1e-12 * CUTTER_SIZE


@pytest.mark.parametrize("name", sorted(BODIES))
def test_the_candidate_ranges_by_the_loops_equal_numpy(name):
    """The candidate faces' ranges searched bin by bin by the loops (run as Python, and
    compiled where numba is installed) are numpy's search of all the keys, index for
    index, at pitches from -40 to 40 degrees and stations before, along and past the
    body, in order (each search from the station before), backwards and shuffled; and
    from guesses (the one-call stage's, from its last stage: near the ranges, or anywhere
    at all), which the loops update to the ranges found."""
    hull = BODIES[name]
    index = plane_index(hull)
    g = np.asarray(hull.cg, dtype=np.float64)
    x0, x1 = (float(v) - g[0] for v in hull.bounds[:, 0])
    rng = np.random.default_rng(7)
    cases = []
    for pitch in np.radians([-40.0, -3.0, 0.0, 1e-9, 6.0, 17.0, 40.0]):
        x = np.sort(rng.uniform(x0 - 0.2 * (x1 - x0), x1 + 0.2 * (x1 - x0), 37))
        x[5] = x[6]  # two stations at one place
        cases += [(pitch, x), (pitch, x[::-1].copy()), (pitch, rng.permutation(x))]
    for pitch, x in cases:
        want = index.ranges(x, pitch, g)
        c, s = np.cos(pitch), np.sin(pitch)
        args = (index.key, index.bin_start, index.bin_zlo, index.bin_zhi, index.bin_reach, x,
                float(g[0]), float(g[2]), float(c), float(s), index.margin, index.key_span,
                index.key_x0)  # fmt: skip
        none = np.empty((0, len(index.bin_zlo), 2), dtype=np.int64)
        got = [planecut_loops.LOOPS["ranges"](*args, none, 0)]
        if planecut_loops.available():
            got.append(index.ranges(x, pitch, g, compiled=True))
        # searched from guesses (an earlier stage's, or anything at all): the same ranges
        k, nb = len(x) + 3, len(index.bin_zlo)
        near = want[0][:, :, None] + rng.integers(-40, 41, (len(x), nb, 2))
        for guess in (rng.integers(-5, len(index.key) + 5, (k, nb, 2)),
                      np.concatenate([np.full((3, nb, 2), -1), near])):  # fmt: skip
            got.append(planecut_loops.LOOPS["ranges"](*args, guess, 3))
            got.append(planecut_loops.compiled("ranges")(*args, guess.copy(), 3)
                       if planecut_loops.available() else got[-1])  # fmt: skip
            np.testing.assert_array_equal(guess[3:, :, 0], want[0])  # updated in place
            np.testing.assert_array_equal(guess[3:, :, 1], want[1])
        for first, last in got:
            np.testing.assert_array_equal(first, want[0])
            np.testing.assert_array_equal(last, want[1])


def test_the_candidate_ranges_by_the_loops_break_ties_as_numpy():
    """Where a bound equals a face's key exactly (faces sharing keys, the bound one margin
    from the station), the loops' first face is the first key not below the lower bound
    and their last the first key above the upper one, as numpy's search gives them."""
    import dataclasses

    rng = np.random.default_rng(3)
    nb, span = 3, 64.0
    t = [np.sort(rng.integers(0, 64, 40)) * 0.25 for _ in range(nb)]  # ties in every bin
    key = np.concatenate([b * span + tb for b, tb in enumerate(t)])
    start = np.concatenate([[0], np.cumsum([len(tb) for tb in t])])
    index = dataclasses.replace(
        plane_index(BODIES["wedge"]), key=key, bin_start=start, bin_zlo=np.zeros(nb),
        bin_zhi=np.zeros(nb), bin_reach=np.zeros(nb), margin=0.25, key_span=span, key_x0=0.0,
    )  # fmt: skip
    x = np.arange(-4, 72) * 0.25  # every bound on a key's value, some before and past all
    want = index.ranges(x, 0.0, np.zeros(3))
    args = (key, start, index.bin_zlo, index.bin_zhi, index.bin_reach, x, 0.0, 0.0, 1.0, 0.0,
            0.25, span, 0.0)  # fmt: skip
    got = [planecut_loops.LOOPS["ranges"](*args, np.empty((0, nb, 2), dtype=np.int64), 0)]
    for guess in (rng.integers(-2, len(key) + 2, (len(x), nb, 2)),):  # from any guess
        got.append(planecut_loops.LOOPS["ranges"](*args, guess, 0))
    if planecut_loops.available():
        got.append(index.ranges(x, 0.0, np.zeros(3), compiled=True))
    for first, last in got:
        np.testing.assert_array_equal(first, want[0])
        np.testing.assert_array_equal(last, want[1])


OUTLINED = ["fuselage_model.obj", "fuselage_full.obj", "cylinder", "asymmetric wedge",
            "paper prism, flipped diagonals"]  # fmt: skip


@pytest.mark.parametrize("name", OUTLINED)
def test_the_outline_by_the_loops_equals_numpy(name):
    """The outline built from the loops' own array (run as Python, and compiled where
    numba is installed) is numpy's outline of the same contours, every field to the last
    bit, at pitches from -0.2 to 0.45 rad (in the cutter's units and moved to earth
    coordinates as the fixed slicing moves them)."""
    from hullslice.kernel.outline import Outline

    hull = BODIES[name]
    paths = [planecut_loops.outline_loops]
    if planecut_loops.available():
        paths.append(planecut_loops.compiled("outline"))
    tol = 1e-9 * hull.size
    for cut in _kernel_cuts(hull, "python"):
        assert cut.flat[0].shape[1] == 2
        for origin, scale in (((0.0, 0.0), 1.0), ((0.3, -1.25), 7.5)):
            ref = Outline.of(list(cut), tol, origin, scale)
            for loops in paths:
                got = Outline.of(cut, tol, origin, scale, loops=loops)
                for key, value in vars(ref).items():
                    assert np.array_equal(getattr(got, key), value), (key, loops)


def _same(a, b) -> bool:
    """Equal to the last bit: values (NaN as NaN) and, for floats, the signs of zeros."""
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape:
        return False
    if a.dtype.kind == "f":
        return np.array_equal(a, b, equal_nan=True) and np.array_equal(np.signbit(a),
                                                                       np.signbit(b))  # fmt: skip
    return np.array_equal(a, b)


@pytest.mark.parametrize("name", OUTLINED)
@pytest.mark.parametrize("deadrise", ["wedge", "waterline-slope"])
def test_the_wetted_properties_by_the_loops_equal_numpy(name, deadrise):
    """hullslice.wetted_loops (run as Python, and compiled where numba is installed) gives
    numpy's wetted properties to the last bit (signs of zeros included): the kernel's cuts
    at three pitches, the water low, middling, high, above the body, and at a random height
    per station."""
    from hullslice.kernel.outline import Outline
    from hullslice.kernel.wetted import wetted_properties
    from hullslice.wetted_loops import wetted_loops

    hull = BODIES[name]
    paths = [wetted_loops]
    if planecut_loops.available():
        paths.append(planecut_loops.compiled("wetted"))
    tol = 1e-9 * hull.size
    rng = np.random.default_rng(7)
    for cut in _kernel_cuts(hull, "numpy"):
        outline = Outline.of(cut, tol, (0.1, -0.2), 3.0)
        lo, hi = float(np.min(outline.zmin)), float(np.max(outline.part_zmax))
        levels = [lo + f * (hi - lo) for f in (0.01, 0.3, 0.7)] + [hi + 1.0]
        for level in [*levels, rng.uniform(lo, hi, outline.n_stations)]:
            ref = wetted_properties(outline, level, tol, deadrise)
            for loops in paths:
                with np.errstate(all="ignore"):
                    got = wetted_properties(outline, level, tol, deadrise, loops)
                assert ref.keys() == got.keys()
                assert all(_same(ref[k], got[k]) for k in ref), [
                    k for k in ref if not _same(ref[k], got[k])
                ]


def test_the_keel_fit_estimator_keeps_numpy(monkeypatch):
    """The loops serve the wedge and waterline-slope estimators; keel-fit stays numpy's."""
    from hullslice.kernel.outline import Outline
    from hullslice.kernel.wetted import wetted_properties

    def refuse(*args):
        raise AssertionError("the loops were called for keel-fit")

    hull = BODIES["cylinder"]
    cut = _kernel_cuts(hull, "numpy")[0]
    outline = Outline.of(cut, 1e-9 * hull.size)
    level = float(np.min(outline.zmin)) + 0.1 * hull.size
    ref = wetted_properties(outline, level, 1e-9 * hull.size, "keel-fit")
    got = wetted_properties(outline, level, 1e-9 * hull.size, "keel-fit", refuse)
    assert all(_same(ref[k], got[k]) for k in ref)
    assert float(np.nanmax(ref["penetration"])) > 0.0  # a wetted section was compared


def _shoelace_sums(points, ring_start) -> np.ndarray:
    """Each contour's shoelace sum, term by term in its points' order, closing last (as the
    cut's loops take it for their test of an area)."""
    sums = []
    for i0, i1 in zip(ring_start[:-1].tolist(), ring_start[1:].tolist(), strict=True):
        y, z = points[i0:i1, 0].tolist(), points[i0:i1, 1].tolist()
        total = 0.0
        for k in range(1, len(y)):
            total += y[k - 1] * z[k] - y[k] * z[k - 1]
        sums.append(total + (y[-1] * z[0] - y[0] * z[-1]))
    return np.array(sums)


_AREAS = (8, 10)  # outline_loops' areas: the station's and the contours'


@pytest.mark.parametrize("name", OUTLINED)
def test_the_cuts_outline_by_order_keys_equals_the_outline_loops(name):
    """The one-call stage's outline (:func:`outline_cut_loops`: extremes, chines and kept
    edges found by integer order keys, areas from the cut's own shoelace sums) is
    :func:`outline_loops`' on the kernel's contours, every array to the bit (signs of
    zeros too) but the areas, which are within 1e-14 of the largest (the sums of the
    cutter's points over its scale squared, not of the moved points): at three pitches,
    two moves and scales, every edge and a random cap per station (some above the body,
    some below it, one NaN)."""
    hull = BODIES[name]
    paths = [planecut_loops.LOOPS["outline_cut"]]
    ref = planecut_loops.LOOPS["outline"]
    if planecut_loops.available():
        paths.append(planecut_loops.compiled("outline_cut"))
        ref = planecut_loops.compiled("outline")
    rng = np.random.default_rng(11)
    for cut in _kernel_cuts(hull, "numba" if planecut_loops.available() else "python"):
        points, ring_start, ring_station = cut.flat
        sums = _shoelace_sums(points, ring_start)
        n_st = len(cut)
        for origin, scale in (((0.0, 0.0), 1.0), ((0.3, -1.25), 7.5)):
            zlo = ref(points, ring_start, ring_station, n_st, 1e-9, scale, *origin,
                      np.full(n_st, np.inf), NO_HINT.copy())[6]  # fmt: skip
            caps = rng.uniform(zlo.min() - 1.0, zlo.max() + 1.0, n_st)
            caps[rng.random(n_st) < 0.2] = np.inf
            caps[0] = np.nan
            for cap in (np.full(n_st, np.inf), caps):
                args = (points, ring_start, ring_station, n_st, 1e-9, scale, *origin, cap)
                want = ref(*args, NO_HINT.copy())
                for loops in paths:
                    got = loops(*args[:3], sums, *args[3:], NO_HINT.copy())
                    for i, (a, b) in enumerate(zip(got, want, strict=True)):
                        if i in _AREAS:
                            top = float(np.abs(b).max(initial=0.0))
                            assert np.abs(a - b).max(initial=0.0) <= 1e-14 * top, (i, a, b)
                        else:
                            assert _same(a, b), (i, a, b)


def test_the_cuts_outline_is_the_outline_loops_where_a_figure_is_zero_or_a_point_not_finite():
    """Where an extreme is a zero (its sign taken from the points' order) or a point is not
    finite, :func:`outline_cut_loops` gives :func:`outline_loops`' outline, areas and all,
    to the bit."""
    hull = BODIES["fuselage_model.obj"]
    paths = [planecut_loops.LOOPS["outline_cut"]]
    if planecut_loops.available():
        paths.append(planecut_loops.compiled("outline_cut"))
    ref = planecut_loops.LOOPS["outline"]
    cut = _kernel_cuts(hull, "python")[1]
    points, ring_start, ring_station = cut.flat
    n_st, scale = len(cut), 3.0
    station = int(ring_station[len(ring_station) // 2])
    lowest = min(float(p[:, 1].min()) for p in cut[station])
    moved_to_zero = (0.0, -(lowest / scale))  # that station's lowest point moved to z = 0
    bad = points.copy()
    bad[ring_start[1], 0] = np.inf
    for pts, origin in ((points, moved_to_zero), (bad, (0.3, -1.25))):
        sums = _shoelace_sums(pts, ring_start)
        args = (pts, ring_start, ring_station, n_st, 1e-9, scale, *origin, np.full(n_st, np.inf))
        with np.errstate(invalid="ignore"):  # the point at infinity: inf - inf
            want = ref(*args, NO_HINT.copy())
            if pts is points:
                assert want[15][station] == 0.0  # the station's lowest point at zero
            for loops in paths:
                got = loops(*args[:3], sums, *args[3:], NO_HINT.copy())
                assert all(_same(a, b) for a, b in zip(got, want, strict=True))


@pytest.mark.parametrize("name", ["fuselage_model.obj", "cylinder"])
def test_the_outline_capped_keeps_the_edges_below_in_the_full_outlines_order(name):
    """With a cap per station (the one-call stage's: the water's height, or none), the
    outline keeps of each station's edges those whose lower end is below its cap, in the
    full outline's order (the wetted properties read no other, in that order); the
    stations' own figures are the full outline's."""
    hull = BODIES[name]
    loops = planecut_loops.compiled("outline") or planecut_loops.outline_loops
    rng = np.random.default_rng(3)
    origin, scale = (0.3, -1.25), 7.5
    # the loops' own rings (numpy's cut gives a list of contours)
    for cut in _kernel_cuts(hull, "numba" if planecut_loops.available() else "python"):
        points, ring_start, ring_station = cut.flat
        n_st = len(cut)
        full = loops(points, ring_start, ring_station, n_st, 1e-9, scale, *origin,
                     np.full(n_st, np.inf), NO_HINT.copy())  # fmt: skip
        zlo, station = full[6], full[1]
        cap = rng.uniform(zlo.min(), zlo.max(), n_st)
        cap[rng.random(n_st) < 0.2] = np.inf
        got = loops(points, ring_start, ring_station, n_st, 1e-9, scale, *origin, cap,
                    NO_HINT.copy())  # fmt: skip
        keep = zlo < cap[station]
        assert 0 < keep.sum() < len(keep)
        for k in (1, 2, 3, 4, 5, 6, 9):  # station, the ends, the lower end, the contour
            np.testing.assert_array_equal(got[k], full[k][keep])
        np.testing.assert_array_equal(got[7], np.concatenate([[0], np.cumsum(
            np.bincount(station[keep], minlength=n_st))]))  # fmt: skip
        for k in (8, *range(10, 19)):  # areas, parts, extremes, chines: of all edges
            np.testing.assert_array_equal(got[k], full[k])


@pytest.mark.parametrize("name", OUTLINED)
def test_an_outline_with_a_top_serves_the_water_below_it_as_the_whole_one(name):
    """An outline of the edges whose lower end is below a top (numpy's, and the loops' from
    the cut's own array) keeps those edges in the whole outline's order, the sections' own
    figures of all the edges, and gives the whole outline's wetted properties to the last
    bit with the water anywhere below the top (one height, or one per station); above
    it, it refuses."""
    from hullslice.kernel.outline import Outline
    from hullslice.kernel.wetted import wetted_properties

    hull = BODIES[name]
    tol = 1e-9 * hull.size
    rng = np.random.default_rng(11)
    loops = planecut_loops.compiled("outline") or planecut_loops.outline_loops
    for cut in _kernel_cuts(hull, "numba" if planecut_loops.available() else "python"):
        whole = Outline.of(list(cut), tol, (0.3, -1.25), 7.5)
        lo, hi = float(np.min(whole.zmin)), float(np.max(whole.part_zmax))
        for f in (0.05, 0.4, 0.8):
            top = lo + f * (hi - lo)
            for got in (
                Outline.of(list(cut), tol, (0.3, -1.25), 7.5, top=top),
                Outline.of(cut, tol, (0.3, -1.25), 7.5, loops=loops, top=top),
            ):
                assert got.top == top
                keep = whole.zlo < top
                assert 0 < keep.sum() < len(keep)
                for key in ("station", "ya", "za", "yb", "zb", "zlo", "contour"):
                    assert _same(getattr(got, key), getattr(whole, key)[keep]), key
                for key in ("area", "part_area", "part_station", "part_zmax", "part_ymin",
                            "part_ymax", "zmin", "ymin", "ymax", "z_chine"):  # fmt: skip
                    assert _same(getattr(got, key), getattr(whole, key)), key
                for level in (lo + 0.5 * (top - lo), top, rng.uniform(lo, top, whole.n_stations)):
                    ref = wetted_properties(whole, level, tol)
                    out = wetted_properties(got, level, tol)
                    assert all(_same(ref[k], out[k]) for k in ref)
                with pytest.raises(ValueError, match="cannot serve water"):
                    wetted_properties(got, top + 1e-9 * hull.size, tol)
                levels = np.full(whole.n_stations, lo)
                levels[0], levels[-1] = np.nan, top + 1e-9 * hull.size
                with pytest.raises(ValueError, match="cannot serve water"):
                    wetted_properties(got, levels, tol)  # a NaN does not hide it
        for top in (np.inf, np.nan):  # no top: every edge, by either path
            for got in (
                Outline.of(list(cut), tol, (0.3, -1.25), 7.5, top=top),
                Outline.of(cut, tol, (0.3, -1.25), 7.5, loops=loops, top=top),
            ):
                assert got.top == np.inf
                assert _same(got.zlo, whole.zlo)


def test_an_outline_of_integer_or_single_contours_is_made_in_doubles():
    """Contours of integers or of single floats, moved by an origin, give the outline of
    the same contours in doubles (numpy's promotion), field by field."""
    from hullslice.kernel.outline import Outline

    square = np.array([[0, 0], [2, 0], [2, 2], [0, 2]])  # counter-clockwise
    ref = Outline.of([(square.astype(np.float64),)], 1e-9, (0.1, -0.2))
    for dtype in (np.int64, np.float32):
        got = Outline.of([(square.astype(dtype),)], 1e-9, (0.1, -0.2))
        for key, value in vars(ref).items():
            assert _same(getattr(got, key), value), (dtype, key)
    assert ref.area[0] == pytest.approx(4.0, rel=1e-15) and ref.zmin[0] == -0.2  # a 2 m square


@pytest.mark.parametrize("name", ["fuselage_model.obj", "cylinder"])
def test_the_outlines_order_from_a_hint_is_the_sorted_one(name, monkeypatch):
    """An order found before (the hint) is taken only where it is the stable sort of this
    call's edges: a stale hint (another pitch's, shuffled, or one edge twice) and none
    give the same outline to the bit, and the call leaves its own order in the hint; the
    right order is taken without sorting (the Python loops, their sort counted)."""
    from hullslice import outline_loops as module

    hull = BODIES[name]
    loops = planecut_loops.compiled("outline") or planecut_loops.outline_loops
    cuts = _kernel_cuts(hull, "numba" if planecut_loops.available() else "python")
    rng = np.random.default_rng(5)
    sorts: list[int] = []
    real = module.stable_order_loops
    monkeypatch.setattr(module, "stable_order_loops", lambda *a: sorts.append(1) or real(*a))
    # the Python loops' sort by key (once compiled, the module holds numba's: see _inject)
    monkeypatch.setattr(module, "edge_order_loops", planecut_loops.LOOPS["edge_order"])
    for a, b in itertools.pairwise(cuts):
        args = (*b.flat, len(b), 1e-9, 7.5, 0.3, -1.25, np.full(len(b), np.inf))
        want = loops(*args, NO_HINT.copy())
        m = len(want[1])
        assert m > 2
        hint = np.full(m + 8, -1, dtype=np.int64)
        loops(*a.flat, len(a), 1e-9, 7.5, 0.3, -1.25, np.full(len(a), np.inf), hint)
        shuffled = np.concatenate([[m], rng.permutation(m), [-1]])
        twice = np.concatenate([[m], np.arange(m - 1), [0], [-1]])
        for given in (hint, shuffled, twice):
            got = loops(*args, given)
            for k in range(1, 19):
                np.testing.assert_array_equal(got[k], want[k])
        right = twice  # now this call's order
        assert right[0] == m
        del sorts[:]
        got = planecut_loops.LOOPS["outline"](*args, right.copy())  # the Python loops
        for k in range(1, 19):
            np.testing.assert_array_equal(got[k], want[k])
        assert not sorts  # taken, not sorted
        planecut_loops.LOOPS["outline"](*args, shuffled.copy() * 0 - 1)
        assert sorts  # no hint: sorted


def test_a_section_with_a_hole_is_outlined_by_numpy():
    """A hole (a clockwise contour) needs numpy's containment tests: the loops decline."""
    ring = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])
    hole = np.array([[0.5, 0.5], [0.5, 1.5], [1.5, 1.5], [1.5, 0.5]])
    points = np.concatenate([ring, hole])
    out = planecut_loops.outline_loops(points, np.array([0, 4, 8]), np.array([0, 0]), 1,
                                       1e-9, 1.0, 0.0, 0.0, np.full(1, np.inf),
                                       NO_HINT.copy())  # fmt: skip
    assert out[0] is False
    from hullslice.kernel.outline import Outline
    from hullslice.planecut import Rings

    cut = Rings([(ring, hole)], (points, np.array([0, 4, 8]), np.array([0, 0])))
    got = Outline.of(cut, 1e-9, loops=planecut_loops.outline_loops)
    assert got.part_area[0] == pytest.approx(4.0 - 1.0, abs=1e-15)  # the square less its hole


def test_import_hullslice_leaves_numba_unimported():
    code = "import sys, hullslice, hullslice.planecut; print('numba' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_an_unknown_loops_path_is_refused():
    hull = BODIES["wedge_prism.stl"]
    fr = frame(hull, 0.1)
    with pytest.raises(ValueError, match="path 'gpu' is unknown"):
        plane_index(hull).cut(np.zeros(1), fr.pitch, fr.cg, fr._matrix, path="gpu")


@pytest.mark.parametrize("name", ["fuselage_model.obj", "paper_prism.stl", "cylinder"])
def test_the_keel_line_by_the_loops_equals_numpy(name):
    """The keel line's loops (run as Python, and compiled where numba is installed) give
    numpy's keel line to the last bit at pitches from -20 to 40 degrees, the side view's
    turn included."""
    from hullslice.geometry import _turn, silhouette_edges
    from hullslice.kernel.envelope import lower_envelope, lowest_segments, refined

    hull = BODIES[name]
    a, b = silhouette_edges(hull)
    g = np.asarray(hull.cg)
    from .test_keel_line import as_envelope

    paths = [planecut_loops.envelope_loops, as_envelope(planecut_loops.LOOPS["lowest"])]
    if planecut_loops.available():
        paths.append(planecut_loops.compiled("envelope"))
        paths.append(as_envelope(planecut_loops.compiled("lowest")))
    sides = [planecut_loops.side_view_loops]
    if planecut_loops.available():
        sides.append(planecut_loops.compiled("side"))
    # the ends' order: kept from pitch to pitch (each side's own), or none (in index order,
    # the insertion sort over its budget: a full sort), or reversed
    kept = [np.arange(2 * len(a)) for _ in sides]
    for pitch in np.radians([-20.0, -3.0, 0.0, 0.5, 6.0, 17.0, 40.0]):
        c, s = np.cos(pitch), np.sin(pitch)
        ta, tb = _turn(a - g, c, s), _turn(b - g, c, s)
        want = lower_envelope(ta, tb)
        for loops in paths:
            got = lower_envelope(ta, tb, loops)
            np.testing.assert_array_equal(got.x, want.x)
            np.testing.assert_array_equal(got.z, want.z)
        orders = [(k, o) for k in range(len(sides)) for o in (kept[k], None, "reversed")]
        for k, order in orders:  # the turn too, in the loops
            side = sides[k]
            if order is None or isinstance(order, str):
                order = np.arange(2 * len(a))[:: -1 if order else 1].copy()
            args = (float(g[0]), float(g[2]), float(c), float(s))
            xa, za, xb, zb, seg, xs, mid, z, zm, _, _ = side(a, b, *args, order)
            assert sorted(order.tolist()) == list(range(2 * len(a)))  # still a permutation
            assert _same(xa, ta[:, 0]) and _same(xb, tb[:, 0])
            assert _same(za, ta[:, 1]) and _same(zb, tb[:, 1])
            assert (np.diff(np.minimum(xa, xb)[seg]) >= 0.0).all()  # by lower end
            # a jump of the line (a vertical edge's foot) is read off the turned edges, by
            # numpy or by the loops' walk along the segments in that order
            walk = planecut_loops.compiled("walk") or planecut_loops.LOOPS["walk"]
            none = np.empty(0)
            for lowest in (
                lowest_segments(ta, tb),
                lambda q: walk(q, none, xa, za, xb, zb, seg)[0],  # noqa: B023
            ):
                got = refined(xs, mid, z, zm, lowest=lowest)
                assert _same(got.x, want.x) and _same(got.z, want.z)


def test_the_keel_lines_merge_by_the_loops_in_groups():
    """Break points closer than the merge distance, in groups of one to eight: each group's
    mean abscissa and lowest height as numpy's ``reduceat`` gives them; a group of nine
    (numpy sums it pairwise) left to numpy; a gap between parts (infinite middle) as
    numpy's refinement adds it (tests/test_frame_loops.py: the rest of the refinement)."""
    from hullslice.kernel.envelope import refined

    rng = np.random.default_rng(3)
    sizes = [1, 2, 3, 8, 5, 1, 4]
    xs, x = [], 0.0
    for k in sizes:
        for _ in range(k):
            xs.append(x)
            x += float(rng.uniform(1e-7, 9e-7))
        x += 0.1
    xs = np.array(xs)
    z = -np.abs(np.sin(7.0 * xs)) - rng.uniform(0.0, 1e-3, len(xs))
    zm = np.full(len(xs) - 1, -10.0)  # middles below the chords: nothing to refine
    first = np.cumsum([0, *sizes[:-1]])
    want_x = np.add.reduceat(xs, first) / np.array(sizes)
    want_z = np.minimum.reduceat(z, first)
    refines = [planecut_loops.LOOPS["refine"]]
    if planecut_loops.available():
        refines.append(planecut_loops.compiled("refine"))
    mid = 0.5 * (xs[1:] + xs[:-1])
    none, seg = np.empty(0), np.empty(0, dtype=np.int64)  # no segments: none is asked for
    for refine in refines:
        ok, got_x, got_z = refine(xs, mid, z, zm, 1e-6, none, none, none, none, seg)
        assert ok and _same(got_x, want_x) and _same(got_z, want_z)
        nine = np.concatenate([xs, xs[-1] + 0.1 + 1e-7 * np.arange(9)])
        flat = np.full(len(nine) - 1, -1.0)
        ok, _, _ = refine(nine, nine[1:], np.zeros(len(nine)), flat, 1e-6, none, none, none,
                          none, seg)  # fmt: skip
        assert not ok
        gap = zm.copy()
        gap[3] = np.inf
        want = refined(xs, mid, z, gap, 1e-6)
        ok, got_x, got_z = refine(xs, mid, z, gap, 1e-6, none, none, none, none, seg)
        assert ok and _same(got_x, want.x) and _same(got_z, want.z)


@pytest.mark.parametrize("name", sorted(BODIES))
def test_the_keel_line_by_numpy_equals_every_pair_at_once(name):
    """numpy's lowest silhouette segment over each abscissa, taken a few thousand pairs at a
    time, equals all pairs at once to the last bit at pitches from -20 to 40 degrees, and
    so does the keel line."""
    from hullslice.geometry import _turn, silhouette_edges
    from hullslice.kernel.envelope import _Segments, lower_envelope
    from hullslice.kernel.keel import KeelLine

    from .test_keel_line import _abscissae, _bits, every_pair, lowest_every_pair

    hull = BODIES[name]
    a, b = silhouette_edges(hull)
    g = np.asarray(hull.cg)
    for pitch in np.radians([-20.0, -3.0, 0.0, 0.5, 6.0, 17.0, 40.0]):
        c, s = np.cos(pitch), np.sin(pitch)
        ta, tb = _turn(a - g, c, s), _turn(b - g, c, s)
        segments = _Segments(ta, tb)
        for xs in _abscissae(ta, tb):
            want = lowest_every_pair(ta, tb, xs)
            np.testing.assert_array_equal(_bits(segments.lowest(xs)), _bits(want))
        got: KeelLine = lower_envelope(ta, tb)
        every = lower_envelope(ta, tb, every_pair)
        np.testing.assert_array_equal(_bits(got.x), _bits(every.x))
        np.testing.assert_array_equal(_bits(got.z), _bits(every.z))


def test_the_rings_walked_equal_the_rings_by_pointer_jumping(monkeypatch):
    """The contours' order of numpy's path: scipy's depth-first walk (checked) against
    the pointer jumping it replaces where the check fails, and against a plain walk."""
    from hullslice import planecut_numpy

    rng = np.random.default_rng(3)
    for n in (1, 2, 7, 400, 3000):
        succ = rng.permutation(n)
        seen, plain = np.zeros(n, dtype=bool), []
        for j in range(n):  # each ring from its lowest segment, the rings by it
            while not seen[j]:
                seen[j] = True
                plain.append(j)
                j = succ[j]
        order, first = planecut_numpy._walk(succ)
        assert np.array_equal(order, plain)
        point = rng.normal(size=(n, 2))
        ordered, roots, length = planecut_numpy._jump(point, succ)
        assert np.array_equal(ordered, point[order])
        assert np.array_equal(roots, order[first])
        assert np.array_equal(length, np.diff(np.append(first, n)))
    # a body's cuts, walked and (the walk refused) jumped: the same contours
    hull = BODIES["fuselage_model.obj"]
    walked = _kernel_cuts(hull, "numpy")
    monkeypatch.setattr(planecut_numpy, "_walk", lambda succ: None)
    assert _largest_difference(walked, _kernel_cuts(hull, "numpy")) == 0.0


def test_the_station_view_of_the_contours_is_rings_of_them():
    """The one call's contours split by station as they are read (:class:`StationRings`)
    are those :meth:`Rings.of` splits all at once, rings out of station order included
    (a first contact's slices come after the window's stations), each a view of the one
    array; reading past the last station stops an iteration, and a result's polygons
    looked up through an index are those of its list."""
    from hullslice.planecut import Rings, StationRings
    from hullslice.slicing.record import ShiftedPolygons

    rng = np.random.default_rng(7)
    sizes = np.array([3, 4, 5, 3, 6, 4])
    ring_station = np.array([1, 0, 1, 3, 0, 4])  # station 2 none, 0 and 1 twice, unsorted
    start = np.concatenate([[0], np.cumsum(sizes)])
    points = rng.normal(size=(start[-1], 2))
    want = Rings.of(points, start, ring_station, 5)
    got = StationRings(points, start, ring_station, 5)
    assert len(got) == len(want) == 5 and got.flat[0] is points
    for i in range(-5, 5):
        a, b = got[i], want[i]
        assert len(a) == len(b) and all(p.base is points for p in a)
        assert all(np.array_equal(p, q) for p, q in zip(a, b, strict=True))
    assert all(
        len(p) == len(q) and all(np.array_equal(u, v) for u, v in zip(p, q, strict=True))
        for p, q in zip(got[1:4], want[1:4], strict=True)
    )
    assert len(list(got)) == 5
    with pytest.raises(IndexError, match="station 5 out of range for 5 stations"):
        got[5]
    slices = np.array([4, 0, 0, 1, 3])  # a slice's station: read through the index
    lift = np.array([0.0, 0.5, 0.0, 0.0, -0.25])
    viewed = ShiftedPolygons(got, (0.1, -0.2), 2.0, lift, slices)
    listed = ShiftedPolygons([want[k] for k in slices], (0.1, -0.2), 2.0, lift)
    assert len(viewed) == len(listed) == 5 and len(list(viewed)) == 5
    assert np.array_equal(viewed.contour_counts(), listed.contour_counts())
    assert np.array_equal(viewed.extent_below(np.arange(5)), listed.extent_below(np.arange(5)),
                          equal_nan=True)  # fmt: skip
    for a, b in zip(viewed, listed, strict=True):
        assert all(np.array_equal(p, q) for p, q in zip(a, b, strict=True))
