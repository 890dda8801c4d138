"""The benchmark scripts' own figures: the helpers of ``benchmarks/run.py`` and the study of
``benchmarks/sweep.py`` (the timings themselves are the scripts' business)."""

from __future__ import annotations

import importlib.util
from pathlib import Path
from types import ModuleType, SimpleNamespace

import pytest

ROOT = Path(__file__).resolve().parents[1]


def load(name: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(f"bench_{name}", ROOT / "benchmarks" / name)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def run() -> ModuleType:
    return load("run.py")


@pytest.fixture(scope="module")
def sweep() -> ModuleType:
    return load("sweep.py")


def test_relative_error_takes_the_largest_of_force_horizontal_force_and_moment(run):
    fresh = SimpleNamespace(total=-200.0, total_x=10.0, moment=50.0)
    kept = SimpleNamespace(total=-200.0 + 1e-9, total_x=10.0 - 4e-9, moment=50.0 + 3e-8)
    # moment over a 5 m body: 6e-9 N, the largest; relative to |total| = 200 N
    assert run.relative_error(kept, fresh, 5.0) == pytest.approx(3e-11, rel=1e-6)


@pytest.mark.parametrize(("t_free", "verdict"), [(2.9e-3, "met"), (3.1e-3, "NOT MET")])
def test_the_free_over_held_pitch_ratio_is_judged_against_3_with_numpy(run, t_free, verdict):
    """numpy's free step over numpy's held step (target 3); the compiled free step over the
    fused held step (target 2), and over numpy's, reported."""
    table = run.Table()
    times = {"held": 1e-3, "held, numba": 0.25e-3, "manifold3d": 5e-3,
             "exact, numpy": t_free, "exact, numba": 0.46e-3}  # fmt: skip
    run.pitch_rows(table, "10k", times, 100)
    assert [r[3] for r in table.rows] == ["", "", "", "", "", verdict, "", "met", ""]
    assert table.rows[1][1] == "250 us"  # the fused held step
    assert table.rows[3][1] == "5.00"  # manifold3d's ratio, reported without a target
    assert table.rows[5][1] == f"{t_free / 1e-3:.2f}"
    assert table.rows[5][2] == "<= 3" and "numpy's path" in table.rows[5][0]
    assert table.rows[7][1] == "1.84" and table.rows[7][2] == "<= 2"
    assert "fused, compiled" in table.rows[7][0]
    assert table.rows[8][1] == "0.5" and table.rows[8][2] == ""
    assert "100 steps, cut once" in table.rows[0][0]


def test_without_numba_the_compiled_run_is_reported_missing(run):
    table = run.Table()
    run.pitch_rows(table, "10k", {"held": 1e-3, "manifold3d": 5e-3, "exact, numpy": 2e-3}, 9)
    assert table.rows[1][1] == "not run: numba missing (.[fast])"
    assert table.rows[-1][1] == "not run: numba missing (.[fast])"


def test_the_step_runs_time_the_same_steps_at_held_and_free_pitch(run, tmp_path, monkeypatch):
    import hullslice as hs

    monkeypatch.setattr(run, "PITCH_STEPS", 4)
    monkeypatch.setattr(run, "WARM_STEPS", 1)
    hull = hs.load_hull(run.fuselage_file(tmp_path, "10k"), mass=60000.0)
    times, steps, rounds = run.step_runs(hull, 1)
    assert steps == 4
    assert set(times) == set(rounds) == set(run.pitch_runs())
    assert all(0.0 < t < 1.0 for t in times.values())
    assert all(rounds[k] == [t] for k, t in times.items())  # one round: its times


def test_the_ratio_of_rounds_is_the_median_of_each_rounds_own(run):
    """With each round's times, free over held is the median of the rounds' ratios (the
    two runs of a round back to back: 2.5, 2.42 and 3.08 here, median 2.5), not the
    ratio of the medians (2.9 / 1.2 = 2.42), and judged on it."""
    import statistics

    def rows(rounds):
        table = run.Table()
        times = {k: statistics.median(v) for k, v in rounds.items()}
        run.pitch_rows(table, "10k", times, 100, rounds)
        return next(r for r in table.rows if "ratio free (exact, numpy)" in r[0])

    row = rows({"held": [1.0e-3, 1.2e-3, 1.2e-3], "exact, numpy": [2.5e-3, 2.9e-3, 3.7e-3]})
    assert row[1] == "2.50" and row[3] == "met" and "median of 3 rounds' ratios" in row[0]
    row = rows({"held": [1.0e-3, 1.0e-3, 1.0e-3], "exact, numpy": [3.2e-3, 3.5e-3, 3.1e-3]})
    assert row[1] == "3.20" and row[3] == "NOT MET"


def test_the_128k_size_has_about_128k_faces(run):
    from hullslice import shapes

    stations, points = run.SIZES["128k"]
    _, faces = shapes.fuselage(stations=stations, points=points)
    assert len(faces) == pytest.approx(128_000, rel=0.01)


def test_fresh_cut_figures_agree_with_the_cuts_kept(run, tmp_path):
    table = run.Table()
    run.bench_fresh_cuts(table, run.fuselage_file(tmp_path, "10k"))
    values = {what: value for what, value, _, _ in table.rows}
    (kept,) = [v for w, v in values.items() if w.startswith("10k, held pitch: kept cut")]
    assert float(kept) <= 1e-12  # the kept cut and its table agree with fresh cuts
    (noise,) = [float(v) for w, v in values.items() if w.startswith("free pitch: a fresh cut's")]
    slope = float(values["free pitch: of which the force's own change (its slope over 1e-6 rad)"])
    assert 0.0 < noise < 1e-7 and 0.0 < slope < 1e-7
    assert values["free pitch against fresh cuts"] == "none: each stage cut afresh"


def test_the_sweep_row_says_what_to_install_without_distributed(run, monkeypatch):
    find = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "distributed" else find(name)
    )
    table = run.Table()
    run.bench_sweep(table, 1)
    assert len(table.rows) == 1
    assert 'pip install -e ".[sweep]"' in table.rows[0][1] and "distributed" in table.rows[0][1]


def test_the_sweep_study_frees_the_pitch_only_when_asked(sweep):
    held, grid = sweep.study(0.05)
    free, same = sweep.study(0.05, free_pitch=True)
    assert "free_pitch" not in held and free["free_pitch"] is True
    assert grid == same and len(grid["velocity"]) * len(grid["pitch"]) == sweep.CASES == 64
    assert {k: v for k, v in free.items() if k not in ("free_pitch", "title")} == {
        k: v for k, v in held.items() if k != "title"
    }


def test_the_face_pressure_figures_come_from_a_real_mapping(run, tmp_path):
    import hullslice as hs

    pytest.importorskip("hullslice_mlm")
    hull = hs.load_hull(run.fuselage_file(tmp_path, "10k"), mass=60000.0)
    table = run.Table()
    run.bench_face_loads(table, {"128k": {"hull": hull}}, 1)
    rows = {r[0]: r for r in table.rows}
    # the mapped loads add up to the slices' forces (the target row is judged, and met)
    assert rows["128k: face loads against slice forces"][3] == "met"
    assert float(rows["128k: face loads against slice forces"][1]) < 1e-3
