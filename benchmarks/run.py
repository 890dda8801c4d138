"""hullslice's benchmark suite: one command, a table of measured figures against targets.

    python benchmarks/run.py [--quick] [--repeat 5] [--no-sweep] [--envelope]

Meshes: the generic fuselage of ``hullslice.shapes`` at about 10k, 100k and 1M faces
(``--quick`` stops at 100k). For each: the time to load it from a file; the time to cut
it at 200 stations with the sections' properties, against manifold3d's own 200 ``slice``
calls and trimesh's ``section_multiplane`` on the same planes; the cost of one force
evaluation (a stage of a time step) with 128 slices at a fixed pitch, with the fixed
slicing cut once (cached, with its waterline table) against re-cutting the 3D hull at
every step (naive); the cost of an evaluation at a new pitch (the cut must be redone),
once the hull has its first region, and the cost of making that region. Then: the cached
cost against the slice count (32 to 512), whole free falls of 100 to 10,000 steps, a
2,000-step free fall of the 1M-face fuselage in a process of its own (time, time over
its steps with its first frame and cut, peak memory), the face pressures of a saved
instant and its ``.vtu`` file at 128k and 1M faces (time, peak memory), the paper's
free-fall case from process start to printed report, and the time of ``import
hullslice`` and ``hullslice --help``.

Free pitch: the time step with free pitch (each of its 4 stages at a new pitch, cut
afresh by manifold3d on the turned mesh, and by the exact kernel of
``hullslice.planecut``) against the same run at a held pitch, 100 steps of 0.2 ms each
with 128 fixed slices, at 10k, 128k (in this process) and 1M faces (in the 1M free fall's
process), the runs interleaved (A B C D E A B C D E; the held run by numpy's path and, with
the ``fast`` extra, by the fused evaluation compiled by numba; the kernel with numpy's
loops and numba's) after a warm-up (the held runs over all their steps, cut once; each
free run over 5 steps: the hull's first region, its plane index, numba's compilation);
target free / held <= 3 with numpy alone, <= 2 compiled (compiled free over compiled
held). The 1M process's held RK4 step (target 0.5 ms) is the median step of its compiled
held run (numpy's without numba). The kernel's
force at 40 random new poses of the 128k fuselage against manifold3d's cut (target 1e-9
relative), and a 100-step free-pitch history by the kernel against a manifold3d-only run
(the largest force difference over the peak force). What the approximations cost
against fresh cuts: the held pitch's kept cut and waterline table against fresh cuts over
20 drafts of the 128k fuselage (largest difference of the force, the horizontal force and
the moment / body size, relative to the force); free pitch has none (every stage is cut
afresh), and the fresh cut's own resolution is shown: the largest relative change of the
force from one pitch to the next, 1e-10 rad apart, over 10 such steps (the 1:10 model
``meshes/fuselage_model.obj``, 32 fixed slices, draft 0.012 m, pitch 6 deg, 19 m/s
forward, 1 m/s down), next to the force's own change over that step. A real airliner's
ditching with its nacelles wet (``meshes/airliner``): its time step at a held and a free
pitch, compiled and by numpy's path, interleaved. Unless ``--quick``
or ``--no-sweep``: the 64-case free-pitch sweep of ``benchmarks/sweep.py`` (cases of
0.03 s at 1 ms, 2 to 3 minutes) in this process and on 1 and 2 Dask workers, cases per
second, the median of 3 sweeps each, target 2 / 1 workers >= 1.7 (it needs the ``sweep``
extra); and the envelope
study's case (the 1:10 model, free pitch, 0.5 s at 1 ms, 32 fixed slices): its time in
this process, 24 such cases on 1 and 2 Dask workers once each worker has started, the two
clusters alternated over 3 rounds (target: the median ratio 2 / 1 >= 1.7), and 1,000 of
them on two workers: their start, then that rate (target under 10 minutes), about 5
minutes in all (``--envelope`` runs this part alone).

Times are medians of ``--repeat`` runs on this machine (the 1M process and the sweep run
once); ratios compare figures measured in the same run.
"""

from __future__ import annotations

import argparse
import gc
import importlib.util
import os
import statistics
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

import numpy as np

import hullslice as hs
from hullslice import planecut_loops, shapes
from hullslice.forces import solve_accelerations
from hullslice.geometry import frame
from hullslice.motion import ForceModel
from hullslice.regions import REGIONS

ROOT = Path(__file__).resolve().parents[1]
# stations, points; 128k only for the time step at a held and at a free pitch
SIZES = {"10k": (63, 80), "100k": (313, 160), "128k": (400, 160), "1M": (1563, 320)}
#: the pitch-step comparison: steps of each timed run (0.02 s at 0.2 ms), steps of warm-up
PITCH_STEPS, WARM_STEPS = 100, 5
#: the 64-case free-pitch sweep's case length, s (at 1 ms steps)
SWEEP_T_END = 0.03


def median_time(fn, repeat: int) -> float:
    gc.collect()  # no garbage of an earlier measurement collected during this one
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def per_call(fn, calls: int, repeat: int) -> float:
    """Median over ``repeat`` runs of the mean time of ``calls`` calls of ``fn(i)``."""

    def run():
        for i in range(calls):
            fn(i)

    return median_time(run, repeat) / calls


def fmt(seconds: float) -> str:
    if seconds < 1e-3:
        return f"{seconds * 1e6:.0f} us"
    if seconds < 1.0:
        return f"{seconds * 1e3:.2f} ms"
    return f"{seconds:.2f} s"


class Table:
    def __init__(self) -> None:
        self.rows: list[tuple[str, str, str, str]] = []

    def add(self, what: str, value: str, target: str = "", ok: bool | None = None) -> None:
        verdict = "" if ok is None else ("met" if ok else "NOT MET")
        self.rows.append((what, value, target, verdict))
        print(f"  {what}: {value}" + (f"  (target {target}: {verdict})" if target else ""))

    def show(self) -> None:
        heads = ("measure", "value", "target", "")
        widths = [max(len(r[i]) for r in [heads, *self.rows]) for i in range(4)]
        line = "  ".join(h.ljust(w) for h, w in zip(heads, widths, strict=True))
        print("\n" + line.rstrip())
        print("  ".join("-" * w for w in widths))
        for r in self.rows:
            print("  ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)).rstrip())


def fuselage_file(tmp: Path, size: str) -> Path:
    """The fuselage as a binary STL (written here: trimesh stays out of this process)."""
    stations, points = SIZES[size]
    v, f = shapes.fuselage(stations=stations, points=points)
    tri = v[f].astype(np.float32)
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normal /= np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-30)
    facet = np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    data = np.zeros(len(f), dtype=facet)
    data["n"], data["v"] = normal, tri
    path = tmp / f"fuselage_{size}.stl"
    with path.open("wb") as fh:
        fh.write(b"hullslice benchmark fuselage".ljust(80, b" "))
        fh.write(np.uint32(len(f)).tobytes())
        fh.write(data.tobytes())
    return path


def bench_mesh(table: Table, tmp: Path, size: str, repeat: int) -> dict:
    path = fuselage_file(tmp, size)
    t_load = median_time(lambda: hs.load_hull(path, mass=60000.0), max(1, repeat // 2))
    hull = hs.load_hull(path, mass=60000.0)
    faces = len(hull.faces)
    table.add(f"{size} ({faces} faces): load from STL", fmt(t_load))

    # cutting at 200 stations with their properties, against manifold3d's own 200 slice
    # calls and trimesh's section_multiplane on the same planes
    xs = np.linspace(hull.bounds[0, 0], hull.bounds[1, 0], 202)[1:-1]
    draft = float(hull.extents[2])
    hs.cut(hull, draft, stations=xs)
    t_cut = median_time(lambda: hs.cut(hull, draft, stations=xs), repeat)
    fr = frame(hull, 0.0)
    t_raw = median_time(lambda: fr.cut(xs - fr.cg[0]), repeat)
    table.add(f"{size}: cut at 200 stations with their properties", fmt(t_cut))
    table.add(f"{size}: manifold3d's own 200 slice calls", fmt(t_raw))
    table.add(f"{size}: ratio cut / manifold3d slices", f"{t_cut / t_raw:.2f}")
    bench_trimesh(table, size, path, hull, t_cut, repeat)

    # one force evaluation, level, 128 slices: cut once against re-cutting every step
    motion = hs.Motion(-1.5, 60.0)
    drafts = np.linspace(0.05, 0.3, 50)
    cached = ForceModel(hull, slices=128, slicing="fixed")
    cached._fused = None  # numpy's path (the fused one is timed below)
    fused = ForceModel(hull, slices=128, slicing="fixed")
    naive = ForceModel(hull, slices=128, slicing="fixed", cache=False)
    for d in drafts:  # its cut, and its waterline table (made from the 8th evaluation)
        cached(hs.Pose(d, 0.08), motion)
        fused(hs.Pose(d, 0.08), motion)
    t_cached = per_call(lambda i: cached(hs.Pose(drafts[i % 50], 0.08), motion), 50, repeat)
    t_fused = per_call(lambda i: fused(hs.Pose(drafts[i % 50], 0.08), motion), 50, repeat)
    t_sums = per_call(lambda i: fused.totals(hs.Pose(drafts[i % 50], 0.08), motion), 50, repeat)
    t_naive = per_call(lambda i: naive(hs.Pose(drafts[i % 50], 0.08), motion), 5, repeat)
    wetted = ForceModel(hull, slices=128)
    t_wetted = per_call(lambda i: wetted(hs.Pose(drafts[i % 50], 0.08), motion), 5, repeat)
    table.add(
        f"{size}: evaluation, fixed pitch, 128 slices, cached (numpy's path)",
        fmt(t_cached),
        "< 1 ms" if size == "1M" else "",
        (t_cached < 1e-3) if size == "1M" else None,
    )
    if fused.fused is None:
        table.add(f"{size}: the same, fused and compiled", 'not run: numba missing (".[fast]")')
    else:
        table.add(f"{size}: the same, fused and compiled (the result)", fmt(t_fused))
        table.add(f"{size}: the same, fused and compiled (its sums only)", fmt(t_sums))

    # the same evaluation with a momentum-form solver, as a stage of a time step: the added
    # mass and its rate, the section accelerations' terms, the body's accelerations solved
    # with the added mass on the left, and the forces formed
    # (the closed form on the equivalent wedge, as the paper's solver; and the same solver
    # with each round section's own contour, Wagner's condition)
    def stage_of(model: ForceModel):
        def stage(i: int) -> None:
            pose = hs.Pose(drafts[i % 50], 0.08)
            terms = model.terms(pose, motion)
            acc = solve_accelerations(terms, 60000.0, None, 9.81, (True, False, False))
            terms.result(acc, model.solver, model.fluid, motion, float(hull.cg[0]))

        for i in range(50):
            stage(i)
        return stage

    wedge = hs.get_solver("wagner", section_method="wedge")
    t_momentum = per_call(
        stage_of(ForceModel(hull, slices=128, solver=wedge, slicing="fixed")), 50, repeat
    )
    table.add(
        f"{size}: the same with the momentum-form wagner solver (a stage, solved)",
        fmt(t_momentum),
    )
    table.add(
        f"{size}: ratio momentum form / free-fall form",
        f"{t_momentum / t_cached:.2f}",
        "<= 1.2",
        t_momentum <= 1.2 * t_cached,
    )
    contour = hs.get_solver("wagner", section_method="contour")
    t_contour = per_call(
        stage_of(ForceModel(hull, slices=128, solver=contour, slicing="fixed")), 10, repeat
    )
    table.add(
        f"{size}: the same, round sections by their contour (Wagner's condition)", fmt(t_contour)
    )
    table.add(f"{size}: same, naive (re-cut the 3D hull every step)", fmt(t_naive))
    table.add(f"{size}: ratio naive / cached", f"{t_naive / t_cached:.0f}")
    table.add(f"{size}: same, slices over the wetted length (re-cut)", fmt(t_wetted))

    # an evaluation at a new pitch: everything that depends on the pitch is redone. A
    # second pitch makes the hull's first region (a band of it, turned at each pitch
    # after); its cost is shown apart, then the steady cost of new pitches
    turning = ForceModel(hull.with_mass(60000.0), slices=128, slicing="fixed")
    turning(hs.Pose(0.1, 0.08), motion)
    t_region = median_time(lambda: turning(hs.Pose(0.1, 0.09), motion), 1)
    pitches = np.radians(np.linspace(6.0, 7.0, 15))
    t_pitch = per_call(lambda i: turning(hs.Pose(0.1, pitches[i % 15] + 1e-7 * i), motion), 15, 1)
    regions = turning.hull.cache[REGIONS]
    band = ", ".join(f"x {a:.1f} to {b:.1f} m" for a, b in regions) or "the whole hull"
    table.add(f"{size}: first evaluation at a second pitch (makes a region: {band})", fmt(t_region))
    table.add(
        f"{size}: evaluation at a new pitch, 128 slices",
        fmt(t_pitch),
        "< 30 ms" if size == "1M" else "",
        (t_pitch < 0.03) if size == "1M" else None,
    )
    table.add(f"{size}: ratio new pitch / cached evaluation", f"{t_pitch / t_cached:.0f}")
    return {"hull": hull, "load": t_load, "path": path}


TRIMESH = textwrap.dedent(
    """
    import statistics, sys, time
    import numpy as np
    import trimesh
    path, x0, x1, repeat = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
    tm = trimesh.load(path, process=False)
    xs = np.linspace(x0, x1, 202)[1:-1]
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        tm.section_multiplane([xs[0], 0.0, 0.0], [1.0, 0.0, 0.0], xs - xs[0])
        times.append(time.perf_counter() - t0)
    print(statistics.median(times))
    """
)


def bench_trimesh(table: Table, size: str, path: Path, hull, t_cut: float, repeat: int) -> None:
    """trimesh's section_multiplane on the same planes, in a process of its own: what it
    leaves behind would slow the measurements that follow (by half, for a million faces)."""
    x0, x1 = (str(float(v)) for v in hull.bounds[:, 0])
    out = subprocess.run(
        [sys.executable, "-c", TRIMESH, str(path), x0, x1, str(repeat)],
        capture_output=True,
        text=True,
        check=True,
    )
    t_tm = float(out.stdout.split()[-1])
    table.add(f"{size}: trimesh section_multiplane, same planes", fmt(t_tm))
    table.add(f"{size}: ratio trimesh / cut", f"{t_tm / t_cut:.1f}")


def bench_slices(table: Table, hull, repeat: int) -> None:
    motion = hs.Motion(-1.5, 60.0)
    for n in (32, 128, 512):
        model = ForceModel(hull, slices=n, slicing="fixed")
        model(hs.Pose(0.1, 0.08), motion)
        t = per_call(lambda i, m=model: m(hs.Pose(0.1 + 1e-4 * (i % 20), 0.08), motion), 40, repeat)
        table.add(f"100k: cached evaluation, {n} slices", fmt(t))


def bench_solvers(table: Table, hull, repeat: int) -> None:
    """One momentum-form evaluation (the solver on every section and the terms of the
    equations of motion) of ``mlm`` against ``zarnick``, interleaved on the same cut: the
    100k-face fuselage at 0.8 m draft, 6 deg, 60 m/s forward, 128 fixed slices."""
    from hullslice.forces import momentum_terms

    sections = hs.cut(hull, hs.Pose(0.8, 0.105), 128, slicing="fixed")
    motion, fluid, x_cg = hs.Motion(-1.5, 60.0), hs.Fluid(), float(hull.cg[0])
    solvers = {name: hs.get_solver(name) for name in ("zarnick", "mlm")}
    times: dict[str, list[float]] = {name: [] for name in solvers}
    for _ in range(repeat):
        for name, solver in solvers.items():

            def once(i: int, s=solver) -> None:
                momentum_terms(sections, motion, s, fluid, x_cg)

            times[name].append(per_call(once, 10, 1))
    t = {name: statistics.median(v) for name, v in times.items()}
    for name in solvers:
        table.add(f"100k: {name} evaluation, 128 fixed slices", fmt(t[name]))
    ratio = t["mlm"] / t["zarnick"]
    table.add("mlm / zarnick evaluation", f"{ratio:.2f}", "at most 2", ratio <= 2.0)


def bench_face_loads(table: Table, results: dict, repeat: int) -> None:
    """The face pressures of one saved instant (:func:`hullslice.face_pressures`) and one
    ``.vtu`` file of them, at 128k and 1M faces: the fuselage at 0.8 m draft, 6 deg,
    60 m/s forward, 1.5 m/s down, ``mlm`` on 128 fixed slices; time per instant and the
    mapping's peak memory (tracemalloc, which counts numpy's arrays)."""
    import tracemalloc

    from hullslice.loads import SectionRecord, face_geometry, face_pressures

    for size in ("128k", "1M"):
        if size not in results:
            continue
        hull = results[size]["hull"]
        r = hs.compute_force(
            hull, hs.Pose(0.8, 0.105), hs.Motion(-1.5, 60.0), solver="mlm", slices=128,
            slicing="fixed",
        )  # fmt: skip
        rec = SectionRecord.of(0.0, r)
        face_geometry(hull)  # kept on the hull, made once per run
        t = median_time(lambda h=hull, s=rec: face_pressures(h, s), repeat)
        tracemalloc.start()
        fp = face_pressures(hull, rec)
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
        err = abs(fp.total / r.total - 1.0)
        table.add(f"{size}: face pressures of one instant", fmt(t))
        table.add(f"{size}: face pressures' peak memory", f"{peak / 2**20:.0f} MiB")
        table.add(
            f"{size}: face loads against slice forces", f"{err:.1e}", "below 1e-3", err < 1e-3
        )
        if importlib.util.find_spec("meshio") is not None:
            import meshio

            from hullslice.loads.files import _vtu

            with tempfile.TemporaryDirectory() as tmp:
                path = Path(tmp) / "p.vtu"
                t_vtu = median_time(
                    lambda h=hull, f=path, p=fp.pressure: _vtu(meshio, h, f, {"pressure": p}), 1
                )
                table.add(
                    f"{size}: one .vtu of the face pressures",
                    f"{fmt(t_vtu)}, {path.stat().st_size / 2**20:.1f} MiB",
                )


def bench_steps(table: Table, repeat: int) -> None:
    hull = hs.load_hull(ROOT / "meshes" / "paper_prism.stl", mass=1.0)
    t_end = 0.02
    for steps in (100, 1000, 10000):
        t = median_time(
            lambda s=steps: hs.simulate(
                hull, -4.0, t_end, dt=t_end / s, slices=64, slicing="fixed", stop_on=()
            ),
            1 if steps > 1000 else repeat,
        )
        table.add(f"paper prism free fall, {steps} steps, fixed 64 slices", fmt(t))


def bench_airliner(table: Table, repeat: int) -> None:
    """A real airliner's ditching (``meshes/airliner``, 17k faces, 37.6 m, 60 t) from 0.3 m
    at 6 deg, 60 m/s forward and 1.5 m/s down, 32 fixed slices, 0.1 s at 1 ms: its nacelles
    wet with its fuselage (slices of two and three entries), its keel line crossed by its
    wings and fairings in the side view at every pitch. The time per step at a held and a
    free pitch, compiled and by numpy's path (the median of ``repeat`` interleaved rounds:
    A B C D A B C D)."""
    hull = hs.load_hull(ROOT / "meshes" / "airliner" / "airliner.obj", length=37.6, mass=60000.0)
    runs = {(free, numba): hull.with_mass(hull.mass) for free in (False, True)
            for numba in (True, False)}  # fmt: skip

    def run(free: bool, numba: bool, t_end: float):
        os.environ["HULLSLICE_NUMBA"] = "1" if numba else "0"
        try:
            return hs.simulate(runs[free, numba], -1.5, t_end, dt=1e-3, draft=0.3, pitch_deg=6.0,
                               forward_speed=60.0, slices=32, slicing="fixed", stop_on=(),
                               free_pitch=free)  # fmt: skip
        finally:
            os.environ.pop("HULLSLICE_NUMBA", None)

    for free, numba in runs:  # warm-up: the held pitch's cut and table, the compilation
        run(free, numba, 0.1 if not free else 0.005)
    times: dict[tuple[bool, bool], list[float]] = {key: [] for key in runs}
    for _ in range(max(1, repeat)):
        for free, numba in runs:
            t0 = time.perf_counter()
            history = run(free, numba, 0.1)
            times[free, numba].append((time.perf_counter() - t0) / (len(history) - 1))
    med = {key: statistics.median(ts) for key, ts in times.items()}
    what = "airliner ditching (17k faces, nacelles wet), time step"
    for free in (False, True):
        pitch = "free pitch" if free else "held pitch"
        if planecut_loops.available():
            table.add(f"{what}, {pitch}, compiled / numpy's path",
                      f"{fmt(med[free, True])} / {fmt(med[free, False])}")  # fmt: skip
        else:
            table.add(f"{what}, {pitch}, numpy's path", fmt(med[free, False]))
    if planecut_loops.available():
        ratio = med[True, True] / med[False, True]
        table.add(f"{what}: ratio free / held, compiled", f"{ratio:.1f}")


#: Rounds of the 1M-face pitch steps (each about 4 s, most of it manifold3d's turns).
BIG_ROUNDS = 3
CHILD = textwrap.dedent(
    """
    import resource, runpy, sys, time
    import hullslice as hs
    t0 = time.perf_counter()
    hull = hs.load_hull(sys.argv[1], mass=60000.0)
    t_load = time.perf_counter() - t0
    t0 = time.perf_counter()
    h = hs.simulate(hull, -1.5, 0.4, dt=0.0002, pitch_rad=0.08, forward_speed=60.0,
                    slices=128, slicing="fixed", stop_on=())
    t_sim = time.perf_counter() - t0
    try:  # this process's own peak (ru_maxrss keeps the parent's across the exec, on Linux)
        with open("/proc/self/status") as fh:
            peak = int(next(ln for ln in fh if ln.startswith("VmHWM:")).split()[1]) / 1024
    except (OSError, StopIteration):
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    # then the same 100 steps at the held pitch and with free pitch by either cutter,
    # interleaved, by run.py's own code
    bench = runpy.run_path(sys.argv[2])
    times, steps, rounds = bench["step_runs"](hull, bench["BIG_ROUNDS"])
    print(t_load, t_sim, len(h), peak, steps,
          *(f"{k.replace(' ', '_')}={','.join(map(str, v))}" for k, v in rounds.items()))
    """
)


def bench_big_simulation(table: Table, path: Path) -> None:
    out = subprocess.run(
        [sys.executable, "-c", CHILD, str(path), __file__],
        capture_output=True,
        text=True,
        check=True,
    )
    words = out.stdout.split()
    t_load, t_sim, steps, peak, pair_steps = (float(v) for v in words[:5])
    rounds = {
        k.replace("_", " "): [float(t) for t in v.split(",")]
        for k, v in (w.split("=") for w in words[5:])
    }
    times = {k: statistics.median(v) for k, v in rounds.items()}
    table.add("1M: load (in the simulating process)", fmt(t_load))
    table.add(
        f"1M: free fall, {int(steps) - 1} steps, 128 fixed slices, pitch 4.6 deg, 60 m/s",
        fmt(t_sim),
        f"< 1.5 x load = {fmt(1.5 * t_load)}",
        t_sim < 1.5 * t_load,
    )
    table.add("1M: ratio simulation / load", f"{t_sim / t_load:.2f}")
    step = t_sim / (steps - 1)
    table.add("1M: that free fall's time over its steps (its pitch's turn and cut too)", fmt(step))
    held = times.get("held, numba", times["held"])
    how = "fused, compiled" if "held, numba" in times else "numpy's path"
    table.add(
        f"1M: a held pitch's RK4 step (4 evaluations; {how}; the median step of 100)",
        fmt(held),
        "<= 0.5 ms",
        held <= 5e-4,
    )
    table.add("1M: peak memory of that process", f"{peak:.0f} MB", "< 2048 MB", peak < 2048)
    pitch_rows(table, "1M", times, int(pair_steps), rounds)


#: The runs the pitch-step comparison interleaves, by name: (free pitch, cutter, numba).
PITCH_RUNS = {
    "held": (False, "manifold3d", False),
    "held, numba": (False, "manifold3d", True),
    "manifold3d": (True, "manifold3d", False),
    "exact, numpy": (True, "exact", False),
    "exact, numba": (True, "exact", True),
}
#: What each free run's stages are cut by, for the table.
PITCH_HOW = {
    "manifold3d": "manifold3d, the mesh turned",
    "exact, numpy": "the exact kernel, numpy's loops",
    "exact, numba": "the exact kernel, compiled by numba",
}
#: The free / held targets: at most 3 with numpy alone, 2 compiled.
PITCH_TARGETS = {"exact, numpy": 3.0, "exact, numba": 2.0}


def pitch_runs() -> dict[str, tuple[bool, str, bool]]:
    """:data:`PITCH_RUNS` that this machine can run (the compiled one needs numba)."""
    have_numba = importlib.util.find_spec("numba") is not None
    return {name: run for name, run in PITCH_RUNS.items() if have_numba or not run[2]}


def step_runs(hull, repeat: int) -> tuple[dict[str, float], int, dict[str, list[float]]]:
    """The time per step (s) of the same run at a held pitch and with free pitch (4 new
    pitches a step, each cut afresh) by either cutter (the kernel with numpy's loops and,
    with numba, compiled), the steps of each, and each round's times (for
    :func:`pitch_rows`' ratios round by round): the median of ``repeat`` rounds, each
    round one run of :data:`PITCH_STEPS` steps of 0.2 ms of each of :func:`pitch_runs` in
    turn (interleaved: A B C D A B C D), 128 fixed slices, from pitch 4.6 deg at 60 m/s
    forward and 1.5 m/s down. Warm-up first: the held run over all its steps (its pitch's
    cut and waterline table, cut once), each free run over :data:`WARM_STEPS` steps (the
    hull's first region, its plane index, numba's compilation), and the compiled one two
    steps more turning (its stages' one compiled call). The held run has a copy of
    the hull of its own (the same mesh, its own frames), so that the free runs' pitches do
    not push its frame out of the hull's few kept ones."""
    dt = 2e-4
    runs = pitch_runs()
    held_hull = hull.with_mass(hull.mass)

    def run(steps: int, free: bool, cutter: str, numba: bool):
        os.environ["HULLSLICE_NUMBA"] = "1" if numba else "0"
        body = hull if free else held_hull
        try:
            return hs.simulate(body, -1.5, steps * dt, dt=dt, pitch_rad=0.08, forward_speed=60.0,
                               slices=128, slicing="fixed", stop_on=(), free_pitch=free,
                               cutter=cutter)  # fmt: skip
        finally:
            os.environ.pop("HULLSLICE_NUMBA", None)

    for free, cutter, numba in runs.values():
        run(WARM_STEPS if free else PITCH_STEPS, free, cutter, numba)
        if free and numba:  # a stage whose pitch has no frame yet (the one compiled call),
            os.environ["HULLSLICE_NUMBA"] = "1"  # which a run dropped level reaches late
            try:
                hs.simulate(hull.with_mass(hull.mass), -1.5, 2 * dt, dt=dt, pitch_rad=0.08,
                            pitch_rate_rad_s=0.5, forward_speed=60.0, slices=128,
                            slicing="fixed", stop_on=(), free_pitch=True,
                            cutter=cutter)  # fmt: skip
            finally:
                os.environ.pop("HULLSLICE_NUMBA", None)
    times: dict[str, list[float]] = {name: [] for name in runs}
    counts = set()
    for _ in range(max(1, repeat)):
        for name, (free, cutter, numba) in runs.items():
            gc.collect()
            t0 = time.perf_counter()
            history = run(PITCH_STEPS, free, cutter, numba)
            t = time.perf_counter() - t0
            counts.add(len(history) - 1)
            times[name].append(t / (len(history) - 1))
    assert len(counts) == 1, counts
    return {name: statistics.median(ts) for name, ts in times.items()}, counts.pop(), times


def pitch_rows(
    table: Table,
    size: str,
    times: dict[str, float],
    steps: int,
    rounds: dict[str, list[float]] | None = None,
) -> None:
    """The rows of :func:`step_runs`' times (medians): each free step, and its ratio over the
    held step by the same path, judged against its target. With ``rounds`` (each round's
    times, the runs of a round back to back), the ratio is the median of the rounds' own
    ratios: a slow spell of a shared machine that lasts a round slows both of its runs,
    where the medians of the times may take the held step from one round and the free
    step from another."""
    held = times["held"]
    table.add(
        f"{size}: time step, held pitch, 128 fixed slices ({steps} steps, cut once), numpy's path",
        fmt(held),
    )
    fused = times.get("held, numba")
    if fused is None:
        table.add(f"{size}: the same, fused and compiled", "not run: numba missing (.[fast])")
    else:
        table.add(f"{size}: the same, fused and compiled", fmt(fused))
    for name, how in PITCH_HOW.items():
        if name not in times:
            table.add(f"{size}: free pitch cut by {how}", "not run: numba missing (.[fast])")
            continue
        free = times[name]
        table.add(f"{size}: time step, free pitch (each stage cut afresh by {how})", fmt(free))
        target = PITCH_TARGETS.get(name)
        compiled = name == "exact, numba"
        # free over held by the same path: numpy's over numpy's, compiled over compiled
        base = fused if compiled and fused is not None else held
        base_name = "held, numba" if base is fused else "held"
        ratio = free / base
        paired = ""
        if rounds is not None and len(rounds.get(name, ())) > 1:
            ratio = statistics.median(
                f / h for f, h in zip(rounds[name], rounds[base_name], strict=True)
            )
            paired = f", the median of {len(rounds[name])} rounds' ratios"
        table.add(
            f"{size}: ratio free ({name}) / held pitch step"
            + (" (fused, compiled" if base is fused else " (numpy's path")
            + paired
            + ")",
            f"{ratio:.2f}",
            "" if target is None else f"<= {target:g}",
            None if target is None else ratio <= target,
        )
        if compiled and base is fused:
            table.add(
                f"{size}: ratio free ({name}) / held pitch step (numpy's path)",
                f"{free / held:.1f}",
            )


def bench_pitch_steps(table: Table, tmp: Path, results: dict, repeat: int) -> None:
    """The time step at a held and at a free pitch by either cutter at 10k and 128k faces,
    interleaved in this process (1M: in the 1M free fall's process)."""
    for size in ("10k", "128k"):
        path = results[size]["path"] if size in results else fuselage_file(tmp, size)
        hull = hs.load_hull(path, mass=60000.0)
        times, steps, rounds = step_runs(hull, repeat)
        pitch_rows(table, f"{size} ({len(hull.faces)} faces)", times, steps, rounds)
        results.setdefault(size, {"hull": hull, "path": path})


def bench_kernel_cut(table: Table, path: Path) -> None:
    """The exact kernel's force at new pitches against manifold3d's fresh cut, over random
    poses (fixed slicing, 128 slices, cut afresh)."""
    hull = hs.load_hull(path, mass=60000.0)
    motion = hs.Motion(-1.5, 60.0)
    exact = ForceModel(hull, slices=128, slicing="fixed", cache=False, cutter="exact")
    ref = ForceModel(hull, slices=128, slicing="fixed", cache=False, cutter="manifold3d")
    rng = np.random.default_rng(28)
    poses = [hs.Pose(d, p) for d, p in zip(rng.uniform(0.02, 0.6, 40),
                                           rng.uniform(-0.05, 0.15, 40), strict=True)]  # fmt: skip
    errs = [relative_error(exact(p, motion), ref(p, motion), hull.size) for p in poses]
    table.add(
        f"{len(hull.faces) / 1000:.0f}k, new pitches: the kernel's cut against manifold3d's, "
        f"{len(poses)} random poses (largest / median relative difference of Fz, Fx, My / size)",
        f"{max(errs):.1e} / {statistics.median(errs):.1e}",
        "<= 1e-9",
        max(errs) <= 1e-9,
    )
    dt = 2e-4
    runs = [hs.simulate(hs.load_hull(path, mass=60000.0), -1.5, 100 * dt, dt=dt, pitch_rad=0.08,
                        forward_speed=60.0, slices=128, slicing="fixed", stop_on=(),
                        free_pitch=True, cutter=cutter)
            for cutter in ("manifold3d", "exact")]  # fmt: skip
    a, b = (np.asarray(h.force) for h in runs)
    err = float(np.max(np.abs(a - b)) / np.max(np.abs(a)))
    table.add(
        f"{len(hull.faces) / 1000:.0f}k: a 100-step free-pitch history by the kernel against a "
        "manifold3d-only run (largest force difference / peak force)",
        f"{err:.1e}",
    )


def relative_error(a, b, size: float) -> float:
    """The largest difference of two force results' ``total``, ``total_x`` and ``moment /
    size`` (``size`` in m) relative to the second's ``abs(total)``."""
    diffs = (a.total - b.total, a.total_x - b.total_x, (a.moment - b.moment) / size)
    return max(abs(float(d)) for d in diffs) / abs(float(b.total))


def bench_fresh_cuts(table: Table, path: Path) -> None:
    """What the approximations cost against fresh cuts: the fixed slicing's reuse at a held
    pitch, and (free pitch cutting afresh at every stage) the fresh cut's own resolution."""
    hull = hs.load_hull(path, mass=60000.0)
    motion = hs.Motion(-1.5, 60.0)
    kept = ForceModel(hull, slices=128, slicing="fixed")
    fresh = ForceModel(hull, slices=128, slicing="fixed", cache=False)
    for d in np.linspace(0.05, 0.3, 8):  # its cut, and its waterline table (the 8th)
        kept(hs.Pose(d, 0.08), motion)
    poses = [hs.Pose(d, 0.08) for d in np.linspace(0.055, 0.295, 20)]
    err = max(relative_error(kept(p, motion), fresh(p, motion), hull.size) for p in poses)
    table.add(
        f"{len(hull.faces) / 1000:.0f}k, held pitch: kept cut and table against fresh cuts, "
        f"{len(poses)} drafts (largest relative difference of Fz, Fx, My / size)",
        f"{err:.1e}",
    )

    # free pitch: no approximation, every stage cut afresh at its own pitch; the fresh
    # cut's own resolution, on the model fuselage barely wetted
    model = hs.load_hull(ROOT / "meshes" / "fuselage_model.obj", mass=60.0)
    cut = ForceModel(model, slices=32, slicing="fixed", cache=False)
    motion = hs.Motion(-1.0, 19.0)
    p0, step = np.radians(6.0), 1e-10

    def force(pitch: float) -> float:
        return float(cut(hs.Pose(0.012, pitch), motion).total)

    f = np.array([force(p0 + k * step) for k in range(11)])
    noise = float(np.max(np.abs(np.diff(f)) / np.abs(f[:-1])))
    slope = abs(force(p0 + 1e-6) - f[0]) / 1e-6 * step / abs(f[0])
    table.add("free pitch against fresh cuts", "none: each stage cut afresh")
    table.add(
        "free pitch: a fresh cut's force, largest relative change over a pitch step of 1e-10 rad"
        " (10 steps)",
        f"{noise:.1e}",
    )
    table.add(
        "free pitch: of which the force's own change (its slope over 1e-6 rad)", f"{slope:.1e}"
    )


#: Sweeps of the 64 short cases per setting, the rate their median: the first on a
#: cluster is its workers' start too (each builds the hull and loads the compiled loops,
#: 1.3 to 1.5 s, against 64 cases of 0.03 s), the later ones are the workers' own rate.
SWEEP_REPEAT = 3


def bench_sweep(table: Table, repeat: int) -> None:
    """The 64-case free-pitch sweep's cases per second in this process and on 1 and 2
    Dask workers (``benchmarks/sweep.py``), the median of ``repeat`` sweeps each."""
    missing = [m for m in ("distributed", "xarray") if importlib.util.find_spec(m) is None]
    if missing:
        table.add(
            "64-case free-pitch sweep",
            f'not run: {" and ".join(missing)} missing: pip install -e ".[sweep]"',
        )
        return
    sweep = _sweep_module()
    what = (
        f"64-case free-pitch sweep ({SWEEP_T_END:g} s cases at 1 ms, 1:10 model; the median "
        f"of {repeat} sweeps, the first on just-started workers)"
    )
    rates = sweep.throughput(SWEEP_T_END, repeat=repeat, free_pitch=True)
    one, two = rates[sweep.workers_name(1)], rates[sweep.workers_name(2)]
    table.add(f"{what}, in this process", f"{rates[sweep.IN_PROCESS]:.2f} cases/s")
    table.add(f"{what}, 1 worker", f"{one:.2f} cases/s")
    table.add(f"{what}, 2 workers", f"{two:.2f} cases/s")
    table.add("ratio 2 / 1 workers", f"{two / one:.2f}", ">= 1.7", two >= 1.7 * one)
    table.add(
        "free-pitch sweep: largest relative difference of a peak force between settings",
        f"{rates['peak difference']:.1e}",
    )


#: The envelope study: the 1:10 model (128k faces), free pitch, 32 fixed slices, cases of
#: 0.5 s at 1 ms; a sample of it is run, and 1,000 cases are extrapolated from its rate.
#: The sample is 24 cases on a cluster whose workers have run :data:`ENVELOPE_WARM` first:
#: a worker's start (its hull, its compiled loops loaded, its plane index: 1 to 2 s) is
#: paid once in 1,000 cases, not once in 12, so it is measured apart (the warm-up's wall
#: time less its cases at the sample's rate) and counted once. The clusters of 1 and of 2
#: workers are both up, and the sample runs on one, then the other, :data:`ENVELOPE_ROUNDS`
#: times: the ratio is the median of the rounds' own ratios.
ENVELOPE_T_END = 0.5
ENVELOPE_GRID = {"velocity": [-1.0, -1.5, -2.0], "pitch": [2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]}
ENVELOPE_WARM = {"velocity": [-1.5], "pitch": [4.0, 7.0]}
ENVELOPE_CASES = 1000
ENVELOPE_ROUNDS = 3


def bench_envelope(table: Table) -> None:
    """The envelope case (the 1:10 model, free pitch, 0.5 s at 1 ms, 32 fixed slices): its
    time per case in this process, and the rate of a sample of such cases on 1 and 2 Dask
    workers once each worker has started (alternated, :data:`ENVELOPE_ROUNDS` rounds), with
    the time of :data:`ENVELOPE_CASES` cases on two workers extrapolated: the workers'
    start once, then the cases at that rate."""
    if any(importlib.util.find_spec(m) is None for m in ("distributed", "xarray")):
        table.add("envelope cases", 'not run: pip install -e ".[sweep]"')
        return
    sweep = _sweep_module()
    from hullslice.sweeps.engine import local_client

    base, _ = sweep.study(ENVELOPE_T_END, free_pitch=True)
    n = len(ENVELOPE_GRID["velocity"]) * len(ENVELOPE_GRID["pitch"])
    n_warm = len(ENVELOPE_WARM["velocity"]) * len(ENVELOPE_WARM["pitch"])
    here = sweep.measure(base, ENVELOPE_GRID, workers=1)
    clients: dict = {}
    runs: dict = {1: [], 2: []}
    try:
        warm = {}
        for k in (1, 2):
            clients[k] = local_client(k)
            warm[k] = sweep.measure(base, ENVELOPE_WARM, client=clients[k])
        for _ in range(ENVELOPE_ROUNDS):
            for k in (1, 2):
                runs[k].append(sweep.measure(base, ENVELOPE_GRID, client=clients[k]))
    finally:
        for client in clients.values():
            client.close()
            client.cluster.close()
    rates = {k: [r["rate"] for r in runs[k]] for k in (1, 2)}
    pairs = [b / a for a, b in zip(rates[1], rates[2], strict=True)]
    ratio = statistics.median(pairs)
    rate = {k: statistics.median(rates[k]) for k in (1, 2)}
    starts = {k: max(warm[k]["wall"] - n_warm / rate[k], 0.0) for k in (1, 2)}
    what = f"envelope: 1:10 model (128k faces), free pitch, {ENVELOPE_T_END:g} s at 1 ms, 32 fixed"
    table.add(f"{what}: a case in this process ({n} cases, compute / case)",
              fmt(here["compute"] / n))  # fmt: skip
    table.add(f"envelope: {n} cases on 1 / 2 started Dask workers (median of "
              f"{ENVELOPE_ROUNDS} rounds, alternated)",
              f"{rate[1]:.3f} / {rate[2]:.3f} cases/s")  # fmt: skip
    own = [statistics.median(r["compute"] for r in runs[k]) / n for k in (1, 2)]
    table.add("envelope: a case's own time in a worker, 1 / 2 workers (the two share the "
              "machine's memory)", f"{own[0]:.2f} / {own[1]:.2f} s")  # fmt: skip
    table.add("envelope: the workers' start (hull, compiled loops), 1 / 2 workers",
              f"{starts[1]:.1f} / {starts[2]:.1f} s")  # fmt: skip
    table.add("envelope: ratio 2 / 1 workers (the median of the rounds' ratios: "
              + ", ".join(f"{p:.2f}" for p in pairs) + ")",
              f"{ratio:.2f}", ">= 1.7", ratio >= 1.7)  # fmt: skip
    total = starts[2] + ENVELOPE_CASES / rate[2]
    table.add(
        f"envelope: {ENVELOPE_CASES} cases on 2 workers (their start, then the {n}-case rate)",
        f"{total / 60:.1f} min",
        "< 10 min",
        total < 600,
    )


def _sweep_module():
    """``benchmarks/sweep.py`` as a module."""
    spec = importlib.util.spec_from_file_location(
        "sweep_benchmark", ROOT / "benchmarks" / "sweep.py"
    )
    assert spec is not None and spec.loader is not None
    sweep = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(sweep)
    return sweep


def bench_process(table: Table, repeat: int) -> None:
    exe = [sys.executable, "-m", "hullslice"]
    paper = [
        *exe,
        "simulate",
        str(ROOT / "meshes" / "paper_prism.stl"),
        "--mass",
        "1",
        "--velocity=-4",
        "--t-end",
        "0.03",
        "--dt",
        "2e-4",
    ]
    t = median_time(lambda: subprocess.run(paper, capture_output=True, check=True), repeat)
    table.add("paper free fall, process start to printed report", fmt(t), "< 2 s", t < 2.0)
    t = median_time(
        lambda: subprocess.run([sys.executable, "-c", "import hullslice"], check=True), repeat
    )
    table.add("import hullslice (process)", fmt(t), "< 0.5 s", t < 0.5)
    t = median_time(
        lambda: subprocess.run([*exe, "--help"], capture_output=True, check=True), repeat
    )
    table.add("hullslice --help (process)", fmt(t), "< 0.5 s", t < 0.5)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="skip the 1M-face mesh and the sweep")
    ap.add_argument("--repeat", type=int, default=5, help="repetitions (default 5)")
    ap.add_argument(
        "--no-sweep",
        action="store_true",
        help="skip the 64-case free-pitch sweep on 1 and 2 Dask workers (2 to 3 minutes; "
        "--quick skips it too)",
    )
    ap.add_argument(
        "--envelope",
        action="store_true",
        help="run only the envelope cases (free pitch, 0.5 s at 1 ms, 128k faces) on 1 and 2 "
        "Dask workers (about 5 minutes)",
    )
    args = ap.parse_args()
    if args.envelope:
        table = Table()
        bench_envelope(table)
        table.show()
        return
    if importlib.util.find_spec("trimesh") is None:
        # the comparison with trimesh runs in a process of its own, after minutes of work
        sys.exit(
            "benchmarks/run.py: trimesh is not installed (the benchmark compares with it): "
            'pip install -e ".[test]" or pip install trimesh'
        )
    table = Table()
    print(f"hullslice {hs.__version__}, numpy {np.__version__}, {os.cpu_count()} cores")
    with tempfile.TemporaryDirectory() as tmp:
        sizes = ("10k", "100k") if args.quick else ("10k", "100k", "1M")
        results = {}
        for size in sizes:
            print(f"mesh {size} ...")
            results[size] = bench_mesh(table, Path(tmp), size, args.repeat)
        bench_slices(table, results["100k"]["hull"], args.repeat)
        bench_solvers(table, results["100k"]["hull"], args.repeat)
        bench_steps(table, args.repeat)
        print("time step at a held and a free pitch ...")
        bench_pitch_steps(table, Path(tmp), results, args.repeat)
        bench_fresh_cuts(table, results["128k"]["path"])
        bench_kernel_cut(table, results["128k"]["path"])
        print("an airliner's ditching ...")
        bench_airliner(table, args.repeat)
        print("face pressures ...")
        bench_face_loads(table, results, args.repeat)
        if not args.quick:
            bench_big_simulation(table, results["1M"]["path"])
            if not args.no_sweep:
                print("64-case free-pitch sweep ...")
                bench_sweep(table, SWEEP_REPEAT)
                print("envelope cases (about 5 minutes) ...")
                bench_envelope(table)
        bench_process(table, args.repeat)
    table.show()


if __name__ == "__main__":
    main()
