"""Planing strip theory for hullslice: the momentum form with what a real hull needs.

The strip theory of Zarnick (1978, DTNSRDC report 78/032; extended by Keuning 1994 and
Garme 2005), as the momentum-form solver ``zarnick``. Per section, with the penetration
``p``, the penetration velocity ``v`` (negative down) and the wetted half-width ``c`` on
each side:

- **Momentum.** Added mass per metre ``m_a = rho pi (c_port + c_stbd)^2 / 8`` and its rate
  ``dm_a/dp``; hullslice forms ``m_a' v^2 - m_a a`` and drops the flux term on a section
  leaving the water (``v >= 0``), as Zarnick does. ``c`` follows the option ``pile_up``
  (Wagner's ``pi / 2`` by default, the wave rise of Zarnick's added mass) and, on a section
  that is not a wedge (a fuselage's round bottom), the section's own contour by Wagner's
  condition (``section_method``, see :mod:`hullslice.solvers.contour`).
- **Flow separation at the chine.** Once the spray root reaches the chine on a side (its
  ``c`` at the half-width of the section's part), that side's ``c`` stays there
  (``dc/dp = 0``: the added mass is frozen at its chine value) and a cross-flow drag takes
  over, ``C_D,c rho b v^2`` per metre (``b`` half the wetted width, on a section moving
  down). ``C_D,c = 1.0`` by default (Zarnick 1978; Keuning 1994 proposes 1.33).
- **Buoyancy.** ``a_B rho g A`` per metre, ``A`` the area below the calm water of the
  section's part that the entry is on (one float of a catamaran),
  with the empirical factor ``a_B = 0.5`` by default (Zarnick 1978, at planing speeds;
  ``a_B = 1`` is the full hydrostatic force of a body at rest).
- **Transom.** Behind the transom there is no section, so no force: the momentum leaves
  with the flow (the planes behind it are dry).

Gravity on the body is hullslice's; the buoyancy here is the water's hydrostatic force.
The flow separation and the buoyancy are modelled, so the solver flags neither a section
past its chine nor one whose Froude number is low; it flags a section whose whole area is
under the water (the strip theory of a planing bottom does not describe it).
"""

from __future__ import annotations

import math
from numbers import Real
from typing import Any, ClassVar

import numpy as np

from hullslice import AddedMass, InputError, MomentumSolver
from hullslice.solvers import join_reasons
from hullslice.solvers.section_parts import submerged_shares

__all__ = ["Zarnick"]
__version__ = "0.1.0"


class Zarnick(MomentumSolver):
    """Planing strip theory (Zarnick 1978): momentum, separation, cross-flow drag, buoyancy.

    Parameters
    ----------
    pile_up : str or float, optional
        The pile-up law (default ``"wagner"``, ``gamma = pi / 2``).
    section_method : str, optional
        ``"auto"`` (default), ``"wedge"`` or ``"contour"``, see
        :class:`hullslice.MomentumSolver`.
    cross_flow_drag : float, optional
        Cross-flow drag coefficient ``C_D,c`` after the chine, >= 0 (default 1.0, Zarnick
        1978).
    buoyancy_factor : float, optional
        Buoyancy reduction factor ``a_B`` in [0, 1] (default 0.5, Zarnick 1978).
    """

    name = "zarnick"
    description = (
        "Planing strip theory (Zarnick 1978): momentum form, separation at the chine with "
        "cross-flow drag, buoyancy, round sections by Wagner's condition"
    )
    models_separation = True
    own_checks = ("cross_flow_drag", "buoyancy_factor")  # zero is allowed
    options: ClassVar[dict[str, Any]] = {
        "pile_up": "wagner",
        "section_method": "auto",
        "cross_flow_drag": 1.0,
        "buoyancy_factor": 0.5,
    }

    def __init__(self, **options: Any) -> None:
        super().__init__(**options)
        self.settings["cross_flow_drag"] = self._coefficient("cross_flow_drag", 0.0, math.inf)
        self.settings["buoyancy_factor"] = self._coefficient("buoyancy_factor", 0.0, 1.0)

    def _coefficient(self, key: str, lo: float, hi: float) -> float:
        value = self.settings[key]
        ok = isinstance(value, Real) and not isinstance(value, bool)
        v = float(value) if ok else math.nan
        if not (math.isfinite(v) and lo <= v <= hi):
            span = f"in [{lo:g}, {hi:g}]" if math.isfinite(hi) else f">= {lo:g}"
            raise InputError(
                f"solver 'zarnick': option {key}={value!r} is not a finite number {span} "
                f"(default {self.options[key]!r})"
            )
        return v

    def added_mass(self, sections, velocity, fluid) -> AddedMass:
        n = len(sections)
        v = np.asarray(velocity, dtype=np.float64)
        t = self.momentum_terms(sections, fluid)
        b = t["wetted_half_width"]
        separated = t["past_chine"]
        drag = np.where(
            separated & (v < 0.0), self.settings["cross_flow_drag"] * fluid.rho * b * v * v, 0.0
        )
        area, whole, breadth = submerged_shares(sections)
        buoyancy = self.settings["buoyancy_factor"] * fluid.rho * fluid.g * area
        under = (whole > 0) & (area >= (1.0 - 1e-9) * whole)
        reason = join_reasons(
            n, [(under, "the whole section is under the water (not a planing bottom)")]
        )
        return AddedMass(
            added_mass=t["added_mass"],
            rate=t["rate"],
            valid=reason == "",
            reason=reason,
            extra=drag,
            vertical=buoyancy,  # hydrostatic: vertical, whatever the keel's slope
            diagnostics={
                "gamma": t["gamma"],
                "wetted_half_width": b,
                "chine_half_width": t["chine_half_width"],
                "separated": separated.astype(np.float64),
                "cross_flow_drag": drag,
                "submerged_area": area,
                "buoyancy": buoyancy,
                "contour": t["contour"].astype(np.float64),
            },
            girth=breadth,  # the bound on suction: the wetted bottom's breadth
        )
