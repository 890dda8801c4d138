"""Sweep throughput: cases per second on 1 and 2 Dask workers, and the cost per case beyond
the simulation itself.

    python benchmarks/sweep.py [--t-end 0.05,0.2] [--repeat 1] [--free-pitch]

The sweep: the 1:10 model fuselage (``meshes/fuselage_model.obj``, 128k faces, 60 kg) at
19 m/s forward, its pitch held (not free), with the fixed slicing (32 slices, cut once per
pitch), 8 sink rates by 8 pitches = 64 cases of ``--t-end`` seconds at 1 ms steps, each run
to its end (``continue_invalid``); by default twice, with short cases (0.05 s, 50 steps: the
sweep's fixed costs weigh) and with cases of a ditching's length (0.2 s, 200 steps). With
``--free-pitch`` the same grid with free pitch: the 8 pitches are the initial ones, and
every stage of every step is cut afresh at its own pitch (about 5 ms a stage on this mesh,
against about 0.3 ms at a held pitch). It runs in this process (``workers=1``, no Dask),
then on a local cluster of 1 and of 2 worker processes (1 thread each), made as
``hullslice.sweep`` makes its own (``hullslice.sweeps.engine.local_client``); the cluster's
start is timed apart.
For each: the wall time of ``hullslice.sweep`` (the mesh read and checked, the hull sent to
the workers as its state and built by each, the cases, the dataset), the cases per second,
and the overhead per case, ``(wall time x workers - the cases' own computing time) /
cases``: what the sweep adds to the simulations (the scheduler, the workers' hulls, the
results, idle workers at the end). Targets: 2 workers at least 1.7 times as fast as 1; overhead
below 50 ms a case. The machine may be shared: its load average is printed with the
figures.

``benchmarks/run.py`` calls :func:`throughput` for its free-pitch sweep rows.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from pathlib import Path

import hullslice as hs

ROOT = Path(__file__).resolve().parents[1]
MESH = ROOT / "meshes" / "fuselage_model.obj"

VELOCITIES = [-0.5, -0.75, -1.0, -1.25, -1.5, -1.75, -2.0, -2.25]  # m/s
PITCHES = [2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]  # deg
CASES = len(VELOCITIES) * len(PITCHES)
IN_PROCESS = "in this process"


def study(t_end: float, free_pitch: bool = False) -> tuple[dict, dict]:
    """The sweep's base case and grid: cases of ``t_end`` s at 1 ms steps, the pitch held
    or (``free_pitch``) free from its initial value."""
    held = "free from its initial value" if free_pitch else "at a held pitch"
    base = {
        "title": f"1:10 fuselage, 64 ditching cases {held}",
        "mesh": str(MESH),
        "mass": 60.0,
        "velocity": -1.5,
        "forward_speed": 19.0,
        "t_end": t_end,
        "dt": 0.001,
        "slices": 32,
        "slicing": "fixed",
        "continue_invalid": True,
    }
    if free_pitch:
        base["free_pitch"] = True
    return base, {"velocity": VELOCITIES, "pitch": PITCHES}


def measure(base, grid, client=None, workers=None) -> dict:
    """One sweep's wall time (s), cases per second, computing time (s), overhead per case
    (s) and peak forces (N)."""
    start = time.perf_counter()
    ds = hs.sweep(base, grid, client=client, workers=workers)
    wall = time.perf_counter() - start
    n = int(ds.attrs["cases"])
    assert int(ds.attrs["failed"]) == 0, ds["error"].values
    compute = float(ds["runtime"].sum())
    k = workers or len(client.scheduler_info()["workers"])
    return {
        "wall": wall,
        "rate": n / wall,
        "compute": compute,
        "overhead": (wall * k - compute) / n,
        "peak": ds["peak_force"].values.copy(),
    }


def settings(
    t_end: float,
    repeat: int = 1,
    free_pitch: bool = False,
    in_process: bool = True,
    grid: dict | None = None,
) -> list[tuple[str, int, float | None, list[dict]]]:
    """The sweep measured ``repeat`` times in this process (unless ``in_process`` is
    False) and on a local Dask cluster of 1 and of 2 workers: rows of (setting, workers,
    the cluster's start in s or None, the runs' :func:`measure` figures). ``grid``, when
    given, replaces the study's 8 sink rates by 8 pitches."""
    from hullslice.sweeps.engine import local_client

    base, own_grid = study(t_end, free_pitch)
    grid = own_grid if grid is None else grid
    rows: list[tuple[str, int, float | None, list[dict]]] = []
    if in_process:
        runs = [measure(base, grid, workers=1) for _ in range(repeat)]
        rows.append((IN_PROCESS, 1, None, runs))
    for n in (1, 2):
        t0 = time.perf_counter()
        client = local_client(n)  # the cluster hullslice.sweep starts for workers=n
        try:
            startup = time.perf_counter() - t0
            runs = [measure(base, grid, client=client) for _ in range(repeat)]
        finally:
            client.close()
            client.cluster.close()
        rows.append((workers_name(n), n, startup, runs))
    return rows


def workers_name(n: int) -> str:
    return f"Dask, {n} worker{'s' * (n > 1)}"


def throughput(
    t_end: float, repeat: int = 1, free_pitch: bool = True, in_process: bool = True
) -> dict[str, float]:
    """Cases per second of the 64-case sweep (median of ``repeat`` sweeps) by setting:
    ``"in this process"`` (unless ``in_process`` is False), ``"Dask, 1 worker"``,
    ``"Dask, 2 workers"``; and ``"peak difference"``, the largest relative difference of a
    peak force between settings."""
    rows = settings(t_end, repeat, free_pitch, in_process)
    rates = {name: statistics.median(r["rate"] for r in runs) for name, _, _, runs in rows}
    rates["peak difference"] = peak_difference(rows)
    return rates


def peak_difference(rows) -> float:
    """The largest relative difference of a peak force between the settings' sweeps."""
    ref = rows[0][3][0]["peak"]
    return max(float(abs(r["peak"] / ref - 1).max()) for row in rows for r in row[3])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument(
        "--t-end",
        type=lambda text: [float(v) for v in text.split(",")],
        default=[0.05, 0.2],
        help="duration of each case, s; several, comma-separated, for one sweep each "
        "(default 0.05,0.2)",
    )
    ap.add_argument("--repeat", type=int, default=1, help="sweeps per setting (median)")
    ap.add_argument(
        "--free-pitch",
        action="store_true",
        help="integrate the pitch from its initial value (2 to 9 deg) in every case "
        "(default: held); about 5 times the cost of a held pitch a case",
    )
    args = ap.parse_args()
    for t_end in args.t_end:
        run_sweeps(t_end, args.repeat, args.free_pitch)
        print()


def run_sweeps(t_end: float, repeat: int, free_pitch: bool = False) -> None:
    t0 = time.perf_counter()
    hs.load_hull(MESH, mass=60.0)
    load = time.perf_counter() - t0
    pitch = "free pitch" if free_pitch else "held pitch"
    print(f"sweep of {CASES} cases: {MESH.name}, {t_end:g} s at 1 ms, {pitch}, fixed "
          f"slicing, 32 slices; load average {os.getloadavg()[0]:.2f} "
          f"on {os.cpu_count()} cores")  # fmt: skip
    rows = settings(t_end, repeat, free_pitch)
    diff = peak_difference(rows)
    print()
    print(f"{'setting':<18} {'start [s]':>9} {'wall [s]':>9} {'cases/s':>8} "
          f"{'compute [s]':>11} {'overhead [ms/case]':>18}")  # fmt: skip
    medians = {}
    for name, _, startup, runs in rows:
        wall = statistics.median(r["wall"] for r in runs)
        rate = statistics.median(r["rate"] for r in runs)
        compute = statistics.median(r["compute"] for r in runs)
        over = statistics.median(r["overhead"] for r in runs)
        medians[name] = rate
        start = "" if startup is None else f"{startup:.2f}"
        print(f"{name:<18} {start:>9} {wall:>9.2f} {rate:>8.2f} {compute:>11.2f} "
              f"{over * 1e3:>18.1f}")  # fmt: skip
    speedup = medians[workers_name(2)] / medians[workers_name(1)]
    print()
    print(f"reading and checking the mesh, once in each sweep's wall time: {load:.2f} s "
          f"({load / CASES * 1e3:.1f} ms a case of this sweep)")  # fmt: skip
    print(f"2 workers / 1 worker: {speedup:.2f} x (target >= 1.7 x)")
    # a worker reuses the cuts of its earlier cases: the fixed slicing's kept cuts agree
    # with fresh ones to rounding, so the order of the cases shows in the last bits
    print(f"largest relative difference of a peak force between settings: {diff:.1e}")
    assert diff <= 1e-9, "the settings disagree beyond rounding"
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
