"""Time to load a closed mesh of about 1M faces and to cut it at 200 stations.

    python benchmarks/bench_cut.py [--faces 1000000] [--stations 200] [--repeat 5]

The cut (wetted extent, 200 manifold3d slices, section properties) is compared with
manifold3d's own 200 ``slice`` calls on the same Manifold, in the same run; the target is
a ratio of about 1.2 or less. Medians of ``--repeat`` runs.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np
import trimesh

import hullslice as hs


def lofted_body(faces: int) -> trimesh.Trimesh:
    """A closed, slender body of revolution with about ``faces`` triangles."""
    seg = int(np.sqrt(faces / 4))  # around the body
    rings = max(faces // (2 * seg), 4)  # along it
    x = np.linspace(-1.0, 1.0, rings)
    radius = 0.1 * np.sqrt(np.clip(1 - x**2, 1e-4, None))
    t = np.linspace(0.0, 2 * np.pi, seg, endpoint=False)
    sec = np.stack([np.cos(t), np.sin(t)], 1)
    from hullslice.shapes import prism_from_sections

    v, f = prism_from_sections(x * 5.0, radius[:, None, None] * sec[None] * 5.0)
    return trimesh.Trimesh(v, f, process=False)


def median_time(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--faces", type=int, default=1_000_000, help="mesh size (default 1e6)")
    ap.add_argument("--stations", type=int, default=200, help="stations (default 200)")
    ap.add_argument("--repeat", type=int, default=5, help="repetitions (default 5)")
    args = ap.parse_args()

    mesh = lofted_body(args.faces)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "body.stl"
        mesh.export(path)
        t0 = time.perf_counter()
        hull = hs.load_hull(path, mass=1000.0)
        t_load = time.perf_counter() - t0
    draft = 0.5 * hull.extents[2]
    hs.cut(hull, draft, args.stations)  # warm the cached edges and slicer

    t_cut = median_time(lambda: hs.cut(hull, draft, args.stations), args.repeat)
    slicer, _ = hull._slicer
    xs = np.linspace(-4.9, 4.9, args.stations)
    t_raw = median_time(lambda: [slicer.slice(float(x)) for x in xs], args.repeat)

    print(f"mesh: {len(hull.faces)} faces, {len(hull.vertices)} vertices")
    print(f"{'step':<40}{'time [s]':>12}")
    print(f"{'load_hull (read, check, Manifold)':<40}{t_load:>12.3f}")
    print(f"{'cut at ' + str(args.stations) + ' stations':<40}{t_cut:>12.4f}")
    print(f"{'manifold3d slice x ' + str(args.stations):<40}{t_raw:>12.4f}")
    print(f"ratio cut / manifold3d slices: {t_cut / t_raw:.2f} (target <= 1.2)")


if __name__ == "__main__":
    main()
