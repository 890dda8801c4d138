"""Fixed slicing: cut once per pitch and reused, the same numbers as cut afresh, and the
same limit as the paper's slicing of the wetted length."""

from __future__ import annotations

import numpy as np
import pytest

import hullslice as hs
from hullslice.motion import ForceModel, simulate


@pytest.mark.parametrize("pitch_deg", [0.0, 5.0])
def test_cached_fixed_slicing_equals_cutting_afresh(paper_hull, pitch_deg):
    cached = ForceModel(paper_hull, slices=96, slicing="fixed")
    fresh = ForceModel(paper_hull, slices=96, slicing="fixed", cache=False)
    motion = hs.Motion(-3.0, forward_speed=2.0, pitch_rate=0.3)
    for draft in (0.0005, 0.004, 0.02, 0.05, 0.09):
        pose = hs.Pose(draft, np.radians(pitch_deg))
        a, b = cached(pose, motion), fresh(pose, motion)
        # the same planes cut by the same manifold3d calls: identical to the last bit
        np.testing.assert_array_equal(a.force, b.force)
        assert a.total == b.total and a.moment == b.moment
        for name in ("penetration", "deadrise", "mass_per_metre", "keel_slope", "x", "dx"):
            np.testing.assert_array_equal(getattr(a.sections, name), getattr(b.sections, name))


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


def test_first_contact_with_fixed_slicing(paper_hull):
    # the wetted part narrower than a slice: cut where it is (no wetted section to borrow)
    r = hs.compute_force(paper_hull, 1e-4, -4.0, slices=16, slicing="fixed")
    w = hs.compute_force(paper_hull, 1e-4, -4.0, slices=1)
    assert len(r.sections) == 1 and r.sections.wetted_length < 0.35 / 16
    assert r.total == pytest.approx(w.total, rel=1e-9)


def test_unknown_slicing(paper_hull):
    with pytest.raises(hs.InputError, match="slicing 'even' is unknown"):
        hs.compute_force(paper_hull, 0.02, -3.0, slicing="even")
