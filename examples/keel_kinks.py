"""The force per metre along a faceted fuselage, with the keel's curvature averaged over a
slice and over half the beam.

    python examples/keel_kinks.py [--plot keel_kinks.png]

A fuselage of 48 points around (``hullslice.shapes.fuselage(points=48)``, 37.6 m, 60 t) at
0.5 m draft, pitched 6 degrees, 60 m/s forward and sinking at 1.5 m/s, by the strip theory
``zarnick``. With forward speed a section's acceleration includes the forward speed squared
times the keel line's curvature; a mesh's keel line is a polyline, whose curvature sits at
its kinks. Averaged over each slice only (the slice's width: hullslice's scheme before the
half-beam window), the curvature is spiky and the force does not converge with the slices
(the suction bound clips the spikes: the sum depends on which slices land on them);
averaged over at least half the body's beam (the default), it does.

It prints, at 32 to 512 fixed slices, the total force and the most negative force per
metre of both schemes.
"""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np

import hullslice as hs
from hullslice import shapes
from hullslice.slicing import assemble

COUNTS = (32, 64, 128, 256, 512)


def body() -> hs.Hull:
    v, f = shapes.fuselage(points=48)
    return hs.Hull.from_arrays(v, f, mass=60000.0, name="fuselage, 48 points around")


def force(hull: hs.Hull, slices: int, window: float) -> hs.ForceResult:
    """The force at the case's state with the curvature window ``window`` (beams)."""
    kept = assemble.KEEL_WINDOW_BEAMS
    assemble.KEEL_WINDOW_BEAMS = window
    try:
        return hs.compute_force(
            hull, hs.Pose(0.5, math.radians(6.0)), hs.Motion(-1.5, 60.0), slices=slices,
            solver="zarnick", slicing="fixed", acceleration=0.0,
        )  # fmt: skip
    finally:
        assemble.KEEL_WINDOW_BEAMS = kept


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--plot", metavar="FILE", help="draw the force per metre at 256 slices")
    args = ap.parse_args(argv)
    hull = body()
    schemes = (("over a slice", 0.0), ("over half the beam", assemble.KEEL_WINDOW_BEAMS))
    print("slices   curvature averaged over a slice     over half the beam (default)")
    print("           total [kN]   lowest [kN/m]       total [kN]   lowest [kN/m]")
    results = {}
    for n in COUNTS:
        row = []
        for label, window in schemes:
            r = force(hull, n, window)
            results[label, n] = r
            fpm = np.asarray(r.force) / np.asarray(r.sections.dx)
            row.append(f"{r.total / 1e3:12.1f} {fpm.min() / 1e3:15.1f}")
        print(f"{n:6d}   " + "       ".join(row))
    if args.plot:
        plot(results, schemes, args.plot)
        print(f"wrote {args.plot}")
    return 0


def plot(results, schemes, path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4.2))
    for label, _ in schemes:
        r = results[label, 256]
        wet = r.sections.wetted
        x = np.asarray(r.sections.x)[wet]
        fpm = (np.asarray(r.force) / np.asarray(r.sections.dx))[wet]
        ax.plot(x, fpm / 1e3, lw=1.0, label=f"curvature averaged {label}")
    title = "Faceted fuselage (48 points around), 6 deg, 60 m/s, zarnick, 256 slices"
    ax.set(xlabel="x along the body [m]", ylabel="force per metre [kN/m]", title=title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
