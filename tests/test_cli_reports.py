"""Reports: info, figures, case files, run, report folders; checked against the library."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import hullslice as hs
from hullslice.case import load_case
from hullslice.cli import build_parser, main

from .conftest import DATA, MESHES, ROOT

PRISM = str(MESHES / "paper_prism.stl")
PAPER_CASE = str(ROOT / "examples" / "paper.toml")
PNG = b"\x89PNG\r\n\x1a\n"


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_golden_paper_case(capsys):
    golden = json.loads((DATA / "golden_paper_force.json").read_text())
    code, out, err = run(capsys, "run", PAPER_CASE, "--format", "json")
    assert code == 0, err
    data = json.loads(out)
    for key in ("force", "extrapolated_force", "wetted_length", "order"):
        assert data[key] == pytest.approx(golden[key], rel=1e-6), key
    assert data["gci_fraction"] == pytest.approx(golden["gci"], rel=1e-3)
    assert [c["force"] for c in data["convergence"]] == pytest.approx(
        [c["force"] for c in golden["convergence"]], rel=1e-6
    )
    for ref in golden["slices_sample"]:
        row = min(data["slices"], key=lambda r: abs(r["x"] - ref["x"]))
        for key, value in ref.items():
            assert row[key] == pytest.approx(value, rel=1e-6), key
    assert data["extrapolated_force"] == pytest.approx(147.7947, rel=2e-3)  # the paper


def test_info_matches_the_library(capsys, paper_hull):
    code, out, err = run(
        capsys, "info", PRISM, "--mass", "1", "--format", "json", "--stations", "70"
    )
    assert code == 0, err
    data = json.loads(out)
    assert data["volume"] == pytest.approx(paper_hull.volume, rel=1e-12)
    assert data["faces"] == len(paper_hull.faces)
    assert data["pitch_inertia"] == pytest.approx(paper_hull.pitch_inertia, rel=1e-12)
    x, area = np.array(data["area_curve"]["x"]), np.array(data["area_curve"]["area"])
    # the area of the prism's triangle: (W/2) h(x), h linear from 0.1 to 0.1 tan(10 deg)
    h = 0.1 + (0.1 * np.tan(np.radians(10)) - 0.1) * x / 0.35
    np.testing.assert_allclose(area, 0.1 * h, rtol=1e-6)
    # the midpoint rule over the curve gives the volume (exact for a linear area)
    assert area.sum() * 0.35 / 70 == pytest.approx(paper_hull.volume, rel=1e-6)
    code, out, _ = run(capsys, "info", PRISM)
    assert code == 0 and "no mass given" in out and "[m^2]" in out


@pytest.mark.parametrize(
    "argv",
    [
        ["info", PRISM],
        ["sections", PRISM, "--draft", "0.03", "--slices", "8"],
        ["force", PRISM, "--mass", "1", "--draft", "0.03", "--velocity=-3", "--slices", "8,16"],
        ["simulate", PRISM, "--mass", "1", "--velocity=-4", "--t-end", "0.004", "--dt", "4e-4"],
    ],
)
def test_plot_is_written(capsys, tmp_path, argv):
    target = tmp_path / "figure.png"
    code, _, err = run(capsys, *argv, "--plot", str(target))
    assert code == 0, err
    assert target.read_bytes()[:8] == PNG and target.stat().st_size > 10_000
    assert f"wrote {target}" in err


def test_without_matplotlib_a_one_line_message(capsys, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # import matplotlib fails
    target = tmp_path / "figure.png"
    code, _, err = run(capsys, "info", PRISM, "--plot", str(target))
    assert code == 3
    assert "pip install 'hullslice[plot]'" in err and len(err.strip().splitlines()) == 1
    assert not target.exists()


@pytest.mark.parametrize(
    "argv",
    [
        [
            "force",
            PRISM,
            "--mass",
            "1",
            "--draft",
            "0.0383",
            "--velocity=-3.4943",
            "--slices",
            "8,16,32",
            "--pitch",
            "2",
            "--forward-speed",
            "1.5",
            "--solver-option",
            "froude_min=5",
        ],
        [
            "simulate",
            PRISM,
            "--mass",
            "1",
            "--velocity=-4",
            "--t-end",
            "0.004",
            "--dt",
            "4e-4",
            "--slices",
            "12",
            "--free-pitch",
            "--continue-invalid",
            "--slicing",
            "fixed",
        ],
        ["sections", PRISM, "--draft", "0.03", "--slices", "6", "--deadrise", "keel-fit"],
        ["info", PRISM, "--mass", "1", "--stations", "9", "--units", "m"],
    ],
)
def test_saved_case_repeats_the_run(capsys, tmp_path, argv):
    case = tmp_path / "sub" / "case.toml"
    case.parent.mkdir()
    code, first, err = run(capsys, *argv, "--format", "json", "--save-case", str(case))
    assert code == 0, err
    assert load_case(case)["command"] == argv[0]
    code, again, err = run(capsys, "run", str(case))
    assert code == 0, err
    a, b = json.loads(again), json.loads(first)
    # the same numbers; the mesh named by another path to the same file
    assert Path(a.pop("mesh")).resolve() == Path(b.pop("mesh")).resolve()
    assert a == b


def test_case_paths_are_relative_to_the_case(tmp_path, capsys):
    case = tmp_path / "c.toml"
    case.write_text(f'mesh = "{MESHES.relative_to(ROOT).as_posix()}/paper_prism.stl"\n')
    code, _, err = run(capsys, "run", str(case))
    assert code == 3 and "does not exist" in err  # resolved from the case's own folder
    case.write_text(f'mesh = "{PRISM}"\ndraft = 0.03\nvelocity = -3.0\nt_end = 0.01\n')
    code, out, _ = run(capsys, "run", str(case), "--print-command")
    assert code == 0 and out.startswith("hullslice simulate ")


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ('mesh = "m.stl"\ncommand = "sections"\nvelocity = -3.0\n', "does not apply"),
        ('mesh = "m.stl"\nslices = "many"\n', "must be a whole number"),
        ("mesh = \n", "not valid TOML"),
    ],
)
def test_bad_case_files(capsys, tmp_path, text, message):
    case = tmp_path / "bad.toml"
    case.write_text(text)
    code, _, err = run(capsys, "run", str(case))
    assert code == 3 and message in err and len(err.strip().splitlines()) == 1


def test_report_folder(capsys, tmp_path, paper_hull):
    out = tmp_path / "paper"
    code, _, err = run(capsys, "report", PAPER_CASE, "-o", str(out))
    assert code == 0, err
    names = sorted(p.name for p in out.iterdir())
    assert names == sorted([
        "report.md", "case.toml", "results.json", "results.csv", "mesh.json",
        "convergence.png", "force_distribution.png", "sections.png", "area_curve.png", "views.png",
    ])  # fmt: skip
    text = (out / "report.md").read_text()
    data = json.loads((out / "results.json").read_text())
    study = hs.convergence(paper_hull, 0.0383, -3.4943, slices=(16, 32, 64))
    assert data["extrapolated_force"] == pytest.approx(study.richardson.extrapolated, rel=1e-12)
    assert f"{study.richardson.extrapolated:.4f} N" in text
    assert "| draft | 0.0383 | m |" in text and "![convergence](convergence.png)" in text
    for png in out.glob("*.png"):
        assert png.read_bytes()[:8] == PNG
    # the report's own case file repeats the study, its mesh named relative to the folder
    case = (out / "case.toml").read_text()
    mesh = next(line for line in case.splitlines() if line.startswith("mesh = "))
    rel = mesh.split('"')[1]
    assert (out / rel).resolve() == (MESHES / "paper_prism.stl").resolve()
    code, again, _ = run(capsys, "run", str(out / "case.toml"), "--format", "json")
    assert json.loads(again)["force"] == data["force"]


def test_report_is_written_whole_or_not_at_all(capsys, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(
        f'mesh = "{PRISM}"\nmass = 1.0\ndraft = 0.03\nvelocity = -3.0\nsolver = "nope"\n'
    )
    out = tmp_path / "rep"
    code, _, err = run(capsys, "report", str(bad), "-o", str(out))
    assert code == 3 and "no solver named 'nope'" in err
    assert list(tmp_path.iterdir()) == [bad]  # no folder, no temporary left
    out.mkdir()
    (out / "keep.txt").write_text("x")
    code, _, err = run(capsys, "report", PAPER_CASE, "-o", str(out))
    assert code == 3 and "exists and is not empty" in err
    code, _, _ = run(capsys, "report", PAPER_CASE, "-o", str(out), "--overwrite", "--html")
    assert code == 0 and not (out / "keep.txt").exists()
    assert "<h2>Results</h2>" in (out / "report.html").read_text()


def test_every_option_says_its_unit_or_default():
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    units = ("[", " in ", "kg", " m", "deg", "s)", "m/s", "default")
    for name, p in sub.choices.items():
        for action in p._actions:
            if action.dest in ("help",) or not action.option_strings:
                continue
            text = action.help or ""
            if (
                action.nargs == 0
                or action.choices
                or action.dest
                in (
                    "output",
                    "plot",
                    "save_case",
                    "print_command",
                    "solver_option",
                    "mesh",
                    "mass_distribution",
                    "kinematics",
                )
            ):
                assert text, f"{name} {action.option_strings} has no help"
                continue
            assert any(u in text for u in units), f"{name} {action.option_strings}: {text!r}"


def test_console_script_and_version():
    out = subprocess.run(
        [sys.executable, "-m", "hullslice", "--version"], capture_output=True, text=True
    )
    assert out.returncode == 0 and out.stdout.startswith("hullslice ")
    bad = subprocess.run(
        [sys.executable, "-m", "hullslice", "force"], capture_output=True, text=True
    )
    assert bad.returncode == 2 and len(bad.stderr.strip().splitlines()) == 1
    assert "Traceback" not in bad.stderr


def test_report_refuses_a_folder_holding_its_inputs(capsys, tmp_path):
    import shutil

    shutil.copy(MESHES / "paper_prism.stl", tmp_path / "hull.stl")
    case = tmp_path / "case.toml"
    case.write_text('mesh = "hull.stl"\nmass = 1.0\ndraft = 0.02\nvelocity = -3.0\n')
    code, _, err = run(capsys, "report", str(case), "-o", str(tmp_path), "--overwrite")
    assert code == 3 and "holds the input" in err
    assert (tmp_path / "hull.stl").exists() and case.exists()


def test_a_solver_file_in_a_case_is_relative_to_the_case(capsys, tmp_path):
    import shutil

    shutil.copy(ROOT / "plugins" / "curves" / "examples" / "paper_curves.csv", tmp_path / "c.csv")
    case = tmp_path / "case.toml"
    case.write_text(
        f'mesh = "{PRISM}"\nmass = 1.0\ndraft = 0.0383\nvelocity = -3.4943\nslices = [16]\n'
        'solver = "curves"\n[solver_options]\ntable = "c.csv"\n'
    )
    code, out, err = run(capsys, "run", str(case), "--format", "json")
    assert code == 0, err
    default = hs.compute_force(hs.load_hull(PRISM, mass=1.0), 0.0383, -3.4943, slices=16)
    assert json.loads(out)["force"] == pytest.approx(default.total, rel=1e-4)  # same curves


def test_the_report_lists_the_cases_inputs_only(capsys, tmp_path):
    case = tmp_path / "fall.toml"
    case.write_text(
        f'title = "A short fall"\ncommand = "simulate"\nmesh = "{MESHES / "paper_prism.stl"}"\n'
        "mass = 1.0\nvelocity = -4.0\nt_end = 0.004\ndt = 0.0004\nslices = 8\nevery = 2\n"
        'format = "json"\noutput = "fall.json"\nplot = "fall.png"\n',
        encoding="utf-8",
    )
    out = tmp_path / "report"
    code, _, err = run(capsys, "report", str(case), "-o", str(out))
    assert code == 0, err
    text = (out / "report.md").read_text()
    table = text.split("## Inputs", 1)[1].split("## Mesh", 1)[0]
    keys = [line.split("|")[1].strip() for line in table.splitlines() if line.startswith("| ")]
    keys = set(keys) - {"key", "---"}
    assert {"command", "mesh", "mass", "velocity", "t_end", "dt", "slices", "rho"} <= keys
    assert not keys & {"title", "format", "output", "plot", "every", "at"}
    assert "| t_end | 0.004 | s |" in table and "| mass | 1.0 | kg |" in table
    assert text.startswith("# A short fall\n")  # the title heads the page
    assert not (tmp_path / "fall.json").exists() and not (tmp_path / "fall.png").exists()
