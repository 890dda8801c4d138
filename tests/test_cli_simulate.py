"""``hullslice simulate`` in-process, against the library's histories."""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest

from hullslice.cli import main
from hullslice.motion import simulate

from .conftest import MESHES

PRISM = str(MESHES / "paper_prism.stl")
FALL = ["--mass", "1", "--velocity=-4", "--t-end", "0.006", "--dt", "2e-4", "--slices", "16"]


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_csv_history_matches_the_library(capsys, paper_hull):
    code, out, err = run(capsys, "simulate", PRISM, *FALL, "--format", "csv")
    assert code == 0, err
    rows = list(csv.DictReader(io.StringIO(out)))
    assert list(rows[0])[:5] == ["t", "draft", "velocity", "acceleration", "force"]
    h = simulate(paper_hull, -4.0, 0.006, dt=2e-4, slices=16)
    assert len(rows) == len(h)
    np.testing.assert_allclose([float(r["force"]) for r in rows], h.force, rtol=1e-15)
    np.testing.assert_allclose([float(r["velocity"]) for r in rows], h.velocity, rtol=1e-15)


def test_json_and_table(capsys):
    code, out, _ = run(capsys, "simulate", PRISM, *FALL, "--format", "json")
    assert code == 0
    data = json.loads(out)
    assert data["mode"] == "free fall" and data["stop_reason"] == "t_end"
    assert data["peak"]["force"] == max(data["history"]["force"])
    code, out, _ = run(capsys, "simulate", PRISM, *FALL)
    assert code == 0
    assert "peak force" in out and "[m/s^2]" in out and "ended:" in out


def test_prescribed_from_csv(capsys, tmp_path):
    _, out, _ = run(capsys, "simulate", PRISM, *FALL, "--format", "csv")
    kin = tmp_path / "kin.csv"
    kin.write_text(out)  # the free-fall history is itself a kinematics table
    code, out2, err = run(
        capsys,
        "simulate",
        PRISM,
        "--mass",
        "1",
        "--slices",
        "16",
        "--kinematics",
        str(kin),
        "--format",
        "csv",
    )
    assert code == 0, err
    a = [float(r["force"]) for r in csv.DictReader(io.StringIO(out))]
    b = [float(r["force"]) for r in csv.DictReader(io.StringIO(out2))]
    np.testing.assert_allclose(b, a, rtol=1e-12)


@pytest.mark.parametrize(
    ("argv", "message", "status"),
    [
        (["--mass", "1", "--t-end", "0.01"], "needs --velocity", 2),
        (["--mass", "1", "--velocity=-4"], "needs --t-end", 2),
        (["--mass", "1", "--velocity=4", "--t-end", "0.01"], "not downward", 3),
        (
            ["--mass", "1", "--velocity=-4", "--t-end", "0.01", "--dt", "1"],
            "longer than the run",
            3,
        ),
        (["--mass", "1", "--kinematics", "nope.csv"], "does not exist", 3),
        (["--mass", "1", "--kinematics", "k.csv", "--velocity=-1"], "leave out --velocity", 2),
    ],
)
def test_errors(capsys, argv, message, status):
    # 2: the command line does not parse (usage); 3: it parses, and the input is refused
    code, _, err = run(capsys, "simulate", PRISM, *argv)
    assert code == status
    assert message in err and len(err.strip().splitlines()) == 1
