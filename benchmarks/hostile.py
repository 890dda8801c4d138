"""Memory and time of loading hostile and large mesh files: peak memory against file size.

    python benchmarks/hostile.py [--large] [--limit-gb 6]

Each file is written to a temporary folder and loaded by ``hullslice.load_hull`` in a
process of its own (so that one file's memory does not count for the next), under an
address-space limit of ``--limit-gb`` GB; the process reports its peak resident memory
(``resource.getrusage``), the time the load took and its outcome (the hull's face count, or
the error's first words). Peak memory is the process's high-water mark (``VmHWM`` of
``/proc/self/status``; Linux). The table gives the peak against the file's size, as
``peak = base + k * size``, with ``base`` the peak of a process that imports hullslice and
loads a tetrahedron. The files:

- binary STL, ASCII STL and OBJ of the generic fuselage at about 1, 10 and 50 MB (200 MB
  with ``--large``): the ordinary files whose cost the bound must cover;
- an open mesh 1e6 m from the origin and a closed mesh with one stray vertex 1e9 m away
  (1 MB each): the vertex merge must not scale its tolerance up to the whole body;
- an OBJ of 4 MB of backslash continuation lines, and one 4 MB line without a line end:
  parsing must be linear, a line longer than the parser allows is refused.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import textwrap
from pathlib import Path

import numpy as np

from hullslice import shapes

ROOT = Path(__file__).resolve().parents[1]

CHILD = textwrap.dedent(
    """
    import json, resource, sys, time, warnings
    limit = int(sys.argv[2])
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    import hullslice as hs
    warnings.simplefilter("ignore")
    t0 = time.perf_counter()
    try:
        hull = hs.load_hull(sys.argv[1])
        outcome = f"loaded, {len(hull.faces)} faces"
    except hs.HullsliceError as exc:
        outcome = "refused: " + str(exc).split(": ", 1)[-1][:70]
    except MemoryError:
        outcome = "MemoryError"
    seconds = time.perf_counter() - t0
    # the peak of this process since it started (getrusage's ru_maxrss would also count
    # the parent's memory at the fork, on Linux)
    with open("/proc/self/status") as fh:
        hwm = next(ln for ln in fh if ln.startswith("VmHWM:"))
    peak = int(hwm.split()[1]) * 1024
    print(json.dumps({"peak": peak, "seconds": seconds, "outcome": outcome}))
    """
)


def measure(path: Path, limit: int) -> dict:
    """Load ``path`` in a process of its own; its peak memory (bytes), time and outcome."""
    proc = subprocess.run(
        [sys.executable, "-c", CHILD, str(path), str(limit)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=1800,
    )
    if proc.returncode != 0:
        last = (proc.stderr.strip().splitlines() or ["?"])[-1]
        return {"peak": float("nan"), "seconds": float("nan"), "outcome": f"crashed: {last}"}
    return json.loads(proc.stdout.strip().splitlines()[-1])


def stl_binary(path: Path, v: np.ndarray, f: np.ndarray) -> Path:
    tri = v[f].astype("<f4")
    rec = np.zeros(len(f), dtype=[("n", "<f4", (3,)), ("c", "<f4", (3, 3)), ("a", "<u2")])
    rec["c"] = tri
    with open(path, "wb") as fh:
        fh.write(b"\0" * 80 + np.uint32(len(f)).tobytes() + rec.tobytes())
    return path


def stl_ascii(path: Path, v: np.ndarray, f: np.ndarray) -> Path:
    with open(path, "w") as fh:
        fh.write("solid hull\n")
        for a, b, c in v[f]:
            fh.write(
                "facet normal 0 0 0\n outer loop\n"
                f"  vertex {a[0]:.7g} {a[1]:.7g} {a[2]:.7g}\n"
                f"  vertex {b[0]:.7g} {b[1]:.7g} {b[2]:.7g}\n"
                f"  vertex {c[0]:.7g} {c[1]:.7g} {c[2]:.7g}\n endloop\nendfacet\n"
            )
        fh.write("endsolid hull\n")
    return path


def obj(path: Path, v: np.ndarray, f: np.ndarray) -> Path:
    with open(path, "w") as fh:
        np.savetxt(fh, v, fmt="v %.9g %.9g %.9g")
        np.savetxt(fh, f + 1, fmt="f %d %d %d")
    return path


def fuselage_faces(faces: int):
    """The generic fuselage with about ``faces`` faces."""
    stations = max(8, round(float(np.sqrt(faces / 2 * 400 / 160))))
    points = max(8, round(faces / 2 / stations))
    return shapes.fuselage(stations=stations, points=points)


def files(folder: Path, large: bool) -> list[tuple[str, Path]]:
    out = []
    sizes = [1, 10, 50] + ([200] if large else [])
    for mb in sizes:
        n = int(mb * 1024**2 / 50)  # binary STL: 50 bytes a face
        v, f = fuselage_faces(n)
        out.append((f"binary STL, {mb} MB", stl_binary(folder / f"f{mb}.stl", v, f)))
        if mb <= 50:
            m = int(mb * 1024**2 / 260)  # ASCII STL: about 260 bytes a face
            v, f = fuselage_faces(m)
            out.append((f"ASCII STL, {mb} MB", stl_ascii(folder / f"a{mb}.stl", v, f)))
            k = int(mb * 1024**2 / 45)  # OBJ: about 45 bytes a face (half a vertex each)
            v, f = fuselage_faces(k)
            out.append((f"OBJ, {mb} MB", obj(folder / f"o{mb}.obj", v, f)))
    # about 1 MB each: an open mesh far from the origin, a stray far vertex
    v, f = fuselage_faces(20000)
    out.append(("open mesh 1e6 m from the origin, 1 MB", obj(folder / "far.obj", v + 1e6, f[1:])))
    stray = np.vstack([v, [[1e9, 0.0, 0.0], [1e9, 1.0, 0.0], [1e9, 0.0, 1.0]]])
    ff = np.vstack([f, [[len(v), len(v) + 1, len(v) + 2]]])
    out.append(("one stray vertex 1e9 m away, 1 MB", stl_binary(folder / "stray.stl", stray, ff)))
    cont = folder / "continued.obj"
    cont.write_bytes(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2 \\\n" + b"1 \\\n" * 1024**2)
    out.append(("OBJ of 4 MB of continuation lines", cont))
    line = folder / "oneline.obj"
    line.write_bytes(b"v 0 0 0 " * (4 * 1024**2 // 8))
    out.append(("OBJ of one 4 MB line", line))
    tetra = folder / "tetra.obj"
    tetra.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    out.insert(0, ("base: a tetrahedron (imports and start-up)", tetra))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--large", action="store_true", help="also 200 MB files")
    parser.add_argument("--limit-gb", type=float, default=6.0, help="address-space limit")
    args = parser.parse_args()
    limit = int(args.limit_gb * 1024**3)
    with tempfile.TemporaryDirectory() as tmp:
        rows = []
        for label, path in files(Path(tmp), args.large):
            r = measure(path, limit)
            rows.append((label, path.stat().st_size, r))
            print(f"measured {label}", file=sys.stderr)
    base = rows[0][2]["peak"]
    print("| file | size | peak memory | (peak - base) / size | time | outcome |")
    print("| --- | ---: | ---: | ---: | ---: | --- |")
    for label, size, r in rows:
        extra = (r["peak"] - base) / size if size > 1000 else float("nan")
        ratio = "" if np.isnan(extra) else f"{extra:.1f}"
        print(
            f"| {label} | {size / 1024**2:.2f} MB | {r['peak'] / 1024**2:.0f} MB | {ratio} | "
            f"{r['seconds']:.2f} s | {r['outcome']} |"
        )


if __name__ == "__main__":
    main()
