"""The command line, run in-process, against the library's own numbers."""

from __future__ import annotations

import csv
import io
import json

import pytest

import hullslice as hs
from hullslice.cli import main

from .conftest import MESHES

PRISM = str(MESHES / "paper_prism.stl")
PAPER_ARGS = ["--mass", "1", "--draft", "0.0383", "--velocity=-3.4943"]


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_force_json_matches_the_library(capsys, paper_hull):
    code, out, err = run(capsys, "force", PRISM, *PAPER_ARGS, "--format", "json")
    assert code == 0, err
    data = json.loads(out)
    study = hs.convergence(paper_hull, 0.0383, -3.4943, slices=(16, 32, 64))
    assert data["force"] == pytest.approx(study.finest.total, rel=1e-12)
    assert data["extrapolated_force"] == pytest.approx(study.richardson.extrapolated, rel=1e-12)
    assert data["gci_fraction"] == pytest.approx(study.richardson.gci, rel=1e-9)
    assert data["extrapolated_force"] == pytest.approx(147.7947, rel=2e-3)  # the paper
    assert len(data["slices"]) == 64
    first = data["slices"][0]
    for key in (
        "x",
        "penetration",
        "velocity",
        "deadrise_deg",
        "mass_per_metre",
        "force_per_metre",
        "force",
        "valid",
    ):
        assert key in first
    assert sum(s["force"] for s in data["slices"]) == pytest.approx(data["force"], rel=1e-12)
    assert first["velocity"] == -3.4943
    assert data["valid"] is True


def test_force_table_is_readable(capsys):
    code, out, _ = run(capsys, "force", PRISM, *PAPER_ARGS, "--slices", "8,16,32")
    assert code == 0
    assert "extrapolated force 147.9" in out
    assert "[N]" in out and "[m/s]" in out and "[deg]" in out
    assert "all slices inside the method's validity range" in out


def test_force_csv(capsys):
    code, out, _ = run(capsys, "force", PRISM, *PAPER_ARGS, "--slices", "16", "--format", "csv")
    assert code == 0
    rows = list(csv.DictReader(io.StringIO(out)))
    slices = [r for r in rows if r["row"] == "slice"]
    assert len(slices) == 16 and [r["row"] for r in rows[16:]] == ["total"]
    assert {"x", "penetration", "force", "valid"} <= set(rows[0])
    assert sum(float(r["force"]) for r in slices) == pytest.approx(148.06, rel=1e-3)
    assert float(rows[16]["force"]) == pytest.approx(148.06, rel=1e-3)


def test_force_with_mesh_in_mm_and_other_axes(capsys, tmp_path):
    import trimesh

    from hullslice import shapes
    from hullslice.mesh import axis_matrix

    v, f = shapes.paper_prism()
    rot = axis_matrix("+y", "-x")
    path = tmp_path / "prism_mm.stl"
    trimesh.Trimesh(v @ rot * 1000.0, f, process=False).export(path)
    args = [*PAPER_ARGS, "--slices", "16", "--format", "json"]
    _, ref, _ = run(capsys, "force", PRISM, *args)
    code, out, err = run(
        capsys, "force", str(path), *args, "--units", "mm", "--forward", "y", "--up=-x"
    )
    assert code == 0, err
    assert json.loads(out)["force"] == pytest.approx(json.loads(ref)["force"], rel=1e-6)


def test_sections(capsys, paper_hull):
    code, out, _ = run(
        capsys, "sections", PRISM, "--draft", "0.0383", "--slices", "4", "--format", "json"
    )
    assert code == 0
    data = json.loads(out)
    s = hs.cut(paper_hull, 0.0383, 4)
    assert [r["penetration"] for r in data["sections"]] == pytest.approx(list(s.penetration))
    assert data["wetted_length"] == pytest.approx(0.16275, abs=1e-5)
    code, out, _ = run(capsys, "sections", PRISM, "--draft", "0.0383", "--slices", "4")
    assert code == 0 and "[deg]" in out


def test_solvers_lists_the_default(capsys):
    code, out, _ = run(capsys, "solvers")
    assert code == 0
    assert "extended-von-karman (default)" in out
    code, out, _ = run(capsys, "solvers", "--format", "json")
    names = {s["name"]: s for s in json.loads(out)["solvers"]}
    assert names["extended-von-karman"]["distribution"] == "hullslice"
    assert names["extended-von-karman"]["status"] == "ok"


@pytest.mark.parametrize(
    ("argv", "message", "status"),
    [
        (["force", PRISM, *PAPER_ARGS, "--solver", "nope"], "no solver named 'nope'", 3),
        (["force", "missing.stl", *PAPER_ARGS], "does not exist", 3),
        (["force", PRISM, "--mass", "1", "--draft", "0.0383"], "--velocity", 2),
        (["force", PRISM, *PAPER_ARGS, "--slices", "0"], "not positive", 2),
        (["force", PRISM, *PAPER_ARGS, "--slices", "a,b"], "not a whole number", 2),
        (["force", PRISM, "--mass", "-1", "--draft", "0.01", "--velocity=-1"], "not positive", 3),
        (["sections", PRISM, "--draft", "0.5"], "deeper than the body", 3),
        (["sections", PRISM, "--draft=-0.1"], "negative", 3),
        (["sections", PRISM, "--draft", "0.01", "--units", "yd"], "invalid choice", 2),
        (["frobnicate"], "invalid choice", 2),
    ],
)
def test_errors_are_one_line_with_their_status(capsys, argv, message, status):
    # 2: the command line does not parse (usage); 3: it parses, and the input is refused
    code, _, err = run(capsys, *argv)
    assert code == status
    assert message in err
    assert len(err.strip().splitlines()) == 1
    assert "Traceback" not in err


def test_output_file_is_written_whole(capsys, tmp_path):
    target = tmp_path / "force.json"
    code, out, _ = run(
        capsys, "force", PRISM, *PAPER_ARGS, "--slices", "8", "--format", "json", "-o", str(target)
    )
    assert code == 0 and out == ""
    assert json.loads(target.read_text())["slice_count"] == 8
    # a failing run leaves no file behind
    bad = tmp_path / "bad.json"
    code, _, _ = run(capsys, "force", PRISM, *PAPER_ARGS, "--solver", "nope", "-o", str(bad))
    assert code == 3 and not bad.exists()
    assert [p.name for p in tmp_path.iterdir()] == ["force.json"]


def test_version(capsys):
    code, out, _ = run(capsys, "--version")
    assert code == 0 and out.startswith("hullslice ")


def test_messages_suggest_what_was_meant(capsys):
    # a misspelt solver (any case) or option gets the closest name; slice counts given
    # without commas get the hint
    prism = str(MESHES / "paper_prism.stl")
    state = [prism, "--mass", "1", "--draft", "0.03", "--velocity=-3"]
    for extra, hint in (
        (["--solver", "Wagnr"], "did you mean 'wagner'?"),
        (["--solver", "WAGNER"], "did you mean 'wagner'?"),
        (["--solver", "wagner", "--solver-option", "pileup=wagner"], "did you mean 'pile_up'?"),
        (["--slices", "16", "32", "64"], "several slice counts take commas: --slices 16,32,64"),
    ):
        assert main(["force", *state, *extra]) in (2, 3)
        err = capsys.readouterr().err
        assert hint in err and len(err.strip().splitlines()) == 1, err


def test_json_outputs_carry_the_version_and_the_schema(capsys):
    import json

    import hullslice as hs

    assert main(["solvers", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["hullslice_version"] == hs.__version__ and data["schema_version"] == 3
