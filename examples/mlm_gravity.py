"""Gravity's first-order correction in the MLM (option ``gravity = "hulin"``).

    python examples/mlm_gravity.py

Wedges of 10, 20 and 30 degrees deadrise entering calm water at constant speed ``V``, each
at the effective Froude number ``Fr* = V / (sqrt(g h) sqrt(tan(beta)))`` set by ``g``:
the force per metre as ``F / (rho V^3 t)`` (``t = h / V``) by ``mlm`` without gravity,
with gravity's correction of the contact alone, with the contact and the gravity
potential's own pressure ``-rho phi1_t`` (the complete first-order correction of the
water's flow; derived in ``plugins/mlm/hullslice_mlm/gravity.py``) and its ratio to the
first, the contact's ratio ``c / c0`` (``1 - kappa / Fr*^2``, ``kappa = 0.00894``), and
the buoyancy ``rho g A`` in the same units (``1 / (Fr*^2 tan^2(beta))``), which
``gravity = "hulin"`` adds too. Each is the middle slice of a prism mesh, computed by
hullslice.
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
HEADER = (
    "  deadrise   Fr*   F/(rho V^3 t): mlm" + "   +contact   +pressure   (ratio)   c/c0   buoyancy"
)


def section(deadrise_deg: float, froude_star: float, **options) -> dict[str, float]:
    """The middle slice's forces per metre in units of ``rho V^3 t``: the total, the
    gravity potential's pressure (``extra``) and the buoyancy (``vertical``); its wetted
    half-width."""
    k = math.tan(math.radians(deadrise_deg))
    p = 0.02 * k  # the contact near a quarter of the chine's half-width
    g = 0.0 if math.isinf(froude_star) else SPEED**2 / (froude_star**2 * p * k)
    v, f = shapes.wedge_prism(length=1.0, beam=0.4, deadrise_deg=deadrise_deg, sides=0.0)
    r = hs.compute_force(
        hs.Hull.from_arrays(v, f), p, -SPEED, slices=4, solver=hs.get_solver("mlm", **options),
        acceleration=0.0, fluid=hs.Fluid(RHO, g),
    )  # fmt: skip
    d = r.loads.diagnostics
    scale = RHO * SPEED**2 * p  # rho V^3 t
    return {
        "force": float((np.asarray(r.force) / np.asarray(r.sections.dx))[1]) / scale,
        "pressure": float(d["extra_force"][1]) / scale,
        "buoyancy": float(d["vertical_force"][1]) / scale,
        "c": float(d["wetted_half_width"][1]),
    }


def main() -> int:
    print(HEADER)
    for deg in DEADRISES:
        for fr in FROUDE_STARS:
            off = section(deg, fr)
            on = section(deg, fr, gravity="hulin")
            flow = on["force"] - on["buoyancy"]  # contact and pressure, no buoyancy
            contact = flow - on["pressure"]
            name = "inf" if math.isinf(fr) else f"{fr:g}"
            print(
                f"  {deg:6.0f}   {name:>5}   {off['force']:14.3f}   {contact:8.3f}"
                f"   {flow:9.3f}   ({flow / off['force']:.4f})   {on['c'] / off['c']:.4f}"
                f"   {on['buoyancy']:8.3f}"
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
