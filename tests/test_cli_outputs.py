"""Complete outputs, chosen rows, progress, column names and messages of the commands."""

from __future__ import annotations

import csv
import io
import json
import math
import re
import sys

import numpy as np
import pytest

import hullslice as hs
from hullslice.cli import main
from hullslice.cli.cmd_simulate import Progress
from hullslice.textout import JSON_SCHEMA_VERSION, Column, coordinate_text, table_text

from .conftest import MESHES

PRISM = str(MESHES / "paper_prism.stl")
WEDGE = str(MESHES / "wedge_prism.stl")
PAPER_ARGS = ["--mass", "1", "--draft", "0.0383", "--velocity=-3.4943"]
FALL = ["--mass", "1", "--velocity=-4", "--t-end", "0.006", "--dt", "2e-4", "--slices", "16"]
PITCHED = ["--pitch", "4", "--forward-speed", "5", "--pitch-rate", "10"]


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


# -- 1. complete outputs ----------------------------------------------------------------------


def test_force_csv_holds_every_count_and_the_extrapolation(capsys, paper_hull):
    code, out, err = run(capsys, "force", PRISM, *PAPER_ARGS, "--format", "csv")
    assert code == 0, err
    rows = list(csv.DictReader(io.StringIO(out)))  # one call loads it all
    study = hs.convergence(paper_hull, 0.0383, -3.4943, slices=(16, 32, 64))
    for n, result in zip(study.counts, study.results, strict=True):
        mine = [r for r in rows if r["row"] == "slice" and r["slices"] == str(n)]
        assert [int(r["j"]) for r in mine] == list(range(1, n + 1))
        np.testing.assert_allclose([float(r["force"]) for r in mine], result.force, rtol=1e-15)
        (total,) = [r for r in rows if r["row"] == "total" and r["slices"] == str(n)]
        assert float(total["force"]) == pytest.approx(result.total, rel=1e-15)
        assert float(total["moment"]) == pytest.approx(result.moment, rel=1e-15, abs=1e-15)
    (extra,) = [r for r in rows if r["row"] == "extrapolated"]
    rich = study.richardson
    assert float(extra["force"]) == pytest.approx(rich.extrapolated, rel=1e-15)
    assert float(extra["order"]) == pytest.approx(rich.order, rel=1e-15)
    assert float(extra["gci_fraction"]) == pytest.approx(rich.gci, rel=1e-15)
    assert extra["convergence_behaviour"] == rich.behaviour
    assert len(rows) == 16 + 32 + 64 + 3 + 1


def test_force_json_names_the_gci_a_fraction(capsys, paper_hull):
    code, out, err = run(capsys, "force", PRISM, *PAPER_ARGS, *PITCHED, "--format", "json")
    assert code == 0, err
    data = json.loads(out)
    assert data["schema_version"] == JSON_SCHEMA_VERSION == 3
    assert "gci" not in data
    study = hs.convergence(
        paper_hull,
        hs.Pose(0.0383, math.radians(4)),
        hs.Motion(-3.4943, 5.0, math.radians(10)),
        slices=(16, 32, 64),
    )
    assert data["gci_fraction"] == pytest.approx(study.richardson.gci, rel=1e-12)
    for entry, result in zip(data["convergence"], study.results, strict=True):
        assert entry["force_x"] == pytest.approx(result.total_x, rel=1e-12)
        assert entry["moment"] == pytest.approx(result.moment, rel=1e-12)


def test_force_table_of_a_pitched_state_shows_the_state_and_the_moment(capsys, paper_hull):
    code, out, err = run(capsys, "force", PRISM, *PAPER_ARGS, *PITCHED)
    assert code == 0, err
    assert "pitch 4 deg, forward speed 5 m/s, pitch rate 10 deg/s" in out
    ref = hs.compute_force(
        paper_hull,
        hs.Pose(0.0383, math.radians(4)),
        hs.Motion(-3.4943, 5.0, math.radians(10)),
        slices=64,
    )
    m = re.search(r"force_x (\S+) N, pitch moment My (\S+) N m", out)
    assert m is not None, out
    assert float(m.group(1)) == pytest.approx(ref.total_x, rel=1e-6)
    assert float(m.group(2)) == pytest.approx(ref.moment, rel=1e-6)
    heads = out.splitlines()[4].split()
    assert heads == ["slices", "force", "force_x", "My", "valid"]
    assert " Fx " in out  # the per-slice horizontal force
    code, plain, _ = run(capsys, "force", PRISM, *PAPER_ARGS)
    assert "My" not in plain and "pitch " not in plain and "force_x" not in plain


def test_forces_are_printed_with_seven_significant_digits(capsys):
    code, out, _ = run(capsys, "force", PRISM, *PAPER_ARGS)
    assert code == 0
    m = re.search(r"^force (\S+) N at 64 slices", out, re.M)
    assert m is not None
    digits = m.group(1).replace("-", "").replace(".", "").lstrip("0")
    assert len(digits) <= 7
    m = re.search(r"extrapolated force (\S+) N", out)
    assert m is not None and len(m.group(1).replace(".", "").lstrip("0")) <= 7


def test_rounding_noise_prints_as_zero_in_tables():
    assert coordinate_text(-1.2e-14, 1.0) == "0"
    assert coordinate_text(-6.5e-18, 40.0) == "0"
    assert coordinate_text(0.134155459, 0.4) == "0.134155"
    assert coordinate_text(2e-6, 1.0) == "2e-06"  # above the tolerance: a value
    text = table_text([Column("x", "x", "m", "~7")], [{"x": -6.5e-18}, {"x": 12.5}])
    assert text.splitlines()[2:] == [" 0.00000", "12.50000"]  # 7 digits for 12.5, no "-"


def test_info_prints_a_centre_of_volume_without_noise(capsys, tmp_path):
    # a box centred on y = 0 up to rounding: its centre's y is noise
    import trimesh

    box = trimesh.creation.box(extents=(3.0, 0.7, 0.5))
    box.apply_translation((1.5 + 1e-3, 1e-16, -0.25))
    path = tmp_path / "box.stl"
    box.export(path)
    code, out, err = run(capsys, "info", str(path))
    assert code == 0, err
    line = next(ln for ln in out.splitlines() if "centre of volume" in ln)
    assert re.search(r"centre of volume \(1\.501, 0, -0\.25\) m", line), line
    data = json.loads(run(capsys, "info", str(path), "--format", "json")[1])
    assert data["centre_of_volume"][0] == pytest.approx(1.501, rel=1e-7)  # STL floats


# -- 2. progress and chosen rows --------------------------------------------------------------


def test_progress_shows_time_elapsed_and_left():
    now = [100.0]
    stream = io.StringIO()
    p = Progress(stream, clock=lambda: now[0])
    now[0] = 110.0
    p(0.025, 0.1)
    assert "t = 0.02500 s of 0.1 s ( 25 %), 10 s elapsed, about 30 s left" in stream.getvalue()
    now[0] = 190.0
    p(0.05, 0.1)
    assert "1 min 30 s elapsed, about 1 min 30 s left" in stream.getvalue()
    p.done()
    assert stream.getvalue().endswith("\r")


def test_progress_on_a_terminal_only(capsys, monkeypatch):
    code, _, err = run(capsys, "simulate", PRISM, *FALL)
    assert code == 0 and "simulating" not in err  # not a terminal: nothing
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)
    code, out, err = run(capsys, "simulate", PRISM, *FALL)
    assert code == 0
    assert "simulating: t = " in err and "elapsed" in err and "left" in err
    assert "simulating" not in out


def test_every_picks_rows_with_the_first_and_the_last(capsys):
    code, out, err = run(capsys, "simulate", PRISM, *FALL, "--every", "7", "--format", "csv")
    assert code == 0, err
    t = [float(r["t"]) for r in csv.DictReader(io.StringIO(out))]
    assert t == pytest.approx([0.0, 0.0014, 0.0028, 0.0042, 0.0056, 0.006], abs=1e-12)
    code, out, _ = run(capsys, "simulate", PRISM, *FALL, "--every", "7")
    assert "(6 of 31 instants shown, every 7)" in out
    code, out, _ = run(capsys, "simulate", PRISM, *FALL, "--every", "7", "--format", "json")
    data = json.loads(out)
    assert data["history"]["t"] == pytest.approx(t, abs=1e-15)
    assert data["steps"] == 31 and data["rows"]["every"] == 7


def test_at_picks_the_nearest_instants(capsys):
    code, out, err = run(capsys, "simulate", PRISM, *FALL, "--at", "0.0041,0.001,0.00105")
    assert code == 0, err
    rows = [ln.split() for ln in out.splitlines() if re.match(r"^0\.\d{5} ", ln)]
    assert [r[0] for r in rows] == ["0.00100", "0.00400"]
    code, out, _ = run(capsys, "simulate", PRISM, *FALL, "--at", "0.003", "--format", "csv")
    (row,) = list(csv.DictReader(io.StringIO(out)))
    full = list(
        csv.DictReader(io.StringIO(run(capsys, "simulate", PRISM, *FALL, "--format", "csv")[1]))
    )
    assert row == full[15]


def test_at_outside_the_run_names_its_range(capsys):
    code, _, err = run(capsys, "simulate", PRISM, *FALL, "--at", "0.01")
    assert code == 2
    assert "0.01 s is outside the run, from 0 to 0.006 s" in err and len(err.splitlines()) == 1
    code, _, err = run(capsys, "simulate", PRISM, *FALL, "--at", "0.001", "--every", "2")
    assert code == 2 and "not allowed with" in err
    code, _, err = run(capsys, "simulate", PRISM, *FALL, "--at", "0.001,x")
    assert code == 2 and "'x' is not a time in s" in err


def test_at_after_an_early_stop_names_the_run_it_made(capsys):
    # the body bounces off: the run stops before t_end, and 0.5 s is past it
    argv = ["--mass", "0.05", "--velocity=-1", "--t-end", "1", "--dt", "1e-3", "--slices", "8"]
    code, _, err = run(capsys, "simulate", PRISM, *argv, "--at", "0.5")
    assert code == 3, err  # bad input, not an internal error
    assert "0.5 s is outside the run, which goes from t = 0 to" in err and "ended:" in err


def test_every_and_at_as_case_keys(capsys, tmp_path):
    case = tmp_path / "case.toml"
    case.write_text(
        f'mesh = "{PRISM}"\nmass = 1.0\nvelocity = -4.0\nt_end = 0.006\ndt = 2e-4\n'
        'slices = 16\nat = [0.001, 0.004]\nformat = "csv"\n'
    )
    code, out, err = run(capsys, "run", str(case))
    assert code == 0, err
    t = [float(r["t"]) for r in csv.DictReader(io.StringIO(out))]
    assert t == pytest.approx([0.001, 0.004], abs=1e-12)
    code, out, _ = run(capsys, "run", str(case), "--print-command")
    assert "--at=0.001,0.004" in out
    case.write_text(case.read_text().replace("at = [0.001, 0.004]", "every = 10"))
    code, out, err = run(capsys, "run", str(case))
    assert code == 0, err
    t = [float(r["t"]) for r in csv.DictReader(io.StringIO(out))]
    assert t == pytest.approx([0.0, 0.002, 0.004, 0.006], abs=1e-12)  # 30 is the last
    case.write_text(case.read_text().replace("every = 10", "every = 0"))
    code, _, err = run(capsys, "run", str(case))
    assert code in (2, 3) and "every" in err, err  # refused as input, not an internal error


# -- 3. names and messages --------------------------------------------------------------------


def test_mass_per_metre_and_moment_have_their_own_names(capsys):
    _, out, _ = run(capsys, "sections", PRISM, "--draft", "0.03", "--slices", "4", "--mass", "1")
    assert "mass/m" in out.splitlines()[1] and " M " not in out
    assert "no mass given" not in out
    _, out, _ = run(capsys, "simulate", PRISM, *FALL, "--pitch", "3")
    heads = out.splitlines()[2].split()
    assert "My" in heads and "Fx" in heads and "M" not in heads
    _, out, _ = run(capsys, "force", PRISM, *PAPER_ARGS)
    assert "mass/m" in out and " M " not in out


def test_sections_without_mass_say_why_mass_per_metre_is_missing(capsys):
    code, out, _ = run(capsys, "sections", PRISM, "--draft", "0.03", "--slices", "4")
    assert code == 0
    lines = [ln for ln in out.splitlines() if "no mass given" in ln]
    assert lines == [
        "mass/m is '-': no mass given (give --mass KG or --mass-distribution CSV for the "
        "mass per metre)"
    ]


def test_info_gives_the_span_of_a_flat_largest_area(capsys):
    code, out, err = run(capsys, "info", WEDGE, "--stations", "10")
    assert code == 0, err
    assert re.search(r"largest \S+ m\^2 from x = 0\.05 to 0\.95 m, within 0\.1% of it", out), out
    data = json.loads(run(capsys, "info", WEDGE, "--stations", "10", "--format", "json")[1])
    assert (data["max_area_x_from"], data["max_area_x_to"]) == pytest.approx((0.05, 0.95))
    _, out, _ = run(capsys, "info", PRISM, "--stations", "8")
    assert "largest 0.0094852 m^2 at x = 0.021875 m" in out
