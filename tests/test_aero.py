"""The air's forces, the water's friction and the end of a ditching, against closed forms.

References:

- Lift equal to the weight: a body held at the surface with no sink rate stays there.
- A pitch oscillation with a restoring moment ``C_m,alpha`` and a damping ``C_m,q``:
  ``I theta'' = q S c (C_m,alpha theta + C_m,q theta' c / (2 V))``, a damped oscillator
  whose closed form the run follows.
- The ITTC-57 line: ``C_F = 0.075 / (log10(Re) - 2)^2`` on the wetted surface.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import hullslice as hs
from hullslice import shapes
from hullslice.aero import AIR_DENSITY, Coefficients, WeightLift, aero_model, path
from hullslice.cli import main
from hullslice.forces.friction import ittc57

from .conftest import MESHES


def prism(mass: float = 50.0, length: float = 4.0) -> hs.Hull:
    v, f = shapes.wedge_prism(length=length, beam=0.5, deadrise_deg=20.0, stations=3)
    return hs.Hull.from_arrays(v, f, mass=mass)


def test_the_path_gives_the_angle_of_attack():
    speed, gamma, alpha = path(60.0, -1.5, math.radians(8.0))
    assert speed == pytest.approx(math.hypot(60.0, 1.5), rel=1e-15)
    assert gamma == pytest.approx(math.atan2(-1.5, 60.0), rel=1e-15)
    assert alpha == pytest.approx(math.radians(8.0) - gamma, rel=1e-15)


def test_lift_equal_to_the_weight_holds_a_body_at_the_surface():
    hull = prism()
    g = 9.81
    u = 20.0
    # level, no sink rate: coefficients whose lift is the weight at zero angle of attack
    area = 2.0
    cl0 = hull.mass * g / (0.5 * AIR_DENSITY * u * u * area)
    level = Coefficients(area, 0.5, cl0=cl0)
    h = hs.simulate(hull, 0.0, 0.2, dt=0.002, forward_speed=u, solver="mlm", aero=level,
                    stop_on=())  # fmt: skip
    assert np.all(h.draft == 0.0) and np.all(h.force == 0.0)
    np.testing.assert_allclose(h.air_force, hull.mass * g, rtol=1e-12)
    assert np.all(h.acceleration == pytest.approx(0.0, abs=1e-12))
    # pitched 4 deg on a level path: lift equal to the weight at touchdown
    h = hs.simulate(hull, 0.0, 0.2, dt=0.002, forward_speed=u, pitch_rad=math.radians(4.0),
                    solver="mlm", aero="weight", stop_on=())  # fmt: skip
    assert np.all(h.draft == 0.0) and np.all(h.force == 0.0)
    np.testing.assert_allclose(h.air_force, hull.mass * g, rtol=1e-12)
    assert h.settings["aero"] == "weight" and h.settings["lift_fraction"] == 1.0


def test_the_weight_lift_scales_with_the_speed_squared_and_the_angle():
    model = WeightLift(0.8).start(1000.0, 9.81, math.radians(6.0), 50.0, -1.0)
    at_start = model.forces(math.radians(6.0), 50.0, -1.0, 0.0)
    assert at_start.lift == pytest.approx(0.8 * 1000.0 * 9.81, rel=1e-14)
    _, _, a0 = path(50.0, -1.0, math.radians(6.0))
    later = model.forces(math.radians(3.0), 40.0, 0.0, 0.0)
    expected = 0.8 * 1000.0 * 9.81 * (40.0**2 / (50.0**2 + 1.0)) * math.radians(3.0) / a0
    assert later.lift == pytest.approx(expected, rel=1e-13)
    assert later.force_z == pytest.approx(expected, rel=1e-13)  # a level path: lift is up


def test_the_weight_lift_stays_at_its_stall_value_beyond_the_stall():
    # linear up to the stall angle of attack, held there beyond it (either way)
    model = WeightLift(1.0, stall_deg=12.0).start(1000.0, 9.81, math.radians(6.0), 50.0, 0.0)
    w = 1000.0 * 9.81
    at_stall = model.forces(math.radians(12.0), 50.0, 0.0, 0.0).lift
    assert at_stall == pytest.approx(2.0 * w, rel=1e-13)
    for deg in (12.5, 20.0, 45.0):
        assert model.forces(math.radians(deg), 50.0, 0.0, 0.0).lift == at_stall
    assert model.forces(math.radians(-30.0), 50.0, 0.0, 0.0).lift == -at_stall
    # the default stall is 15 deg; a lift coefficient cap holds the coefficients' model
    default = WeightLift().start(1000.0, 9.81, math.radians(5.0), 50.0, 0.0)
    assert default.forces(math.radians(25.0), 50.0, 0.0, 0.0).lift == pytest.approx(3.0 * w)
    wing = Coefficients(10.0, 1.0, cl0=0.2, cl_alpha=5.0, cl_max=1.2)
    q = 0.5 * AIR_DENSITY * 50.0**2 * 10.0
    assert wing.forces(math.radians(5.0), 50.0, 0.0, 0.0).lift == pytest.approx(
        q * (0.2 + 5.0 * math.radians(5.0)), rel=1e-13
    )
    assert wing.forces(math.radians(30.0), 50.0, 0.0, 0.0).lift == pytest.approx(q * 1.2)
    assert wing.forces(math.radians(-30.0), 50.0, 0.0, 0.0).lift == pytest.approx(-q * 1.2)
    assert WeightLift(stall_deg=12.0).settings()["stall_deg"] == 12.0


def test_a_flat_touchdown_of_the_weight_lift_is_warned_of():
    # at 0.48 deg of angle of attack the model's lift grows by 1 / alpha_0 = 209 % of itself
    # per degree, some 20 times a wing's; at 5 deg (20 % a degree) nothing is said
    with pytest.warns(hs.HullsliceWarning, match=r"0\.477 deg: it then grows by 209 %"):
        WeightLift().start(6e4, 9.81, 0.0, 60.0, -0.5)
    WeightLift().start(6e4, 9.81, math.radians(5.0), 60.0, -0.0)


def test_a_pitch_damping_damps_at_the_rate_of_its_closed_form():
    # water of a negligible density: the air's moment alone turns the body
    hull = prism(mass=20.0)
    inertia = hull.pitch_inertia
    u, area, chord = 30.0, 1.0, 0.5
    qsc = 0.5 * AIR_DENSITY * u * u * area * chord
    cm_alpha, cm_q = -0.05, -15.0
    cl0 = hull.mass * 9.81 / (0.5 * AIR_DENSITY * u * u * area)
    model = Coefficients(area, chord, cl0=cl0, cm_alpha=cm_alpha, cm_q=cm_q)
    theta0 = math.radians(2.0)
    t_end = 1.0
    h = hs.simulate(
        hull, 0.0, t_end, dt=1e-3, pitch_rad=theta0, forward_speed=u, free_pitch=True,
        solver="zarnick", aero=model, fluid=hs.Fluid(rho=1e-9), stop_on=(),
    )  # fmt: skip
    omega2 = -qsc * cm_alpha / inertia
    two_zeta_omega = -qsc * cm_q * chord / (2.0 * u) / inertia
    decay = 0.5 * two_zeta_omega
    wd = math.sqrt(omega2 - decay**2)
    t = np.asarray(h.t)
    closed = theta0 * np.exp(-decay * t) * (np.cos(wd * t) + decay / wd * np.sin(wd * t))
    assert decay * t_end > 0.5  # the run shows the damping
    np.testing.assert_allclose(np.asarray(h.pitch), closed, atol=2e-4 * theta0)


def test_the_friction_is_the_ittc_line_on_the_wetted_surface():
    hull = prism()
    beta = math.radians(20.0)
    p, u = 0.03, 12.0
    fluid = hs.Fluid()
    h = hs.simulate(hull, -0.5, 0.002, dt=0.001, draft=p, forward_speed=u, solver="zarnick",
                    friction=True, stop_on=())  # fmt: skip
    girth = 2.0 * p / math.sin(beta)  # the wedge's two sides to the calm water
    length = 4.0  # level: the whole prism is wetted
    re = u * length / fluid.nu
    cf = 0.075 / (math.log10(re) - 2.0) ** 2
    assert ittc57(re) == pytest.approx(cf, rel=1e-15)
    expected = -0.5 * fluid.rho * u * u * girth * length * cf
    assert h.friction[0] == pytest.approx(expected, rel=1e-9)
    assert h.settings["friction"] == "ITTC-57"


def test_a_peak_at_the_last_sample_is_reported_as_such(capsys):
    hull = hs.load_hull(MESHES / "paper_prism.stl", mass=1.0)
    rising = hs.simulate(hull, -4.0, 0.002, dt=0.0005, slices=16)  # cut while rising
    assert rising.peak["at_end"]
    whole = hs.simulate(hull, -4.0, 0.02, dt=0.0005, slices=16, stop_on=())
    assert not whole.peak["at_end"]
    rc = main(["simulate", str(MESHES / "paper_prism.stl"), "--mass", "1", "--velocity=-4",
               "--t-end", "0.002", "--dt", "0.0005", "--slices", "16"])  # fmt: skip
    assert rc == 0 and "still rising at the end of the run" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("build", "words"),
    [
        (lambda: Coefficients(math.nan, 1.0), "reference area nan"),
        (lambda: Coefficients(-2.0, 1.0), "reference area -2.0"),
        (lambda: Coefficients(2.0, 0.0), "reference chord 0.0"),
        (lambda: Coefficients(2.0, 1.0, cl_alpha=math.inf), "C_L,alpha inf"),
        (lambda: Coefficients(2.0, 1.0, cd=-0.1), "C_D -0.1"),
        (lambda: WeightLift(2.5), "lift fraction 2.5"),
        (lambda: WeightLift(math.nan), "lift fraction nan"),
        (lambda: WeightLift(stall_deg=0.0), "stall angle 0.0 deg"),
        (lambda: WeightLift(stall_deg=120.0), "stall angle 120.0 deg is above 90"),
        (
            lambda: WeightLift(stall_deg=10.0).start(1e3, 9.81, math.radians(12.0), 50.0, 0.0),
            "above the stall at 10 deg",
        ),
        (lambda: Coefficients(2.0, 1.0, cl_max=-1.0), "C_L,max -1.0"),
        (lambda: aero_model("wings"), "unknown aerodynamic model 'wings'"),
    ],
)
def test_bad_aerodynamics_are_refused_in_one_line(build, words):
    with pytest.raises(hs.InputError, match=words) as err:
        build()
    assert "\n" not in str(err.value)


def test_the_command_line_refuses_bad_aerodynamics_in_one_line(capsys):
    base = ["simulate", str(MESHES / "paper_prism.stl"), "--mass", "1", "--velocity=-4",
            "--t-end", "0.01", "--forward-speed", "5", "--pitch", "4"]  # fmt: skip
    for extra, words in (
        (["--lift", "weight", "--lift-fraction", "3"], "lift fraction 3"),
        (["--lift", "coefficients", "--wing-area=-1", "--wing-chord", "1"], "reference area"),
        (["--cl0", "0.5"], "--lift coefficients"),
        (["--lift", "weight", "--pitch", "-45"], "positive angle of attack"),
        (["--lift", "weight", "--stall-deg", "3"], "above the stall at 3 deg"),
        (["--stall-deg", "12"], "--stall-deg is the stall of --lift weight"),
    ):
        rc = main(base + extra)
        err = capsys.readouterr().err.strip()
        assert rc != 0 and words in err and len(err.splitlines()) == 1, err


def test_sea_water_by_name(capsys):
    mesh = str(MESHES / "paper_prism.stl")
    rc = main(["force", mesh, "--mass", "1", "--draft", "0.02", "--velocity=-3", "--water",
               "sea", "--slices", "16", "--format", "json"])  # fmt: skip
    assert rc == 0
    import json

    assert json.loads(capsys.readouterr().out)["rho"] == 1025.0
    assert hs.Fluid.sea().rho == 1025.0 and hs.Fluid.sea().nu == pytest.approx(1.19e-6)


def test_check_reruns_at_half_the_step_and_twice_the_slices(capsys):
    import json

    mesh = MESHES / "paper_prism.stl"
    rc = main(["simulate", str(mesh), "--mass", "1", "--velocity=-4", "--t-end", "0.02",
               "--dt", "0.001", "--slices", "8", "--check", "--format", "json"])  # fmt: skip
    assert rc == 0
    check = json.loads(capsys.readouterr().out)["check"]
    hull = hs.load_hull(mesh, mass=1.0)
    base = hs.simulate(hull, -4.0, 0.02, dt=0.001, slices=8)
    half = hs.simulate(hull, -4.0, 0.02, dt=0.0005, slices=8)
    double = hs.simulate(hull, -4.0, 0.02, dt=0.001, slices=16)
    assert check["peak"] == pytest.approx(base.peak["force"], rel=1e-12)
    for key, run in (("half_step", half), ("double_slices", double)):
        assert check[key]["peak"] == pytest.approx(run.peak["force"], rel=1e-12)
        change = run.peak["force"] / base.peak["force"] - 1.0
        assert check[key]["peak_change"] == pytest.approx(change, rel=1e-9, abs=1e-15)
    largest = max(abs(check[k]["peak_change"]) for k in ("half_step", "double_slices"))
    assert check["largest_change"] == largest
    # the force at the instants both runs hold: every other instant of the half step's
    peak = np.abs(base.force).max()
    n = len(base.t)
    np.testing.assert_allclose(np.asarray(half.t)[::2][:n], base.t, rtol=0, atol=1e-12)
    half_change = np.abs(np.asarray(half.force)[::2][:n] - base.force).max() / peak
    double_change = np.abs(np.asarray(double.force) - base.force).max() / peak
    assert check["half_step"]["history_change"] == pytest.approx(half_change, rel=1e-9)
    assert check["double_slices"]["history_change"] == pytest.approx(double_change, rel=1e-9)
    rc = main(["simulate", str(mesh), "--mass", "1", "--velocity=-4", "--t-end", "0.02",
               "--dt", "0.001", "--slices", "8", "--check"])  # fmt: skip
    out = capsys.readouterr().out
    assert "twice the slices (dt 0.001 s, 16 slices)" in out and "converged to 2 %" in out


def test_a_planing_run_out_ends_when_the_body_has_settled():
    # a prism at a held trim of 4 deg, 8 m/s: it sinks to the draft where the water carries
    # its weight and stays there; the run ends once it has been still for 0.25 s
    v, f = shapes.wedge_prism(length=2.0, beam=0.5, deadrise_deg=20.0, stations=3, sides=0.5)
    hull = hs.Hull.from_arrays(v, f, mass=40.0)
    h = hs.simulate(hull, -0.3, 10.0, dt=0.005, pitch_rad=math.radians(4.0), forward_speed=8.0,
                    solver="zarnick", slicing="fixed", slices=32)  # fmt: skip
    assert h.stop_reason == "settled" and h.t[-1] < 2.0
    still = h.t >= h.t[-1] - 0.25
    assert np.all(np.abs(h.velocity[still]) <= 0.05)
    assert np.all(np.abs(h.acceleration[still]) <= 0.1)
    # settled: the water's force carries the weight (the acceleration within 0.1 m/s^2)
    assert h.force[-1] == pytest.approx(hull.mass * 9.81, rel=0.1 / 9.81)


def test_a_step_too_long_for_the_load_is_said_to_be(capsys):
    mesh = str(MESHES / "paper_prism.stl")
    hull = hs.load_hull(mesh, mass=1.0)
    coarse = hs.simulate(hull, -4.0, 0.02, dt=0.002, slices=16)
    fine = hs.simulate(hull, -4.0, 0.02, dt=0.0002, slices=16)
    f = np.asarray(coarse.force)
    largest = np.abs(np.diff(f)).max() / f.max()
    assert coarse.step_change["share"] == pytest.approx(largest, rel=1e-15) and largest > 0.1
    assert fine.step_change["share"] < 0.1
    args = ["simulate", mesh, "--mass", "1", "--velocity=-4", "--t-end", "0.02", "--slices", "16"]
    assert main([*args, "--dt", "0.002"]) == 0
    assert "the step may be too long for the load" in capsys.readouterr().out
    assert main([*args, "--dt", "0.0002"]) == 0
    assert "the step may be too long" not in capsys.readouterr().out


def test_check_tells_a_peak_between_samples_from_a_history_that_moves():
    from hullslice.cli.cmd_simulate import check_text

    def check(peak_change, history_change):
        run = {"dt": 0.001, "slices": 64, "peak_t_change": 0.0, "pitch_max_change_deg": 0.0}
        return {
            "peak": 1.3e6, "peak_t": 1.0, "pitch_max_deg": 8.0, "dt": 0.002, "slices": 64,
            "half_step": {**run, "peak_change": peak_change, "history_change": history_change},
            "double_slices": {**run, "peak_change": 0.001, "history_change": 0.01},
            "largest_change": abs(peak_change),
        }  # fmt: skip

    # the 48-point fuselage's 8-degree ditching at 64 slices: the peak 3.1 % up at 1 ms,
    # the force at the 2 ms instants within 1.5 % (docs/validation.md)
    text = check_text(check(0.031, 0.015))
    assert "NOT converged" in text and "falls between the step's samples" in text
    assert "within 1.500 % of the peak" in text
    text = check_text(check(0.031, 0.04))
    assert "refine the step or the slices" in text and "between" not in text
    assert "converged to 2 %" in check_text(check(0.01, 0.04))
