"""Bad input to ``hullslice sweep``: one line on stderr naming the value and the fix, exit
status 2, no traceback, and nothing written (neither the output nor its partial folder)."""

from __future__ import annotations

import json
import socket
import sys
import time
from pathlib import Path

import pytest

import hullslice as hs
from hullslice.cli import main

pytest.importorskip("xarray")

ROOT = Path(__file__).resolve().parents[1]
WEDGE = ROOT / "meshes" / "wedge_prism.stl"
BASE = {"mesh": str(WEDGE), "mass": 10.0, "velocity": -4.0, "t_end": 0.01, "dt": 0.001,
        "slices": 8}  # fmt: skip


def case_file(tmp: Path, sweep: str | None, base: dict | None = None) -> Path:
    lines = [f"{k} = {json.dumps(v)}" for k, v in (base or BASE).items()]
    if sweep is not None:
        lines += ["", "[sweep]", sweep]
    path = tmp / "case.toml"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def refused(capsys, tmp: Path, argv: list[str], *expected: str, status: int = 3) -> str:
    """Run the command line; check the one-line error, its exit status (3: an input that
    parses and is refused; 2 is a command line that does not parse) and that nothing was
    written."""
    before = set(tmp.iterdir())
    got = main(argv)
    err = capsys.readouterr().err
    assert got == status, err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err
    for text in expected:
        assert text in lines[0], lines[0]
    assert set(tmp.iterdir()) == before  # no output, no partial folder, no temporary file
    return lines[0]


# (grid, what the one-line error says)
GRIDS = [
    ('mesh = ["a.stl", "b.stl"]', "[sweep] key 'mesh' is not a number key of a simulate case"),
    ("free_pitch = [true, false]", "key 'free_pitch' is not a number key"),
    ("pitchh = [4.0, 6.0]", "unknown key 'pitchh'; did you mean 'pitch'?"),
    ('pitch = ["4", "6"]', "key 'pitch': every value must be a finite number in deg, not '4'"),
    ("pitch = [4.0, true]", "every value must be a finite number in deg, not True"),
    ("pitch = []", "[sweep] key 'pitch' is an empty list: give at least one value"),
    ("pitch = 4.0", "[sweep] key 'pitch' must be a list of values, e.g. pitch = [1.0, 2.0]"),
    ("pitch = [4.0, 4.0]", "[sweep] key 'pitch' repeats a value"),
    ("slices = [8, 8.5]", "key 'slices': every value must be a whole number"),
    ("mass = [10.0, -1.0]", "[sweep] case mass=-1: key 'mass' (mass of the body) must be positive"),
    ("", "[sweep] is empty: give at least one case key with a list of values"),
]  # fmt: skip


@pytest.mark.parametrize(("grid", "message"), GRIDS, ids=[g or "empty" for g, _ in GRIDS])
def test_a_bad_sweep_table_is_refused_by_name(grid, message, tmp_path, capsys):
    case = case_file(tmp_path, grid)
    out = tmp_path / "out.nc"
    refused(capsys, tmp_path, ["sweep", str(case), "-o", str(out), "--workers", "1"], message)


@pytest.mark.parametrize(
    ("table", "message"),
    [
        ("pich,mass\n4.0,10.0\n", "column 'pich': [sweep] unknown key 'pich'; did you mean"),
        ("mesh,mass\nx.stl,10.0\n", "column 'mesh': [sweep] key 'mesh' is not a number key"),
        ("pitch,mass\n4.0,heavy\n", "line 2 column 'mass': 'heavy' is not a finite number"),
        ("pitch,mass\n4.0\n", "line 2 has 1 values for 2 columns"),
        ("pitch,mass\n", "has no rows: give a header of case keys and one case per row"),
    ],
)  # fmt: skip
def test_a_cases_table_whose_columns_are_not_case_keys_is_refused(table, message, tmp_path, capsys):
    (tmp_path / "doe.csv").write_text(table)
    case = case_file(tmp_path, 'cases = "doe.csv"')
    refused(capsys, tmp_path, ["sweep", str(case), "-o", str(tmp_path / "o.nc")], message)


def test_a_case_file_that_is_not_a_sweep(tmp_path, capsys):
    case = case_file(tmp_path, None)
    refused(capsys, tmp_path, ["sweep", str(case)], "has no [sweep] table: add one")
    base = {"mesh": str(WEDGE), "mass": 10.0, "draft": 0.02, "velocity": -4.0}
    case = case_file(tmp_path, "mass = [8.0]", base)
    refused(capsys, tmp_path, ["sweep", str(case)], "a sweep runs time histories")


def test_outputs_that_cannot_be_written(tmp_path, capsys):
    case = case_file(tmp_path, "mass = [8.0, 12.0]")
    refused(
        capsys, tmp_path, ["sweep", str(case), "-o", str(tmp_path / "out.csv")],
        "cannot write", "give one of these extensions",
    )  # fmt: skip
    refused(
        capsys, tmp_path,
        ["sweep", str(case), "-o", str(tmp_path / "no" / "out.nc"), "--workers", "1"],
        "the folder", "does not exist; create it first",
    )  # fmt: skip
    refused(
        capsys, tmp_path,
        ["sweep", str(case), "-o", str(tmp_path / "o.parquet"), "--keep-histories"],
        "a Parquet file holds one row per case",
    )  # fmt: skip
    refused(capsys, tmp_path, ["sweep", str(case), "--resume"], "give -o PATH")
    refused(  # a command line that does not parse: status 2
        capsys, tmp_path, ["sweep", str(case), "--workers", "0"], "'0' is not positive", status=2
    )


def test_a_partial_sweep_is_not_overwritten_without_resume(tmp_path, capsys):
    case = case_file(tmp_path, "mass = [8.0, 12.0]")
    out = tmp_path / "out.nc"
    partial = tmp_path / "out.nc.partial"
    hs.sweep(case, workers=1, partial=partial)  # a sweep whose output was never written
    kept = sorted(p.name for p in partial.iterdir())
    refused(
        capsys, tmp_path, ["sweep", str(case), "-o", str(out), "--workers", "1"],
        f"a partial sweep is in '{partial}': give --resume",
    )  # fmt: skip
    assert sorted(p.name for p in partial.iterdir()) == kept
    other = case_file(tmp_path, "mass = [8.0, 11.0]")
    refused(
        capsys, tmp_path, ["sweep", str(other), "-o", str(out), "--workers", "1", "--resume"],
        "are of another sweep",
    )  # fmt: skip


def test_without_the_extra_the_command_says_what_to_install(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "xarray", None)  # import xarray now fails
    case = case_file(tmp_path, "mass = [8.0, 12.0]")
    refused(capsys, tmp_path, ["sweep", str(case)], "pip install 'hullslice[sweep]'")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_a_scheduler_that_does_not_answer_python_api():
    address = f"tcp://127.0.0.1:{_free_port()}"
    start = time.monotonic()
    with pytest.raises(hs.InputError, match=r"no Dask scheduler answers at 'tcp://127\.0\.0\.1"):
        hs.sweep(BASE, {"mass": [8.0]}, client=address, timeout=1.0)
    assert time.monotonic() - start < 8.0


@pytest.mark.slow
def test_a_scheduler_that_does_not_answer_within_10_s(tmp_path, capsys):
    case = case_file(tmp_path, "mass = [8.0, 12.0]")
    address = f"tcp://127.0.0.1:{_free_port()}"
    start = time.monotonic()
    refused(
        capsys, tmp_path,
        ["sweep", str(case), "-o", str(tmp_path / "o.nc"), "--scheduler", address],
        f"no Dask scheduler answers at '{address}' within 10 s",
    )  # fmt: skip
    assert time.monotonic() - start < 20.0


def test_the_progress_line_counts_cases_failures_and_time_left(capsys):
    from hullslice.progress import CaseProgress

    clock = iter([100.0, 100.0, 104.0])  # 2 finished cases found on resuming, 2 run in 4 s
    progress = CaseProgress(clock=lambda: next(clock))
    progress(2, 10, 0)
    progress(4, 10, 1)
    progress.done()
    err = capsys.readouterr().err
    # 2 cases in 4 s, 6 to go: 12 s left
    assert "\rsweep: 4/10 cases done, 1 failed, 4 s elapsed, about 12 s left" in err
    assert "\rsweep: 2/10 cases done, 0 failed, 0 s elapsed, time left unknown" in err
    assert err.endswith("\r")  # cleared


def test_a_sweep_applies_the_mesh_options_and_protects_its_inputs(tmp_path, capsys):
    # the base case's scale reaches the sweep's hull (a sweep equals single runs of its
    # cases); -o onto the cases table is refused; a non-header first line is not quoted
    import shutil

    import hullslice as hs

    shutil.copy(WEDGE, tmp_path / "wedge.stl")
    (tmp_path / "doe.nc").write_text("velocity\n-1.0\n-2.0\n")  # a CSV, oddly named
    case = tmp_path / "case.toml"
    case.write_text(
        'mesh = "wedge.stl"\nmass = 10.0\nvelocity = -2.0\nt_end = 0.004\ndt = 0.001\n'
        'continue_invalid = true\nscale = 2.0\n\n[sweep]\ncases = "doe.nc"\n'
    )
    ds = hs.sweep(case, workers=1)
    hull = hs.load_hull(tmp_path / "wedge.stl", mass=10.0, scale=2.0)
    ref = hs.simulate(hull, -1.0, 0.004, dt=0.001, stop_on=())
    assert ds["peak_force"].values[0] == ref.peak["force"]
    refused(
        capsys, tmp_path, ["sweep", str(case), "--workers", "1", "-o", str(tmp_path / "doe.nc")],
        "it is the input cases table file",
    )  # fmt: skip
    (tmp_path / "doe.nc").write_text("SECRET=abc,zz\n1,2\n")
    message = refused(capsys, tmp_path, ["sweep", str(case), "--workers", "1"], "not a header")
    assert "SECRET" not in message


def test_a_sweep_whose_every_case_fails_exits_with_the_bad_input_status(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text(
        f'mesh = "{WEDGE.as_posix()}"\nmass = 10.0\nvelocity = -2.0\nt_end = 0.004\n'
        "dt = 0.001\n\n[sweep]\ndraft = [1.0, 2.0]\n"
    )
    assert main(["sweep", str(case), "--workers", "1"]) == 3
    err = capsys.readouterr().err
    assert "deeper than the body's height" in err and "every case of the sweep failed" in err


def test_workers_above_four_per_core_start_four_per_core(tmp_path, monkeypatch):
    # --workers 9 on 2 cores: a warning, and a cluster of 8 workers (4 per core) is asked for
    import os

    from hullslice.sweeps import engine

    asked: list[int] = []

    def local_client(workers: int):
        asked.append(workers)
        raise hs.InputError("no cluster in this test")

    monkeypatch.setattr(engine, "local_client", local_client)
    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    case = case_file(tmp_path, "velocity = [-3.0, -4.0]")
    with (
        pytest.warns(hs.HullsliceWarning, match=r"workers 9 is more than 4 per core \(2 cores"),
        pytest.raises(hs.InputError, match="no cluster in this test"),
    ):
        hs.sweep(case, workers=9)
    assert asked == [8]
