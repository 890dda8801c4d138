"""The Modified Logvinovich Model (MLM) for hullslice: pressures on the real body.

Korobkin (2004), "Analytical models of water impact", Eur. J. Appl. Math. 15, 821-838,
as the momentum-form solver ``mlm``. Wagner's theory finds the wetted width of a section
well and its force badly at moderate deadrise (its flat plate gives a 30-degree wedge
about 1.5 times the nonlinear force). The MLM keeps Wagner's contact and evaluates the
pressure on the real body.

Per side of a section with its bottom at height ``f(y)`` above the keel, ``y`` the
distance from the keel, penetration ``h`` and penetration speed ``V = dh/dt`` (down):

- **Contact.** Wagner's condition on the side's own contour,
  ``integral_0^{pi/2} f(c sin t) dt = (pi / 2) h``, gives the wetted half-width ``c`` and
  ``c' = dc/dh`` (:mod:`hullslice.solvers.contour`).
- **Pressure.** Logvinovich's potential on the body, ``phi = -V (sqrt(c^2 - y^2) + f - h)``,
  in Bernoulli's equation with the exact body condition:

      p / rho = dV/dt (sqrt(c^2 - y^2) + f - h)
              + V^2 [c c' / sqrt(c^2 - y^2) - 1/2 - y^2 / (2 (c^2 - y^2) (1 + f'^2))].

  The bracket is negative near the spray root (it falls to minus infinity there); the
  force per metre is the integral, over ``dy``, of its positive part (Korobkin 2004): from
  the keel to the point ``y*`` where the bracket changes sign, or, on a side steeper than
  ``atan(pi) = 72.3`` deg at the keel (where ``c' < 1/2`` makes it negative), from where
  it turns positive to ``y*``.
- **Momentum form.** The ``dV/dt`` term is an added mass,
  ``m_a = rho integral_0^{y*} (sqrt(c^2 - y^2) + f - h) dy`` both sides, on the left of the
  body's equations of motion; the bracket's integral times ``rho`` is the coefficient of
  ``v^2`` (hullslice's ``rate``): ``f = rate v^2 - m_a a`` per metre (``a`` up, ``v < 0``
  down), the ``v^2`` term dropped on a section leaving the water. At constant speed a
  wedge of deadrise ``beta`` (``k = tan(beta)``, ``c = pi h / (2 k)``) gets, with
  ``s = sin(t*)`` at the sign change,

      f = 2 rho V^2 c [c' t* - s / 2 - (atanh(s) - s) / (2 (1 + k^2))],   c' = pi / (2 k),

  less the same bracket at the start of the positive part on a steep wedge
  (:func:`wedge_force`), which tends to Wagner's ``rho pi c c' V^2`` as ``beta -> 0``.
- **A sharp edge** (a chine or a knuckle: the bottom meets the section's widest point at
  a deadrise below ``smooth_edge_deg``, or a side as steep as the continuation from its
  keel on, a steep wedge's): once ``c`` passes the edge the flow separates.
  The contact goes on along a fictitious body continuing the bottom from the edge
  (Tassin, Korobkin & Cooker 2014, Appl. Ocean Res. 48, 33-41: the fictitious body
  continuation), a straight line at the deadrise ``continuation`` (``"tangent"``: the
  bottom's own slope at the edge), and the pressure is integrated over the real body
  only (``y`` up to the edge).
- **A smooth widest point** (a round section, whose side is steeper than
  ``smooth_edge_deg`` there): the flow does not separate. The side leaves its contour for
  the same straight fictitious line where it first becomes as steep as the continuation
  (on a circle at the default 57.5 deg, ``s/D = 0.107``), so that the contact goes on
  growing (on the circle itself Wagner's contact would stop at the widest point), and the
  pressure is integrated over the real body up to its widest point; the load falls
  steadily towards the line's drag. A section wholly under water keeps its added mass.
- **Gravity** (option ``gravity = true``): the hydrostatic pressure ``rho g`` times the
  depth below the calm water on the wetted contour, integrated as the section's area below
  the calm water (a vertical force, buoyancy).
- **Gravity's first-order correction** (``gravity = "hulin"``: the buoyancy and both
  terms below, after the approach of Hulin et al. 2022; derived in
  :mod:`hullslice_mlm.gravity`). *The contact*: gravity pulls the raised free surface
  down, so the contact is Wagner's at the penetration ``h (1 - delta)``, to first order
  exactly for a section ``f = A y^n`` at constant speed:
  ``delta = lambda(m) g h^2 / (m V^2 c)``, ``m = c' h / c = 1/n`` (a wedge's
  ``delta = kappa / Fr*^2``, ``Fr*^2 = V^2 / (g h tan(beta))``, ``kappa = 0.00894``), any
  other section by the power law of its own ``m``; ``c'`` times ``1 - (3 - m) delta``
  (quasi-steady, at the current speed); ``delta`` is held at 0.2, and such sections
  flagged. *The gravity potential's pressure* ``p1 = -rho phi1_t = rho g h S_m(y / c)``
  on the same points as the rest of the pressure (up to the velocity term's change of
  sign), a force normal to the keel line that does not depend on ``V`` at a given ``h``
  (``extra``: on wedges of 10 to 30 deg 0.12 to 0.14 buoyancies ``rho g h^2 / tan(beta)``,
  0.105 over the whole disc); on entering sections (``v < 0``) only.
  Neither the hydrostatic pressure nor ``p1`` is in the returned ``SectionPressures``,
  whose points carry the ``v^2`` and acceleration terms only.

Sections are flagged (``reason``) where the bottom turns back down (a re-entrant
contour: the MLM takes the contour's running maximum) and where the section Froude number
``|v| / sqrt(g h)`` is below ``froude_min``; a separation or a continuation is modelled,
not flagged (diagnostics ``separated``, ``continued``, ``submerged``).
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import numpy as np

from hullslice import AddedMass
from hullslice.solvers import join_reasons
from hullslice.solvers.base import MomentumFormSolver, SectionPressures
from hullslice.solvers.contour import submerged_parts

from .contours import (
    WU,
    RealBottom,
    U,
    contact,
    continued_contours,
    side_contours,
    sign_change,
)
from .gravity import DELTA_MAX, contact_shift, disc_pressure, growth_exponent
from .options import check_options

__all__ = [
    "CONTINUATION",
    "CROSS_FLOW_DRAG",
    "MLM",
    "SMOOTH_EDGE_DEG",
    "continuation_for_drag",
    "wedge_force",
]
__version__ = "0.1.0"

#: The separated section's drag coefficient that sets the default continuation:
#: Zarnick's (1978) cross-flow drag after the chine, ``C_D,c rho b v^2`` per metre with
#: ``b`` the half-beam (Keuning 1994 gives 1.33 for the same drag).
CROSS_FLOW_DRAG = 1.0


def continuation_for_drag(drag: float) -> float:
    """The continuation's deadrise (deg) whose separated section, entering deep at constant
    speed, carries the cross-flow drag ``drag rho b V^2`` per metre (``b`` the half-beam).

    Far past the edge the contact on a straight continuation of deadrise ``beta_c`` grows
    as a wedge's, ``c' -> pi / (2 tan(beta_c))``, and ``c >> b``: the velocity term's
    pressure tends to ``rho V^2 (c' - 1/2)`` over the whole real width ``2 b``, a force of
    ``rho V^2 b (pi / tan(beta_c) - 1)``. So ``tan(beta_c) = pi / (1 + drag)``.
    """
    return math.degrees(math.atan(math.pi / (1.0 + drag)))


#: Default deadrise of the fictitious body past a sharp edge, deg: the continuation whose
#: late drag is Zarnick's cross-flow drag (57.52 deg; Keuning's 1.33 gives 53.4 deg).
CONTINUATION: str | float = continuation_for_drag(CROSS_FLOW_DRAG)

#: A side meeting its widest point steeper than this (deg) is smooth there.
SMOOTH_EDGE_DEG = 75.0


def wedge_force(deadrise: float, penetration: float, speed: float, rho: float = 1000.0) -> float:
    """The MLM force per metre on a wedge at constant speed (Korobkin 2004), N/m.

    Parameters
    ----------
    deadrise : float
        Deadrise angle, rad, in (0, pi/2).
    penetration : float
        Depth of the keel below the calm water, m.
    speed : float
        Entry speed, m/s (down, positive).
    rho : float
        Water density, kg/m^3.
    """
    k = math.tan(deadrise)
    cp = math.pi / (2.0 * k)
    c = cp * penetration

    def bracket(t: float) -> float:  # the velocity term's pressure times cos(t)
        return cp - 0.5 * math.cos(t) - math.sin(t) ** 2 / (2.0 * math.cos(t) * (1.0 + k * k))

    def root(lo: float, hi: float) -> float:  # the sign change in (lo, hi)
        rising = bracket(lo) <= 0.0
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if (bracket(mid) > 0.0) != rising else (lo, mid)
        return 0.5 * (lo + hi)

    def primitive(t: float) -> float:  # integral of bracket from 0 to t
        s = math.sin(t)
        return cp * t - 0.5 * s - (math.atanh(s) - s) / (2.0 * (1.0 + k * k))

    top = 0.5 * math.pi * (1.0 - 1e-15)
    t_a = 0.0
    if bracket(0.0) <= 0.0:  # steeper than atan(pi): the bracket's maximum, where
        # d/dt = sin(t) (1/2 - (1 + cos^2 t) / (2 cos^2 t (1 + k^2))) vanishes
        t_peak = math.acos(1.0 / k)
        if bracket(t_peak) <= 0.0:
            return 0.0
        t_a = root(0.0, t_peak)
        t_b = root(t_peak, top)
    else:
        t_b = root(0.0, top)
    return 2.0 * rho * speed**2 * c * (primitive(t_b) - primitive(t_a))


class MLM(MomentumFormSolver):
    """The Modified Logvinovich Model (Korobkin 2004) with flow separation.

    Parameters
    ----------
    section_method : str, optional
        ``"auto"`` (default: each section's own contour, the equivalent wedge on a flat
        bottom), ``"contour"`` or ``"wedge"`` (the equivalent wedge of every section, its
        chine at the section's widest point).
    continuation : str or float, optional
        The fictitious body past a sharp edge: ``"tangent"`` (the bottom's slope at the
        edge) or its deadrise in degrees, in (0, 90), steeper than the bottom at every
        sharp edge met (default :data:`CONTINUATION`).
    smooth_edge_deg : float, optional
        A side meeting its widest point at a deadrise above this (deg, in (0, 90]) is
        smooth there (no separation); default 75.
    gravity : bool or str, optional
        False (default): no gravity in the water; True: the hydrostatic pressure
        (buoyancy); ``"hulin"``: the buoyancy and gravity's first-order correction of the
        flow, the contact and the gravity potential's pressure
        (:mod:`hullslice_mlm.gravity`).
    froude_min : float, optional
        Smallest section Froude number ``|v| / sqrt(g h)`` inside the range (default 2),
        where ``gravity`` is off (with it the hydrostatic force is in the load).
    """

    name = "mlm"
    description = (
        "Modified Logvinovich Model (Korobkin 2004): Wagner's contact, the pressure on the "
        "real body, separation at sharp edges on a fictitious body, pressures returned"
    )
    models_separation = True
    positive_pressure = True
    gives_pressures = True
    own_checks = ("continuation", "smooth_edge_deg", "gravity", "froude_min")
    options: ClassVar[dict[str, Any]] = {
        "section_method": "auto",
        "continuation": CONTINUATION,
        "smooth_edge_deg": SMOOTH_EDGE_DEG,
        "gravity": False,
        "froude_min": 2.0,
    }

    def __init__(self, **options: Any) -> None:
        super().__init__(**options)
        self._cont_tan, self._cont_given = check_options(self, options)

    # -- the solver ------------------------------------------------------------------------

    def added_mass(self, sections, velocity, fluid) -> AddedMass:
        n = len(sections)
        p = np.asarray(sections.penetration, dtype=np.float64)
        v = np.asarray(velocity, dtype=np.float64)
        raw, ds, last, extent, edge_in, reentrant, wedge = side_contours(
            sections, self.settings["section_method"]
        )
        g, step, e, line, sharp, smooth, (y_last, s_last) = continued_contours(
            sections,
            raw,
            ds,
            last,
            extent,
            edge_in,
            self.settings,
            self._cont_tan,
            self._cont_given,
        )
        pen = np.broadcast_to(p, (2, n))
        c, cp, capped, i_end = contact(g, step, pen, edge_in, line)
        shift = held = np.zeros((2, n))
        hulin = self.settings["gravity"] == "hulin"
        if hulin:  # Wagner's contact at h (1 - delta)
            m, grows = growth_exponent(pen, c, cp)
            shift, held, factor = contact_shift(pen, v, fluid.g, c, cp)
            if shift.any():
                c, cp, capped, i_end = contact(g, step, pen * (1.0 - shift), edge_in, line)
                cp = cp * factor  # quasi-steady: V and the growth exponent held
        # past the end of the continuation the contact and the added mass stay
        h_cap = i_end / (0.5 * np.pi) / (1.0 - shift)
        h = np.where(capped, np.minimum(h_cap, p), p)
        # the pressure: on the real body only, up to the velocity term's change of sign
        y_lim = np.where(edge_in, np.minimum(e, c), c)
        t_lim = np.arcsin(np.clip(y_lim / np.where(c > 0, c, 1.0), 0.0, 1.0))
        t_lim = np.minimum(t_lim, 0.5 * np.pi * (1.0 - 1e-12))

        body = RealBottom(raw, ds, y_last, s_last)  # its height and slope up to its widest
        t_a, t_star = sign_change(c, cp, body.slope, t_lim)
        tk = t_a[..., None] + (t_star - t_a)[..., None] * U
        wk = (t_star - t_a)[..., None] * WU
        yk = c[..., None] * np.sin(tk)
        fk, fpk = body(yk)
        cos = np.cos(tk)
        pv = cp[..., None] / cos - 0.5 - np.tan(tk) ** 2 / (2.0 * (1.0 + fpk**2))
        pa = c[..., None] * cos + fk - h[..., None]
        dy = c[..., None] * cos * wk
        rho = fluid.rho
        phi = (pv * dy).sum(axis=-1)  # (2, n), m
        ma = np.maximum((pa * dy).sum(axis=-1), 0.0)
        # the bound on suction is the pressure's, point by point: over the loaded width
        girth = dy.sum(axis=-1)
        added = rho * ma.sum(axis=0)
        rate = rho * np.maximum(phi, 0.0).sum(axis=0)
        extra = np.zeros(n)
        if hulin and fluid.g > 0:  # the gravity potential's pressure, rho g h S_m(y / c)
            entering = grows & (v < 0.0) & (c > 0)
            p_g = rho * fluid.g * pen[..., None] * disc_pressure(tk, m)
            extra = (np.where(entering[..., None], p_g, 0.0) * dy).sum(axis=(0, -1))
        vertical = np.zeros(n)
        if self.settings["gravity"]:
            area, _ = submerged_parts(sections)
            vertical = rho * fluid.g * area
        with np.errstate(divide="ignore", invalid="ignore"):
            froude = np.abs(v) / np.sqrt(fluid.g * p) if fluid.g > 0 else np.full(n, np.inf)
        fr_min = self.settings["froude_min"]
        separated = np.any(sharp & (c > e), axis=0)
        continued = np.any(smooth & (c > e), axis=0)
        submerged = np.any(capped & edge_in, axis=0)
        re_in = np.any(reentrant, axis=0)
        slow = (froude <= fr_min) & (not self.settings["gravity"])  # else buoyancy is in
        reason = join_reasons(
            n,
            [
                (slow, f"Fr = |v| / sqrt(g p) <= {fr_min:g} (gravity not negligible)"),
                (
                    re_in,
                    "re-entrant contour (the bottom turns back down): its running maximum used",
                ),
                (
                    np.any(held, axis=0),
                    f"kappa / Fr*^2 > {DELTA_MAX:g}: gravity's contact correction held there",
                ),
            ],
        )
        more = {"gravity_shift": 0.5 * (shift[0] + shift[1])} if hulin else {}
        pressure = SectionPressures(
            y=np.moveaxis(yk, 0, 1),
            z=np.moveaxis(fk, 0, 1),
            weight=np.moveaxis(dy, 0, 1),
            velocity_coefficient=rho * np.moveaxis(pv, 0, 1),
            acceleration_coefficient=rho * np.moveaxis(pa, 0, 1),
        )
        return AddedMass(
            added_mass=added,
            rate=rate,
            valid=reason == "",
            reason=reason,
            extra=extra,
            vertical=vertical,
            diagnostics={
                "wetted_half_width": 0.5 * (c[0] + c[1]),
                "pressure_half_width": 0.5 * (c * np.sin(t_star)).sum(axis=0),
                "pressure_start": 0.5 * (c * np.sin(t_a)).sum(axis=0),
                "edge_half_width": 0.5 * (e[0] + e[1]),
                "separated": separated.astype(np.float64),
                "continued": continued.astype(np.float64),
                "submerged": submerged.astype(np.float64),
                "froude": froude,
                "buoyancy": vertical,
                # the equivalent wedge is no contour: a flat bottom's is flagged
                "contour": (~wedge).astype(np.float64),
                **more,
            },
            girth=girth.sum(axis=0),
            pressure=pressure,
        )
