"""Transoms and steps: the keel line's faces steeper than 75 degrees in the side view.

A pitched transom dips under the water aft of the keel's corner, and the planes through
its face cut flat-bottomed sections that are no slender body's; a step's face does the
same in the middle of a bottom, and the bottom's slope must not blend across it. The
references are closed forms (Wagner's flux integrated over a tapered keel) and the
invariance of the result to how finely the same body is meshed and sliced.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import hullslice as hs
from hullslice import shapes
from hullslice.geometry import KeelLine, frame


@pytest.mark.parametrize("slicing", ["wetted", "fixed"])
def test_a_pitched_wedge_dropped_vertically_gets_wagners_tapered_keel_force(slicing):
    # a 20 deg wedge prism (transoms at both ends) pitched 5 deg nose up, 0.02 m deep,
    # sinking at 1 m/s with no forward speed, g = 0. Each plane's section is a wedge whose
    # deadrise, in the plane, has tan(beta') = tan(beta) / cos(theta), its depth falling
    # linearly from the transom's corner: Wagner's flux integrated over the wetted keel,
    # d / tan(theta) long, is rho pi gamma^2 V^2 cos^2(theta) d^2 / (2 tan^2(beta) tan(theta)).
    # The face of the transom under the water aft of the corner is no section of the bottom.
    v, f = shapes.wedge_prism(length=1.0, beam=0.3, deadrise_deg=20.0, stations=11)
    hull = hs.Hull.from_arrays(v, f)
    th, d, speed, beta = math.radians(5.0), 0.02, 1.0, math.radians(20.0)
    closed = (
        1000.0 * math.pi * (math.pi / 2) ** 2 * speed**2 * math.cos(th) ** 2 * d**2
        / (2.0 * math.tan(beta) ** 2 * math.tan(th))
    )  # fmt: skip
    for slices in (16, 256, 1024, 4096):
        r = hs.compute_force(
            hull, hs.Pose(d, th), hs.Motion(-speed), solver="wagner", slices=slices,
            slicing=slicing, acceleration=0.0, fluid=hs.Fluid(g=0.0),
        )  # fmt: skip
        # (a fixed slice at the corner whose mid-station lies behind it, through the
        # transom's face, takes its inward neighbour's section: 2.3e-4 off at 1024 before)
        assert r.total == pytest.approx(closed, rel=1e-9)
        # the force normal to a keel sloping at -tan(theta): a drag of F tan(theta) aft
        assert r.total_x == pytest.approx(-r.total * math.tan(th), rel=1e-9)


def stepped_float(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A 1 m float of 25 deg deadrise, 0.3 m beam, with a 3 cm step at x = 0.5 m (the
    forebody deeper), lofted through stations ``x``."""

    def section(keel: float) -> list[tuple[float, float]]:
        chine = keel + 0.15 * math.tan(math.radians(25.0))
        return [(0.0, keel), (0.15, chine), (0.15, 0.25), (-0.15, 0.25), (-0.15, chine)]

    return shapes.prism_from_sections(
        x, np.array([section(k) for k in np.where(x < 0.5, 0.03, 0.0)])
    )


def test_a_step_gives_the_same_force_however_the_float_is_meshed_and_sliced():
    # the same body in 36 faces and in 1,016: the bottom's slope blended across the step's
    # face gave the sections ahead of it a slope of -8.8 (0.105 is true) on the coarse mesh,
    # and a keel curvature of 263 1/m on the fine one: 556 N and 324 N
    coarse = hs.Hull.from_arrays(*stepped_float(np.array([0.0, 0.4999, 0.5, 1.0])))
    x = np.concatenate([np.linspace(0.0, 0.4999, 51), np.linspace(0.5, 1.0, 51)])
    fine = hs.Hull.from_arrays(*stepped_float(x))
    assert coarse.volume == pytest.approx(fine.volume, rel=1e-12)
    pose, motion = hs.Pose(draft=0.03, pitch_rad=math.radians(6.0)), hs.Motion(-1.0, 10.0)
    forces = []
    for hull in (coarse, fine):
        for slices in (16, 64, 128):
            r = hs.compute_force(
                hull, pose, motion, slices=slices, solver="wagner", acceleration=0.0
            )
            forces.append((r.total, r.total_x))
            # the bottom's slope is the pitch's, tan(6 deg), up to the step's face; a
            # section on the face (where a plane falls there) is dry, or gets no force and
            # is flagged
            face = np.abs(r.sections.keel_slope) > 1.0
            np.testing.assert_allclose(r.sections.keel_slope[~face], math.tan(pose.pitch))
            assert np.all(r.loads.force_per_metre[face] == 0.0)
            assert not (r.valid & r.sections.wetted)[face].any()
    np.testing.assert_allclose(forces, [forces[0]] * len(forces), rtol=1e-9)


def test_the_slope_does_not_blend_across_a_step_and_its_jump_is_not_curvature():
    # a bottom at slope 0.1, a face steeper than 75 deg (slope -20) at x = 1, then a bottom
    # at slope 0.1 again: the bottoms keep 0.1 up to the face, the face its own slope, and
    # the curvature averaged over any slice is zero (straight runs; the jumps are edges)
    x = np.array([0.0, 0.5, 1.0, 1.01, 1.51, 2.01])
    z = np.array([0.0, 0.05, 0.1, -0.1, -0.05, 0.0])
    keel = KeelLine(x, z)
    at = np.array([0.2, 0.74, 0.99, 1.005, 1.02, 1.9])
    _, slope = keel.at(at)
    np.testing.assert_allclose(slope, [0.1, 0.1, 0.1, -20.0, 0.1, 0.1], rtol=1e-12)
    centres = np.linspace(0.05, 1.95, 39)
    np.testing.assert_allclose(keel.mean_curvature(centres, 0.1), 0.0, atol=1e-9)
    np.testing.assert_allclose(keel.curvature(at), 0.0, atol=1e-12)
    # without the face, a kink blends over the facets beside it as before
    bend = KeelLine(np.array([0.0, 1.0, 2.0]), np.array([0.0, 0.1, 0.3]))
    assert bend.at(np.array([1.0]))[1][0] == pytest.approx(0.15, rel=1e-12)
    assert bend.mean_curvature(np.array([1.0]), np.array([1.0]))[0] == pytest.approx(0.1, rel=1e-12)


def test_an_end_face_turning_is_not_the_keels_curvature():
    # a bottom on the parabola z = 0.05 x^2 (curvature 0.1 1/m) up to x = 1, then a tail's
    # cap as a fan of micro-facets whose slopes turn from 20 to 1300 (a mesh's end face):
    # a slice whose window reaches into the cap gets the bottom's own turn of slope only,
    # the same as with the cap a single facet, and the cap has no local curvature
    xb = np.linspace(0.0, 1.0, 21)
    cap_slopes = np.array([20.0, 80.0, 300.0, 800.0, 1300.0])
    xc = 1.0 + np.cumsum(np.full(len(cap_slopes), 0.004))
    zc = 0.05 + np.cumsum(0.004 * cap_slopes)
    fan = KeelLine(np.concatenate([xb, xc]), np.concatenate([0.05 * xb**2, zc]))
    one = KeelLine(np.concatenate([xb, xc[-1:]]), np.concatenate([0.05 * xb**2, zc[-1:]]))
    centres, width = np.array([0.5, 0.8, 0.95, 1.0, 1.01]), 0.5
    # the continuous slope is 0.1 x up to the last bottom facet's middle, held beyond it
    last = 0.5 * (xb[-1] + xb[-2])
    lo, hi = centres - width / 2, np.minimum(centres + width / 2, last)
    expected = 0.1 * (hi - lo) / width
    np.testing.assert_allclose(fan.mean_curvature(centres, width), expected, rtol=1e-10)
    np.testing.assert_allclose(one.mean_curvature(centres, width), expected, rtol=1e-10)
    np.testing.assert_allclose(fan.curvature(xc[1:] - 0.002), 0.0, atol=1e-9)
    assert fan.curvature(np.array([0.5]))[0] == pytest.approx(0.1, rel=1e-9)


def _polyline(slopes_and_widths, x0: float = 0.0) -> KeelLine:
    """A keel line of facets given as (slope, width) pairs from ``(x0, 0)``."""
    slopes, widths = np.array(slopes_and_widths, dtype=float).T
    x = x0 + np.concatenate([[0.0], np.cumsum(widths)])
    return KeelLine(x, np.concatenate([[0.0], np.cumsum(slopes * widths)]))


@pytest.mark.parametrize(
    "corner",
    [
        [(-2.5, 0.0004), (-9.0, 0.009)],  # a step's corner at a pitch: 0.4 mm at -2.5, then -9
        [(2.0, 0.02)],  # a step's face leaned below END_FACE_SLOPE by the pitch
        [(1.2, 0.004), (3.0, 0.004), (30.0, 0.01)],  # an end face rounding to vertical
    ],
)
def test_a_corner_steeper_than_45_degrees_is_not_the_keels_curvature(corner):
    # straight bottoms (slopes 0.1 and -0.23, facets of 5 cm) on either side of a corner
    # whose facets are steeper than 45 degrees: over any window the bottom does not turn
    # (the step from one bottom to the other is the corner's, as at a single steep
    # facet), and the corner has no local curvature
    before, after = [(0.1, 0.05)] * 20, [(-0.23, 0.05)] * 20
    line = _polyline(before + corner + after)
    centres = np.array([0.6, 0.8, 0.95, 1.0, 1.004, 1.01, 1.2])
    np.testing.assert_allclose(line.mean_curvature(centres, 0.5), 0.0, atol=1e-9)
    width = sum(w for _, w in corner)
    inside = 1.0 + np.linspace(0.05, 0.95, 5) * width
    np.testing.assert_allclose(line.curvature(inside), 0.0, atol=1e-9)
    # a bottom that does turn keeps its curvature up to the corner
    bent = _polyline([(0.1 + 0.01 * i, 0.05) for i in range(20)] + corner + after)
    assert bent.mean_curvature(np.array([0.5]), 0.4)[0] == pytest.approx(0.2, rel=1e-9)


def spindle(offset: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """A 1 m body of revolution (radius 0.1 m, round ends) lying on z = 0, from x = offset."""
    x = np.linspace(0.0, 1.0, 41)
    r = np.maximum(0.1 * np.sqrt(np.clip(1.0 - ((x - 0.5) / 0.5) ** 2, 0.0, None)), 1e-3)
    t = np.linspace(0.0, 2.0 * np.pi, 48, endpoint=False) - np.pi / 2
    sec = np.stack([np.cos(t)[None] * r[:, None], 0.1 + np.sin(t)[None] * r[:, None]], axis=2)
    v, f = shapes.prism_from_sections(x, sec)
    return v + np.array([offset, 0.0, 0.0]), f


@pytest.mark.parametrize("slicing", ["wetted", "fixed"])
def test_two_bodies_one_behind_the_other_carry_twice_ones_force(slicing):
    # level, the stations in the 0.3 m gap between them have no section: dry entries with
    # their keel put at the water (an infinite keel height gave NaN forces, marked valid).
    # Each body then meets the water as it would alone: twice one body's force
    (v1, f1), (v2, f2) = spindle(), spindle(1.3)
    pair = hs.Hull.from_arrays(np.vstack([v1, v2]), np.vstack([f1, f2 + len(v1)]))
    one = hs.Hull.from_arrays(v1, f1)
    pose, motion = hs.Pose(draft=0.03), hs.Motion(-3.0)
    for solver in ("wagner", "zarnick"):
        r = hs.compute_force(pair, pose, motion, slices=256, solver=solver, slicing=slicing,
                             acceleration=0.0)  # fmt: skip
        alone = hs.compute_force(one, pose, motion, slices=256, solver=solver, slicing=slicing,
                                 acceleration=0.0)  # fmt: skip
        assert np.isfinite(r.total) and np.isfinite(r.moment)
        # the gap takes some of the wetted slicing's slices: 256 over 2.3 m, not 1 m
        assert r.total == pytest.approx(2.0 * alone.total, rel=0.015)


def test_a_keel_steeper_than_45_degrees_is_flagged():
    # a V bottom whose last panel rises 0.14 m to the bow at 60 deg, met at 10 m/s: the
    # sections there are pressed down at 10 m/s times the slope, beyond a slender body;
    # computed, flagged, so the validity rule sees them
    def vsec(keel: float) -> np.ndarray:
        chine = keel + 0.25 * math.tan(math.radians(20.0))
        return np.array([[-0.25, 0.4], [-0.25, chine], [0.0, keel], [0.25, chine], [0.25, 0.4]])

    rise = 0.14 / math.tan(math.radians(60.0))
    x = np.array([0.0, 0.5, 1.0, 2.0 - rise, 2.0])
    hull = hs.Hull.from_arrays(
        *shapes.prism_from_sections(x, np.stack([vsec(k) for k in (0, 0, 0, 0, 0.14)]))
    )
    # a draft of 0.1 m wets 58 mm of the panel, more than a slice (a slice's slope is the
    # keel's chord over it)
    pose, motion = hs.Pose(draft=0.1), hs.Motion(-1.0, 10.0)
    r = hs.compute_force(hull, pose, motion, slices=64, solver="zarnick", acceleration=0.0)
    steep = r.sections.wetted & (np.abs(r.sections.keel_slope) > 1.0)
    assert steep.any()
    assert not r.valid[steep].any() and all(
        "steeper than 45 deg" in s for s in r.loads.reason[steep]
    )
    assert r.valid[r.sections.wetted & ~steep].all()


def _v_prism(x, keels, y=0.0, deadrise=25.0, half=0.15, top=0.25):
    def section(keel):
        chine = min(keel + half * math.tan(math.radians(deadrise)), top - 0.01)
        return [(y, keel), (y + half, chine), (y + half, top), (y - half, top), (y - half, chine)]

    return shapes.prism_from_sections(np.array(x), np.array([section(k) for k in keels]))


def test_a_vertical_step_face_is_a_jump_of_the_keel_line_not_a_ramp():
    # the stepped float with its 3 cm step's face vertical (two sections at x = 0.5 m)
    # against the same face 0.1 mm long: level, the keel line is flat to the step and
    # jumps there; it was a ramp from x = 0 to the step, for 2.3 % more force and a
    # horizontal force on a level flat bottom
    with pytest.warns(hs.MeshRepairWarning, match="degenerate"):  # the face's lofted strip
        v, f = _v_prism([0, 0.5, 0.5, 1.0], [0.03, 0.03, 0, 0])
        vertical = hs.Hull.from_arrays(v, f, mass=5.0)
    leaned = hs.Hull.from_arrays(*_v_prism([0, 0.4999, 0.5, 1.0], [0.03, 0.03, 0, 0]), mass=5.0)
    fr = frame(vertical, 0.0)
    z = fr.keel.height(np.array([0.25, 0.4999, 0.5001, 0.75]) - fr.cg[0]) + fr.cg[2]
    np.testing.assert_allclose(z, [0.03, 0.03, 0.0, 0.0], atol=1e-12)
    pose, motion = hs.Pose(draft=0.02), hs.Motion(-1.0, 5.0)
    a, b = (hs.compute_force(h, pose, motion, slices=16) for h in (vertical, leaned))
    assert a.total == pytest.approx(b.total, rel=1e-4)  # the faces differ by 0.1 mm
    assert a.total_x == pytest.approx(0.0, abs=1e-9 * a.total)


def test_a_parts_vertical_end_over_another_parts_bottom_ends_the_wetted_part_there():
    # a lower float (keel at 0) ending at x = 2.1 m in a vertical face, beside a longer one
    # whose keel is 0.3 m up: at a 5 cm draft the keel line is wet to 2.1 m, not along a
    # ramp from 2.1 to 4.0 m, and the slice from 2.0 m is the lower float's 0.1 m
    low = _v_prism([0.0, 2.1], [0.0, 0.0], y=1.5, deadrise=30.0, half=0.4, top=0.8)
    high = _v_prism([0.0, 4.0], [0.3, 0.3], deadrise=10.0, half=0.4, top=1.3)
    v = np.concatenate([high[0], low[0]])
    f = np.concatenate([high[1], low[1] + len(high[0])])
    hull = hs.Hull.from_arrays(v, f, mass=100.0)
    r = hs.compute_force(
        hull, hs.Pose(draft=0.05), hs.Motion(-1.0), slices=8, slicing="fixed",
        solver="von-karman", acceleration=0.0,
    )  # fmt: skip
    s = r.sections
    assert s.wetted.all() and len(s.dx) == 5
    assert s.dx[-1] == pytest.approx(0.1, rel=1e-6)
    per_metre = r.force / s.dx
    np.testing.assert_allclose(per_metre, per_metre[0], rtol=1e-9)
