"""Time histories: the paper's free fall, the 2D theory of a uniform wedge, convergence,
prescribed motion and the stop rules."""

from __future__ import annotations

import numpy as np
import pytest

import hullslice as hs
from hullslice import shapes
from hullslice.motion import prescribed, read_kinematics, simulate
from hullslice.solvers.karman import PAPER_CURVES, dobrovolskaya_pile_up


@pytest.fixture(scope="module")
def paper_fall(paper_hull):
    """The paper's prism falling from -4 m/s, to t = 0.02 s (past the force peak)."""
    return simulate(paper_hull, -4.0, 0.02, dt=1e-4, slices=32)


def test_paper_free_fall_matches_table_1(paper_fall, paper):
    ref = paper["table1_t_0.01s"]
    i = int(np.argmin(abs(paper_fall.t - ref["t_s"])))
    assert paper_fall.t[i] == pytest.approx(0.01, abs=1e-12)
    # the motion predicted by 2D+t against the CFD motion of Table 1: within 2 %
    assert paper_fall.draft[i] == pytest.approx(ref["delta_z_m"], rel=0.02)
    assert paper_fall.velocity[i] == pytest.approx(ref["velocity_m_s"], rel=0.02)
    # the force against the CFD force m (a + g): within the paper's 10 % band (Fig. 9)
    assert paper_fall.force[i] == pytest.approx(paper["force_cfd_N"], rel=0.10)
    assert paper_fall.valid[: i + 1].all()


def test_history_is_consistent(paper_fall, paper_hull):
    h = paper_fall
    assert h.t[0] == 0.0 and h.draft[0] == 0.0 and h.velocity[0] == -4.0
    assert h.force[0] == 0.0  # nothing wetted at first contact
    # Newton: a = F / m - g at every instant
    np.testing.assert_allclose(h.acceleration, h.force / paper_hull.mass - 9.81, rtol=1e-12)
    # the draft grows by the integral of -v (trapezoid rule, second order in dt)
    dz = np.diff(h.draft)
    np.testing.assert_allclose(
        dz, -0.5 * (h.velocity[1:] + h.velocity[:-1]) * np.diff(h.t), rtol=1e-3
    )
    assert h.stop_reason == "t_end"
    assert h.settings["scheme"].startswith("classical Runge-Kutta")


def test_uniform_wedge_prism_reproduces_its_2d_free_fall():
    # a prism of constant 30-degree wedge section is a 2D wedge: the body's acceleration
    # is the slices' own, so the characteristic curves predict its peak (Eqs. 3-6)
    mass, length, beta, v0 = 10.0, 1.0, np.radians(30.0), -5.0
    v, f = shapes.wedge_prism(length=length, beam=0.2, deadrise_deg=30.0)
    hull = hs.Hull.from_arrays(v, f, mass=mass)
    h = simulate(hull, v0, 0.008, dt=5e-5, slices=4)
    M = mass / length
    gamma = dobrovolskaya_pile_up(beta)
    z_peak, a_peak = PAPER_CURVES.peak
    expected_a = a_peak * v0**2 * gamma / (np.sqrt(M) * np.tan(beta))  # Eq. 4
    expected_v = PAPER_CURVES.v(z_peak) * v0  # Eq. 3b
    i = int(np.argmax(h.acceleration))
    assert h.acceleration[i] == pytest.approx(expected_a, rel=0.01)
    assert h.velocity[i] == pytest.approx(expected_v, rel=0.01)
    assert 0 < i < len(h) - 1  # a true peak inside the run


def test_prescribed_motion_reproduces_the_free_fall_force(paper_fall, paper_hull):
    kin = {k: getattr(paper_fall, k) for k in ("t", "draft", "velocity")}
    h = prescribed(paper_hull, kin, slices=32)
    assert h.mode == "prescribed" and h.stop_reason == "end of table"
    np.testing.assert_allclose(h.force, paper_fall.force, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(h.acceleration, paper_fall.acceleration, rtol=1e-12, atol=1e-9)


def test_kinematics_csv_round_trip(tmp_path, paper_fall):
    path = tmp_path / "kin.csv"
    rows = ["# CFD kinematics", "time_note,t,draft,velocity"]
    cols = (paper_fall.t, paper_fall.draft, paper_fall.velocity)
    rows += [f"x,{float(t)!r},{float(p)!r},{float(v)!r}" for t, p, v in zip(*cols, strict=True)]
    path.write_text("\n".join(rows) + "\n")
    kin = read_kinematics(path)
    np.testing.assert_array_equal(kin["t"], paper_fall.t)
    np.testing.assert_array_equal(kin["velocity"], paper_fall.velocity)


@pytest.mark.slow
def test_peak_force_converges_in_time_step_and_slices(paper_hull):
    runs = {
        (dt, n): simulate(paper_hull, -4.0, 0.016, dt=dt, slices=n, stop_on=()).peak["force"]
        for dt, n in [(2e-4, 32), (1e-4, 32), (1e-4, 64)]
    }
    ref = runs[(1e-4, 32)]
    assert runs[(2e-4, 32)] == pytest.approx(ref, rel=0.005)  # halving the time step
    assert runs[(1e-4, 64)] == pytest.approx(ref, rel=0.005)  # doubling the slices


def test_validity_stop_and_continue(paper_hull):
    stopped = simulate(paper_hull, -4.0, 0.03, dt=2e-4, slices=16)
    assert stopped.stop_reason == "validity"
    t_cross = stopped.first_crossed["validity"]
    assert stopped.t[-1] == t_cross
    assert not stopped.valid[-1] and "z~ outside" in stopped.reason[-1]
    assert stopped.valid[:-1].all()
    going = simulate(paper_hull, -4.0, 0.03, dt=2e-4, slices=16, stop_on=())
    assert going.stop_reason == "t_end" and going.t[-1] == pytest.approx(0.03)
    assert going.first_crossed["validity"] == t_cross
    np.testing.assert_array_equal(going.force[: len(stopped)], stopped.force)


def test_velocity_stop(wedge_hull):
    # with F = M (a + g) the wedge curves only slow a body down towards rest; a solver that
    # pushes harder (10 g upward on every wetted slice) makes it stop and rise
    from .fake_solvers import ConstantSolver

    h = simulate(
        wedge_hull, -1.0, 0.2, dt=5e-4, slices=4, solver=ConstantSolver, stop_on=("velocity",)
    )
    assert h.stop_reason == "velocity"
    assert h.velocity[-1] >= 0 and np.all(h.velocity[:-1] < 0)


def test_chine_stop(wedge_hull):
    # a heavy wedge goes under to its deck (0.0577 m) before it slows down
    heavy = wedge_hull.with_mass(100.0)
    h = simulate(heavy, -5.0, 0.05, dt=2e-4, slices=4, stop_on=("chine",))
    assert h.stop_reason == "chine"
    assert h.draft[-1] == pytest.approx(0.1 * np.tan(np.radians(30)), abs=2e-3)
    assert h.chine_wetted[-1] and not h.chine_wetted[:-1].any()


@pytest.mark.parametrize(
    ("kw", "message"),
    [
        ({"velocity": 1.0}, "not downward"),
        ({"velocity": 0.0}, "not downward"),
        ({"t_end": 0.0}, "end time 0.0 s is not positive"),
        ({"dt": 0.1}, "longer than the run"),
        ({"dt": -1e-3}, "time step -0.001 s is not positive"),
        ({"slices": 0}, "slice count 0 is not positive"),
        ({"draft": 1.0}, "deeper than the body"),
        ({"stop_on": ("sunk",)}, "unknown stop rule 'sunk'"),
    ],
)
def test_bad_simulation_input(paper_hull, kw, message):
    args = {"velocity": -4.0, "t_end": 0.01, **kw}
    with pytest.raises(hs.InputError, match=message):
        simulate(paper_hull, args.pop("velocity"), args.pop("t_end"), **args)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("t,velocity\n0,-1\n", "lacks the column"),
        ("t,draft,velocity\n0,0,-1\n0.002,0.001,x\n", "line 3"),
        ("t,draft,velocity\n0,0,-1\n0.002,0.001,-1\n0.001,0.002,-1\n", "backwards"),
        ("t,draft,velocity\n0,-0.01,-1\n", "negative"),
        ("t,draft,velocity\n0,5,-1\n", "deeper than the body"),
        ("", "is empty"),
    ],
)
def test_bad_kinematics(tmp_path, paper_hull, text, message):
    path = tmp_path / "kin.csv"
    path.write_text(text)
    with pytest.raises(hs.CaseError, match=message):
        prescribed(paper_hull, read_kinematics(path))


def test_draft_past_the_body_height_is_recorded_as_it_is(wedge_hull):
    # a heavy wedge going under: the force is computed at the height (fully wetted, flagged)
    # but the history keeps the body's own draft, the integral of its velocity
    heavy = wedge_hull.with_mass(100.0)
    h = simulate(heavy, -5.0, 0.05, dt=2e-4, slices=4, stop_on=())
    height = heavy.extents[2]
    assert h.draft.max() > 1.5 * height
    travel = np.concatenate(
        [[0.0], np.cumsum(-0.5 * (h.velocity[1:] + h.velocity[:-1]) * np.diff(h.t))]
    )
    np.testing.assert_allclose(h.draft, travel, rtol=1e-3, atol=1e-6)
    assert h.chine_wetted[h.draft > height].all()


def test_a_run_ends_when_the_pitch_reaches_80_degrees(paper_hull):
    h = simulate(
        paper_hull, -4.0, 0.2, dt=1e-3, pitch_deg=75.0, pitch_rate_deg_s=300.0,
        slices=8, stop_on=(),
    )  # fmt: skip
    assert h.stop_reason == "pitch"
    assert np.degrees(h.pitch[-1]) < 80.0 <= np.degrees(h.pitch[-1]) + 300.0 * 1e-3 + 1e-9
    assert h.first_crossed["pitch"] == pytest.approx(h.t[-1])


def _pitched_kinematics(rows: int = 9) -> dict[str, np.ndarray]:
    t = np.linspace(0.0, 0.004, rows)
    return {
        "t": t,
        "draft": 0.005 + 2.0 * t,
        "velocity": np.full_like(t, -2.0),
        "pitch_rad": np.radians(4.0 + 100.0 * t),
        "pitch_rate_rad_s": np.full_like(t, np.radians(100.0)),
        "forward_speed": np.full_like(t, 5.0),
    }


@pytest.mark.parametrize("solver", ["extended-von-karman", "wagner"])
def test_prescribed_former_keys_and_degrees_give_the_same_history(solver):
    v, f = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=20.0)
    hull = hs.Hull.from_arrays(v, f, mass=5.0)
    kin = _pitched_kinematics()
    now = prescribed(hull, kin, solver=solver, slices=8)
    old = {
        "t": kin["t"],
        "penetration": kin["draft"],
        "velocity": kin["velocity"],
        "pitch": kin["pitch_rad"],
        "pitch_rate": kin["pitch_rate_rad_s"],
        "forward_speed": kin["forward_speed"],
    }
    with pytest.warns(DeprecationWarning) as record:
        before = prescribed(hull, old, solver=solver, slices=8)
    said = {tuple(str(w.message).split("'")[1:4:2]) for w in record}
    assert said == {
        ("penetration", "draft"), ("pitch", "pitch_rad"), ("pitch_rate", "pitch_rate_rad_s")
    }  # fmt: skip
    np.testing.assert_allclose(before.force, now.force, rtol=1e-12)
    np.testing.assert_allclose(before.moment, now.moment, rtol=1e-12, atol=1e-12)
    # the angles in degrees, under the names that say so, without a warning
    deg = {k: v for k, v in kin.items() if not k.startswith("pitch")}
    deg["pitch_deg"] = 4.0 + 100.0 * kin["t"]
    deg["pitch_rate_deg_s"] = np.full_like(kin["t"], 100.0)
    in_deg = prescribed(hull, deg, solver=solver, slices=8)
    np.testing.assert_allclose(in_deg.force, now.force, rtol=1e-12)
    np.testing.assert_allclose(in_deg.moment, now.moment, rtol=1e-12, atol=1e-12)
    with pytest.raises(hs.CaseError, match="give 'draft' only"):
        prescribed(hull, {**kin, "penetration": kin["draft"]}, solver=solver, slices=8)
    with pytest.raises(hs.CaseError, match="give 'pitch_rad' only"):
        prescribed(hull, {**kin, "pitch": kin["pitch_rad"]}, solver=solver, slices=8)
    with pytest.raises(hs.CaseError, match="the angle twice"):
        prescribed(hull, {**kin, "pitch_deg": deg["pitch_deg"]}, solver=solver, slices=8)


def test_history_draft_and_its_former_name(paper_fall):
    assert np.array_equal(paper_fall.columns()["draft"], paper_fall.draft)
    assert "penetration" not in paper_fall.columns()
    assert paper_fall.peak["draft"] == paper_fall.draft[np.argmax(paper_fall.force)]
    with pytest.warns(DeprecationWarning, match="use History.draft"):
        assert np.array_equal(paper_fall.penetration, paper_fall.draft)


def test_kinematics_file_in_degrees_is_read_in_rad(tmp_path):
    path = tmp_path / "k.csv"
    path.write_text(
        "t,draft,velocity,pitch_deg,pitch_rate_deg_s\n0,0.01,-2,4,90\n0.001,0.012,-2,4.09,90\n"
    )
    kin = read_kinematics(path)
    assert list(kin) == ["t", "draft", "velocity", "pitch_rad", "pitch_rate_rad_s"]
    np.testing.assert_array_equal(kin["pitch_rad"], np.radians([4.0, 4.09]))
    np.testing.assert_array_equal(kin["pitch_rate_rad_s"], np.radians([90.0, 90.0]))
    with pytest.warns(DeprecationWarning, match="read 'pitch_rad'"):
        assert kin["pitch"] is kin["pitch_rad"]
    with pytest.raises(KeyError):
        kin["pitch_acceleration"]


def test_a_kinematics_file_may_name_the_draft_by_its_former_name(tmp_path):
    now = tmp_path / "now.csv"
    now.write_text("t,draft,velocity\n0,0.01,-3\n0.001,0.013,-3\n")
    former = tmp_path / "former.csv"
    former.write_text("t,penetration,velocity\n0,0.01,-3\n0.001,0.013,-3\n")
    a, b = read_kinematics(now), read_kinematics(former)
    assert list(a) == list(b) == ["t", "draft", "velocity"]
    for key in a:
        assert np.array_equal(a[key], b[key])
    both = tmp_path / "both.csv"
    both.write_text("t,draft,penetration,velocity\n0,0.01,0.01,-3\n")
    with pytest.raises(hs.CaseError, match="both a draft and a penetration column"):
        read_kinematics(both)
