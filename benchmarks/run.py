"""hullslice's benchmark suite: one command, a table of measured figures against targets.

    python benchmarks/run.py [--quick] [--repeat 5]

Meshes: the generic fuselage of ``hullslice.shapes`` at about 10k, 100k and 1M faces
(``--quick`` stops at 100k). For each: the time to load it from a file; the time to cut
it at 200 stations with the sections' properties, against manifold3d's own 200 ``slice``
calls and trimesh's ``section_multiplane`` on the same planes; the cost of one force
evaluation (a stage of a time step) with 128 slices at a fixed pitch, with the fixed
slicing cut once (cached, with its waterline table) against re-cutting the 3D hull at
every step (naive); the cost of an evaluation at a new pitch (the cut must be redone),
once the hull has its first region, and the cost of making that region. Then: the cached
cost against the slice count (32 to 512), whole free falls of 100 to 10,000 steps, a
2,000-step free fall of the 1M-face fuselage in a process of its own (time, time per
step, peak memory) and 100 steps of it with free pitch, the paper's free-fall case from
process start to printed report, and the time of ``import hullslice`` and ``hullslice
--help``. Times are medians of ``--repeat`` runs on this
machine; ratios compare figures measured in the same run.
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
from hullslice import shapes
from hullslice.forces import solve_accelerations
from hullslice.geometry import REGIONS, frame
from hullslice.motion import ForceModel

ROOT = Path(__file__).resolve().parents[1]
SIZES = {"10k": (63, 80), "100k": (313, 160), "1M": (1563, 320)}  # stations, points


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
    naive = ForceModel(hull, slices=128, slicing="fixed", cache=False)
    for d in drafts:  # its cut, and its waterline table (made from the 8th evaluation)
        cached(hs.Pose(d, 0.08), motion)
    t_cached = per_call(lambda i: cached(hs.Pose(drafts[i % 50], 0.08), motion), 50, repeat)
    t_naive = per_call(lambda i: naive(hs.Pose(drafts[i % 50], 0.08), motion), 5, repeat)
    wetted = ForceModel(hull, slices=128)
    t_wetted = per_call(lambda i: wetted(hs.Pose(drafts[i % 50], 0.08), motion), 5, repeat)
    table.add(
        f"{size}: evaluation, fixed pitch, 128 slices, cached",
        fmt(t_cached),
        "< 1 ms" if size == "1M" else "",
        (t_cached < 1e-3) if size == "1M" else None,
    )

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


CHILD = textwrap.dedent(
    """
    import resource, sys, time
    import hullslice as hs
    t0 = time.perf_counter()
    hull = hs.load_hull(sys.argv[1], mass=60000.0)
    t_load = time.perf_counter() - t0
    t0 = time.perf_counter()
    h = hs.simulate(hull, -1.5, 0.4, dt=0.0002, pitch=0.08, forward_speed=60.0,
                    slices=128, slicing="fixed", stop_on=())
    t_sim = time.perf_counter() - t0
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    # then free pitch: every stage of every step at a new pitch
    t0 = time.perf_counter()
    f = hs.simulate(hull, -1.5, 0.02, dt=0.0002, pitch=0.08, forward_speed=60.0,
                    slices=128, slicing="fixed", stop_on=(), free_pitch=True)
    t_free = time.perf_counter() - t0
    print(t_load, t_sim, len(h), peak, t_free, len(f))
    """
)


def bench_big_simulation(table: Table, path: Path) -> None:
    out = subprocess.run(
        [sys.executable, "-c", CHILD, str(path)], capture_output=True, text=True, check=True
    )
    t_load, t_sim, steps, peak, t_free, free_steps = (float(v) for v in out.stdout.split())
    table.add("1M: load (in the simulating process)", fmt(t_load))
    table.add(
        f"1M: free fall, {int(steps) - 1} steps, 128 fixed slices, pitch 4.6 deg, 60 m/s",
        fmt(t_sim),
        f"< 1.5 x load = {fmt(1.5 * t_load)}",
        t_sim < 1.5 * t_load,
    )
    table.add("1M: ratio simulation / load", f"{t_sim / t_load:.2f}")
    table.add("1M: time step of that free fall (4 evaluations)", fmt(t_sim / (steps - 1)))
    table.add("1M: peak memory of that process", f"{peak:.0f} MB", "< 2048 MB", peak < 2048)
    table.add(
        f"1M: time step with free pitch (4 new pitches), {int(free_steps) - 1} steps",
        fmt(t_free / (free_steps - 1)),
    )


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
    ap.add_argument("--quick", action="store_true", help="skip the 1M-face mesh")
    ap.add_argument("--repeat", type=int, default=5, help="repetitions (default 5)")
    args = ap.parse_args()
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
        bench_steps(table, args.repeat)
        if not args.quick:
            bench_big_simulation(table, results["1M"]["path"])
        bench_process(table, args.repeat)
    table.show()


if __name__ == "__main__":
    main()
