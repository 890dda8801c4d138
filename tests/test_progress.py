"""Progress: the API's callback with the simulated time, and one line on a terminal's stderr
for simulate, sweep, report and the examples, nothing when stderr is not a terminal.

The terminal is a real one: a pseudo-terminal (:mod:`pty`) as the command's stderr, its
stdout a pipe, as ``hullslice simulate ... > out.txt`` in a shell.
"""

from __future__ import annotations

import os
import pty
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import hullslice as hs

from .conftest import MESHES, ROOT

PRISM = str(MESHES / "paper_prism.stl")
FALL = ["--mass", "1", "--velocity=-4", "--t-end", "0.006", "--dt", "2e-4", "--slices", "8"]


def test_simulate_calls_back_with_increasing_times_ending_at_the_final_time(paper_hull):
    calls: list[tuple[float, float]] = []
    history = hs.simulate(
        paper_hull, -4.0, 0.006, dt=2e-4, slices=8, progress=lambda t, end: calls.append((t, end))
    )
    times = np.array([t for t, _ in calls])
    assert len(calls) == len(history) - 1  # after each step: every instant but the first
    assert np.all(np.diff(times) > 0)
    np.testing.assert_allclose(times, np.asarray(history.t)[1:], rtol=0, atol=1e-15)
    assert times[-1] == 0.006 and {end for _, end in calls} == {0.006}
    # the same history as without the callback
    again = hs.simulate(paper_hull, -4.0, 0.006, dt=2e-4, slices=8)
    np.testing.assert_array_equal(history.force, again.force)


def test_a_run_stopped_early_calls_back_up_to_its_last_instant(paper_hull):
    calls: list[float] = []
    history = hs.simulate(
        paper_hull, -4.0, 1.0, dt=1e-3, slices=8, progress=lambda t, end: calls.append(t)
    )
    assert history.stop_reason != "t_end" and history.t[-1] < 1.0  # stopped by a rule
    assert calls[-1] == pytest.approx(history.t[-1], abs=1e-15)
    assert np.all(np.diff(calls) > 0)


def test_a_prescribed_motion_calls_back_with_each_row_and_the_tables_end(paper_hull):
    t = np.linspace(0.001, 0.01, 10)
    kin = {"t": t, "draft": 3.5 * t, "velocity": np.full_like(t, -3.5)}
    calls: list[tuple[float, float]] = []
    hs.prescribed(paper_hull, kin, slices=8, progress=lambda ti, end: calls.append((ti, end)))
    np.testing.assert_allclose([c[0] for c in calls], t, rtol=0, atol=1e-15)
    assert {c[1] for c in calls} == {float(t[-1])}


def _run(argv: list[str], cwd: Path, terminal: bool) -> tuple[int, str, str]:
    """Run ``argv`` with stdout a pipe and stderr a pseudo-terminal (``terminal``) or a
    pipe; its exit status, stdout and stderr."""
    env = dict(os.environ, MPLBACKEND="Agg", COLUMNS="100")
    if not terminal:
        done = subprocess.run(argv, cwd=cwd, env=env, capture_output=True, text=True, timeout=300)
        return done.returncode, done.stdout, done.stderr
    primary, secondary = pty.openpty()
    proc = subprocess.Popen(
        argv, cwd=cwd, env=env, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
        stderr=secondary,
    )  # fmt: skip
    os.close(secondary)
    chunks = []
    while True:
        try:
            data = os.read(primary, 65536)
        except OSError:  # the terminal is closed when the command ends
            break
        if not data:
            break
        chunks.append(data)
    os.close(primary)
    out = proc.stdout.read().decode() if proc.stdout else ""
    return proc.wait(timeout=300), out, b"".join(chunks).decode()


def _cli(*args: str) -> list[str]:
    return [sys.executable, "-m", "hullslice", *args]


SWEEP_CASE = f"""mesh = "{MESHES / "wedge_prism.stl"}"
mass = 10.0
velocity = -4.0
t_end = 0.004
dt = 0.001
slices = 8

[sweep]
mass = [8.0, 12.0]
"""

REPORT_CASE = f"""command = "simulate"
mesh = "{PRISM}"
mass = 1.0
velocity = -4.0
t_end = 0.006
dt = 0.0002
slices = 8
"""


@pytest.mark.parametrize(
    ("name", "line"),
    [
        ("simulate", "simulating: t = 0.00600 s of 0.006 s (100 %)"),
        ("sweep", "sweep: 2/2 cases done, 0 failed"),
        ("report", "report: t = 0.00600 s of 0.006 s (100 %)"),
        ("ditching example", "pitch 8 deg: t = 0.04000 s of 0.04 s (100 %)"),
    ],
)
def test_a_progress_line_on_a_terminal_and_nothing_when_piped(tmp_path, name, line):
    (tmp_path / "sweep.toml").write_text(SWEEP_CASE, encoding="utf-8")
    (tmp_path / "fall.toml").write_text(REPORT_CASE, encoding="utf-8")
    argv = {
        "simulate": _cli("simulate", PRISM, *FALL),
        "sweep": _cli("sweep", "sweep.toml", "--workers", "1"),
        "report": _cli("report", "fall.toml", "-o", "report", "--overwrite"),
        "ditching example": [
            sys.executable, str(ROOT / "examples" / "ditching.py"), "--t-end", "0.04",
            "--dt", "0.01", "--slices", "16", "--out", "figures",
        ],
    }[name]  # fmt: skip
    code, out, err = _run(argv, tmp_path, terminal=True)
    assert code == 0, err
    assert "\r" + line in err and "elapsed" in err  # the last update, at the end
    # then cleared: blanks over the longest line shown, before anything else is written
    longest = max(len(seg.rstrip()) for seg in err.split("\r") if "elapsed" in seg)
    assert re.search(rf"\r {{{longest},}}\r", err[err.rindex("elapsed") :]), err
    assert line not in out  # the results on stdout are untouched
    code, piped_out, piped_err = _run(argv, tmp_path, terminal=False)
    assert code == 0, piped_err
    assert "elapsed" not in piped_err and "\r" not in piped_err
    assert piped_out == out.replace("\r\n", "\n")
