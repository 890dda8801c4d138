"""A generic narrow-body fuselage ditching at 60 m/s with a 1.5 m/s sink rate: the whole impact.

    python examples/ditching.py [--solver mlm] [--slices 64] [--dt 0.002] [--t-end 1.5]
                                [--free-pitch] [--out FOLDER]

Runs the full-scale fuselage of meshes/ (60 t with a uniform density) at 0, 4 and 8 degrees
of pitch (nose up) in sea water (1025 kg/m^3), with the wing's lift equal to the weight at
touchdown (scaled with the speed squared and the angle of attack from then on) and the
water's friction (ITTC-57), by the Modified Logvinovich Model ``mlm`` with its hydrostatic
pressure by default (its round sections keep their load past their widest points, and
water ventilates before it pulls on the upswept tail cone). It prints the peak force of
each, and writes ditching_footprint.png (the wetted footprint over time) and
ditching_history.png (the 8-degree history: force, acceleration, velocity, draft, pitch)
into the folder --out (default: the current folder). The forward speed is held.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import hullslice as hs
from hullslice import plots
from hullslice.progress import terminal_progress

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--slices", type=int, default=64, help="slices (default 64)")
    ap.add_argument("--dt", type=float, default=0.002, help="time step in s (default 0.002)")
    ap.add_argument("--t-end", type=float, default=1.5, help="duration in s (default 1.5)")
    ap.add_argument("--free-pitch", action="store_true", help="integrate the pitch")
    ap.add_argument("--solver", default="mlm", help="2D solver (default mlm)")
    ap.add_argument(
        "--out", type=Path, default=Path("."), help="folder for the figures (default: here)"
    )
    args = ap.parse_args()

    hull = hs.load_hull(ROOT / "meshes" / "fuselage_full.obj", mass=60000.0)
    options = {"gravity": True} if args.solver == "mlm" else {}
    solver = hs.get_solver(args.solver, **options)
    histories, labels = [], []
    for deg in (0.0, 4.0, 8.0):
        # a progress line on a terminal's stderr (nothing when it is not one)
        with terminal_progress(f"pitch {deg:g} deg") as progress:
            h = hs.simulate(
                hull,
                -1.5,
                args.t_end,
                dt=args.dt,
                pitch_rad=math.radians(deg),
                forward_speed=60.0,
                free_pitch=args.free_pitch,
                slices=args.slices,
                slicing="fixed",
                solver=solver,
                fluid=hs.Fluid.sea(),
                aero="weight",
                friction=True,
                progress=progress,
            )
        pk = h.peak
        print(
            f"pitch {deg:3.0f} deg: peak force {pk['force'] / 1e3:8.1f} kN at t = {pk['t']:.3f} s, "
            f"{pk['acceleration'] / 9.81:+.2f} g, pitch moment {pk['moment'] / 1e3:9.1f} kN m; "
            f"pitch {math.degrees(min(h.pitch)):.2f} to {math.degrees(max(h.pitch)):.2f} deg, "
            f"friction up to {-min(h.friction) / 1e3:.1f} kN, ended by {h.stop_reason}, "
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
            histories[-1],
            f"Fuselage, pitch 8 deg, 60 m/s, sink 1.5 m/s, {args.solver}, sea, lift = weight",
        ),
        out / "ditching_history.png",
    )
    print(f"wrote {out / 'ditching_footprint.png'} and {out / 'ditching_history.png'}")


if __name__ == "__main__":
    main()
