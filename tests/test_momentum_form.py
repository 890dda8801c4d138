"""The momentum form of the 2D+t force, against closed forms and the invariants of the theory.

References:

- Von Karman (1929) and Wagner (1932): a wedge of deadrise ``beta`` entering at a constant
  speed ``V`` carries ``f = rho pi gamma^2 V^3 t / tan^2(beta)`` per metre from first
  contact, ``gamma = 1`` (von Karman) or ``pi / 2`` (Wagner: ``rho pi^3 V^3 t /
  (4 tan^2 beta)``). METHOD, section 6.
- The paper's Eq. 2: the peak deceleration of a free-falling wedge in momentum theory (checked
  for every bundled solver in ``tests/test_plugins.py``).
- Newton's laws: a body falling freely with ``g = 0`` keeps the momentum of body and water,
  ``(m + integral of m_a dx) w``; a body free in heave has ``m dw/dt = F - m g``; a water
  force under a prescribed motion does not depend on the body's mass.
"""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

import hullslice as hs
from hullslice import shapes
from hullslice.forces import section_kinematics, section_velocity
from hullslice.geometry import frame
from hullslice.mass import MassDistribution
from hullslice.motion.integrate import ForceModel

from .conftest import MESHES, ROOT

RHO = 1000.0
GAMMA = {"wagner": math.pi / 2, "von-karman": 1.0}


def closed_form(name: str, V: float, t: np.ndarray, beta: float, length: float) -> np.ndarray:
    """Force on a wedge prism at constant speed from first contact, N (METHOD section 6)."""
    gamma = GAMMA[name]
    return RHO * math.pi * gamma**2 * V**3 * t * length / math.tan(beta) ** 2


def constant_speed(V: float, p_max: float, rows: int = 21) -> dict[str, np.ndarray]:
    t = np.linspace(0.0, p_max / V, rows)
    return {"t": t, "draft": V * t, "velocity": np.full(rows, -V)}


@pytest.mark.parametrize("name", ["wagner", "von-karman"])
@pytest.mark.parametrize("deadrise_deg", [20.0, 30.0])
@pytest.mark.parametrize("V", [3.0, 8.0])
def test_constant_speed_entry_of_a_wedge_prism_is_the_closed_form(name, deadrise_deg, V):
    # a 1 m prism of 0.2 m beam, no mass at all: the momentum form needs none. Up to 60 % of
    # the depth at which Wagner's spray root reaches the chine (before it)
    beta = math.radians(deadrise_deg)
    v, f = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=deadrise_deg)
    hull = hs.Hull.from_arrays(v, f)
    p_max = 0.6 * 0.1 * math.tan(beta) / (math.pi / 2)
    kin = constant_speed(V, p_max)
    h = hs.prescribed(hull, kin, solver=name, slices=8)
    assert h.valid.all()
    expected = closed_form(name, V, kin["t"], beta, 1.0)
    assert h.force[0] == 0.0
    # measured up to 1.7e-6 (the cut is in single precision)
    np.testing.assert_allclose(h.force[1:], expected[1:], rtol=1e-5)
    # the heave added mass is that of the flat plate of the wetted width, rho pi c^2 / 2 per
    # metre with c = gamma p / tan(beta)
    c = GAMMA[name] * kin["draft"] / math.tan(beta)
    np.testing.assert_allclose(h.added_mass[1:], RHO * math.pi * c[1:] ** 2 / 2, rtol=1e-5)


def test_the_force_does_not_depend_on_the_mass_or_its_distribution(paper_hull):
    # the paper's tapered prism driven at 4 m/s with a deceleration of 100 m/s^2: uniform
    # 1 kg, 5 kg, two point masses, or no mass at all give the same water force
    t = np.linspace(0.0, 0.008, 17)
    kin = {
        "t": t,
        "draft": 4.0 * t - 50.0 * t**2,
        "velocity": -4.0 + 100.0 * t,
        "acceleration": np.full_like(t, 100.0),
    }
    points = MassDistribution(points=[[0.08, -0.02, 0.6, 0.04], [0.27, -0.02, 0.4, 0.04]])
    bodies = [
        paper_hull,
        paper_hull.with_mass(5.0),
        paper_hull.with_mass(mass_distribution=points),
        hs.load_hull(MESHES / "paper_prism.stl"),
    ]
    forces = [hs.prescribed(b, kin, solver="wagner", slices=16).force for b in bodies]
    for other in forces[1:]:
        np.testing.assert_allclose(other, forces[0], rtol=1e-12, atol=1e-12)
    # while the paper's free-fall form changes with the mass distribution
    ff = [hs.prescribed(b, kin, slices=16).force for b in bodies[:3]]
    assert np.max(np.abs(ff[2] - ff[0])) > 0.05 * np.max(ff[0])


def test_prescribed_acceleration_enters_as_an_added_inertia():
    # f = m_a' V^2 - m_a a per metre on a uniform 30 deg wedge prism (closed form, Wagner)
    beta, p, V, a = math.radians(30.0), 0.02, 5.0, 60.0
    v, f = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0)
    hull = hs.Hull.from_arrays(v, f)
    r = hs.compute_force(hull, p, -V, solver="wagner", slices=8, acceleration=a)
    k = RHO * math.pi * (math.pi / 2) ** 2 / (2 * math.tan(beta) ** 2)  # m_a = k p^2
    assert r.total == pytest.approx(2 * k * p * V**2 - k * p**2 * a, rel=1e-6)
    assert r.added_mass == pytest.approx(k * p**2, rel=1e-6)
    np.testing.assert_allclose(r.section_acceleration, a, rtol=1e-12)


@pytest.mark.parametrize("name", ["wagner", "von-karman"])
def test_a_body_free_in_heave_obeys_newton(paper_hull, name):
    # compute_force with no acceleration frees the body in heave: m dw/dt = F - m g
    r = hs.compute_force(paper_hull, 0.0383, -3.4943, solver=name, slices=32)
    m, g = paper_hull.mass, 9.81
    assert r.total == pytest.approx(m * (r.acceleration.vertical + g), rel=1e-12)
    # and the solved acceleration is (F0 - m g) / (m + A): the force at zero acceleration
    r0 = hs.compute_force(paper_hull, 0.0383, -3.4943, solver=name, slices=32, acceleration=0.0)
    assert r.acceleration.vertical == pytest.approx(
        (r0.total - m * g) / (m + r0.added_mass), rel=1e-12
    )


@pytest.mark.parametrize("name", ["wagner", "von-karman"])
def test_free_fall_without_gravity_keeps_the_momentum_of_body_and_water(paper_hull, name):
    # the paper's prism is not uniform (deadrise 45 to 10 deg): its slices would each
    # decelerate on their own, the rigid body keeps (m + A) w. RK4 at 1e-4 s, 128 fixed
    # slices: measured drift 2e-4 (wagner) over the impact
    h = hs.simulate(
        paper_hull, -4.0, 0.02, dt=1e-4, slices=128, slicing="fixed", solver=name,
        fluid=hs.Fluid(RHO, 0.0), stop_on=(),
    )  # fmt: skip
    momentum = (paper_hull.mass + h.added_mass) * h.velocity
    assert h.added_mass[-1] > 0.5 * paper_hull.mass  # the water matters
    np.testing.assert_allclose(momentum, -4.0, rtol=2e-3)


def test_replaying_a_free_fall_as_a_prescribed_motion_gives_its_forces(paper_hull):
    # the water force of a momentum solver is a function of the motion alone: the free
    # fall's own history, replayed with its accelerations, gives the same forces
    h = hs.simulate(paper_hull, -4.0, 0.015, dt=1e-4, slices=32, solver="wagner", stop_on=())
    kin = {
        "t": h.t,
        "draft": h.draft,
        "velocity": h.velocity,
        "acceleration": h.acceleration,
    }
    replay = hs.prescribed(paper_hull, kin, solver="wagner", slices=32)
    np.testing.assert_allclose(replay.force, h.force, rtol=1e-10, atol=1e-9)
    # and with the accelerations derived from the velocities (second-order differences)
    kin.pop("acceleration")
    derived = hs.prescribed(paper_hull, kin, solver="wagner", slices=32)
    peak = h.force.max()
    assert np.max(np.abs(derived.force - h.force)) < 2e-3 * peak


def test_section_acceleration_is_the_time_derivative_of_its_velocity():
    # a 1:10 fuselage pitched 6 deg, moving forward and pitching with accelerations: the
    # penetration velocity at fixed earth planes, differentiated numerically in time, is
    # the formula's J . (dw/dt, dq/dt, du/dt) + b (the module notes of hullslice.forces).
    # 1600 stations along it: the planes stay on the same facets for the central difference
    v, f = shapes.fuselage(scale=0.1, stations=1600, points=24)
    hull = hs.Hull.from_arrays(v, f, mass=60.0)
    w0, q0, u0 = -1.0, 0.3, 20.0  # m/s, rad/s, m/s
    dw, dq, du = 5.0, 2.0, -3.0  # m/s^2, rad/s^2, m/s^2
    th0, draft0 = math.radians(6.0), 0.1
    z0 = frame(hull, th0).z_cg(draft0)
    model = ForceModel(hull)
    x_cg = float(hull.cg[0])
    centres = np.array([-1.2, -0.9, -0.6, 0.2, 1.0])  # earth X - X_g(0), m: tail cone to nose
    # each between two guards 1 mm off: its slice is 1 mm thick whatever the wetted extent
    # (a slice's slope is the keel's chord over it), within the facets beside its plane
    planes = (centres[:, None] + np.array([-1e-3, 0.0, 1e-3])).ravel()
    middle = np.arange(1, len(planes), 3)

    def state(t):
        th = th0 + q0 * t + 0.5 * dq * t * t
        z = z0 + w0 * t + 0.5 * dw * t * t
        x_g = u0 * t + 0.5 * du * t * t
        motion = hs.Motion(w0 + dw * t, u0 + du * t, q0 + dq * t)
        secs = hs.cut(hull, hs.Pose(model.draft(z, th), th), stations=planes - x_g + x_cg)
        return secs, motion

    def v_at(t):
        secs, motion = state(t)
        return section_velocity(secs, motion, x_cg)[middle]

    secs, motion = state(0.0)
    assert len(secs.x) == len(planes)
    # the formula with the derivative along X of the sections' own slope, the keel line's
    # chord over each slice (the sections carry a curvature averaged over half a beam)
    keel, rel, eps = frame(hull, th0).keel, secs.x - x_cg, 1e-6
    local = (keel.mean_slope(rel + eps, secs.dx) - keel.mean_slope(rel - eps, secs.dx)) / (2 * eps)
    secs = dataclasses.replace(secs, keel_curvature=local)
    jac, bias = section_kinematics(secs, motion, x_cg, section_velocity(secs, motion, x_cg))
    formula = (jac @ np.array([dw, dq, du]) + bias)[middle]
    h = 1e-5
    numeric = (v_at(h) - v_at(-h)) / (2 * h)
    assert np.abs(bias).max() > 10.0  # the terms without an acceleration matter here
    # measured 5.8e-7 of the largest term (the chord's second-order terms over a 1 mm slice)
    np.testing.assert_allclose(numeric, formula, atol=1e-6 * np.abs(formula).max())


def test_slice_averaged_keel_curvature_converges_to_the_local_one():
    # the curvature a slice carries is its slope's change over its thickness: on the 1:10
    # fuselage's tail cone it tends to the keel line's own as the slices get thin
    hull = hs.load_hull(MESHES / "fuselage_model.obj", mass=60.0)
    keel = frame(hull, 0.0).keel
    x = np.linspace(-1.9, -1.0, 10)  # relative to the centre of gravity: the tail cone
    smooth = keel.mean_curvature(x, 0.05)
    assert np.all(smooth > 0.2)  # the keel sweeps up towards the tail, ever more steeply
    # over 5, 2 and 1 cm: measured within 3.3 % of each other (the mesh's facets, 3-6 mm)
    for dx in (0.02, 0.01):
        np.testing.assert_allclose(keel.mean_curvature(x, dx), smooth, rtol=0.05)
    # its integral over the tail cone is the change of slope, whatever the slicing
    edges = np.linspace(-1.9, -0.6, 29)
    mids, widths = 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)
    total = (keel.mean_curvature(mids, widths) * widths).sum()
    assert total == pytest.approx(keel.at(-0.6)[1] - keel.at(-1.9)[1], rel=1e-12)


def test_added_mass_matrix_is_symmetric_and_positive():
    hull = hs.load_hull(MESHES / "fuselage_model.obj", mass=60.0)
    model = ForceModel(hull, solver="wagner", slices=32, slicing="fixed")
    terms = model.terms(hs.Pose(0.05, math.radians(6.0)), hs.Motion(-1.0, 20.0, 0.0))
    a = terms.matrix
    np.testing.assert_allclose(a, a.T, rtol=0, atol=1e-12 * np.abs(a).max())
    assert np.all(np.linalg.eigvalsh(a) >= -1e-9 * np.abs(a).max())
    assert a[0, 0] == pytest.approx(terms.sections.dx @ terms.added.added_mass, rel=1e-12)


def test_ditching_with_free_pitch_runs_with_the_added_mass_on_the_left():
    # a light model fuselage (6 kg) pitched 8 deg at 6 m/s, free in pitch and surge: the
    # run ends by its end time, the history is finite, the water's added mass is of the
    # body's order, the tail touching first pitches the nose down (the slap-down) and the
    # keel's slope makes a drag
    hull = hs.load_hull(MESHES / "fuselage_model.obj", mass=6.0)
    h = hs.simulate(
        hull, -0.5, 0.05, dt=5e-4, pitch_rad=math.radians(8.0), forward_speed=6.0,
        free_pitch=True, free_surge=True, slices=32, slicing="fixed", solver="wagner",
        stop_on=(),
    )  # fmt: skip
    assert h.stop_reason == "t_end"
    for name in ("force", "moment", "pitch", "forward_speed", "added_mass"):
        assert np.all(np.isfinite(getattr(h, name))), name
    assert h.added_mass.max() > 0.5 * hull.mass
    assert h.pitch[-1] < h.pitch[0] - math.radians(0.5)
    assert h.forward_speed[-1] < h.forward_speed[0]


def test_the_readme_plugin_example_is_a_working_momentum_solver(paper_hull):
    # the plugin guide's worked example of a momentum-form plugin, run as it is written: with
    # gamma = pi / 2 it is the wagner plugin
    readme = (ROOT / "docs" / "plugins.md").read_text(encoding="utf-8")
    section = readme.split("**A momentum-form solver** implements", 1)[1]
    code = section.split("```python\n", 1)[1].split("```", 1)[0]
    namespace: dict = {}
    exec(compile(code, "docs/plugins.md", "exec"), namespace)
    mine = namespace["FlatPlate"](gamma=math.pi / 2)
    assert mine.kind == "momentum"
    ref = hs.compute_force(paper_hull, 0.0383, -3.4943, slices=16, solver="wagner")
    got = hs.compute_force(paper_hull, 0.0383, -3.4943, slices=16, solver=mine)
    assert got.total == pytest.approx(ref.total, rel=1e-12)


def test_the_command_line_needs_no_mass_for_a_given_acceleration(capsys):
    # force at a state with the body's acceleration given: the momentum form's force is
    # the closed form m_a' V^2 - m_a a, whatever the body's mass, which is not asked for
    from hullslice.cli import main

    beta, p, V, a = math.radians(30.0), 0.02, 5.0, 40.0
    argv = [
        "force", str(MESHES / "wedge_prism.stl"), "--draft", str(p), f"--velocity={-V}",
        "--acceleration", str(a), "--solver", "wagner", "--slices", "8", "--format", "json",
    ]  # fmt: skip
    assert main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    k = RHO * math.pi * (math.pi / 2) ** 2 / (2 * math.tan(beta) ** 2)
    assert data["mass"] is None
    assert data["force"] == pytest.approx(2 * k * p * V**2 - k * p**2 * a, rel=1e-6)
    # without the acceleration the body is free in heave: its mass is a missing option
    assert main(argv[:5] + argv[7:]) == 2
    assert "give the body's mass" in capsys.readouterr().err


def test_kinematics_rates_are_derived_or_checked():
    # a pitch that changes without its rate: the rate is its derivative, so the force is
    # that of the table with the rate given; a forward acceleration that contradicts the
    # forward speed is refused
    v, f = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=20.0)
    hull = hs.Hull.from_arrays(v, f)
    t = np.linspace(0.0, 0.004, 9)
    kin = {
        "t": t,
        "draft": 0.005 + 2.0 * t,
        "velocity": np.full_like(t, -2.0),
        "pitch_rad": np.radians(4.0 + 100.0 * t),
        "forward_speed": np.full_like(t, 5.0),
    }
    derived = hs.prescribed(hull, kin, solver="wagner", slices=8)
    given = hs.prescribed(
        hull,
        {**kin, "pitch_rate_rad_s": np.full_like(t, np.radians(100.0))},
        solver="wagner",
        slices=8,
    )
    np.testing.assert_allclose(derived.force, given.force, rtol=1e-9)
    bad = {**kin, "forward_acceleration": np.full_like(t, 100.0)}
    with pytest.raises(hs.CaseError, match="forward_acceleration disagrees with forward_speed"):
        hs.prescribed(hull, bad, solver="wagner", slices=8)


def test_a_history_says_how_much_of_the_wetted_length_is_held_at_the_suction_bound(capsys):
    # zarnick, nose down on the full fuselage: the tail cone's sections reach the water's
    # vapour bound. The history's share is the wetted length of the sections the solver
    # held there, recomputed at that instant from its state; the report says it in a line
    from hullslice.cli import main

    hull = hs.load_hull(MESHES / "fuselage_full.obj", mass=60000.0)
    kw = dict(solver="zarnick", slices=32, slicing="fixed", fluid=hs.Fluid.sea())
    h = hs.simulate(hull, -3.0, 0.36, dt=0.004, pitch_deg=-2.0, forward_speed=60.0,
                    free_pitch=True, stop_on=(), **kw)  # fmt: skip
    i = int(np.argmax(h.suction_share))
    assert 0.2 < h.suction_share[i] < 0.5
    pose = hs.Pose(draft=h.draft[i], pitch_rad=h.pitch[i])
    motion = hs.Motion(h.velocity[i], h.forward_speed[i], pitch_rate_rad_s=h.pitch_rate[i])
    r = hs.compute_force(hull, pose, motion, acceleration=h.acceleration[i], **kw)
    s, limited = r.sections, r.loads.diagnostics["suction_limited"] > 0
    wet = s.penetration > 0
    share = s.dx[wet & limited].sum() / s.dx[wet].sum()
    assert h.suction_share[i] == pytest.approx(share, rel=1e-6)
    assert np.all(h.suction_share >= 0.0) and h.suction_share[0] == 0.0
    assert (
        hs.simulate(
            hull,
            -3.0,
            0.02,
            dt=0.004,
            pitch_deg=-2.0,
            forward_speed=60.0,
            solver="mlm",
            slices=32,
            slicing="fixed",
        ).suction_share.max()
        == 0.0
    )
    rc = main(["simulate", str(MESHES / "fuselage_full.obj"), "--mass", "60000",
               "--velocity=-3", "--forward-speed", "60", "--pitch", "-2", "--free-pitch",
               "--solver", "zarnick", "--t-end", "0.36", "--dt", "0.004", "--slices", "32",
               "--slicing", "fixed", "--water", "sea", "--continue-invalid"])  # fmt: skip
    out = capsys.readouterr().out
    assert rc == 0 and f"on up to {100 * h.suction_share[i]:.3g} % of the wetted length" in out
