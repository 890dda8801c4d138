"""The Modified Logvinovich Model against outside references at constant speed.

    python examples/mlm_validation.py [--plot cylinder.png]

Two references, each computed by hullslice on a prism mesh (every slice the 2D section):

- **Wedges** of 10 to 40 degrees deadrise entering calm water at constant speed ``V``,
  against the fully nonlinear similarity solution of Zhao & Faltinsen (1993, "Water entry
  of two-dimensional bodies", J. Fluid Mech. 246, 593-612), as tabulated in Faltinsen
  (2005, "Hydrodynamics of High-Speed Marine Vehicles", Cambridge, Table 8.3): the
  vertical force per metre as ``F / (rho V^3 t)`` and the largest pressure as
  ``C_p,max = p_max / (rho V^2 / 2)``. Wagner's flat-plate force is beside them.
- **A circular cylinder** of diameter ``D`` entering at constant speed, against the
  slamming coefficient ``C_s = F / (rho R V^2)`` that Campbell & Weynberg (1980, Offshore
  Technology Report OTH 80 033) fitted to their drop tests, in the form of DNV-RP-C205
  (section 8): ``C_s = 5.15 / (1 + 19 s / D) + 0.55 s / D`` at the penetration ``s``.
  ``zarnick`` (Wagner's momentum with the contour) is beside it.
"""

from __future__ import annotations

import argparse
import math
import sys
import warnings

import numpy as np

import hullslice as hs
from hullslice import shapes

RHO = 1000.0
SPEED = 5.0  # m/s

#: Zhao & Faltinsen (1993), Faltinsen (2005) Table 8.3: deadrise (deg), C_p,max and
#: F / (rho V^3 t).
SIMILARITY = (
    (10.0, 77.847, 213.980),
    (15.0, 33.271, 85.522),
    (20.0, 17.774, 42.485),
    (25.0, 10.691, 23.657),
    (30.0, 6.927, 14.139),
    (40.0, 3.266, 5.252),
)
#: Penetrations of the cylinder over its diameter.
S_OVER_D = (0.0025, 0.005, 0.01, 0.02, 0.05, 0.1, 0.15, 0.18, 0.2, 0.3, 0.5, 0.7, 1.0)


def campbell_weynberg(s_over_d: float) -> float:
    """Campbell & Weynberg's (1980) slamming coefficient, in DNV-RP-C205's form."""
    return 5.15 / (1.0 + 19.0 * s_over_d) + 0.55 * s_over_d


def wedge_run(deadrise_deg: float) -> tuple[float, float, float]:
    """For a wedge at constant speed: ``F / (rho V^3 t)`` of ``mlm`` and of Wagner, and the
    MLM's largest pressure coefficient (at a quarter of the chine's half-width)."""
    beta = math.radians(deadrise_deg)
    v, f = shapes.wedge_prism(length=1.0, beam=0.4, deadrise_deg=deadrise_deg, stations=3)
    hull = hs.Hull.from_arrays(v, f)
    p = 0.05 * math.tan(beta) * 2.0 / math.pi  # Wagner's contact at a quarter of the chine
    t = p / SPEED
    fluid = hs.Fluid(RHO, 0.0)
    scale = RHO * SPEED**3 * t
    r = hs.compute_force(hull, p, -SPEED, slices=2, solver="mlm", fluid=fluid, acceleration=0.0)
    w = hs.compute_force(hull, p, -SPEED, slices=2, solver="wagner", fluid=fluid, acceleration=0.0)
    assert r.pressures is not None
    cp = float(r.pressures.peak().max()) / (0.5 * RHO * SPEED**2)
    return r.total / scale, w.total / scale, cp


def cylinder_run(solver: str) -> np.ndarray:
    """The slamming coefficient of a cylinder (R = 0.5 m) at :data:`S_OVER_D`."""
    R = 0.5
    v, f = shapes.circular_cylinder(length=1.0, radius=R, points=720)
    hull = hs.Hull.from_arrays(v, f)
    fluid = hs.Fluid(RHO, 0.0)
    out = []
    for s in S_OVER_D:
        r = hs.compute_force(hull, 2 * R * s, -SPEED, slices=2, solver=solver, fluid=fluid,
                             acceleration=0.0)  # fmt: skip
        out.append(r.total / (RHO * R * SPEED**2))
    return np.array(out)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--plot", metavar="FILE", help="draw the cylinder's C_s into FILE")
    args = parser.parse_args(argv)
    warnings.simplefilter("ignore", hs.HullsliceWarning)

    print("Wedges at constant speed against Zhao & Faltinsen (1993), Faltinsen (2005) Table 8.3")
    print("  deadrise  F/(rho V^3 t): nonlinear   mlm   (ratio)  Wagner (ratio)"
          "   C_p,max: nonlinear    mlm  (ratio)")  # fmt: skip
    for deg, cp_ref, f_ref in SIMILARITY:
        f_mlm, f_wag, cp = wedge_run(deg)
        print(
            f"  {deg:6.0f}   {f_ref:22.3f}  {f_mlm:7.3f} ({f_mlm / f_ref:5.3f})  {f_wag:7.3f}"
            f" ({f_wag / f_ref:5.3f})   {cp_ref:18.3f}  {cp:7.3f} ({cp / cp_ref:5.3f})"
        )
    print("\nA circular cylinder at constant speed against Campbell & Weynberg (1980)")
    print("     s/D   C_s: C&W     mlm  (ratio)  zarnick  (ratio)")
    mlm, zar = cylinder_run("mlm"), cylinder_run("zarnick")
    for s, a, b in zip(S_OVER_D, mlm, zar, strict=True):
        ref = campbell_weynberg(s)
        print(f"  {s:6.4f}  {ref:10.3f}  {a:6.3f} ({a / ref:5.3f})  {b:7.3f} ({b / ref:5.3f})")
    if args.plot:
        plot(mlm, zar, args.plot)
        print(f"\nwrote {args.plot}")
    return 0


def plot(mlm: np.ndarray, zar: np.ndarray, path: str) -> None:
    """The cylinder's slamming coefficient against the penetration."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    s = np.array(S_OVER_D)
    fine = np.linspace(0.0, s[-1], 200)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(fine, [campbell_weynberg(x) for x in fine], "k-", label="Campbell & Weynberg (1980)")
    ax.plot(s, mlm, "o-", label="mlm")
    ax.plot(s, zar, "s--", label="zarnick")
    ax.axvline(0.18, color="0.6", lw=0.8, ls=":")
    ax.text(0.185, 5.6, "Wagner's contact at the\nwidest point", fontsize=8, color="0.4")
    ax.set(xlabel="penetration s / D", ylabel="slamming coefficient F / (rho R V^2)")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
