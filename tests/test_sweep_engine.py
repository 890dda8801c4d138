"""How a sweep's cases are grouped into tasks, and how a worker gets its hull."""

from __future__ import annotations

import contextlib
import json
import re
import socket
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import hullslice as hs
from hullslice.sweeps import HullState, groups, make_plan, run_batch

ROOT = Path(__file__).resolve().parents[1]
WEDGE = ROOT / "meshes" / "wedge_prism.stl"

BASE = {"mesh": str(WEDGE), "mass": 10.0, "velocity": -4.0, "t_end": 0.01, "dt": 0.001,
        "slices": 8, "forward_speed": 2.0, "slicing": "fixed"}  # fmt: skip


def _key(plan, i):
    case = plan.case(i)
    return case["mass"], case.get("pitch", 0.0)


def test_cases_of_one_pitch_stay_together_and_the_last_tasks_are_small():
    plan = make_plan(BASE, {"pitch": [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0],
                            "velocity": [-1.0, -2.0, -3.0, -4.0]})  # fmt: skip
    tasks = groups(plan, list(range(32)), 2)
    assert sorted(i for t in tasks for i in t) == list(range(32))
    # every task is of one pitch and mass: 6 whole pitches, then 2 pitches a case a task
    assert all(len({_key(plan, i) for i in t}) == 1 for t in tasks)
    assert [len(t) for t in tasks] == [4] * 6 + [1] * 8
    # one worker: the same, the last task split
    assert [len(t) for t in groups(plan, list(range(32)), 1)] == [4] * 7 + [1] * 4


class _Client:
    """What DaskRun asks of a Dask client, recording each task's cases and priority."""

    def __init__(self):
        self.tasks = []

    def scheduler_info(self):
        return {"workers": {"a": {}, "b": {}}}

    def submit(self, fn, *args, pure=True, retries=0, priority=0):
        if fn is run_batch:
            self.tasks.append(([i for i, _ in args[1]], priority))
        return object()


def test_the_tasks_go_to_dask_with_priorities_in_their_order():
    # Dask hands out the waiting task of the highest priority first; without priorities it
    # does not keep the order they were submitted in, and a large task could come last
    from hullslice.sweeps.engine import DaskRun

    plan = make_plan(BASE, {"pitch": [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0],
                            "velocity": [-1.0, -2.0, -3.0, -4.0]})  # fmt: skip
    client = _Client()
    DaskRun(client, plan, list(range(32)), {}, False, "t", None)
    assert [cases for cases, _ in client.tasks] == groups(plan, list(range(32)), 2)
    priorities = [p for _, p in client.tasks]
    assert priorities == sorted(priorities, reverse=True) and len(set(priorities)) == 14


def test_too_few_pitches_are_split_to_give_every_worker_tasks():
    plan = make_plan(BASE, {"velocity": [-1.0 - 0.1 * k for k in range(40)]})
    tasks = groups(plan, list(range(40)), 2)
    assert sorted(i for t in tasks for i in t) == list(range(40))
    assert len(tasks) >= 8 and max(len(t) for t in tasks) <= 16


def test_a_hull_built_from_its_state_computes_the_same():
    hull = hs.load_hull(WEDGE)
    plan = make_plan(BASE, {"mass": [10.0]})
    items = [(0, plan.case(0))]
    ref = run_batch(hull, items, {}, False)[0][1]
    got = run_batch(HullState(hull), items, {}, False, token="test-state")[0][1]
    assert got["error"] == ""
    assert got["peak_force"] == ref["peak_force"]
    assert got["final_velocity"] == ref["final_velocity"]


class _Unbuildable:
    def build(self):
        raise hs.InputError("this hull cannot be built")


def test_a_hull_that_cannot_be_built_fails_the_cases_by_name(monkeypatch):
    from hullslice.sweeps import run as sweep_run

    monkeypatch.setattr(sweep_run, "HullState", _Unbuildable)
    plan = make_plan(BASE, {"mass": [8.0, 12.0]})
    out = run_batch(_Unbuildable(), [(0, plan.case(0)), (1, plan.case(1))], {}, False, "none")
    assert [i for i, _ in out] == [0, 1]
    assert all(r["error"] == "this hull cannot be built" for _, r in out)


def _counting_reads(monkeypatch) -> list:
    """Every mesh a sweep reads from its file, by path."""
    import hullslice.mesh

    reads: list = []
    load = hullslice.mesh.load_hull

    def counted(path, **kw):
        reads.append(Path(path).name)
        return load(path, **kw)

    monkeypatch.setattr(hullslice.mesh, "load_hull", counted)
    return reads


def _nothing_kept(monkeypatch) -> None:
    """This process's kept hulls, as at its start (other tests keep the catalogued ones)."""
    from hullslice.sweeps import run as sweep_run

    monkeypatch.setattr(sweep_run, "_SHARED", {})
    monkeypatch.setattr(sweep_run, "_READ_WARNINGS", {})


def test_a_second_sweep_of_the_same_file_does_not_read_it_again(monkeypatch, tmp_path):
    # the process keeps the hull under the file's SHA-256, path and shaping, as a worker
    _nothing_kept(monkeypatch)
    reads = _counting_reads(monkeypatch)
    mesh = tmp_path / "hull.stl"
    mesh.write_bytes(WEDGE.read_bytes())
    base = {**BASE, "mesh": str(mesh)}
    first = hs.sweep(base, {"mass": [8.0, 12.0]}, workers=1)
    again = hs.sweep(base, {"mass": [8.0, 12.0]}, workers=1)
    assert reads == ["hull.stl"]
    # the same hull, its fixed slicing's cuts kept from the first sweep: equal to rounding
    # (as a worker's, test_with_the_fixed_slicing_a_worker_reuses_its_cuts_to_rounding)
    np.testing.assert_allclose(again["peak_force"].values, first["peak_force"].values, rtol=1e-12)
    # shaped otherwise (scaled): read again, and a larger hull takes a larger load
    scaled = hs.sweep({**base, "scale": 1.5}, {"mass": [8.0, 12.0]}, workers=1)
    assert reads == ["hull.stl"] * 2
    assert (scaled["peak_force"].values > first["peak_force"].values).all()
    # the file changed under the same name (another hull): read again, not the one kept
    hs.Hull(*hs.shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=10.0)).save(mesh)
    changed = hs.sweep(base, {"mass": [8.0, 12.0]}, workers=1)
    assert reads == ["hull.stl"] * 3
    assert (changed["peak_force"].values != first["peak_force"].values).all()
    # the same bytes under another name: a hull of its own (its messages name its file)
    twin = tmp_path / "twin.stl"
    twin.write_bytes(mesh.read_bytes())
    hs.sweep({**base, "mesh": str(twin)}, {"mass": [8.0]}, workers=1)
    assert reads == ["hull.stl"] * 3 + ["twin.stl"]


def test_a_mass_distribution_changed_between_sweeps_is_read_again(monkeypatch, tmp_path):
    # the kept hull's mass properties come from the files as this sweep reads them
    _nothing_kept(monkeypatch)
    line = tmp_path / "mass.csv"
    base = {**BASE, "mass_distribution": str(line)}
    line.write_text("x,mass_per_metre\n0,10\n1,10\n")  # 10 kg, even
    even = hs.sweep(base, {"velocity": [-4.0]}, workers=1)
    line.write_text("x,mass_per_metre\n0,2\n1,18\n")  # 10 kg, aft-heavy
    aft = hs.sweep(base, {"velocity": [-4.0]}, workers=1)
    want = hs.sweep(base, {"velocity": [-4.0]}, workers=1)  # read again, the same
    assert aft["peak_moment"].item() != even["peak_moment"].item()
    assert aft["peak_moment"].item() == pytest.approx(want["peak_moment"].item(), rel=1e-12)


def test_a_kept_hull_shows_its_reading_warnings_again(monkeypatch, tmp_path):
    # a mesh that needed a fix warns once at every sweep, whether it is read or kept, as
    # from where it was given (a filter on its module sees it)
    from .conftest import flipped_wedge_obj

    _nothing_kept(monkeypatch)
    reads = _counting_reads(monkeypatch)
    mesh = flipped_wedge_obj(tmp_path)
    for _ in range(2):
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            hs.sweep({**BASE, "mesh": str(mesh)}, {"velocity": [-3.0]}, workers=1)
        fixed = [w for w in seen if issubclass(w.category, hs.MeshRepairWarning)]
        assert len(fixed) == 1 and "re-oriented 1 faces" in str(fixed[0].message)
    assert reads == ["flipped.obj"]
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        warnings.filterwarnings("ignore", category=hs.MeshRepairWarning, module="hullslice")
        hs.sweep({**BASE, "mesh": str(mesh)}, {"velocity": [-3.0]}, workers=1)
    assert not [w for w in seen if issubclass(w.category, hs.MeshRepairWarning)]


def test_a_sweeps_own_cluster_leaves_the_malloc_threshold_unset(monkeypatch):
    # Dask sets MALLOC_TRIM_THRESHOLD_ in its workers (and in the process that starts
    # them), which doubles the time of a free-pitch case there; the cluster a sweep starts
    # leaves it unset, and Dask's settings and this process's environment as they were
    import os

    pytest.importorskip("distributed")
    import dask

    from hullslice.sweeps import engine

    before = dict(dask.config.get("distributed.nanny.pre-spawn-environ"))
    monkeypatch.setenv("MALLOC_TRIM_THRESHOLD_", "65536")  # as an earlier cluster leaves it
    with engine.session(None, 2, 30.0, True) as client:
        seen = client.run(lambda: os.environ.get("MALLOC_TRIM_THRESHOLD_"))
        threads = client.run(lambda: os.environ.get("OMP_NUM_THREADS"))
        client.restart()  # workers started again (as after a crash) go without it too
        again = client.run(lambda: os.environ.get("MALLOC_TRIM_THRESHOLD_"))
    assert list(seen.values()) == [None, None] and list(again.values()) == [None, None]
    assert set(threads.values()) == {str(before["OMP_NUM_THREADS"])}
    assert dict(dask.config.get("distributed.nanny.pre-spawn-environ")) == before
    assert os.environ["MALLOC_TRIM_THRESHOLD_"] == "65536"


def _profiled(dask_worker) -> tuple[bool, bool]:
    """A worker's setting of Dask's statistical profiler, and whether its callbacks run."""
    import dask

    return (
        bool(dask.config.get("distributed.worker.profile.enabled")),
        "profile" in dask_worker.periodic_callbacks,
    )


def test_a_sweeps_own_cluster_runs_its_workers_without_the_profiler():
    # Dask's workers sample every thread's stack every 10 ms for a dashboard; a sweep's
    # cluster has none, and a free-pitch case took a tenth longer with it
    pytest.importorskip("distributed")
    import dask

    from hullslice.sweeps import engine

    before = dask.config.get("distributed.worker.profile.enabled")
    with engine.session(None, 2, 30.0, True) as client:
        seen = client.run(_profiled)
        client.restart()  # workers started again (as after a crash) go without it too
        again = client.run(_profiled)
    assert list(seen.values()) == [(False, False)] * 2
    assert list(again.values()) == [(False, False)] * 2
    assert dask.config.get("distributed.worker.profile.enabled") == before


@contextlib.contextmanager
def _port_taken(port: int):
    """``port`` on this machine taken for the while (already taken by another program: as
    good)."""
    s = socket.socket()
    try:
        s.bind(("", port))
        s.listen()
    except OSError:
        pass
    try:
        yield
    finally:
        s.close()


def test_a_taken_dashboard_port_is_no_warning_and_the_sweep_runs(tmp_path):
    """With Dask's port 8787 taken, a sweep's cluster takes a free one without a word: no
    line on stderr, and the results of the cluster are those of this process."""
    pytest.importorskip("distributed")
    from hullslice.sweeps import engine

    case = tmp_path / "case.toml"
    case.write_text(
        "\n".join(f"{k} = {json.dumps(v)}" for k, v in BASE.items())
        + "\n\n[sweep]\nmass = [8.0, 12.0]\n",
        encoding="utf-8",
    )
    with _port_taken(8787):
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            client = engine.local_client(1)
        try:
            http = client.cluster.scheduler.http_server
            host, port = http.address, http.port
            assert host == "127.0.0.1" and port != 8787
        finally:
            client.close()
            client.cluster.close()
        assert [str(w.message) for w in seen if issubclass(w.category, UserWarning)] == []
        done = subprocess.run(
            [sys.executable, "-m", "hullslice", "sweep", str(case), "--workers", "2"],
            capture_output=True,
            text=True,
            timeout=300,
        )
    # manifold3d 3.4 (the floor) has its bindings report the objects still alive when a
    # worker process exits ("nanobind: leaked ..."): the library's own exit report, not a
    # warning of the sweep; everything else on stderr is
    said = re.sub(r"nanobind: leaked .*?refleaks\.html\n?", "", done.stderr, flags=re.DOTALL)
    assert done.returncode == 0 and said == "", done.stderr
    reference = hs.sweep(BASE, {"mass": [8.0, 12.0]}, workers=1)
    rows = done.stdout.splitlines()[2:]
    peaks = [float(row.split()[1]) for row in rows]
    assert peaks == pytest.approx(reference["peak_force"].values, rel=1e-3)  # 4 digits shown
