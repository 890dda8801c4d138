"""Parameter sweeps on a real Dask cluster (2 worker processes, 1 thread each).

Every value is compared with the reference it must equal exactly: the same case run alone,
by ``hullslice.simulate`` or by ``hullslice simulate`` on the command line.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import hullslice as hs
from hullslice.cli import main
from hullslice.xarray_io import read_dataset

distributed = pytest.importorskip("distributed")

ROOT = Path(__file__).resolve().parents[1]
WEDGE = ROOT / "meshes" / "wedge_prism.stl"
PAPER = ROOT / "meshes" / "paper_prism.stl"

# a 1 m prism of 30-degree wedge section dropped at 3 or 4 m/s, 8 slices, 10 steps
BASE = {"mesh": str(WEDGE), "mass": 10.0, "velocity": -4.0, "t_end": 0.01, "dt": 0.001,
        "slices": 8}  # fmt: skip
GRID = {"velocity": [-3.0, -4.0], "mass": [8.0, 12.0]}


@pytest.fixture(scope="module")
def client():
    """A local cluster of two worker processes, one thread each (the workers import this
    tree's hullslice through the inherited environment)."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), *filter(None, [env.get("PYTHONPATH")])])
    with (
        distributed.LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            env={"PYTHONPATH": env["PYTHONPATH"]},
        ) as cluster,
        distributed.Client(cluster) as c,
    ):
        yield c


def single(velocity: float, mass: float, **kw) -> hs.History:
    """The reference: one case run alone, as ``hullslice simulate`` runs it."""
    hull = hs.load_hull(WEDGE, mass=mass)
    return hs.simulate(hull, velocity, 0.01, dt=0.001, slices=8, **kw)


def write_case(tmp: Path, grid: str, base: dict | None = None, name: str = "case.toml") -> Path:
    lines = [f"{k} = {json.dumps(v)}" for k, v in (base or BASE).items()]
    path = tmp / name
    path.write_text("\n".join([*lines, "", "[sweep]", grid, ""]), encoding="utf-8")
    return path


def test_a_sweep_on_a_cluster_equals_single_runs_exactly(client):
    ds = hs.sweep(BASE, GRID, client=client)
    assert ds["peak_force"].dims == ("velocity", "mass")
    assert ds.sizes == {"velocity": 2, "mass": 2}
    for v in GRID["velocity"]:
        for m in GRID["mass"]:
            ref = single(v, m)
            point = ds.sel(velocity=v, mass=m)
            assert point["error"].item() == ""
            assert point["peak_force"].item() == ref.peak["force"]
            assert point["peak_time"].item() == ref.peak["t"]
            assert point["peak_acceleration"].item() == float(np.max(ref.acceleration))
            assert point["final_velocity"].item() == float(ref.velocity[-1])
            assert point["final_draft"].item() == float(ref.draft[-1])
            assert point["stop_reason"].item() == ref.stop_reason
            assert point["steps"].item() == len(ref)
            share = getattr(ref, "flagged_share", None)
            share = 1.0 - ref.valid_share if share is None else share
            assert point["max_flagged_share"].item() == float(np.max(share))
    # units and provenance
    assert ds["peak_force"].attrs["units"] == "N"
    assert ds["peak_acceleration"].attrs["units"] == "m s-2"
    assert ds["peak_moment"].attrs["units"] == "N m"
    assert ds["velocity"].attrs["units"] == "m s-1" and ds["mass"].attrs["units"] == "kg"
    assert ds.attrs["mesh_sha256"] == hashlib.sha256(WEDGE.read_bytes()).hexdigest()
    assert ds.attrs["hullslice_version"] == hs.__version__
    assert ds.attrs["solver"] == "extended-von-karman"
    assert json.loads(ds.attrs["solver_options"]) == {"froude_min": 6.5}
    assert json.loads(ds.attrs["base_case"])["mass"] == 10.0
    assert ds.attrs["created"].startswith("20")


def test_the_command_line_sweep_equals_the_command_line_simulate(client, tmp_path, capsys):
    """One case of a sweep against `hullslice simulate` of the same case, through the CLI;
    the sweep goes to the running cluster by its address."""
    case = write_case(tmp_path, "pitch = [0.0, 3.0]\nforward_speed = [2.0]")
    out = tmp_path / "out.nc"
    address = client.scheduler.address
    assert main(["sweep", str(case), "-o", str(out), "--scheduler", address]) == 0
    assert not Path(str(out) + ".partial").exists()
    ds = read_dataset(out)
    assert main(["simulate", str(WEDGE), "--mass", "10", "--velocity=-4", "--t-end", "0.01",
                 "--dt", "0.001", "--slices", "8", "--pitch", "3", "--forward-speed", "2",
                 "--format", "json"]) == 0  # fmt: skip
    ref = json.loads(capsys.readouterr().out)
    point = ds.sel(pitch=3.0, forward_speed=2.0)
    assert point["peak_force"].item() == ref["peak"]["force"]
    assert point["peak_moment_time"].item() >= 0.0
    assert point["final_pitch_deg"].item() == ref["history"]["pitch_deg"][-1]
    assert point["stop_reason"].item() == ref["stop_reason"]


def test_a_failing_case_is_recorded_and_the_others_complete(client):
    # at 60 m/s a 1 ms step moves the prism 0.06 m, more than a tenth of its height: refused
    ds = hs.sweep(BASE, {"velocity": [-4.0, -60.0], "mass": [12.0]}, client=client)
    error = ds["error"].sel(velocity=-60.0, mass=12.0).item()
    assert error.startswith("time step 0.001 s at -60 m/s moves the body")
    assert "\n" not in error
    assert math.isnan(ds["peak_force"].sel(velocity=-60.0, mass=12.0).item())
    assert ds["peak_force"].sel(velocity=-4.0, mass=12.0).item() == single(-4.0, 12.0).peak["force"]
    assert ds.attrs["failed"] == 1


def _kill_once(marker: str) -> None:
    """On a worker: the first case with mass 12 kg that meets ``marker`` kills the process."""
    import hullslice.sweeps.run as sw

    original = getattr(sw.run_case, "original", sw.run_case)

    def run_case(hull, case, inputs=None):
        if case.get("mass") == 12.0 and os.path.exists(marker):
            os.remove(marker)
            os._exit(13)
        return original(hull, case, inputs)

    run_case.original = original
    sw.run_case = run_case


def _restore() -> None:
    import hullslice.sweeps.run as sw

    sw.run_case = getattr(sw.run_case, "original", sw.run_case)


def test_the_cases_of_a_worker_that_dies_are_run_again(client, tmp_path):
    marker = tmp_path / "kill-once"
    marker.write_text("")
    client.run(_kill_once, str(marker))
    try:
        ds = hs.sweep(BASE, GRID, client=client)
    finally:
        client.run(_restore)
    assert not marker.exists()  # a worker did die, on a case with mass 12 kg
    assert (ds["error"] == "").all()
    for v in GRID["velocity"]:
        for m in GRID["mass"]:
            assert ds["peak_force"].sel(velocity=v, mass=m).item() == single(v, m).peak["force"]


class _Stop(Exception):
    pass


def test_an_interrupted_sweep_resumes_to_the_same_dataset(client, tmp_path):
    grid = {"velocity": [-3.0, -3.5, -4.0], "mass": [8.0, 12.0]}
    whole = hs.sweep(BASE, grid, client=client)
    partial = tmp_path / "out.nc.partial"

    def stop_after_two(done, total, failed):
        if done >= 2:
            raise _Stop

    with pytest.raises(_Stop):
        hs.sweep(BASE, grid, client=client, partial=partial, progress=stop_after_two)
    kept = sorted(partial.glob("case-*.json"))
    assert 2 <= len(kept) < 6
    with pytest.raises(hs.InputError, match="give --resume"):
        hs.sweep(BASE, grid, client=client, partial=partial)
    seen = []
    resumed = hs.sweep(
        BASE, grid, client=client, partial=partial, resume=True,
        progress=lambda d, t, f: seen.append(d),
    )  # fmt: skip
    assert seen[0] == len(kept)  # the finished cases were not run again
    for name in ("peak_force", "peak_time", "final_velocity", "stop_reason", "error"):
        assert resumed[name].equals(whole[name]), name


def test_keep_histories_and_the_three_formats(tmp_path):
    """In this process (--workers 1): each format reads back what was computed, and the
    histories along t are the single runs' columns."""
    case = write_case(tmp_path, "mass = [8.0, 12.0]")
    for ext in (".nc", ".zarr"):
        out = tmp_path / f"out{ext}"
        assert main(["sweep", str(case), "-o", str(out), "--workers", "1", "--keep-histories"]) == 0
        ds = read_dataset(out)
        for m in (8.0, 12.0):
            ref = single(-4.0, m)
            h = ds.sel(mass=m)
            n = len(ref)
            assert np.array_equal(h["t"].values[:n], ref.t)
            assert np.array_equal(h["history_force"].values[:n], ref.force)
            assert np.isnan(h["history_force"].values[n:]).all()
            assert h["peak_force"].item() == ref.peak["force"]
        assert ds["history_force"].attrs["units"] == "N"
    pd = pytest.importorskip("pandas")
    out = tmp_path / "out.parquet"
    assert main(["sweep", str(case), "-o", str(out), "--workers", "1"]) == 0
    df = pd.read_parquet(out)
    assert list(df["mass"]) == [8.0, 12.0]
    assert list(df["peak_force"]) == [single(-4.0, m).peak["force"] for m in (8.0, 12.0)]
    import pyarrow.parquet as pq

    meta = json.loads(pq.read_schema(out).metadata[b"hullslice"])
    assert meta["variables"]["peak_force"]["units"] == "N"
    assert meta["attrs"]["mesh_sha256"] == hashlib.sha256(WEDGE.read_bytes()).hexdigest()


def test_a_table_of_cases(tmp_path):
    (tmp_path / "doe.csv").write_text("velocity,mass\n-3.0,8.0\n-4.0,12.0\n-3.5,10.0\n")
    case = write_case(tmp_path, 'cases = "doe.csv"')
    ds = hs.sweep(case, workers=1)
    assert ds["peak_force"].dims == ("case",)
    assert list(ds["mass"].values) == [8.0, 12.0, 10.0]
    for i, (v, m) in enumerate([(-3.0, 8.0), (-4.0, 12.0), (-3.5, 10.0)]):
        assert ds["peak_force"].isel(case=i).item() == single(v, m).peak["force"]


@pytest.mark.slow
def test_a_killed_command_line_sweep_resumes(tmp_path):
    """The sweep's process is killed (SIGKILL) after some cases; --resume completes it to
    the dataset of a run that was never killed."""
    base = {"mesh": str(PAPER), "mass": 1.0, "velocity": -4.0, "t_end": 0.03, "dt": 2e-4,
            "slices": 16}  # fmt: skip
    case = write_case(tmp_path, "velocity = [-3.0, -3.5, -4.0, -4.5, -5.0, -5.5]", base)
    out = tmp_path / "out.nc"
    partial = Path(str(out) + ".partial")
    path = os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])
    env = dict(os.environ, PYTHONPATH=path)
    proc = subprocess.Popen(
        [sys.executable, "-m", "hullslice", "sweep", str(case), "-o", str(out), "--workers", "1"],
        env=env, stderr=subprocess.DEVNULL,
    )  # fmt: skip
    deadline = time.monotonic() + 60
    while len(list(partial.glob("case-*.json"))) < 2 and proc.poll() is None:
        assert time.monotonic() < deadline
        time.sleep(0.02)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    done = len(list(partial.glob("case-*.json")))
    assert 2 <= done < 6, "the kill came too late to test resuming"
    assert not out.exists()  # -o is written completely or not at all
    assert main(["sweep", str(case), "-o", str(out), "--workers", "1", "--resume"]) == 0
    assert not partial.exists()
    resumed = read_dataset(out)
    fresh = tmp_path / "fresh.nc"
    assert main(["sweep", str(case), "-o", str(fresh), "--workers", "1"]) == 0
    whole = read_dataset(fresh)
    assert set(resumed.data_vars) == set(whole.data_vars)
    for name in whole.data_vars:
        if name != "runtime":  # the computing time, which is never the same twice
            assert resumed[name].equals(whole[name]), name


def test_with_the_fixed_slicing_a_worker_reuses_its_cuts_to_rounding(client):
    """The fixed slicing's cuts are kept on the worker's hull from case to case; they agree
    with a fresh hull's to rounding (the reference: each case alone on a fresh hull)."""
    base = {**BASE, "slicing": "fixed", "forward_speed": 3.0, "continue_invalid": True}
    grid = {"pitch": [1.0, 2.0, 3.0], "velocity": [-3.0, -4.0]}
    ds = hs.sweep(base, grid, client=client)
    for p in grid["pitch"]:
        for v in grid["velocity"]:
            hull = hs.load_hull(WEDGE, mass=10.0)
            ref = hs.simulate(hull, v, 0.01, dt=0.001, slices=8, slicing="fixed",
                              pitch_rad=math.radians(p), forward_speed=3.0, stop_on=())  # fmt: skip
            got = ds.sel(pitch=p, velocity=v)
            assert got["peak_force"].item() == pytest.approx(ref.peak["force"], rel=1e-12)
            assert got["final_velocity"].item() == pytest.approx(ref.velocity[-1], rel=1e-12)
            assert got["steps"].item() == len(ref) == 11
    # the workers kept their hull of this mesh, and on it the frames (and cuts) of the
    # pitches (besides those of earlier sweeps of the same hull on the same cluster)
    kept = client.run(_pitches_kept, ds.attrs["mesh_sha256"])
    assert set().union(*kept.values()) >= {round(math.radians(p), 12) for p in grid["pitch"]}


def _pitches_kept(sha: str) -> list[float]:
    """On a worker: the pitches (rad) whose frames its 10 kg hull of the mesh ``sha`` keeps."""
    import hullslice.sweeps as sw

    shared = [h for token, h in sw._SHARED.items() if token.startswith(sha)]
    assert len(shared) <= 1  # the mesh is kept once, whatever copies Dask handed over
    hulls = [h for base, _, h in sw._HULLS.values() if base in shared and h.mass == 10.0]
    from hullslice.geometry import FRAMES

    return sorted(round(p, 12) for h in hulls for p in h.cache[FRAMES])


KILLER = '''
import os

import numpy as np

from hullslice import SectionLoads, Solver


class Killer(Solver):
    """test: kills its process on sections heavier than 10 kg/m, else f = 3 M g"""

    name = "killer"
    description = "test: kills its process on sections heavier than 10 kg/m"

    def section_loads(self, sections, velocity, fluid):
        if sections.mass_per_metre.max() > 10.0:
            os._exit(13)
        n = len(sections)
        return SectionLoads(
            sections.mass_per_metre * 3.0 * fluid.g,
            np.ones(n, dtype=bool),
            np.full(n, "", dtype=object),
        )
'''


@pytest.fixture
def killer_solver(tmp_path, monkeypatch):
    """The solver 'killer', installed by hand (a dist-info folder on sys.path, which worker
    processes inherit)."""
    import importlib

    from hullslice.solvers import registry

    root = tmp_path / "killer"
    info = root / "hullslice_killer-1.0.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: hullslice-killer\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text("[hullslice.solvers]\nkiller = killer_solver:Killer\n")
    (root / "killer_solver.py").write_text(KILLER)
    monkeypatch.syspath_prepend(str(root))
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([str(root), str(ROOT)]))
    importlib.invalidate_caches()
    registry.refresh()
    yield
    sys.modules.pop("killer_solver", None)
    registry.refresh()


@pytest.mark.slow
def test_a_case_that_kills_its_worker_every_time_is_recorded(killer_solver):
    """The case of 12 kg kills its worker process whenever it runs: Dask gives up on it and
    it is recorded as failed; the case of 8 kg completes."""
    dask = pytest.importorskip("dask")
    base = {**BASE, "solver": "killer", "continue_invalid": True}
    with (
        dask.config.set({"distributed.scheduler.allowed-failures": 0}),
        distributed.LocalCluster(
            n_workers=1, threads_per_worker=1, processes=True, dashboard_address=":0"
        ) as cluster,
        distributed.Client(cluster) as c,
    ):
        ds = hs.sweep(base, {"mass": [8.0, 12.0]}, client=c)
    error = ds["error"].sel(mass=12.0).item()
    assert error.startswith("the worker running this case stopped (KilledWorker")
    assert math.isnan(ds["peak_force"].sel(mass=12.0).item())
    hull = hs.load_hull(WEDGE, mass=8.0)
    ref = hs.simulate(hull, -4.0, 0.01, dt=0.001, slices=8, solver="killer", stop_on=())
    assert ds["error"].sel(mass=8.0).item() == ""
    assert ds["peak_force"].sel(mass=8.0).item() == ref.peak["force"]
