"""Gravity's correction of Wagner's contact in the MLM (option ``gravity_contact``).

    python examples/mlm_gravity.py

Wedges of 10, 20 and 30 degrees deadrise entering calm water at constant speed ``V``, each
at the effective Froude number ``Fr* = V / (sqrt(g h) sqrt(tan(beta)))`` set by ``g``:
the force per metre as ``F / (rho V^3 t)`` (``t = h / V``) by ``mlm`` without and with the
correction, their ratio, the contact's ratio ``c / c0`` (``1 - kappa / Fr*^2``,
``kappa = 0.00894``, derived in ``plugins/mlm/hullslice_mlm/gravity.py``), and for scale
the buoyancy ``rho g A`` of the option ``gravity`` in the same units (``1 / (Fr*^2
tan^2(beta))``). Each is the middle slice of a prism mesh, computed by hullslice.
"""

from __future__ import annotations

import math

import numpy as np

import hullslice as hs
from hullslice import shapes

RHO = 1000.0
SPEED = 5.0  # m/s
DEADRISES = (10.0, 20.0, 30.0)
FROUDE_STARS = (1.0, 2.0, 4.0, 8.0, math.inf)


def section(deadrise_deg: float, froude_star: float, **options) -> tuple[float, float, float]:
    """The middle slice's ``F / (rho V^3 t)``, wetted half-width and buoyancy coefficient."""
    k = math.tan(math.radians(deadrise_deg))
    p = 0.02 * k  # the contact near a quarter of the chine's half-width
    g = 0.0 if math.isinf(froude_star) else SPEED**2 / (froude_star**2 * p * k)
    v, f = shapes.wedge_prism(length=1.0, beam=0.4, deadrise_deg=deadrise_deg, sides=0.0)
    r = hs.compute_force(
        hs.Hull.from_arrays(v, f), p, -SPEED, slices=4, solver=hs.get_solver("mlm", **options),
        acceleration=0.0, fluid=hs.Fluid(RHO, g),
    )  # fmt: skip
    force = float((np.asarray(r.force) / np.asarray(r.sections.dx))[1])
    c = float(r.loads.diagnostics["wetted_half_width"][1])
    scale = RHO * SPEED**2 * p  # rho V^3 t
    return force / scale, c, RHO * g * p * p / k / scale


def main() -> int:
    print("  deadrise   Fr*   F/(rho V^3 t): mlm   +contact   (ratio)   c/c0   buoyancy")
    for deg in DEADRISES:
        for fr in FROUDE_STARS:
            f0, c0, buoy = section(deg, fr)
            f1, c1, _ = section(deg, fr, gravity_contact=True)
            name = "inf" if math.isinf(fr) else f"{fr:g}"
            print(
                f"  {deg:6.0f}   {name:>5}   {f0:14.3f}   {f1:8.3f}   ({f1 / f0:.4f})"
                f"   {c1 / c0:.4f}   {buoy:8.3f}"
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
