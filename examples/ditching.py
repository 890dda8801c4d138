"""A generic narrow-body fuselage ditching at 60 m/s with a 1.5 m/s sink rate.

    python examples/ditching.py [--solver zarnick] [--slices 64] [--dt 0.004] [--t-end 0.3]
                                [--free-pitch] [--out FOLDER]

Runs the full-scale fuselage of meshes/ at 0, 4 and 8 degrees of pitch (nose up) with the
strip theory ``zarnick`` by default, prints the peak force of each, and writes
ditching_footprint.png (the wetted footprint over time) and ditching_history.png (the
8-degree history: force, pitch, draft) into the folder --out (default: the current
folder). Mass 60 t with a uniform density; wing lift is not modelled (the whole weight is
on the fuselage).
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import hullslice as hs
from hullslice import plots

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--slices", type=int, default=64, help="slices (default 64)")
    ap.add_argument("--dt", type=float, default=0.004, help="time step in s (default 0.004)")
    ap.add_argument("--t-end", type=float, default=0.3, help="duration in s (default 0.3)")
    ap.add_argument("--free-pitch", action="store_true", help="integrate the pitch")
    ap.add_argument("--solver", default="zarnick", help="2D solver (default zarnick)")
    ap.add_argument(
        "--out", type=Path, default=Path("."), help="folder for the figures (default: here)"
    )
    args = ap.parse_args()

    hull = hs.load_hull(ROOT / "meshes" / "fuselage_full.obj", mass=60000.0)
    histories, labels = [], []
    for deg in (0.0, 4.0, 8.0):
        h = hs.simulate(
            hull,
            -1.5,
            args.t_end,
            dt=args.dt,
            pitch=math.radians(deg),
            forward_speed=60.0,
            free_pitch=args.free_pitch,
            slices=args.slices,
            solver=args.solver,
        )
        pk = h.peak
        print(
            f"pitch {deg:3.0f} deg: peak force {pk['force'] / 1e3:8.1f} kN at t = {pk['t']:.3f} s, "
            f"{pk['acceleration'] / 9.81:+.2f} g, pitch moment {pk['moment'] / 1e3:9.1f} kN m; "
            f"pitch at the end {math.degrees(h.pitch[-1]):.2f} deg, ended by {h.stop_reason}, "
            f"largest flagged share {100 * h.max_flagged_share:.3g} %"
        )
        histories.append(h)
        labels.append(f"pitch {deg:g} deg")
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    x = hull.bounds[:, 0]
    footprint = plots.plot_footprint(histories, labels, (x[0], x[1]))
    plots.save(footprint, out / "ditching_footprint.png")
    plots.save(
        plots.plot_history(
            histories[-1], f"Fuselage, pitch 8 deg, 60 m/s, sink 1.5 m/s, {args.solver}"
        ),
        out / "ditching_history.png",
    )
    print(f"wrote {out / 'ditching_footprint.png'} and {out / 'ditching_history.png'}")


if __name__ == "__main__":
    main()
