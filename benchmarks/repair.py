"""Benchmark of ``--repair close``: time, memory and volume error on open fuselage meshes.

    python benchmarks/repair.py [--sizes 10k,100k] [--level-set]

Meshes: the generic fuselage of ``hullslice.shapes`` at about 10k and 100k faces, holed in
four places (0.3 to 1.5 m radius on the 3.95 m-wide body), with 50 loose open sheets and
triangles around it (a modelling tool's export), written as a binary STL. For each:
loading the undamaged closed mesh (the reference), loading the open one with
``repair="close", keep="largest"`` (read, stitch, fill, drop, check), the repair alone,
the peak memory of each load in a process of its own (pymeshfix and scipy imported before
the clock starts, as they are once per process), and the volume error against the
undamaged body. ``--level-set`` also measures the other candidate, rebuilding the surface
as a level set (manifold3d ``Manifold.level_set``) of the generalized winding number
(computed with numpy, per point, as manifold3d asks), on the 10k mesh only.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import textwrap
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SIZES = {"10k": (63, 80), "100k": (313, 160)}  # stations, points
HOLES = [
    ((20.0, 0.0, 0.0), 0.3),
    ((10.0, 1.9, 2.0), 0.8),
    ((30.0, -1.5, 3.5), 1.5),
    ((34.0, 0.0, 3.0), 0.6),
]


def write_stl(path: Path, v: np.ndarray, f: np.ndarray) -> None:
    """A binary STL (no normals)."""
    rec = np.zeros(len(f), dtype=[("n", "<f4", 3), ("c", "<f4", (3, 3)), ("a", "<u2")])
    rec["c"] = v[f]
    with open(path, "wb") as fh:
        fh.write(b"\0" * 80 + np.uint32(len(f)).tobytes() + rec.tobytes())


def dirty(stations: int, points: int):
    """The fuselage, holed, with loose sheets; and the undamaged fuselage."""
    from hullslice import shapes

    v, f = shapes.fuselage(stations=stations, points=points)
    centre = v[f].mean(axis=1)
    keep = np.ones(len(f), dtype=bool)
    for p, r in HOLES:
        keep &= np.linalg.norm(centre - np.array(p), axis=1) > r
    rng = np.random.default_rng(3)
    vs, fs = [v], [f[keep]]
    n = len(v)
    for _ in range(50):
        c = rng.uniform((-5, -15, -3), (45, 15, 8))
        vs.append(c + rng.normal(0, 0.2, (3, 3)))
        fs.append(np.array([[n, n + 1, n + 2]]))
        n += 3
    return (np.vstack(vs), np.vstack(fs)), (v, f)


CHILD = textwrap.dedent(
    """
    import json, resource, sys, time, warnings
    t0 = time.perf_counter()
    import hullslice as hs
    import pymeshfix, scipy.spatial  # once per process: not part of a load
    warnings.simplefilter("ignore")
    path, options = sys.argv[1], json.loads(sys.argv[2])
    t1 = time.perf_counter()
    hull = hs.load_hull(path, **options)
    t2 = time.perf_counter()
    try:  # this process's own peak (ru_maxrss keeps the parent's across the exec, on Linux)
        with open("/proc/self/status") as fh:
            peak = int(next(ln for ln in fh if ln.startswith("VmHWM:")).split()[1]) / 1024
    except (OSError, StopIteration):
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(json.dumps({"load": t2 - t1, "volume": hull.volume, "faces": len(hull.faces),
                      "peak_mb": peak}))
    """
)


def in_process_of_its_own(path: Path, options: dict) -> dict:
    out = subprocess.run(
        [sys.executable, "-c", CHILD, str(path), json.dumps(options)],
        capture_output=True,
        text=True,
        check=True,
        cwd=ROOT,
        env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"},
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def level_set_volume(v: np.ndarray, f: np.ndarray, edge: float) -> tuple[float, float]:
    """Volume and time of the level set at 0.5 of the generalized winding number."""
    import manifold3d

    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]

    def winding(x, y, z):
        p = np.array([x, y, z])
        ra, rb, rc = a - p, b - p, c - p
        la, lb, lc = (np.linalg.norm(r, axis=1) for r in (ra, rb, rc))
        num = np.einsum("ij,ij->i", ra, np.cross(rb, rc))
        den = (
            la * lb * lc
            + np.einsum("ij,ij->i", ra, rb) * lc
            + np.einsum("ij,ij->i", rb, rc) * la
            + np.einsum("ij,ij->i", rc, ra) * lb
        )
        return float(np.arctan2(num, den).sum() / (2 * np.pi)) - 0.5

    # the grid over the fuselage's box only (the loose triangles around it are left out)
    lo, hi = np.array([-1.0, -3.0, -1.0]), np.array([38.6, 3.0, 5.2])
    t0 = time.perf_counter()
    m = manifold3d.Manifold.level_set(winding, [*lo, *hi], edge)
    return float(m.volume()), time.perf_counter() - t0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="10k,100k", help="of 10k, 100k (default both)")
    parser.add_argument("--level-set", action="store_true", help="also the level-set route")
    args = parser.parse_args()
    sys.path.insert(0, str(ROOT))
    import hullslice as hs
    from hullslice.repair import close_mesh

    rows = []

    def row(name: str, value: str) -> None:
        rows.append((name, value))
        print(f"| {name} | {value} |", flush=True)

    with tempfile.TemporaryDirectory() as tmp:
        for size in args.sizes.split(","):
            (dv, df), (cv, cf) = dirty(*SIZES[size])
            clean_path, dirty_path = Path(tmp, "clean.stl"), Path(tmp, "dirty.stl")
            write_stl(clean_path, cv, cf)
            write_stl(dirty_path, dv, df)
            ref = in_process_of_its_own(clean_path, {})
            rep = in_process_of_its_own(dirty_path, {"repair": "close", "keep": "largest"})
            hull_v, hull_f = hs.mesh.read_mesh(dirty_path)
            from hullslice.topology import unique_rows

            uv, inv = unique_rows(hull_v)
            close_mesh(*dirty(20, 16)[0])  # the imports, once
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                t0 = time.perf_counter()
                _, _, report = close_mesh(uv, inv[hull_f])
                t_close = time.perf_counter() - t0
            err = rep["volume"] / ref["volume"] - 1.0
            row(
                f"{size}: faces of the open mesh / holes filled / loose shells dropped",
                f"{len(df):,} / {report.holes} / {report.dropped}",
            )
            row(f"{size}: load the undamaged closed mesh", f"{ref['load']:.2f} s")
            row(
                f"{size}: load the open one with repair close, keep largest",
                f"{rep['load']:.2f} s ({rep['load'] / ref['load']:.1f} x)",
            )
            row(f"{size}: the repair alone (stitch, fill, drop)", f"{t_close:.2f} s")
            row(
                f"{size}: peak memory, undamaged / repaired load",
                f"{ref['peak_mb']:.0f} / {rep['peak_mb']:.0f} MB",
            )
            row(f"{size}: volume error of the repaired body", f"{err * 100:+.3f} %")
            if args.level_set and size == "10k":
                for edge in (0.5,):  # 0.25 m: eight times the points
                    vol, t = level_set_volume(dv, df, edge)
                    row(
                        f"10k: level set of the winding number, edge {edge} m",
                        f"{t:.1f} s, volume error {(vol / ref['volume'] - 1) * 100:+.2f} %",
                    )
    print()
    width = max(len(r[0]) for r in rows)
    print(f"| {'measure'.ljust(width)} | value |")
    print(f"| {'-' * width} | --- |")
    for name, value in rows:
        print(f"| {name.ljust(width)} | {value} |")


if __name__ == "__main__":
    main()
