"""Pitch, forward speed and the deadrise of curved and multi-part sections."""

from __future__ import annotations

import numpy as np
import pytest

import hullslice as hs
from hullslice import shapes
from hullslice.motion import prescribed, simulate
from hullslice.sections import section_properties


def rotated(v, cg, theta):
    """Body points turned nose up by ``theta`` about ``cg`` (what a pitched pose does)."""
    c, s = np.cos(theta), np.sin(theta)
    r = v - cg
    return np.stack(
        [cg[0] + r[:, 0] * c - r[:, 2] * s, v[:, 1], cg[2] + r[:, 0] * s + r[:, 2] * c], 1
    )


@pytest.mark.parametrize("pitch_deg", [-6.0, 5.0, 12.0])
def test_pitched_prism_equals_the_prism_meshed_rotated(paper_hull, pitch_deg):
    theta = np.radians(pitch_deg)
    turned = hs.Hull.from_arrays(
        rotated(paper_hull.vertices, paper_hull.cg, theta), paper_hull.faces, mass=1.0
    )
    motion = hs.Motion(-3.0, forward_speed=4.0, pitch_rate_rad_s=0.5)
    for draft in (0.01, 0.04):
        a = hs.compute_force(paper_hull, hs.Pose(draft, theta), motion, slices=24)
        b = hs.compute_force(turned, hs.Pose(draft, 0.0), motion, slices=24)
        # the keel line comes from the mesh's own vertices in double precision: the wetted
        # extent and the velocities agree to rounding; manifold3d cuts the sections in
        # single precision, and turning the body inside it or before rounds differently
        assert a.sections.wetted_length == pytest.approx(b.sections.wetted_length, rel=1e-12)
        np.testing.assert_allclose(a.sections.x, b.sections.x, rtol=0, atol=1e-12)
        np.testing.assert_allclose(a.velocity, b.velocity, rtol=1e-10)
        assert a.total == pytest.approx(b.total, rel=1e-5)
        assert a.moment == pytest.approx(b.moment, rel=1e-5)


def test_zero_pitch_and_speed_give_the_level_results(paper_hull):
    level = hs.convergence(paper_hull, 0.0383, -3.4943, slices=(16, 32, 64))
    general = hs.convergence(
        paper_hull, hs.Pose(0.0383, 0.0), hs.Motion(-3.4943, 0.0, 0.0), slices=(16, 32, 64)
    )
    np.testing.assert_array_equal(general.forces, level.forces)
    fall = simulate(paper_hull, -4.0, 0.006, dt=2e-4, slices=16)
    free = simulate(paper_hull, -4.0, 0.006, dt=2e-4, slices=16, pitch_rad=0.0, forward_speed=0.0)
    np.testing.assert_array_equal(free.force, fall.force)
    assert fall.mode == "free fall"


def test_a_symmetric_body_with_free_pitch_stays_level(wedge_hull):
    # the wedge prism is symmetric fore and aft about its centre of gravity: no moment
    a = simulate(wedge_hull, -4.0, 0.006, dt=2e-4, slices=8)
    b = simulate(wedge_hull, -4.0, 0.006, dt=2e-4, slices=8, free_pitch=True)
    assert np.abs(b.pitch).max() < 1e-9
    np.testing.assert_allclose(b.force, a.force, rtol=1e-7)


def test_forward_speed_velocity_follows_the_keel_slope(paper_hull):
    # the prism's keel rises along x at a constant slope: (h0 - h1) / L in the body frame;
    # pitched by theta it rises at tan(alpha + theta), and moving forward at u presses each
    # fixed plane's section down at u times that slope
    p = shapes.PAPER_PRISM
    alpha = np.arctan((p["h_start"] - p["h_end"]) / p["length"])
    theta, u, w = np.radians(4.0), 6.0, -2.0
    r = hs.compute_force(paper_hull, hs.Pose(0.03, theta), hs.Motion(w, u), slices=40)
    # the transom's face, dipped aft of the keel's corner by the pitch, is not sliced: the
    # slices cover the bottom, from the corner on (the corner is the keel's lowest point)
    corner = float(
        hs.geometry.frame(paper_hull, theta).keel.x[
            np.argmin(hs.geometry.frame(paper_hull, theta).keel.z)
        ]
    ) + float(paper_hull.cg[0])
    assert r.sections.x.min() - 0.5 * r.sections.dx[0] == pytest.approx(corner, abs=1e-9)
    inner = slice(None)
    slope = np.tan(alpha + theta)
    # the mesh file is single precision (STL): its keel vertices, 0.25 mm apart, are within
    # 6e-9 m of the exact line, so each facet's slope is good to about 5e-5
    np.testing.assert_allclose(r.sections.keel_slope[inner], slope, rtol=1e-4)
    np.testing.assert_allclose(r.velocity[inner], w - u * slope, rtol=1e-4)
    # the horizontal force is the slice forces' drag along the keel
    assert r.total_x == pytest.approx(-(r.force * r.sections.keel_slope).sum(), rel=1e-12)


def test_section_velocity_is_the_keel_rate_at_fixed_planes(paper_hull):
    # an independent reference: move the body for a short time (heave w, forward speed u,
    # pitch rate q about the cg) and watch how fast the keel sinks at fixed earth planes
    from hullslice.geometry import frame

    theta, draft, dt = np.radians(4.0), 0.03, 1e-6
    w, u, q = -2.0, 5.0, 1.5
    r = hs.compute_force(paper_hull, hs.Pose(draft, theta), hs.Motion(w, u, q), slices=24)
    stations = r.sections.x[2:]  # away from the transom at x = 0

    def keel_at(t):
        th = theta + q * t
        z_cg = frame(paper_hull, theta).z_cg(draft) + w * t
        d = -(frame(paper_hull, th).lowest + z_cg)
        # the stations follow the cg along X: a plane fixed in the earth falls back by u t
        return hs.cut(paper_hull, hs.Pose(d, th), stations=stations - u * t).keel_z

    rate = (keel_at(dt) - keel_at(-dt)) / (2 * dt)
    # the keel's facets, 0.25 mm apart in a single-precision STL, have slopes good to
    # about 5e-5 (see above); the keel line's slope blends them
    np.testing.assert_allclose(r.velocity[2:], rate, rtol=1e-4)


def test_free_pitch_history_obeys_its_equations(paper_hull):
    # the paper's prism hits with its 45-degree end, behind the centre of gravity: it pitches
    # nose down; the history must satisfy I dq/dt = M and m dw/dt = F - m g
    h = simulate(paper_hull, -4.0, 0.012, dt=1e-4, slices=24, free_pitch=True, stop_on=())
    assert h.mode == "free motion" and h.pitch[-1] < 0
    t = h.t
    dq = np.gradient(h.pitch_rate, t)
    dw = np.gradient(h.velocity, t)
    inner = slice(5, -5)
    inertia = paper_hull.pitch_inertia
    np.testing.assert_allclose(
        dq[inner], (h.moment / inertia)[inner], rtol=2e-2, atol=1e-3 * abs(h.moment / inertia).max()
    )
    np.testing.assert_allclose(dw[inner], h.acceleration[inner], rtol=2e-2, atol=0.2)
    # and a prescribed motion along it reproduces its forces and moments
    kin = {
        "t": h.t,
        "draft": h.draft,
        "velocity": h.velocity,
        "pitch_rad": h.pitch,
        "pitch_rate_rad_s": h.pitch_rate,
        "forward_speed": h.forward_speed,
    }
    again = prescribed(paper_hull, kin, slices=24)
    np.testing.assert_allclose(again.force, h.force, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(again.moment, h.moment, rtol=1e-9, atol=1e-9)


# -- deadrise estimators ------------------------------------------------------------------------


@pytest.fixture(scope="module")
def cylinder():
    v, f = shapes.circular_cylinder(length=1.0, radius=0.5, points=1440)
    return hs.Hull.from_arrays(v, f, mass=300.0)


@pytest.mark.parametrize("p", [0.02, 0.1, 0.3])
def test_deadrise_estimators_on_a_circle(cylinder, p):
    R = 0.5
    c = np.sqrt(2 * R * p - p**2)  # half-width at the waterline
    closed = {
        "wedge": p / c,
        # the tangent where the circle meets the water
        "waterline-slope": c / (R - p),
        # least squares through the keel of z = R - sqrt(R^2 - y^2) over 0 <= y <= c:
        # tan(beta) = int y z dy / int y^2 dy
        "keel-fit": (R * c**2 / 2 + ((R**2 - c**2) ** 1.5 - R**3) / 3) / (c**3 / 3),
    }
    # a 1440-gon: its chords sag by R (1 - cos(pi/1440)) = 1.2e-6 m, and the edge where the
    # contour meets the water is inclined up to pi/1440 rad off the circle's tangent there
    tol = {"wedge": 1e-4, "waterline-slope": np.pi / 1440, "keel-fit": 1e-4}
    for method, tan_beta in closed.items():
        s = hs.cut(cylinder, p, 3, deadrise=method)
        for beta in (s.deadrise_port, s.deadrise_stbd, s.deadrise):
            assert beta == pytest.approx(np.full(3, np.arctan(tan_beta)), abs=tol[method])
        assert s.half_beam == pytest.approx(np.full(3, c), rel=1e-4)


def test_asymmetric_wedge_has_a_deadrise_per_side():
    v, f = shapes.asymmetric_wedge_prism(
        half_beam=0.1, deadrise_port_deg=20.0, deadrise_stbd_deg=40.0
    )
    hull = hs.Hull.from_arrays(v, f, mass=5.0)
    p = 0.02
    for method in ("wedge", "waterline-slope", "keel-fit"):
        s = hs.cut(hull, p, 3, deadrise=method)
        np.testing.assert_allclose(np.degrees(s.deadrise_port), 20.0, rtol=1e-6)
        np.testing.assert_allclose(np.degrees(s.deadrise_stbd), 40.0, rtol=1e-6)
        # both sides together: the equivalent wedge of the whole waterline width
        c = 0.5 * (p / np.tan(np.radians(20)) + p / np.tan(np.radians(40)))
        np.testing.assert_allclose(np.tan(s.deadrise), p / c, rtol=1e-6)
    s = hs.cut(hull, p, 3)
    np.testing.assert_allclose(s.half_beam_port, p / np.tan(np.radians(20)), rtol=1e-6)
    np.testing.assert_allclose(s.half_beam_stbd, p / np.tan(np.radians(40)), rtol=1e-6)


#: A section leaning to starboard, counter-clockwise in (y, z), the water at z = 0: its
#: lowest point, the keel at y = 0, lies beyond the port end of its waterline (y = -0.15).
OVERHANG = np.array([[-1.0, -0.5], [0.0, -1.0], [-0.3, 1.0], [-1.3, 1.0]])


def overhang_prism() -> hs.Hull:
    """A 2 m prism of :data:`OVERHANG`, 500 kg."""
    v, f = shapes.prism_from_sections(np.array([0.0, 2.0]), np.broadcast_to(OVERHANG, (2, 4, 2)))
    return hs.Hull.from_arrays(v, f, mass=500.0)


def test_a_keel_under_an_overhang_has_a_wall_for_its_side():
    # p / c has c = -0.15 m there: the equivalent wedge's port side rises as a wall, 90
    # deg, not the -81.5 deg p / c gives (a negative deadrise, a wedge going down from its
    # keel); the starboard side is p / c = 1 / 1.1. The same from the waterline table,
    # and in a prism of that section cut whole
    from hullslice.kernel.outline import Outline
    from hullslice.kernel.waterline_table import WaterlineTable

    props = section_properties([(OVERHANG,)], tol=1e-9)
    np.testing.assert_allclose(props["half_beam_port"], -0.15, rtol=1e-12)
    assert props["deadrise_port"][0] == np.pi / 2
    np.testing.assert_allclose(np.tan(props["deadrise_stbd"]), 1.0 / 1.1, rtol=1e-12)
    # the two sides' harmonic mean: the wall's 1 / tan is zero
    np.testing.assert_allclose(np.tan(props["deadrise"]), 2.0 / 1.1, rtol=1e-12)
    table = WaterlineTable.of(Outline.of([(OVERHANG,)], 1e-9), 0.0, 1e-9, "wedge")
    at = table.at(0.0, 0, 1)
    for key in ("deadrise", "deadrise_port", "deadrise_stbd"):
        assert at[key][0] == props[key][0], key
    cut = hs.cut(overhang_prism(), 0.5, 4)  # keel 0.5 m under: the port end 0.075 m behind
    np.testing.assert_allclose(cut.half_beam_port, -0.075, rtol=1e-9)
    np.testing.assert_allclose(cut.deadrise_port, np.pi / 2, rtol=1e-15)


def test_two_floats_are_two_wedges(wedge_hull):
    # two 30-degree wedge prisms side by side, each of half the mass: every station has two
    # pieces, each the single wedge of half the mass per metre, so the force is twice
    # that of one float of half the mass
    v, f = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0)
    shift = np.array([0.0, 0.3, 0.0])
    v2 = np.vstack([v - shift, v + shift])
    f2 = np.vstack([f, f + len(v)])
    cat = hs.Hull.from_arrays(v2, f2, mass=20.0)
    one = wedge_hull  # 10 kg
    a = hs.compute_force(cat, 0.03, -4.0, slices=8)
    b = hs.compute_force(one, 0.03, -4.0, slices=8)
    assert len(a.sections) == 16 and np.all(np.bincount(a.sections.station) == 2)
    np.testing.assert_allclose(a.sections.mass_per_metre, 10.0, rtol=1e-6)
    np.testing.assert_allclose(a.sections.deadrise_deg, 30.0, rtol=1e-6)
    np.testing.assert_allclose(np.sort(a.sections.y_keel)[[0, -1]], [-0.3, 0.3], atol=1e-9)
    assert a.total == pytest.approx(2 * b.total, rel=1e-7)


def test_a_w_section_has_two_pieces_and_a_hole_is_ignored():
    # one contour with two keels (a catamaran joined above the water) and a hole (a cavity)
    w = np.array([[-1.0, 0.5], [-0.5, -0.5], [0.0, 0.3], [0.5, -0.5], [1.0, 0.5]])
    outer = np.vstack([w, [[1.0, 1.0], [-1.0, 1.0]]])  # counter-clockwise
    hole = np.array([[-0.2, 0.6], [-0.2, 0.9], [0.2, 0.9], [0.2, 0.6]])  # clockwise
    props = section_properties([(outer, hole)], tol=1e-9)
    assert list(props["station"]) == [0, 0]
    np.testing.assert_allclose(props["penetration"], [0.5, 0.5])
    np.testing.assert_allclose(props["y_keel"], [-0.5, 0.5])
    # outer sides rise 1.0 m over 0.5 m (tan 2, waterline 0.25 m from the keel), inner sides
    # 0.8 m over 0.5 m (tan 1.6, 0.3125 m); the left keel's port side is an inner one
    np.testing.assert_allclose(np.tan(props["deadrise_port"]), [1.6, 2.0], rtol=1e-12)
    np.testing.assert_allclose(np.tan(props["deadrise_stbd"]), [2.0, 1.6], rtol=1e-12)
    np.testing.assert_allclose(props["half_beam_port"], [0.3125, 0.25], rtol=1e-12)
    np.testing.assert_allclose(np.tan(props["deadrise"]), 0.5 / ((0.25 + 0.3125) / 2), rtol=1e-12)
    np.testing.assert_allclose(props["mass_share"], [0.5, 0.5])
    # 2 m x 1.5 m less the triangles outside each keel (0.25 m^2 each) and between the
    # keels (0.4 m^2)
    area_outer = 2.0 * 1.5 - 0.25 - 0.25 - 0.4
    assert props["area"][0] == pytest.approx(area_outer - 0.4 * 0.3, rel=1e-12)


def test_a_flat_bottom_is_computed_at_one_degree_and_flagged():
    # a box: the keel-fit deadrise of its flat bottom is zero, where the wedge theory has no
    # answer; the section is computed at 1 degree and flagged, never a NaN
    v, f = shapes.prism_from_sections(
        np.array([0.0, 1.0]),
        np.broadcast_to([[-0.2, 0.0], [0.2, 0.0], [0.2, 0.3], [-0.2, 0.3]], (2, 4, 2)),
    )
    box = hs.Hull.from_arrays(v, f, mass=20.0)
    r = hs.compute_force(box, 0.02, -3.0, slices=4, deadrise="keel-fit")
    assert np.all(r.sections.deadrise == 0.0)
    assert np.all(np.isfinite(r.force)) and not r.valid.any()
    assert all("a flat bottom" in why for why in r.loads.reason)
    # the keel of a flat bottom is its middle
    np.testing.assert_allclose(r.sections.y_keel, 0.0, atol=1e-9)
