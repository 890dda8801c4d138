"""The ``mlm`` plugin (the Modified Logvinovich Model) and the bound on suction.

References:

- Korobkin (2004), Eur. J. Appl. Math. 15, 821-838: the MLM pressure; on a wedge at
  constant speed its force per metre has the closed form of
  :func:`hullslice_mlm.wedge_force`, and it tends to Wagner's flat-plate force
  ``rho pi^3 V^3 t / (4 tan^2 beta)`` as the deadrise goes to zero.
- The momentum form (METHOD section 6): the pressure's integral over the wetted contour is
  the force per metre ``rate v^2 - m_a a``.
- Far past a sharp edge a straight continuation of deadrise ``beta_c`` gives the drag
  ``rho V^2 b (pi / tan(beta_c) - 1)`` per metre (:func:`continuation_for_drag`).
- On a circle Wagner's condition is ``s / R = 1 - (2 / pi) E(c / R)`` (complete elliptic
  integral of the second kind); the MLM's pressure integrated on the exact circle with that
  contact is the reference of a meshed cylinder's force until its contact leaves the
  circle, where the circle is as steep as the continuation.
- Water cannot pull harder than ``p_atm - p_vapour``: no section's force per metre is
  below that times the horizontal breadth of its wetted bottom (the vertical force of
  that pressure on it).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

import hullslice as hs
from hullslice import shapes

mlm = pytest.importorskip("hullslice_mlm")

from .conftest import MESHES  # noqa: E402

RHO = 1000.0
MOMENTUM_SOLVERS = ("mlm", "zarnick", "wagner", "von-karman")


def wedge(deadrise_deg: float, beam: float = 0.4, sides: float = 0.0) -> hs.Hull:
    v, f = shapes.wedge_prism(length=1.0, beam=beam, deadrise_deg=deadrise_deg, sides=sides)
    return hs.Hull.from_arrays(v, f)


def per_metre(result: hs.ForceResult) -> np.ndarray:
    return np.asarray(result.force) / np.asarray(result.sections.dx)


def test_mlm_is_installed_as_a_plugin_of_the_momentum_kind():
    info = {i.name: i for i in hs.list_solvers()}["mlm"]
    assert (info.status, info.kind, info.distribution) == ("ok", "momentum", "hullslice-mlm")


@pytest.mark.parametrize("deadrise_deg", [10.0, 20.0, 30.0, 45.0])
@pytest.mark.parametrize("method", ["auto", "contour", "wedge"])
def test_a_wedge_at_constant_speed_has_the_closed_form(deadrise_deg, method):
    beta = math.radians(deadrise_deg)
    p = 0.02 * math.tan(beta)  # the contact at a quarter of the chine's half-width
    r = hs.compute_force(
        wedge(deadrise_deg), p, -5.0, slices=4, solver=mlm.MLM(section_method=method),
        acceleration=0.0, fluid=hs.Fluid(RHO, 0.0),
    )  # fmt: skip
    assert r.total == pytest.approx(mlm.wedge_force(beta, p, 5.0, RHO), rel=1e-6)
    assert r.all_valid


def _positive_part_by_quadrature(beta: float, p: float, speed: float) -> float:
    """The velocity term's pressure on a wedge, its positive part integrated by adaptive
    quadrature over y (Korobkin 2004, eq. of the MLM pressure; c = pi p / (2 tan(beta)))."""
    from scipy.integrate import quad

    k = math.tan(beta)
    cp = math.pi / (2.0 * k)
    c = cp * p

    def pressure(y: float) -> float:  # p / (rho V^2) at y on one side
        r = c * c - y * y
        return max(c * cp / math.sqrt(r) - 0.5 - y * y / (2.0 * r * (1.0 + k * k)), 0.0)

    return 2.0 * RHO * speed**2 * quad(pressure, 0.0, c, limit=400, epsabs=0.0)[0]


@pytest.mark.parametrize("deadrise_deg", [60.0, 72.0, 72.5, 76.0, 80.0, 85.0])
def test_a_steep_wedge_loads_the_positive_part_of_its_pressure(deadrise_deg):
    # steeper than atan(pi) = 72.3 deg the pressure is negative at the keel and positive
    # further out: the load is that part's, not nothing
    beta = math.radians(deadrise_deg)
    reference = _positive_part_by_quadrature(beta, 0.1, 5.0)
    assert mlm.wedge_force(beta, 0.1, 5.0, RHO) == pytest.approx(reference, rel=1e-7)
    # a meshed wedge at a quarter and at 95 % of its chine's reach, every slice alike
    for share in (0.25, 0.95):
        p = share * 0.2 * math.tan(beta) * 2.0 / math.pi
        r = hs.compute_force(
            wedge(deadrise_deg), p, -5.0, slices=4, solver="mlm", acceleration=0.0,
            fluid=hs.Fluid(RHO, 0.0),
        )  # fmt: skip
        np.testing.assert_allclose(
            per_metre(r), mlm.wedge_force(beta, p, 5.0, RHO), rtol=1e-6, err_msg=f"{share}"
        )
        assert r.pressures is not None  # whose points carry that part only
        np.testing.assert_allclose(r.pressures.force_per_metre(), per_metre(r), rtol=1e-9)
        assert r.pressures.pressure.min() >= 0.0


def test_the_wedge_force_is_continuous_where_the_keel_pressure_changes_sign():
    edge = math.atan(math.pi)  # where c' = 1/2: the keel's pressure is zero
    below, above = (mlm.wedge_force(edge + d, 0.1, 5.0, RHO) for d in (-1e-7, 1e-7))
    assert above > 0.0
    assert above == pytest.approx(below, rel=1e-5)


def test_the_closed_form_tends_to_wagner_as_the_deadrise_goes_to_zero():
    def ratio(deg: float) -> float:
        beta, p, V = math.radians(deg), 0.01, 5.0
        cp = math.pi / (2.0 * math.tan(beta))  # Wagner: c = cp p, f = rho pi c cp V^2
        return mlm.wedge_force(beta, p, V, RHO) / (RHO * math.pi * cp * cp * p * V * V)

    gaps = [1.0 - ratio(d) for d in (4.0, 2.0, 1.0, 0.5)]
    assert all(0.0 < g for g in gaps)
    assert gaps[-1] < 0.02  # within 2 % at half a degree
    assert all(b < a for a, b in itertools.pairwise(gaps))  # and closing


@pytest.mark.parametrize("acceleration", [0.0, 40.0, -25.0])
def test_the_pressures_integrate_to_the_force(acceleration):
    hull = wedge(30.0, beam=0.5, sides=0.3)
    for p in (0.05, 0.2):  # before and after the knuckles
        r = hs.compute_force(hull, p, -6.0, slices=2, solver="mlm", acceleration=acceleration)
        assert r.pressures is not None
        np.testing.assert_allclose(r.pressures.force_per_metre(), per_metre(r), rtol=1e-9)
        pts = r.pressures.points
        assert np.all(pts.y <= 0.25 + 1e-9)  # the real body only, past the knuckle too


def test_past_a_sharp_edge_the_load_tends_to_the_continuations_drag():
    hull = wedge(30.0, beam=0.5, sides=30.0)
    solver = mlm.MLM()  # the default continuation: Zarnick's cross-flow drag, 1.0
    assert solver.settings["continuation"] == pytest.approx(mlm.continuation_for_drag(1.0))
    b, V = 0.25, 6.0
    for p, tol in ((2.0, 2e-3), (10.0, 1e-4)):
        r = hs.compute_force(hull, p, -V, slices=2, solver=solver, acceleration=0.0)
        assert r.total / (RHO * V**2 * b) == pytest.approx(1.0, rel=tol)
        assert r.loads.diagnostics["separated"].all()


def test_a_round_section_keeps_its_load_past_its_widest_point():
    R = 0.5
    v, f = shapes.circular_cylinder(length=1.0, radius=R, points=720)
    hull = hs.Hull.from_arrays(v, f)
    s_d = np.array([0.05, 0.1, 0.15, 0.18, 0.2, 0.3, 0.5, 0.7, 1.0])
    cs = np.array([
        hs.compute_force(hull, s * 2 * R, -5.0, slices=2, solver="mlm", acceleration=0.0).total
        / (RHO * R * 25.0)
        for s in s_d
    ])  # fmt: skip
    # no loss at the widest point (s/D = 0.18 for Wagner's contact): the slamming
    # coefficient falls steadily and stays above the continuation's drag, 1.0
    assert np.all(np.diff(cs) < 0.0)
    assert np.all(cs > 1.0)
    assert cs[-1] == pytest.approx(1.0, abs=0.15)


def _mlm_on_the_exact_circle(s_over_r: float) -> float:
    """``F / (rho R V^2)`` of the MLM on a circle at constant speed, by quadrature."""
    from scipy.integrate import quad
    from scipy.optimize import brentq
    from scipy.special import ellipe, ellipk

    def depth(k: float) -> float:  # Wagner's condition on the circle, R = 1
        return 1.0 - 2.0 / math.pi * ellipe(k * k) - s_over_r

    c = brentq(depth, 1e-12, 1.0 - 1e-15, xtol=1e-15)
    dc = math.pi * c / (2.0 * (ellipk(c * c) - ellipe(c * c)))

    def bracket(t: float) -> float:  # p / (rho V^2) times cos(t), y = c sin(t)
        y = c * math.sin(t)
        return dc - 0.5 * math.cos(t) - math.sin(t) ** 2 * (1.0 - y * y) / (2.0 * math.cos(t))

    end = brentq(bracket, 0.0, 0.5 * math.pi * (1.0 - 1e-14), xtol=1e-15)
    return 2.0 * c * quad(bracket, 0.0, end, epsabs=1e-13, limit=200)[0]


def test_a_meshed_cylinder_has_the_mlm_force_of_the_exact_circle():
    R, V = 0.5, 5.0
    v, f = shapes.circular_cylinder(length=1.0, radius=R, points=1440)
    hull = hs.Hull.from_arrays(v, f)
    fluid = hs.Fluid(RHO, 0.0)
    # up to s/D = 0.107 the contact stays on the circle (its side is less steep than the
    # default continuation's 57.5 deg)
    for s_d in (0.0025, 0.005, 0.02, 0.05, 0.1):
        r = hs.compute_force(hull, 2 * R * s_d, -V, slices=2, solver="mlm", fluid=fluid,
                             acceleration=0.0)  # fmt: skip
        cs = r.total / (RHO * R * V**2)
        assert cs == pytest.approx(_mlm_on_the_exact_circle(2 * s_d), rel=5e-3), s_d


def test_a_re_entrant_section_is_flagged():
    # a bottom that rises, dips back down and rises again
    sec = np.array([[0.0, 0.0], [0.1, 0.05], [0.15, 0.03], [0.2, 0.2], [0.2, 0.4],
                    [-0.2, 0.4], [-0.2, 0.2], [-0.15, 0.03], [-0.1, 0.05]])  # fmt: skip
    x = np.array([0.0, 1.0])
    v, f = shapes.prism_from_sections(x, np.broadcast_to(sec, (2, len(sec), 2)))
    hull = hs.Hull.from_arrays(v, f)
    r = hs.compute_force(hull, 0.1, -5.0, slices=2, solver="mlm", acceleration=0.0)
    assert not r.valid.any()
    assert all("re-entrant" in why for why in r.loads.reason)


@pytest.mark.parametrize(
    ("options", "words"),
    [
        ({"continuation": math.nan}, "continuation=nan"),
        ({"continuation": -5.0}, "continuation=-5.0"),
        ({"continuation": 90.0}, "vertical"),
        ({"continuation": "curved"}, "tangent"),
        ({"smooth_edge_deg": 0.0}, "smooth_edge_deg=0.0"),
        ({"froude_min": -1.0}, "froude_min=-1.0"),
        ({"froude_min": 0.0}, r"froude_min=0.0 is not a number in \(0, inf\)"),
        ({"froude_min": math.inf}, "froude_min=inf"),
        ({"gravity": "yes"}, "gravity='yes'"),
        ({"section_method": "exact"}, "section_method='exact'"),
    ],
)
def test_bad_options_are_refused_in_one_line(options, words):
    with pytest.raises(hs.InputError, match=words) as err:
        hs.get_solver("mlm", **options)
    assert "\n" not in str(err.value)


def test_a_continuation_not_steeper_than_the_bottom_is_refused():
    hull = wedge(30.0, beam=0.5, sides=0.3)
    with pytest.raises(hs.InputError, match="not steeper than the bottom") as err:
        hs.compute_force(hull, 0.2, -6.0, slices=2, solver=mlm.MLM(continuation=20.0),
                         acceleration=0.0)  # fmt: skip
    assert "x = " in str(err.value) and "\n" not in str(err.value)


def test_gravity_adds_the_hydrostatic_force_of_the_area_below_the_calm_water():
    hull = wedge(30.0)
    p = 0.05
    kw = {"slices": 2, "acceleration": 0.0}
    dry = hs.compute_force(hull, p, -5.0, solver=mlm.MLM(), **kw).total
    wet = hs.compute_force(hull, p, -5.0, solver=mlm.MLM(gravity=True), **kw).total
    area = p * p / math.tan(math.radians(30.0))  # the wedge's triangle below the water
    assert wet - dry == pytest.approx(RHO * 9.81 * area, rel=1e-9)


@pytest.mark.parametrize("solver", MOMENTUM_SOLVERS)
def test_no_section_pulls_harder_than_the_water_can(solver):
    # the bundled fuselage, pitched 6 deg at 60 m/s and sinking at 1.5 m/s, 0.5 m deep:
    # its keel curves up aft, where the inertia term pulls sections down
    hull = hs.load_hull(MESHES / "fuselage_full.obj", mass=60000.0)
    pose = hs.Pose(draft=0.5, pitch_rad=math.radians(6.0))
    motion = hs.Motion(velocity=-1.5, forward_speed=60.0)
    r = hs.compute_force(hull, pose, motion, slices=64, solver=solver)
    fluid = hs.Fluid()
    lower = r.loads.diagnostics["suction_bound"]
    wet = r.sections.wetted
    assert np.all(lower[wet] < 0.0) and np.all(lower[~wet] == 0.0)
    assert np.all(per_metre(r) >= lower - 1e-9 * np.abs(lower))
    limited = r.loads.diagnostics["suction_limited"] > 0
    if hs.get_solver(solver).positive_pressure:
        # the MLM's load is the positive part of its pressure: no suction to bound
        assert r.pressures is not None
        assert r.pressures.pressure.min() >= -fluid.suction_limit
    else:
        assert limited.any()  # the case does reach the bound
    np.testing.assert_allclose(per_metre(r)[limited], lower[limited], rtol=1e-12)
    # the bound is the suction limit times a breadth at least the waterline's
    width = r.sections.half_beam_port + r.sections.half_beam_stbd
    assert np.all(-lower[wet] >= fluid.suction_limit * width[wet] * (1 - 1e-12))


@pytest.mark.parametrize("solver", ["zarnick", "wagner", "von-karman"])
def test_the_suction_bound_is_the_limit_times_the_wetted_breadth(solver):
    # a pressure no lower than -p_lim pulls a section down by at most p_lim times the
    # horizontal breadth of its wetted bottom: on a circle of radius R at draft d,
    # 2 sqrt(R^2 - (R - d)^2) below its widest point and 2 R above it (not the girth,
    # sqrt(2) times as much when half immersed); on a wedge 2 d / tan(beta)
    R = 0.5
    circle = hs.Hull.from_arrays(*shapes.circular_cylinder(length=1.0, radius=R, points=1440))
    limit = hs.Fluid().suction_limit
    for d in (0.1, 0.5, 0.9):
        r = hs.compute_force(circle, d, -1.0, slices=2, solver=solver, acceleration=0.0)
        breadth = 2.0 * math.sqrt(R * R - (R - d) ** 2) if d < R else 2.0 * R
        bound = r.loads.diagnostics["suction_bound"]
        np.testing.assert_allclose(bound, -limit * breadth, rtol=1e-4, err_msg=f"d = {d}")
    r = hs.compute_force(wedge(30.0), 0.02, -1.0, slices=2, solver=solver, acceleration=0.0)
    breadth = 2.0 * 0.02 / math.tan(math.radians(30.0))
    np.testing.assert_allclose(r.loads.diagnostics["suction_bound"], -limit * breadth, rtol=1e-9)


def test_the_suction_bound_leaves_a_body_that_does_not_pull_alone():
    # a wedge entering at constant speed has positive pressure: nothing is limited
    r = hs.compute_force(wedge(20.0), 0.01, -5.0, slices=4, solver="zarnick", acceleration=0.0)
    assert not r.loads.diagnostics["suction_limited"].any()


def test_the_fluid_refuses_a_vapour_pressure_above_the_atmosphere():
    with pytest.raises(hs.InputError, match="vapour pressure"):
        hs.Fluid(p_vapour=2e5)
    with pytest.raises(hs.InputError, match="atmospheric pressure"):
        hs.Fluid(p_atm=-1.0)
    assert hs.Fluid().suction_limit == pytest.approx(101325.0 - 2339.0)


def test_the_force_command_writes_the_pressures_that_sum_to_the_force(tmp_path, capsys):
    import csv
    import json

    from hullslice.cli import main

    mesh = str(MESHES / "wedge_prism.stl")
    args = ["force", mesh, "--mass", "10", "--draft", "0.02", "--velocity=-5", "--slices", "4",
            "--solver", "mlm", "--format", "json"]  # fmt: skip
    path = tmp_path / "p.csv"
    assert main([*args, "--pressures", str(path)]) == 0
    data = json.loads(capsys.readouterr().out)
    rows = list(csv.DictReader(path.open()))
    assert {r["side"] for r in rows} == {"port", "starboard"}
    for s in data["slices"]:  # each slice's weights times pressures: its force per metre
        mine = [r for r in rows if float(r["x"]) == pytest.approx(s["x"], abs=1e-12)]
        total = sum(float(r["weight"]) * float(r["pressure"]) for r in mine)
        assert total == pytest.approx(s["force_per_metre"], rel=1e-9)
    js = tmp_path / "p.json"
    assert main([*args, "--pressures", str(js)]) == 0
    doc = json.loads(js.read_text())
    assert doc["units"]["pressure"] == "Pa" and len(doc["points"]) == len(rows)


def test_pressures_from_a_solver_that_gives_none_are_refused_before_any_work(tmp_path, capsys):
    from hullslice.cli import main

    path = tmp_path / "p.csv"
    rc = main(["force", str(MESHES / "wedge_prism.stl"), "--mass", "10", "--draft", "0.02",
               "--velocity=-5", "--solver", "zarnick", "--pressures", str(path)])  # fmt: skip
    err = capsys.readouterr().err.strip()
    assert rc != 0 and "gives no pressures" in err and "--solver mlm" in err
    assert len(err.splitlines()) == 1 and not path.exists()


def test_the_mlm_carries_no_suction_where_the_keel_curves_up_aft():
    # the bundled fuselage pitched 12 deg at 60 m/s: its tail cone is in the water, whose
    # curvature makes the strip theory's inertia term pull the sections there down
    hull = hs.load_hull(MESHES / "fuselage_full.obj", mass=60000.0)
    pose = hs.Pose(draft=1.6, pitch_rad=math.radians(12.0))
    motion = hs.Motion(velocity=2.0, forward_speed=60.0, pitch_rate_rad_s=math.radians(5.0))
    kw = {"slices": 24, "acceleration": 0.0}
    m = hs.compute_force(hull, pose, motion, solver="mlm", **kw)
    z = hs.compute_force(hull, pose, motion, solver="zarnick", **kw)
    assert m.pressures is not None and m.pressures.pressure.min() >= 0.0
    assert np.all(per_metre(m) >= 0.0)
    leaving = m.velocity >= 0.0  # sections the body leaves behind: no load at all
    assert leaving.any() and np.all(per_metre(m)[leaving] == 0.0)
    assert per_metre(z)[leaving].min() < -1e5  # the strip theory's suction there
    # the load that remains is where the pressure is positive, and integrates to the force
    np.testing.assert_allclose(m.pressures.force_per_metre(), per_metre(m), rtol=1e-9)


@pytest.mark.parametrize("velocity", [0.0, 0.5])
def test_a_section_leaving_the_water_keeps_its_added_mass(velocity):
    # METHOD (the momentum form): on a section leaving the water the v^2 term is dropped
    # and the inertia -m_a a stays; a level body free in heave at rest in the water then
    # falls at -g m / (m + A), A the added mass, and the water's force is -A a
    mass, g = 241.0, 9.81
    hull = hs.Hull.from_arrays(*shapes.wedge_prism(1.0, 0.5, 30.0, sides=0.3), mass=mass)
    r = hs.compute_force(hull, 0.05, velocity, slices=2, solver="mlm", fluid=hs.Fluid(RHO, g))
    added = float(np.sum(r.loads.diagnostics["added_mass"] * r.sections.dx))
    assert added > 0.0
    a = r.acceleration.vertical
    assert a == pytest.approx(-g * mass / (mass + added), rel=1e-12)
    assert r.total == pytest.approx(-added * a, rel=1e-12)
    # and entering at a vanishing speed the body accelerates alike
    entering = hs.compute_force(hull, 0.05, -1e-9, slices=2, solver="mlm", fluid=hs.Fluid(RHO, g))
    assert entering.acceleration.vertical == pytest.approx(a, rel=1e-6)


def test_no_side_carries_a_negative_added_mass(monkeypatch):
    # the momentum form carries the added mass of the loaded points, side by side; a side
    # whose coefficients sum below zero carries none (as the solver's own added mass, which
    # it clips at zero), never a negative one that would take the body's mass matrix out
    # of positive definiteness. A level wedge at constant speed (no kinematic acceleration:
    # its loaded points do not depend on the coefficients) with its port coefficients made
    # negative carries its starboard side's alone: half, by symmetry
    import dataclasses

    hull = hs.Hull.from_arrays(*shapes.wedge_prism(1.0, 0.4, 25.0), mass=40.0)
    kw = dict(slices=2, solver="mlm", fluid=hs.Fluid(RHO, 0.0))
    whole = hs.compute_force(hull, 0.05, -4.0, **kw)
    plain = mlm.MLM.added_mass

    def port_negative(self, sections, velocity, fluid):
        added = plain(self, sections, velocity, fluid)
        pts = added.pressure
        coef = np.array(pts.acceleration_coefficient)
        coef[:, 0, :] = -1e9
        pts = dataclasses.replace(pts, acceleration_coefficient=coef)
        return dataclasses.replace(added, pressure=pts)

    monkeypatch.setattr(mlm.MLM, "added_mass", port_negative)
    half = hs.compute_force(hull, 0.05, -4.0, **kw)
    carried = half.loads.diagnostics["added_mass"]
    assert np.all(whole.loads.diagnostics["added_mass"] > 0.0)
    np.testing.assert_allclose(carried, 0.5 * whole.loads.diagnostics["added_mass"], rtol=1e-9)
    assert np.isfinite(half.acceleration.vertical)  # free in heave: the matrix is solved


@pytest.mark.parametrize("acceleration", [-40.0, 0.0, 40.0])
def test_the_load_is_continuous_as_a_section_turns_to_leave_the_water(acceleration):
    # a section whose motion turns from entering to leaving has no v^2 term left as its
    # speed goes to zero: on either side of the turn its load is the inertia's, -m_a a,
    # whether the body is pushed down or pulled up (the momentum form's added mass, as
    # wagner's: water follows a body pulled up, down to its suction bound, here far off)
    hull = hs.Hull.from_arrays(*shapes.wedge_prism(1.0, 0.5, 30.0, sides=0.3), mass=241.0)
    forces = {}
    for v in (-1e-6, 0.0, 1e-6):
        r = hs.compute_force(hull, 0.05, v, slices=2, solver="mlm", acceleration=acceleration)
        added = float(np.sum(r.loads.diagnostics["added_mass"] * r.sections.dx))
        assert not r.loads.diagnostics["suction_limited"].any()
        forces[v] = r.total
        assert r.total == pytest.approx(-added * acceleration, rel=1e-9, abs=1e-6)
    assert forces[-1e-6] == pytest.approx(forces[1e-6], rel=1e-9, abs=1e-6)


@pytest.mark.parametrize("solver", ["mlm", "zarnick"])
def test_a_flat_bottom_is_flagged_as_outside_the_wedge_theory(solver):
    # a box (zero deadrise, chines at 0.3 m): the 2D theory has no flat plate to give,
    # so every solver computes the 1-degree wedge and says so
    box = np.array([[0.0, 0.0], [0.3, 0.0], [0.3, 0.3], [-0.3, 0.3], [-0.3, 0.0]])
    hull = hs.Hull.from_arrays(*shapes.prism_from_sections(np.array([0.0, 1.0]), [box, box]))
    r = hs.compute_force(hull, 0.001, -5.0, slices=2, solver=solver, acceleration=0.0)
    assert not r.loads.valid.any()
    assert all("deadrise below 1 deg" in why for why in r.loads.reason)


def test_the_breadth_under_the_water_is_the_same_from_the_kept_cut_as_per_contour():
    # the breadths of the suction bound read from the kept cut's contours, all stations at
    # once (ShiftedPolygons.extent_below), against each station's contour as moved when
    # read, one at a time: the same numbers to the last bit (fixed slices, whose partial
    # slices take a moved section, over drafts past the round sections' widest points)
    from dataclasses import replace

    from hullslice.motion import ForceModel
    from hullslice.solvers.section_parts import submerged_widths

    hull = hs.load_hull(MESHES / "fuselage_model.obj", mass=60.0)
    model = ForceModel(hull, slices=32, slicing="fixed", solver="wagner")
    motion = hs.Motion(-1.5, 19.0)
    lifted = 0
    for draft in (0.005, 0.05, 0.15, 0.3):
        for pitch in (0.0, 0.1):
            s = model.terms(hs.Pose(draft, pitch), motion).sections
            lifted += s.polygons._lift is not None
            plain = replace(s, polygons=[s.polygons[i] for i in range(len(s.polygons))])
            np.testing.assert_array_equal(submerged_widths(s), submerged_widths(plain))
            wet = s.wetted
            assert (submerged_widths(s)[wet] > 0.0).all()
    assert lifted  # partial slices moved to their depths were among them


def test_the_sides_sampled_rows_are_read_as_take_along_axis_reads_them():
    # an invariance: the contours' rows, read at many points by flat indices (the
    # bisection of the pressure's change of sign reads them some fifty times an
    # evaluation), give numpy's take_along_axis of the clipped indices to the last bit,
    # out of range, at the ends and at NaN
    from hullslice_mlm.contours import RealBottom, _interp_rows, _slope_at

    rng = np.random.default_rng(7)
    k, n, m = 129, 5, 11
    raw = np.cumsum(rng.random((2, n, k)), axis=-1)
    ds = rng.random((2, n)) * 0.01
    ds[0, 1] = 0.0  # an unsampled side
    y = rng.uniform(-0.2, 1.6, (2, n, m)) * (k - 1) * ds.max()
    y[1, 2, 3], y[0, 4, :2] = np.nan, (k - 1) * ds[0, 4]  # a NaN, the grid's very end

    def reference(f, ds, y, last):
        with np.errstate(invalid="ignore", divide="ignore"):
            x = np.where(ds[..., None] > 0, y / ds[..., None], 0.0)
            if last:
                i = np.clip(np.floor(x).astype(np.int64), 0, f.shape[-1] - 1)
                return np.take_along_axis(f, i, axis=-1)
            x = np.clip(x, 0.0, f.shape[-1] - 1)
            i0 = np.clip(np.floor(x).astype(np.int64), 0, f.shape[-1] - 2)
        frac = x - i0
        a, b = np.take_along_axis(f, i0, axis=-1), np.take_along_axis(f, i0 + 1, axis=-1)
        return a * (1.0 - frac) + b * frac

    slope = np.diff(raw, axis=-1) / np.where(ds > 0, ds, 1.0)[..., None]
    with np.errstate(invalid="ignore"):
        got = (_interp_rows(raw, ds, y), _slope_at(slope, ds, y))
        want = (reference(raw, ds, y, False), reference(slope, ds, y, True))
    for a, b in zip(got, want, strict=True):
        assert a.shape == b.shape == (2, n, m)
        np.testing.assert_array_equal(a.view(np.uint64), b.view(np.uint64))
    # the bottom's slope alone is its height-and-slope's slope
    y_last, s_last = (k - 3) * ds, rng.random((2, n))
    bottom = RealBottom(raw, ds, y_last, s_last)
    with np.errstate(invalid="ignore"):
        both, alone = bottom(y), bottom.slope(y)
    np.testing.assert_array_equal(both[1].view(np.uint64), alone.view(np.uint64))


@pytest.mark.slow
def test_an_airliner_ditching_nose_high_runs_to_its_end():
    # the catalogued airliner (60 t) free in pitch, nose up 20 deg and rising at 1.39
    # rad/s, 27.4 m/s forward and 1.82 m/s down: some sections have their keel at the end
    # of their waterline, and their equivalent wedge's side there is a wall; its -90 deg
    # deadrise once gave the mlm bottom a height hundreds of metres under the keel, a
    # negative added mass of -7.5e5 kg/m and a stop at t = 0.049 s
    hull = hs.load_hull(MESHES / "airliner" / "airliner.obj", mass=6e4)
    h = hs.simulate(
        hull, -1.82, 0.1335, dt=0.00297, pitch_rad=0.3482, pitch_rate_rad_s=1.3875,
        forward_speed=27.42, slices=57, slicing="wetted", free_pitch=True, stop_on=(),
        solver="mlm",
    )  # fmt: skip
    assert h.t[-1] == pytest.approx(0.1335, abs=0.00297)
    assert np.all(np.isfinite(h.force)) and np.max(h.force) > 1e6  # N: the water took it
