"""The loads of a fuselage ditching for its structure: pressures on the skin and frame loads.

    python examples/structure_loads.py [--t-end 1.2] [--every 10] [--out FOLDER]

The full-scale fuselage of meshes/ (60 t, 127,996 faces) ditching at 8 degrees nose up,
60 m/s forward and 1.5 m/s down, free in pitch, in sea water, with the wing's lift equal to
the weight at touchdown and the water's friction, by the Modified Logvinovich Model with
its hydrostatic pressure (as examples/ditching.py). Every 10th instant's sections are kept
and mapped onto the mesh's faces (hullslice.loads). It prints, at each kept instant, the
faces' vertical load against the slices' force (their difference over the run's peak
force), the peak face
pressure, and the most loaded frame bay (frames every 0.5 m), and writes
loads_peak_pressure.png (the fuselage from below coloured by each face's peak pressure)
and loads_frames.png (the most loaded bays' vertical loads over time) into --out.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

import hullslice as hs
from hullslice import plots

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t-end", type=float, default=1.2, help="duration in s (default 1.2)")
    ap.add_argument("--every", type=int, default=10, help="keep every Nth instant (default 10)")
    ap.add_argument(
        "--out", type=Path, default=Path("."), help="folder for the figures (default: here)"
    )
    args = ap.parse_args()
    hull = hs.load_hull(ROOT / "meshes" / "fuselage_full.obj", mass=60000.0)
    h = hs.simulate(
        hull, -1.5, args.t_end, dt=0.002, pitch_rad=math.radians(8.0), forward_speed=60.0,
        free_pitch=True, slices=64, slicing="fixed", solver=hs.get_solver("mlm", gravity=True),
        fluid=hs.Fluid.sea(), aero="weight", friction=True, sections_every=args.every,
    )  # fmt: skip
    print(f"{len(h.t)} instants, {len(h.sections)} kept; ended by {h.stop_reason}")
    print("     t (s)   slices (kN)   faces (kN)   difference   peak face pressure (kPa)")
    peak = hs.loads.FacePeak(len(hull.faces))
    worst = 0.0
    top = float(np.max(np.abs(h.force)))
    for fp, rec in zip(h.face_pressures(hull), h.sections, strict=True):
        diff = (fp.total - rec.total) / top
        worst = max(worst, abs(diff))
        peak.add(fp)
        print(f"  {fp.t:8.3f}  {rec.total / 1e3:11.1f}  {fp.total / 1e3:11.1f}  {diff:+11.1e}"
              f"  {fp.pressure.max() / 1e3:12.1f}")  # fmt: skip
    i = int(np.argmax(peak.pressure))
    c = hs.loads.face_geometry(hull).centroid[i]
    print(f"largest difference {worst:.1e} of the peak force; peak face pressure "
          f"{peak.pressure[i] / 1e3:.1f} kPa at t = {peak.t[i]:.3f} s on face {i} "
          f"(x = {c[0]:.2f} m, y = {c[1]:+.2f} m)")  # fmt: skip
    fl = h.frame_loads(hull, spacing=0.5)
    pk = fl.peak()
    k = int(np.argmax(pk["vertical"]))
    print(f"frames every 0.5 m: {fl.bays} bays; the most loaded, x = {fl.edges[k]:.1f} to "
          f"{fl.edges[k + 1]:.1f} m, {pk['vertical'][k] / 1e3:.1f} kN at t = {pk['t'][k]:.3f} s; "
          f"the bays add up to the body's force within "
          f"{np.abs(fl.vertical.sum(axis=1) - fl.body).max():.1e} N")  # fmt: skip
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    title = "Fuselage ditching, 8 deg, 60 m/s, sink 1.5 m/s, mlm, sea"
    plots.save(
        plots.plot_face_pressure(
            hull, peak.pressure, f"{title}: peak pressure", label="peak pressure"
        ),
        out / "loads_peak_pressure.png",
    )
    plots.save(plots.plot_frame_loads(fl, f"{title}: frame bays (0.5 m)"), out / "loads_frames.png")
    print(f"wrote {out / 'loads_peak_pressure.png'} and {out / 'loads_frames.png'}")


if __name__ == "__main__":
    main()
