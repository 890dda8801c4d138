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
from hullslice.progress import TimeProgress
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
    p = TimeProgress(stream=stream, clock=lambda: now[0])
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


# -- 8. output files: checked before the work, written all or none ------------------------------

FORCE = ["force", WEDGE, "--mass", "10", "--draft", "0.01", "--velocity=-4", "--slices", "8"]


@pytest.fixture
def read_only(tmp_path, monkeypatch):
    """A folder ``ro`` in which no file can be made (as for a read-only folder, whoever
    runs, root included), and a record of whether any computation ran."""
    import errno
    import os

    from hullslice import atomic

    ro = tmp_path / "ro"
    ro.mkdir()
    real = atomic.tempfile.mkstemp

    def mkstemp(*args, dir=None, **kw):
        if dir is not None and os.path.realpath(dir) == os.path.realpath(ro):
            raise PermissionError(errno.EACCES, "Permission denied", str(ro / "x.tmp"))
        return real(*args, dir=dir, **kw)

    monkeypatch.setattr(atomic.tempfile, "mkstemp", mkstemp)
    ran: list[str] = []
    from hullslice.cli import cmd_report, outputs

    def no_work(*args, **kw):
        ran.append("execute")
        raise AssertionError("the work ran before the outputs were checked")

    monkeypatch.setattr(outputs, "execute", no_work)
    monkeypatch.setattr(cmd_report, "execute", no_work)
    monkeypatch.chdir(tmp_path)
    return ro, ran


@pytest.mark.parametrize(
    "argv",
    [
        [*FORCE, "-o", "ro/out.csv", "--plot", "p.png", "--save-case", "c.toml"],
        ["simulate", WEDGE, *FALL, "-o", "ro/out.csv", "--plot", "p.png"],
        [*FORCE, "-o", "out.csv", "--plot", "ro/p.png", "--save-case", "c.toml"],
        [*FORCE, "--save-case", "ro/c.toml", "--plot", "p.png"],
        ["info", WEDGE, "--write-mesh", "ro/w.stl", "-o", "out.txt"],
    ],
    ids=["force-o", "simulate-o", "force-plot", "force-save-case", "info-write-mesh"],
)
def test_an_unwritable_output_is_refused_before_the_work(capsys, tmp_path, read_only, argv):
    ro, ran = read_only
    code, _, err = run(capsys, *argv)
    assert code == 3, err
    assert err.count("\n") == 1 and "Traceback" not in err
    bad = next(a for a in argv if a.startswith("ro/"))
    assert f"cannot write {bad!r}" in err
    assert "Permission denied; give a path in a folder you can write to" in err
    assert ".hullslice-" not in err  # the user's path, never a temporary file
    assert ran == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["ro"]
    assert list(ro.iterdir()) == []


def test_run_refuses_an_unwritable_output_before_the_work(capsys, tmp_path, read_only):
    case = tmp_path / "case.toml"
    case.write_text(
        f'command = "force"\nmesh = {json.dumps(WEDGE)}\nmass = 10.0\ndraft = 0.01\n'
        "velocity = -4.0\nslices = [8]\n",
        encoding="utf-8",
    )
    code, _, err = run(capsys, "run", str(case), "-o", "ro/x.csv", "--plot", "q.png")
    assert code == 3 and "cannot write 'ro/x.csv' (--output): Permission denied" in err
    assert read_only[1] == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["case.toml", "ro"]


def test_report_refuses_an_unwritable_folder_before_the_work(capsys, tmp_path, read_only):
    case = tmp_path / "case.toml"
    case.write_text(
        f'command = "force"\nmesh = {json.dumps(WEDGE)}\nmass = 10.0\ndraft = 0.01\n'
        "velocity = -4.0\nslices = [8]\n",
        encoding="utf-8",
    )
    code, _, err = run(capsys, "report", str(case), "-o", "ro/rep")
    assert code == 3 and err.count("\n") == 1
    assert "cannot write 'ro/rep' (--output): Permission denied" in err
    assert ".hullslice-" not in err and read_only[1] == []


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="/proc takes no new files")
def test_an_output_in_a_folder_that_takes_no_files_names_the_users_path(capsys, tmp_path):
    code, _, err = run(capsys, *FORCE, "--plot", "/proc/p.png", "-o", str(tmp_path / "x.csv"))
    assert code == 3 and err.count("\n") == 1
    assert err.startswith("hullslice: error: cannot write '/proc/p.png' (--plot): ")
    assert "the folder '/proc' takes no new files" in err and ".hullslice-" not in err
    assert list(tmp_path.iterdir()) == []


def test_write_atomic_names_the_target_not_its_temporary(tmp_path):
    from hullslice.atomic import write_atomic

    target = tmp_path / "no" / "x.csv"
    with pytest.raises(OSError) as info:
        write_atomic(target, "a")
    assert info.value.filename == str(target)
    if sys.platform.startswith("linux"):
        with pytest.raises(OSError) as info:
            write_atomic("/proc/x.csv", "a")
        assert info.value.filename == "/proc/x.csv"


def test_the_outputs_of_a_command_are_written_all_or_none(capsys, tmp_path, monkeypatch):
    """A file that cannot be put in place (after every other one is complete) takes the
    others with it: those new are removed, those replaced are put back as they were."""
    import os

    from hullslice import atomic

    monkeypatch.chdir(tmp_path)
    (tmp_path / "c.toml").write_text("old case\n", encoding="utf-8")
    real = atomic.os.replace

    def replace(src, dst, *args, **kw):
        if os.path.basename(dst) == "out.csv":
            raise OSError(28, "No space left on device")
        return real(src, dst, *args, **kw)

    monkeypatch.setattr(atomic.os, "replace", replace)
    argv = [*FORCE, "--plot", "p.png", "--save-case", "c.toml", "-o", "out.csv"]
    code, out, err = run(capsys, *argv)
    assert code == 3 and out == ""
    assert err.strip() == (
        "hullslice: error: cannot write 'out.csv' (--output): No space left on device; free "
        "some space, or give a path on another disk"
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.toml"]  # no temporary left
    assert (tmp_path / "c.toml").read_text(encoding="utf-8") == "old case\n"
    monkeypatch.setattr(atomic.os, "replace", real)
    code, _, err = run(capsys, *argv)
    assert code == 0
    assert err.splitlines() == ["wrote p.png", "wrote c.toml", "wrote out.csv"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.toml", "out.csv", "p.png"]


def test_a_failure_while_drawing_writes_no_other_output(capsys, tmp_path, monkeypatch):
    from hullslice.errors import InputError
    from hullslice.plots import _common

    def save(*args, **kw):
        raise InputError("the figure cannot be drawn")

    monkeypatch.setattr(_common, "save", save)
    monkeypatch.setattr("hullslice.plots.save", save)
    monkeypatch.chdir(tmp_path)
    code, _, err = run(capsys, *FORCE, "--save-case", "c.toml", "-o", "o.csv", "--plot", "p.png")
    assert code == 3 and "the figure cannot be drawn" in err
    assert list(tmp_path.iterdir()) == []


def test_together_puts_every_file_in_place_or_none(tmp_path):
    from hullslice.atomic import together, write_atomic

    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_text("old", encoding="utf-8")
    with pytest.raises(KeyboardInterrupt), together():
        write_atomic(a, "new")
        write_atomic(b, "new")
        assert a.read_text(encoding="utf-8") == "old" and not b.exists()
        raise KeyboardInterrupt
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt"]
    assert a.read_text(encoding="utf-8") == "old"
    with together():
        write_atomic(a, "new")
        write_atomic(b, "new")
    assert a.read_text(encoding="utf-8") == b.read_text(encoding="utf-8") == "new"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt", "b.txt"]


@pytest.mark.parametrize(
    ("argv", "option", "what"),
    [
        ([*FORCE, "-o", ""], "-o/--output", "file"),
        ([*FORCE, "--plot", ""], "--plot", "file"),
        ([*FORCE, "--save-case", ""], "--save-case", "file"),
        (["info", WEDGE, "--write-mesh", ""], "--write-mesh", "file"),
        (["run", "case.toml", "-o", ""], "-o/--output", "file"),
        (["run", "case.toml", "--plot", ""], "--plot", "file"),
        (["report", "case.toml", "-o", ""], "-o/--output", "folder"),
        (["sweep", "case.toml", "-o", ""], "-o/--output", "file"),
    ],
)
def test_an_empty_output_path_is_refused_naming_the_option(capsys, tmp_path, argv, option, what):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert err.count("\n") == 1
    assert f"argument {option}: an empty path; give a {what} name" in err


@pytest.mark.parametrize(
    ("outputs", "message"),
    [
        (["-o", "x.png", "--plot", "./x.png"], "cannot write './x.png' (--plot): --output writes"),
        (["--plot", "x.png", "--save-case", "sub/../x.png"], "(--save-case): --plot writes"),
        (["-o", "f.txt/out.csv"], "a part of the path 'f.txt' is a file, not a folder"),
    ],
)
def test_outputs_that_clash_are_refused_before_the_work(capsys, tmp_path, monkeypatch, outputs,
                                                        message):  # fmt: skip
    monkeypatch.chdir(tmp_path)
    (tmp_path / "sub").mkdir()
    (tmp_path / "f.txt").write_text("keep", encoding="utf-8")
    code, _, err = run(capsys, *FORCE, *outputs)
    assert code == 3 and err.count("\n") == 1 and message in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.txt", "sub"]


def test_a_sweep_refuses_a_case_beyond_the_pitch_limit_before_it_runs(capsys, tmp_path):
    pytest.importorskip("xarray")
    case = tmp_path / "case.toml"
    case.write_text(
        f"mesh = {json.dumps(WEDGE)}\nmass = 10.0\nvelocity = -4.0\nt_end = 0.01\n"
        "dt = 0.001\nslices = 8\n\n[sweep]\npitch = [5.0, 85.0]\n",
        encoding="utf-8",
    )
    code, out, err = run(capsys, "sweep", str(case), "--workers", "1", "-o", "x.nc")
    assert code == 3 and out == "" and err.count("\n") == 1
    assert "[sweep] case pitch=85: pitch 85 deg is too steep for a 2D+t model" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["case.toml"]


def test_output_to_dev_stdout_through_a_pipe_is_written(tmp_path):
    # /dev/stdout links to /proc/self/fd/1, which names no file when the output is a pipe:
    # the link is written through as a device, not refused as a folder taking no files
    import subprocess

    mesh = str(MESHES / "paper_prism.stl")
    run = subprocess.run(
        [sys.executable, "-m", "hullslice", "force", mesh, "--mass", "1", "--draft", "0.03",
         "--velocity=-3", "--slices", "8", "-o", "/dev/stdout"],
        capture_output=True, text=True, cwd=tmp_path, check=False,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert "force" in run.stdout and "N at 8 slices" in run.stdout
    assert list(tmp_path.iterdir()) == []
