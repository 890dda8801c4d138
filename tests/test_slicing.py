"""Fixed slicing: cut once per pitch and reused, the same numbers as cut afresh, and the
same limit as the paper's slicing of the wetted length."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import hullslice as hs
from hullslice import regions, shapes
from hullslice.constants import TOL
from hullslice.geometry import frame
from hullslice.motion import ForceModel, simulate
from hullslice.regions import REGIONS
from hullslice.slicing import fixed as fixed_slicing

MESHES = Path(__file__).resolve().parents[1] / "meshes"


@pytest.mark.parametrize("pitch_deg", [0.0, 5.0])
def test_cached_fixed_slicing_equals_cutting_afresh(paper_hull, pitch_deg, monkeypatch):
    monkeypatch.setattr(fixed_slicing, "TABLE_AFTER", 1)  # the waterline table from the start
    paper_hull = paper_hull.with_mass(1.0)  # frames of its own
    cached = ForceModel(paper_hull, slices=96, slicing="fixed")
    fresh = ForceModel(paper_hull, slices=96, slicing="fixed", cache=False)
    motion = hs.Motion(-3.0, forward_speed=2.0, pitch_rate_rad_s=0.3)
    tabulated = []
    for draft in (0.0005, 0.004, 0.02, 0.05, 0.09):
        pose = hs.Pose(draft, np.radians(pitch_deg))
        a, b = cached(pose, motion), fresh(pose, motion)
        store = fixed_slicing.fixed_cut(
            frame(paper_hull, pose.pitch), 96, TOL.coordinate * paper_hull.size
        )
        tabulated.append("wedge" in store.tables)
        # the same planes cut by the same manifold3d calls; the cached path reads the
        # sections' penetration and half-beams from affine fits of the waterline table
        # (hullslice.waterline), within a few rounding errors of the fresh evaluation
        np.testing.assert_allclose(a.force, b.force, rtol=1e-12, atol=0)
        assert a.total == pytest.approx(b.total, rel=1e-12)
        assert a.moment == pytest.approx(b.moment, rel=1e-12)
        for name in ("penetration", "deadrise", "mass_per_metre"):
            np.testing.assert_allclose(
                getattr(a.sections, name), getattr(b.sections, name), rtol=1e-12, atol=0
            )
        for name in ("station", "keel_slope", "x", "dx", "chine_wetted"):
            np.testing.assert_array_equal(getattr(a.sections, name), getattr(b.sections, name))
    assert tabulated[0]  # the table served (until the water stood too high for it)


def test_fixed_slicing_has_the_same_limit(paper_hull):
    # the paper's state: slicing the wetted length extrapolates to 147.91 N; slicing the
    # body's length converges to the same force (second order: the partly wetted slices at
    # the ends are made similar to their neighbours)
    wetted = hs.convergence(paper_hull, 0.0383, -3.4943, slices=(32, 64, 128))
    forces = [
        hs.compute_force(paper_hull, 0.0383, -3.4943, slices=n, slicing="fixed").total
        for n in (128, 256, 512, 1024)
    ]
    limit = wetted.richardson.extrapolated
    errors = np.abs(np.array(forces) - limit)
    assert errors[-1] < 2e-4 * limit
    assert np.all(np.diff(errors) < 0)  # closer with every doubling
    assert errors[0] / errors[-1] > 16  # at least second order over three doublings


def test_fixed_slicing_free_fall_matches_the_wetted_one(paper_hull):
    kw = {"dt": 2e-4, "stop_on": ()}
    wetted = simulate(paper_hull, -4.0, 0.016, slices=32, **kw)
    fixed = simulate(paper_hull, -4.0, 0.016, slices=256, slicing="fixed", **kw)
    assert fixed.settings["slicing"] == "fixed"
    assert fixed.peak["force"] == pytest.approx(wetted.peak["force"], rel=0.005)
    i = int(np.argmin(abs(fixed.t - 0.01)))
    assert fixed.force[i] == pytest.approx(wetted.force[i], rel=0.005)
    # no jumps as the water reaches new slices: the force changes smoothly step to step
    jumps = np.abs(np.diff(fixed.force, 2))
    assert jumps.max() < 0.01 * fixed.force.max()


@pytest.mark.parametrize("slices", [16, 64])
def test_fixed_slicing_keeps_a_round_bottoms_shape_at_the_ends(slices):
    # a circular cylinder (R = 0.2 m, 2 m) pitched 5 deg: the partial slices at the ends of
    # the wetted part take a station's own contour, wetted as deep as their middle (c grows
    # as sqrt(p), a similar section's would grow as p): the fixed slicing follows the
    # wetted slicing at every draft, and the force has no jump as the water passes a
    # station (it did jump by 176 N of 300 N with sections made similar)
    v, f = shapes.circular_cylinder(length=2.0, radius=0.2, points=180)
    hull = hs.Hull.from_arrays(v, f)
    pitch = np.radians(5.0)

    def force(draft: float, slicing: str) -> float:
        r = hs.compute_force(
            hull, hs.Pose(draft, pitch), hs.Motion(-1.0), solver="wagner", slices=slices,
            slicing=slicing, acceleration=0.0,
        )  # fmt: skip
        return r.total

    drafts = np.linspace(0.005, 0.03, 101)
    fixed = np.array([force(d, "fixed") for d in drafts])
    wetted = np.array([force(d, "wetted") for d in drafts[::10]])
    np.testing.assert_allclose(fixed[::10], wetted, rtol=0.03)
    # the force grows as the wetted length and width do: no step larger than a few times
    # the mean change over one 0.25 mm step
    steps = np.abs(np.diff(fixed))
    assert steps.max() < 3.0 * np.mean(steps)


def test_first_contact_with_fixed_slicing(paper_hull):
    # the wetted part narrower than a slice: cut where it is (no wetted section to borrow)
    r = hs.compute_force(paper_hull, 1e-4, -4.0, slices=16, slicing="fixed")
    w = hs.compute_force(paper_hull, 1e-4, -4.0, slices=1)
    assert len(r.sections) == 1 and r.sections.wetted_length < 0.35 / 16
    assert r.total == pytest.approx(w.total, rel=1e-9)


def test_unknown_slicing(paper_hull):
    with pytest.raises(hs.InputError, match="slicing 'even' is unknown"):
        hs.compute_force(paper_hull, 0.02, -3.0, slicing="even")


# -- regions: a large hull is turned and cut through a band of it -------------------------


@pytest.fixture(scope="module")
def fuselage_model():
    # 128k faces: above regions.REGION_MIN_FACES, so cut through regions
    return hs.load_hull(MESHES / "fuselage_model.obj", mass=60.0)


def _points(polygons) -> np.ndarray:
    p = np.concatenate([np.asarray(c) for c in polygons])
    return p[np.lexsort(p.T)]


@pytest.mark.parametrize("pitch_deg", [0.0, 6.0])
def test_region_cut_has_the_same_points_as_the_whole_hull(fuselage_model, pitch_deg):
    hull = fuselage_model.with_mass(60.0)  # frames and regions of its own
    fr = frame(hull, np.radians(pitch_deg))
    assert fr.cut(fr.fixed_stations(8)[1]) and not hull.cache[REGIONS]  # one pitch
    frame(hull, 0.1)  # a second pitch: regions from now on
    x = fr.fixed_stations(128)[1][20:30]  # a tenth of the body, near the tail
    through_region = fr.cut(x)
    assert len(hull.cache[REGIONS]) == 1  # a region was made ...
    (key,) = hull.cache[REGIONS]
    span = key[1] - key[0]
    assert span < 0.3 * hull.extents[0]  # ... and it is a band of the body
    whole = hull.manifold.transform(fr._matrix)
    for xi, cut in zip(x, through_region, strict=True):
        ref = whole.slice(float((xi - fr._offset[2]) * fr.scale)).to_polygons()
        # the faces the plane crosses are untouched by the trim: the very same points
        np.testing.assert_array_equal(_points(cut), _points(ref))


def test_regions_give_the_forces_of_the_whole_hull(fuselage_model, monkeypatch):
    motion = hs.Motion(-1.5, forward_speed=6.0, pitch_rate_rad_s=0.2)
    poses = [hs.Pose(d, np.radians(p)) for p in (4.0, 4.5) for d in (0.005, 0.02, 0.04)]

    def run(model):
        return [model(pose, motion) for pose in poses]

    banded_hull = fuselage_model.with_mass(60.0)
    banded = run(ForceModel(banded_hull, slices=96, slicing="fixed"))
    assert banded_hull.cache[REGIONS]
    monkeypatch.setattr(regions, "REGION_MIN_FACES", 10**9)
    whole_hull = fuselage_model.with_mass(60.0)
    whole = run(ForceModel(whole_hull, slices=96, slicing="fixed", cache=False))
    assert not whole_hull.cache[REGIONS]
    for a, b in zip(banded, whole, strict=True):
        assert len(a.sections) == len(b.sections) > 3
        # the same points in another order: sums may differ in the last bits only
        np.testing.assert_allclose(a.force, b.force, rtol=1e-12, atol=0)
        assert a.moment == pytest.approx(b.moment, rel=1e-12)


@pytest.mark.parametrize("pitch_deg", [2.0, 6.0])
def test_a_new_pitchs_outline_of_its_low_edges_gives_the_whole_outlines_result(
    pitch_deg, monkeypatch
):
    """A new pitch's first evaluation outlines only the edges below the water plus twice
    the steep slope times a station spacing (the most a moved slice's source is read
    above it): its forces and sections are those of the outline of every edge (the
    fixed slicing cutting afresh), to the last bit. A second evaluation at the pitch, the
    water higher, makes the kept outline whole, with the same result as afresh. (numpy's
    path: the compiled one-call stage caps its own outline.)"""
    from hullslice.kernel.keel import STEEP_SLOPE
    from hullslice.kernel.outline import Outline
    from hullslice.kernel.waterline_table import WaterlineTable

    monkeypatch.setenv("HULLSLICE_NUMBA", "0")
    body = hs.load_hull(MESHES / "fuselage_model.obj", mass=60.0)
    fresh = ForceModel(body.with_mass(60.0), slices=32, slicing="fixed", cache=False)
    cached = ForceModel(body, slices=32, slicing="fixed")
    motion = hs.Motion(-1.0, forward_speed=19.0)
    partial = 0
    for draft in (0.004, 0.012, 0.03):
        pose = hs.Pose(draft, np.radians(pitch_deg) + draft)  # a pitch of its own
        fr = frame(body, pose.pitch)
        kept = fixed_slicing.fixed_cut(fr, 32, TOL.coordinate * body.size)
        for step, depth in enumerate((draft, 1.5 * draft)):
            at = hs.Pose(depth, pose.pitch)
            a, b = cached(at, motion), fresh(at, motion)
            level = fr.lowest + depth
            top = kept.outline.top
            if step == 0:
                d = (fr.keel.x[-1] - fr.keel.x[0]) / 32
                assert top == pytest.approx(level + 2.0 * STEEP_SLOPE * d, rel=1e-12)
                assert np.all(kept.outline.zlo < top)
                whole = Outline.of(kept.rows, kept.tol, fr.origin, fr.scale)
                assert 0 < len(kept.outline.zlo) < len(whole.zlo)  # edges were left out
                with pytest.raises(ValueError, match="every edge"):  # nor tabulated
                    WaterlineTable.of(kept.outline, level, kept.tol, "wedge")
                partial += int(np.count_nonzero(a.sections.dx < 0.999 * d))
            else:
                assert top == np.inf
            assert np.array_equal(a.force, b.force)
            assert (a.total, a.moment) == (b.total, b.moment)
            for name in ("penetration", "half_beam", "deadrise", "mass_per_metre"):
                assert np.array_equal(getattr(a.sections, name), getattr(b.sections, name),
                                      equal_nan=True)  # fmt: skip
    assert partial > 0  # partial slices (their sections moved) were compared


@pytest.mark.parametrize("draft", [0.0123456789, 0.0314159265, 0.05])
def test_sections_exact_to_rounding_not_to_the_cutters_grid(draft):
    # closed form: a wedge of deadrise beta wetted to depth p has half-beam p / tan(beta).
    # manifold3d rounds sections to a grid of 1e-8 of the cutter's units; the body spans
    # geometry.CUTTER_SIZE of them, so the sections hold to about 1e-12 of its size (at
    # unit size they were off by up to 2e-9 of it)
    from hullslice import shapes

    hull = hs.Hull.from_arrays(*shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0))
    s = hs.cut(hull, draft, stations=[0.3, 0.61])
    exact = draft / np.tan(np.radians(30.0))
    assert np.abs(s.half_beam - exact).max() <= 5e-12 * hull.size
    assert np.abs(s.penetration - draft).max() <= 5e-12 * hull.size
