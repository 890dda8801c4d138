"""The pitch of a ditching fuselage over its first second, by the MLM and the strip theory.

    python examples/ditching_pitch.py [--t-end 1.0] [--plot ditching_pitch.png]

The generic narrow-body fuselage of meshes/ (60 t, uniform density) touches the water at
8 degrees nose up, 60 m/s forward and a 1.5 m/s sink rate, free in pitch (the forward
speed held; no wing lift: the whole weight is on the fuselage), with 64 fixed slices and a
4 ms step. Its round sections pass their widest points and the upswept tail cone enters
the water, whose curvature with the forward speed pulls sections down.

- ``mlm``: the load is the positive part of the MLM's pressure (water does not pull, it
  ventilates) and the round sections keep their load past their widest points;
- ``zarnick``: Wagner's momentum, the added mass frozen at the widest point and a cross-flow
  drag, and the inertia term's suction on the tail cone down to the water's vapour
  pressure (the bound of every momentum solver).

It prints the pitch, draft, vertical velocity and force of both every 0.1 s.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

import hullslice as hs
from hullslice.progress import terminal_progress

ROOT = Path(__file__).resolve().parents[1]
SOLVERS = ("mlm", "zarnick")


def run(solver: str, t_end: float) -> hs.History:
    hull = hs.load_hull(ROOT / "meshes" / "fuselage_full.obj", mass=60000.0)
    with terminal_progress(solver) as progress:  # a progress line on a terminal's stderr
        return hs.simulate(
            hull, -1.5, t_end, dt=0.004, pitch_rad=math.radians(8.0), forward_speed=60.0,
            free_pitch=True, slices=64, slicing="fixed", solver=solver, stop_on=(),
            progress=progress,
        )  # fmt: skip


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--t-end", type=float, default=1.0, help="duration in s (default 1.0)")
    ap.add_argument("--plot", metavar="FILE", help="draw the pitch and force histories")
    args = ap.parse_args(argv)
    runs = {name: run(name, args.t_end) for name in SOLVERS}
    heads = "  ".join(
        f"{name + ': pitch [deg]':>18} {'draft [m]':>9} {'w [m/s]':>8} {'F [kN]':>7}"
        for name in SOLVERS
    )
    print(f"  t [s]  {heads}")
    for t in np.arange(0.1, args.t_end + 1e-9, 0.1):
        cells = []
        for h in runs.values():
            ts = np.asarray(h.t)
            i = int(np.argmin(np.abs(ts - t)))
            cells.append(
                f"{math.degrees(h.pitch[i]):18.2f} {h.draft[i]:9.3f} {h.velocity[i]:8.2f} "
                f"{h.force[i] / 1e3:7.0f}"
            )
        print(f"  {t:5.2f}  " + "  ".join(cells))
    for name, h in runs.items():
        deg = np.degrees(np.asarray(h.pitch))
        span = f"{deg.min():.2f} to {deg.max():.2f} deg"
        print(f"{name}: pitch from {span}, ended by {h.stop_reason}")
    if args.plot:
        plot(runs, args.plot)
        print(f"wrote {args.plot}")
    return 0


def plot(runs: dict[str, hs.History], path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_p, ax_f) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    for name, h in runs.items():
        ax_p.plot(h.t, np.degrees(np.asarray(h.pitch)), label=name)
        ax_f.plot(h.t, np.asarray(h.force) / 1e3, label=name)
    ax_p.set(ylabel="pitch [deg] (nose up)")
    ax_f.set(xlabel="time from first contact [s]", ylabel="vertical force [kN]")
    for ax in (ax_p, ax_f):
        ax.grid(alpha=0.3)
        ax.legend()
    ax_p.set_title("Fuselage at 8 deg, 60 m/s, sink 1.5 m/s, free pitch, no lift")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
