"""Command-line options for pitch, forward speed and mass properties."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import hullslice as hs
from hullslice.cli import main

from .conftest import MESHES

PRISM = str(MESHES / "paper_prism.stl")


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_force_with_pitch_and_forward_speed(capsys, paper_hull):
    code, out, err = run(
        capsys,
        "force",
        PRISM,
        "--mass",
        "1",
        "--draft",
        "0.03",
        "--velocity=-2",
        "--pitch",
        "4",
        "--forward-speed",
        "5",
        "--pitch-rate",
        "10",
        "--slices",
        "16,32,64",
        "--format",
        "json",
    )
    assert code == 0, err
    data = json.loads(out)
    ref = hs.compute_force(
        paper_hull,
        hs.Pose(0.03, math.radians(4)),
        hs.Motion(-2.0, 5.0, math.radians(10)),
        slices=64,
    )
    assert data["force"] == pytest.approx(ref.total, rel=1e-12)
    assert data["moment"] == pytest.approx(ref.moment, rel=1e-12)
    assert data["pitch_deg"] == pytest.approx(4.0)
    assert [s["velocity"] for s in data["slices"]] == pytest.approx(list(ref.velocity))


def test_mass_distribution_cg_and_inertia(capsys, tmp_path):
    dist = tmp_path / "mass.csv"
    dist.write_text("x,mass_per_metre\n0,2\n0.35,4\n")  # 1.05 kg, heavier forward
    code, out, err = run(
        capsys,
        "simulate",
        PRISM,
        "--mass-distribution",
        str(dist),
        "--velocity=-4",
        "--t-end",
        "0.004",
        "--dt",
        "2e-4",
        "--free-pitch",
        "--format",
        "json",
    )
    assert code == 0, err
    data = json.loads(out)
    assert data["settings"]["mass"] == pytest.approx(1.05)
    # centre of gravity of a linear density 2 -> 4 kg/m over 0.35 m: x = 0.35 * 5/9
    assert data["settings"]["cg"][0] == pytest.approx(0.35 * 5 / 9, rel=1e-12)
    code, out, _ = run(
        capsys,
        "simulate",
        PRISM,
        "--mass",
        "1",
        "--cg",
        "0.2,-0.03",
        "--inertia",
        "0.02",
        "--velocity=-4",
        "--t-end",
        "0.004",
        "--dt",
        "2e-4",
        "--free-pitch",
        "--format",
        "json",
    )
    settings = json.loads(out)["settings"]
    assert settings["cg"] == [0.2, -0.03] and settings["pitch_inertia"] == 0.02


@pytest.mark.parametrize(
    ("argv", "message", "status"),
    [
        (["force", PRISM, "--draft", "0.03", "--velocity=-2"], "give the body's mass", 2),
        (
            ["force", PRISM, "--mass", "1", "--draft", "0.03", "--velocity=-2", "--cg", "1"],
            "not two numbers",
            2,
        ),
        (
            ["force", PRISM, "--mass", "1", "--draft", "0.03", "--velocity=-2", "--pitch", "85"],
            "too steep",
            3,
        ),
        (
            ["force", PRISM, "--mass", "1", "--draft", "0.03", "--velocity=-2", "--inertia", "-1"],
            "not positive",
            3,
        ),
        (
            ["simulate", PRISM, "--mass", "1", "--kinematics", "k.csv", "--pitch", "3"],
            "leave out --pitch",
            2,
        ),
        (
            ["simulate", PRISM, "--mass-distribution", "nope.csv", "--velocity=-1", "--t-end", "1"],
            "does not exist",
            3,
        ),
    ],
)
def test_errors(capsys, argv, message, status):
    # 2: the command line does not parse (usage); 3: it parses, and the input is refused
    code, _, err = run(capsys, *argv)
    assert code == status
    assert message in err and len(err.strip().splitlines()) == 1


def test_the_cutter_is_an_option_and_named_in_the_result(capsys, tmp_path):
    """``--cutter`` (a row of the option table) reaches the run: a free-pitch history cut
    by manifold3d equals the exact kernel's (the default) within 1e-9 of its peak force,
    the settings name the cutter, and a case file carries it."""
    argv = ["simulate", PRISM, "--mass", "1", "--velocity=-4", "--t-end", "0.004",
            "--dt", "2e-4", "--pitch", "4", "--free-pitch", "--format", "json"]  # fmt: skip
    code, out, err = run(capsys, *argv)
    assert code == 0, err
    exact = json.loads(out)
    case = tmp_path / "case.toml"
    code, out, err = run(capsys, *argv, "--cutter", "manifold3d", "--save-case", str(case))
    assert code == 0, err
    turned = json.loads(out)
    assert exact["settings"]["cutter"] == "exact"
    assert turned["settings"]["cutter"] == "manifold3d"
    f_exact = np.array(exact["history"]["force"])
    f_turned = np.array(turned["history"]["force"])
    assert len(f_exact) == len(f_turned) > 10
    assert np.max(np.abs(f_exact - f_turned)) <= 1e-9 * np.max(np.abs(f_exact))
    assert 'cutter = "manifold3d"' in case.read_text(encoding="utf-8")
    code, _, err = run(capsys, *argv, "--cutter", "sharp")
    assert code == 2 and "invalid choice: 'sharp'" in err
