"""A catamaran is the sum of its floats: the keel line of each separate piece.

    python examples/pieces.py

Two 1 m floats 0.4 m wide, 0.6 m apart (30 deg starboard with a level keel, 20 deg port
with its keel sloping by 0.03 over its length, 1 cm below the other's at the bow), at
0.07 m draft, sinking at 3 m/s and moving forward at 10 m/s, 16 fixed slices; the
acceleration prescribed (zero), so that each float alone moves as the pair does. Rising
forward, the port float is the lower everywhere; falling, the keels cross a third of the
way from the bow.

The reference is each float alone with its share of the mass, where it is in the pair
(2D+t sections of separate floats are separate wedges). It prints the pair's force and
the sum of the floats' with a keel line for each piece (the default) and with one keel line
for the whole body (the lower envelope of both floats, and the curvature's window half the
span across both: hullslice's scheme before).
"""

from __future__ import annotations

import numpy as np

import hullslice as hs
from hullslice import shapes
from hullslice.slicing import assemble, own_keel

SLICES, DRAFT = 16, 0.07
MOTION = hs.Motion(-3.0, 10.0, 0.0)


def floats(rise: float):
    """The two floats' vertices and faces, starboard then port."""
    vs, fs = shapes.wedge_prism(length=1.0, beam=0.4, deadrise_deg=30.0)
    vp, fp = shapes.wedge_prism(length=1.0, beam=0.4, deadrise_deg=20.0)
    vs = vs - np.array([0.0, 0.3, vs[:, 2].min()])
    vp = vp + np.array([0.0, 0.3, -vp[:, 2].min()])
    vp[:, 2] += rise * (vp[:, 0] - vp[:, 0].max()) - 0.01
    return (vs, fs), (vp, fp)


def _joined(rise: float):
    (vs, fs), (vp, fp) = floats(rise)
    return np.vstack([vs, vp]), np.vstack([fs, fp + len(vs)])


def pair_and_sum(rise: float, solver: str) -> tuple[float, float]:
    """The pair's force and the sum of its floats' alone (N)."""
    (vs, fs), (vp, fp) = floats(rise)
    pair = hs.Hull.from_arrays(*_joined(rise), mass=20.0, name="pair")
    low = min(vs[:, 2].min(), vp[:, 2].min())
    kw = dict(slices=SLICES, solver=solver, slicing="fixed", acceleration=0.0)
    total = hs.compute_force(pair, hs.Pose(DRAFT, 0.0), MOTION, **kw).total
    alone = 0.0
    for v, f in ((vs, fs), (vp, fp)):
        one = hs.Hull.from_arrays(v, f)
        one = one.with_mass(20.0 * one.volume / pair.volume)
        draft = DRAFT - (v[:, 2].min() - low)
        alone += hs.compute_force(one, hs.Pose(draft, 0.0), MOTION, **kw).total
    return total, alone


def one_line(fn, *args):
    """``fn(*args)`` with one keel line for the whole body and the window of its span."""
    kept_own, kept_window = assemble.own_keels, assemble.keel_window
    assemble.own_keels = lambda *a, **k: None
    assemble.keel_window = lambda hull: assemble.KEEL_WINDOW_BEAMS * float(hull.extents[1])
    try:
        return fn(*args)
    finally:
        assemble.own_keels, assemble.keel_window = kept_own, kept_window


def main() -> None:
    print(f"two floats at {DRAFT} m draft, 10 m/s forward, -3 m/s, {SLICES} fixed slices")
    n = own_keel.pieces(hs.Hull.from_arrays(*_joined(0.03))).n
    print(f"each float a piece of its own ({n} pieces)\n")
    print(f"{'port keel':>18} {'solver':>8} {'pair, one line':>15} {'pair, a line each':>18}"
          f" {'floats alone':>13}")  # fmt: skip
    print(f"{'':>18} {'':>8} {'[N]':>15} {'[N]':>18} {'[N]':>13}")
    for rise, name in ((0.03, "lower, rising fwd"), (-0.03, "crossing at 2/3")):
        for solver in ("zarnick", "mlm"):
            old, _ = one_line(pair_and_sum, rise, solver)
            new, alone = pair_and_sum(rise, solver)
            print(f"{name:>18} {solver:>8} {old:9.1f} ({old / alone - 1:+5.1%})"
                  f" {new:10.1f} ({new / alone - 1:+.0e}) {alone:13.1f}")  # fmt: skip


if __name__ == "__main__":
    main()
