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
  ``zarnick`` (Wagner's momentum with the contour) is beside it, and other published
  models of the same impact computed here on the exact circle (Wagner's contact from his
  condition in elliptic integrals): Wagner (1932), von Karman (1929), the flat plate's
  potential with the whole Bernoulli pressure, Wienke & Oumeraci's (2005, Coastal Eng. 52,
  435-462) formula for ``t <= D / (8 V)``, and the MLM's own pressure integrated on the
  exact circle (a check of the solver's sampled contour).
"""

from __future__ import annotations

import argparse
import math
import sys
import warnings

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

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


def circle_contact(s_over_r: float) -> tuple[float, float]:
    """Wagner's contact on the exact circle of radius 1 at the penetration ``s / R``:
    ``(c / R, dc/ds)``. Wagner's condition ``integral_0^{pi/2} f(c sin t) dt = pi s / 2`` on
    ``f = R - sqrt(R^2 - y^2)`` is ``s / R = 1 - (2 / pi) E(k)``, ``k = c / R`` (``E`` the
    complete elliptic integral of the second kind, modulus ``k``), so
    ``dc/ds = pi k / (2 (K(k) - E(k)))``; the contact reaches the widest point at
    ``s / D = 0.1817``."""
    k = brentq(lambda k: 1.0 - 2.0 / math.pi * ellipe(k * k) - s_over_r, 1e-12, 1.0 - 1e-15,
               xtol=1e-15)  # fmt: skip
    return k, math.pi * k / (2.0 * (ellipk(k * k) - ellipe(k * k)))


def circle_models(s_over_d: float) -> dict[str, float]:
    """The slamming coefficient ``F / (rho R V^2)`` of a circle at constant speed by other
    models (no gravity), at ``s / D``; each uses Wagner's contact on the exact circle but
    von Karman's and Wienke & Oumeraci's. ``x = c sin(t)`` along the contact."""
    e = 2.0 * s_over_d  # s / R
    c, cp = circle_contact(e)
    out = {"Wagner": math.pi * c * cp, "von Karman": math.pi * (1.0 - e)}  # d(pi c^2 / 2)/ds

    # the flat plate's potential -V sqrt(c^2 - x^2) and the whole Bernoulli pressure,
    # p / (rho V^2) = c c' / sqrt(c^2 - x^2) - x^2 / (2 (c^2 - x^2)) - 1 / 2, its positive part
    t = math.acos(min(1.0, 1.0 / (2.0 * cp)))
    out["plate, Bernoulli"] = 2.0 * (c * cp * t - 0.5 * c * math.atanh(math.sin(t)))

    def mlm_bracket(t: float) -> float:  # the MLM's pressure (Korobkin 2004) times cos(t)
        y = c * math.sin(t)  # on the circle 1 + f'^2 = 1 / (1 - y^2)
        return cp - 0.5 * math.cos(t) - math.sin(t) ** 2 * (1.0 - y * y) / (2.0 * math.cos(t))

    end = brentq(mlm_bracket, 0.0, 0.5 * math.pi * (1.0 - 1e-14), xtol=1e-15)
    out["MLM, exact circle"] = 2.0 * c * quad(mlm_bracket, 0.0, end, epsabs=1e-13, limit=200)[0]
    # Wienke & Oumeraci (2005), their Eq. for 0 <= t <= D / (8 V)
    if s_over_d <= 0.125:
        out["Wienke & Oumeraci"] = 2.0 * math.pi - 2.0 * math.sqrt(e) * math.atanh(
            math.sqrt(1.0 - e / 4.0)
        )
    return out


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
    print("\nOther models of the same impact (C_s and its ratio to Campbell & Weynberg's)")
    names = list(circle_models(S_OVER_D[0]))
    print("     s/D" + "".join(f"  {name:>19s}" for name in names))
    for s in (x for x in S_OVER_D if x <= 0.15):
        ref, row = campbell_weynberg(s), circle_models(s)
        cells = (f"{row[n]:11.3f} ({row[n] / ref:5.3f})" if n in row else f"{'':19s}"
                 for n in names)  # fmt: skip
        print(f"  {s:6.4f}" + "".join(f"  {cell}" for cell in cells))
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
    # where the solver's contact leaves the circle: the side as steep as the continuation
    k = math.sin(math.radians(float(hs.get_solver("mlm").settings["continuation"])))
    leave = 0.5 * (1.0 - 2.0 / math.pi * ellipe(k * k))
    ax.axvline(leave, color="0.6", lw=0.8, ls=":")
    ax.text(leave + 0.005, 5.6, "contact leaves the circle\nfor the continuation", fontsize=8,
            color="0.4")  # fmt: skip
    ax.axvline(0.1817, color="0.6", lw=0.8, ls=":")
    ax.text(0.187, 4.6, "Wagner's contact on the\ncircle at its widest point", fontsize=8,
            color="0.4")  # fmt: skip
    ax.set(xlabel="penetration s / D", ylabel="slamming coefficient F / (rho R V^2)")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
