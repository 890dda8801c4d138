"""The force per metre along a public airliner mesh, with the keel's curvature averaged over
a slice and over half the beam.

    python examples/keel_kinks_airliner.py [--plot keel_kinks_airliner.png]

The mesh is ``meshes/airliner/airliner.obj`` (a twin-engined narrow-body airliner, 17,456
faces, CC BY 3.0; see ``meshes/airliner/README.md``), scaled to 37.6 m, of which the part
within 3.2 m of the centreline is kept: the fuselage with its belly fairing and the wing
roots, without the nacelles (4.9 m out) and the outer wings. At 60 t, 0.5 m draft, pitched
6 degrees, 60 m/s forward and sinking at 1.5 m/s, the aft 12.7 m of the keel are wetted:
the tail cone's upsweep, where the keel line of the mesh is a polyline with kinks.

With forward speed a section's acceleration includes the forward speed squared times the
keel line's curvature, which sits at the kinks. Averaged over each slice only (the slice's
width: hullslice's scheme before the half-beam window), the force per metre has spikes
where a slice holds a kink, and the total grows with the slices; averaged over at least
half the body's beam (the default, here 3.2 m), it has none, and the total converges.

It prints, for ``zarnick`` and ``mlm`` at 32 to 512 fixed slices, each scheme's total
force and the variation of its force per metre: the sum of its changes between
neighbouring wetted slices over its largest value. A load that rises once from zero to its
peak and falls once has a variation of about 2 (less where the foremost slice still
carries load, more with zarnick's suction, a negative plateau aft); each spike adds twice
its height over the peak.
"""

from __future__ import annotations

import argparse
import math
import sys
import warnings
from pathlib import Path

import numpy as np

import hullslice as hs
from hullslice.slicing import assemble

MESH = Path(__file__).resolve().parents[1] / "meshes" / "airliner" / "airliner.obj"
KEEP_BOX = (-25.0, 25.0, -3.2, 3.2, -5.0, 15.0)  # m, body frame after scaling
COUNTS = (32, 64, 128, 256, 512)
SOLVERS = ("zarnick", "mlm")


def body() -> hs.Hull:
    with warnings.catch_warnings():  # the one line saying what the box kept
        warnings.simplefilter("ignore", hs.MeshRepairWarning)
        return hs.load_hull(MESH, length=37.6, keep_box=KEEP_BOX, mass=60000.0)


def force(hull: hs.Hull, solver: str, slices: int, window: float) -> hs.ForceResult:
    """The force at the case's state with the curvature window ``window`` (beams)."""
    kept = assemble.KEEL_WINDOW_BEAMS
    assemble.KEEL_WINDOW_BEAMS = window
    try:
        return hs.compute_force(
            hull, hs.Pose(0.5, math.radians(6.0)), hs.Motion(-1.5, 60.0), slices=slices,
            solver=solver, slicing="fixed", acceleration=0.0,
        )  # fmt: skip
    finally:
        assemble.KEEL_WINDOW_BEAMS = kept


def per_metre(r: hs.ForceResult) -> tuple[np.ndarray, np.ndarray]:
    """The wetted slices' positions (m) and force per metre (N/m), aft to fore."""
    wet = np.asarray(r.sections.wetted)
    x = np.asarray(r.sections.x)[wet]
    fpm = (np.asarray(r.force) / np.asarray(r.sections.dx))[wet]
    order = np.argsort(x)
    return x[order], fpm[order]


def variation(r: hs.ForceResult) -> float:
    """The sum of the changes of force per metre between neighbouring wetted slices, over
    the largest force per metre (about 2 for a load that rises once and falls once)."""
    _, fpm = per_metre(r)
    return float(np.abs(np.diff(fpm)).sum() / np.abs(fpm).max())


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--plot", metavar="FILE", help="draw the force per metre at 256 slices")
    args = ap.parse_args(argv)
    hull = body()
    schemes = (("over a slice", 0.0), ("over half the beam", assemble.KEEL_WINDOW_BEAMS))
    results = {}
    for solver in SOLVERS:
        print(f"{solver}:")
        print("slices   curvature averaged over a slice     over half the beam (default)")
        print("           total [kN]   variation           total [kN]   variation")
        for n in COUNTS:
            row = []
            for label, window in schemes:
                r = force(hull, solver, n, window)
                results[solver, label, n] = r
                row.append(f"{r.total / 1e3:12.1f} {variation(r):11.2f}")
            print(f"{n:6d}   " + "       ".join(row))
    if args.plot:
        plot(results, schemes, args.plot)
        print(f"wrote {args.plot}")
    return 0


def plot(results, schemes, path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 1, figsize=(8, 6.4), sharex=True)
    for ax, solver in zip(axes, SOLVERS, strict=True):
        for label, _ in schemes:
            x, fpm = per_metre(results[solver, label, 256])
            ax.plot(x, fpm / 1e3, lw=1.0, label=f"curvature averaged {label}")
        ax.set(ylabel="force per metre [kN/m]", title=f"{solver}, 256 slices")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[-1].set(xlabel="x along the body [m]")
    fig.suptitle("Public airliner mesh (17,456 faces) at 37.6 m, 6 deg, 60 m/s, -1.5 m/s")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
