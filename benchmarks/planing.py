"""Steady planing of a prismatic hull: hullslice's strip theory against Savitsky's equations.

    pip install openplaning      # Savitsky's method (Savitsky 1964, 1976), as a library
    python benchmarks/planing.py [--solver zarnick] [--slices 64]

The hull is that of the example of Savitsky (1976) that ``openplaning`` ships: a prism of 15
degrees deadrise, 7.315 m beam and 24.38 m length, in water of 1025.87 kg/m^3, with its
centre of gravity b/7 above the keel. The example's loading (827.4 kN, 10.67 m ahead of
the transom) wets more keel than the hull has at these speeds, outside both methods; it is
loaded here with 400 kN, 6.0 m ahead of the transom, so that the wetted keel is 1.7 to 2.3
beams. For three speeds the script finds the equilibrium trim and heave of each method:

- Savitsky: ``openplaning.PlaningBoat.get_steady_trim`` (lift, friction drag and thrust
  through the centre of gravity);
- hullslice: the steady state of the 2D+t force (no acceleration, no pitch rate), where
  the vertical force carries the weight and the pitch moment about the centre of gravity
  is zero (``scipy.optimize.root`` on draft and trim). Friction is not modelled.

It prints, side by side, the trim (deg) and the wetted keel length (m, from the transom to
where the keel meets the calm water: the heave, as Savitsky's ``L_K``).
"""

from __future__ import annotations

import argparse
import math
import sys
import warnings

import numpy as np
from scipy.optimize import brentq

import hullslice as hs
from hullslice import shapes

#: The hull of Savitsky (1976)'s example, as openplaning's README gives it, loaded lighter.
BOAT = {
    "weight": 400000.0,  # N (the example: 827400)
    "beam": 7.315,  # m
    "length": 24.38,  # m
    "lcg": 6.0,  # m, from the transom (the example: 10.67)
    "beta": 15.0,  # deg
    "rho": 1025.87,  # kg/m^3
    "g": 9.8066,  # m/s^2
}
SPEEDS = (12.0, 16.0, 20.0)  # m/s


def savitsky(speed: float) -> tuple[float, float]:
    """Trim (deg) and wetted keel length (m) by Savitsky's method."""
    from openplaning import PlaningBoat

    b = BOAT
    vcg = b["beam"] / 7
    boat = PlaningBoat(
        speed, b["weight"], b["beam"], b["lcg"], vcg, 0.25 * b["length"], b["beta"], 0.0,
        vcg, b["lcg"], b["length"], rho=b["rho"], g=b["g"],
    )  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        boat.get_steady_trim()
        warnings.simplefilter("ignore")  # get_steady_trim sets the filters back
        boat.get_geo_lengths()
    return float(boat.tau), float(boat.L_K)


def hull(topsides: float = 3.0) -> hs.Hull:
    """The prism: a V bottom of the deadrise up to its chines, vertical topsides to
    ``topsides`` m above the keel, a flat transom at ``x = 0``."""
    b = BOAT
    chine = b["beam"] / 2 * math.tan(math.radians(b["beta"]))
    v, f = shapes.wedge_prism(b["length"], b["beam"], b["beta"], stations=3, sides=topsides - chine)
    v[:, 2] += chine  # the keel at z = 0
    mass = b["weight"] / b["g"]
    return hs.Hull.from_arrays(v, f, mass=mass, cg=(b["lcg"], b["beam"] / 7))


def hullslice_steady(body: hs.Hull, speed: float, solver: str, slices: int) -> tuple[float, float]:
    """Trim (deg) and wetted keel length (m) where the 2D+t force holds the hull steady: for
    each trim the draft that carries the weight (Brent), then the trim whose pitch moment
    about the centre of gravity is zero (a scan by 0.25 deg, then Brent)."""
    fluid = hs.Fluid(BOAT["rho"], BOAT["g"])
    solv = hs.get_solver(solver)
    weight = BOAT["weight"]

    def force(draft: float, tau_deg: float):
        return hs.compute_force(
            body, hs.Pose(draft, math.radians(tau_deg)), hs.Motion(0.0, speed),
            slices=slices, solver=solv, fluid=fluid, acceleration=0.0,
        )  # fmt: skip

    def draft_for(tau_deg: float) -> float:
        return brentq(lambda d: force(d, tau_deg).total - weight, 1e-3, 2.9, xtol=1e-6)

    def moment(tau_deg: float) -> float:
        return force(draft_for(tau_deg), tau_deg).moment

    taus = np.arange(0.5, 10.01, 0.25)
    m = [moment(t) for t in taus]
    for i in range(len(taus) - 1):
        if m[i] == 0 or m[i] * m[i + 1] < 0:
            tau = brentq(moment, taus[i], taus[i + 1], xtol=1e-4)
            draft = draft_for(tau)
            return float(tau), float(draft / math.sin(math.radians(tau)))
    raise RuntimeError(f"no trim between 0.5 and 10 deg balances the pitch moment at {speed} m/s")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--solver", default="zarnick", help="2D solver (default zarnick)")
    ap.add_argument("--slices", type=int, default=64, help="slices (default 64)")
    args = ap.parse_args()
    try:
        import openplaning  # noqa: F401
    except ImportError:
        print("this comparison needs Savitsky's method: pip install openplaning", file=sys.stderr)
        return 1
    body = hull()
    print(
        f"Savitsky (1976)'s prism, {BOAT['beta']:g} deg, beam {BOAT['beam']} m, "
        f"{BOAT['weight'] / 1e3:g} kN; hullslice solver {args.solver}, {args.slices} slices"
    )
    print(f"{'speed':>7} {'trim Savitsky':>14} {'trim hullslice':>15} {'L_K Savitsky':>13} "
          f"{'L_K hullslice':>14}")  # fmt: skip
    print(f"{'[m/s]':>7} {'[deg]':>14} {'[deg]':>15} {'[m]':>13} {'[m]':>14}")
    for u in SPEEDS:
        tau_s, lk_s = savitsky(u)
        tau_h, lk_h = hullslice_steady(body, u, args.solver, args.slices)
        print(f"{u:7.2f} {tau_s:14.3f} {tau_h:15.3f} {lk_s:13.3f} {lk_h:14.3f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
