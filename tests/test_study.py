"""The Study: one computation, built in Python, from a case or a command line, executed."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import pytest

import hullslice as hs
from hullslice.case import write_case
from hullslice.cli import build_parser, main
from hullslice.study import ForceStudyResult, SimulationResult, StudyError

from .conftest import MESHES, ROOT

PRISM = str(MESHES / "paper_prism.stl")


def test_a_study_built_in_python_gives_the_library_force(paper_hull):
    study = hs.Study("force", PRISM, mass=1.0, draft=0.0383, velocity=-3.4943, slices=(16, 32))
    result = hs.execute(study)
    assert isinstance(result, ForceStudyResult) and result.study is study
    direct = hs.convergence(paper_hull, 0.0383, -3.4943, slices=(16, 32))
    assert result.convergence.forces == pytest.approx(direct.forces, rel=1e-12)


def test_a_study_is_frozen_and_checked():
    study = hs.Study("sections", PRISM, draft=0.03)
    with pytest.raises(dataclasses.FrozenInstanceError):
        study.draft = 0.04  # type: ignore[misc]
    with pytest.raises(StudyError, match="a free fall needs --t-end"):
        hs.Study("simulate", PRISM, mass=1.0, velocity=-3.0)
    with pytest.raises(StudyError, match="takes one count for sections"):
        hs.Study("sections", PRISM, draft=0.03, slices=(8, 16))
    with pytest.raises(hs.InputError, match="too steep"):
        hs.Study("force", PRISM, mass=1.0, draft=0.03, velocity=-3.0, pitch_deg=85.0)
    with pytest.raises(hs.InputError, match="not one of info, sections, force, simulate"):
        hs.Study("forces", PRISM)


def test_a_case_and_its_command_line_are_one_study(tmp_path, capsys):
    case = hs.load_case(ROOT / "examples" / "paper.toml")
    study = hs.Study.from_case(case, checked=True)
    assert study.command == "force" and study.slice_counts == (16, 32, 64)
    assert main(["run", str(ROOT / "examples" / "paper.toml"), "--print-command"]) == 0
    printed = capsys.readouterr().out.split()
    assert printed[1:] == study.command_line()
    again = hs.Study.from_args(build_parser().parse_args(study.command_line()))
    for name in ("mesh", "units", "mass", "draft", "velocity", "slices", "solver", "rho", "g"):
        assert getattr(again, name) == getattr(study, name), name
    assert (again.pitch_rad, again.horizontal_speed) == (study.pitch_rad, study.horizontal_speed)


def test_to_case_writes_a_case_that_reads_back(tmp_path):
    study = hs.Study(
        "simulate", PRISM, mass=1.0, velocity=-3.0, t_end=0.004, dt=4e-4, slices=12,
        pitch_deg=3.0, free_pitch=True, solver_options={"froude_min": 6.5},
    )  # fmt: skip
    path = write_case(study.to_case(), tmp_path / "c.toml")
    back = hs.Study.from_case(hs.load_case(path), checked=True)
    assert Path(back.mesh).resolve() == Path(PRISM).resolve()
    assert dataclasses.replace(back, mesh=study.mesh) == study
    assert back.pitch_rad == pytest.approx(math.radians(3.0), rel=1e-15)
    result = hs.execute(back)
    assert isinstance(result, SimulationResult) and len(result.history) > 1


def test_a_raw_case_mapping_is_checked():
    with pytest.raises(hs.CaseError, match="does not apply to the command 'sections'"):
        hs.Study.from_case({"mesh": PRISM, "command": "sections", "velocity": -3.0})
    study = hs.Study.from_case({"mesh": "hull.stl", "draft": 0.03}, folder="/data")
    assert study.command == "sections" and study.mesh == str(Path("/data/hull.stl"))
