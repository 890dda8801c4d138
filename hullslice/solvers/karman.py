"""The default 2D solver: the paper's extended von Karman wedge curves, used in inverse form.

Each wetted section is treated as a 2D wedge (deadrise ``beta``, mass per metre ``M``) in a
free fall of its own. Its scaled penetration ``z~`` (Eq. 9) picks a point on the
characteristic curves ``v~(z~)`` and ``a~(z~)`` (Eqs. 5-6); the velocity of the section,
``v = v~ v_z0``, gives the initial velocity ``v_z0`` of that free fall, and Eq. 4 its
acceleration ``a``. The section's force per metre is ``M (a + g)`` (Eq. 12).

The curves were made for water of density 1000 kg/m^3. von Karman's momentum balance
``(M + m_added) v = M v_z0`` with ``m_added`` proportional to ``rho`` depends on ``M`` and
``rho`` only through ``M / rho``, so for another density the scaled quantities use the
equivalent mass ``M' = M rho_curves / rho``; the force still uses the real ``M``.

The curves are in :mod:`hullslice.solvers.curves`, the peak values of Eq. 2 in
:mod:`hullslice.solvers.peaks` and the pile-up laws in :mod:`hullslice.solvers.pileup`; their
names are also importable from here.
"""

from __future__ import annotations

from typing import Any, ClassVar, cast

import numpy as np

from ..sections import Sections
from ..state import Fluid
from .base import SectionLoads, Solver, join_reasons
from .curves import CURVE_COLUMNS, PAPER_CURVES, CharacteristicCurves
from .peaks import peak_froude, peak_values
from .pileup import dobrovolskaya_pile_up

__all__ = [
    "CURVE_COLUMNS",
    "PAPER_CURVES",
    "CharacteristicCurves",
    "CurveSolver",
    "ExtendedVonKarman",
    "dobrovolskaya_pile_up",
    "peak_froude",
    "peak_values",
]


class CurveSolver(Solver):
    """Inverse use of characteristic curves, for any curves and pile-up law.

    Subclasses set :attr:`curves` and may override :meth:`pile_up`.
    """

    curves: ClassVar[CharacteristicCurves] = PAPER_CURVES
    options: ClassVar[dict[str, Any]] = {"froude_min": 6.5}

    def pile_up(self, deadrise: np.ndarray) -> np.ndarray:
        """Pile-up coefficient for deadrise angles in rad."""
        return dobrovolskaya_pile_up(deadrise)

    def section_loads(self, sections: Sections, velocity: np.ndarray, fluid: Fluid) -> SectionLoads:
        curves = self.curves
        M = sections.mass_per_metre
        beta = sections.deadrise
        tb = np.tan(beta)
        gam = self.pile_up(beta)
        m_eq = M * curves.rho / fluid.rho  # same M/rho as the section
        root_m = np.sqrt(m_eq)
        zt = -sections.penetration * gam / (root_m * tb)  # Eq. 9
        vt = curves.v(zt)  # Eq. 6
        at = curves.a(zt)  # Eq. 5
        with np.errstate(divide="ignore", invalid="ignore"):
            v0 = velocity / vt
        a = at * v0**2 / root_m * gam / tb  # Eq. 4
        force = M * (a + fluid.g)  # Eq. 12, per metre
        # a section moving up is leaving the water (behind a transom or the lowest point of a
        # hull moving forward): it is in no free fall, the flow separates, and it gets no force
        force = np.where(velocity < 0.0, force, 0.0)
        froude = peak_froude(v0, m_eq, beta, gam, curves.rho, fluid.g)

        lo, hi = cast(tuple[float, float], curves.z_range)
        fr_min = float(self.settings["froude_min"])
        checks = [
            ((zt < lo) | (zt > hi), f"z~ outside the curves' range [{lo:.4g}, {hi:.4g}]"),
            (vt <= 0.0, "v~ <= 0 (past the end of the curves)"),
            (velocity >= 0.0, "section not moving down into the water (no force)"),
            (froude <= fr_min, f"Fr* <= {fr_min:g} (gravity not negligible)"),
        ]
        reason = join_reasons(len(M), checks)
        return SectionLoads(
            force_per_metre=force,
            valid=reason == "",
            reason=reason,
            diagnostics={
                "gamma": gam,
                "z_tilde": zt,
                "v_tilde": vt,
                "a_tilde": at,
                "v_z0": v0,
                "acceleration": a,
                "froude": froude,
            },
        )


class ExtendedVonKarman(CurveSolver):
    """The paper's 2D solver: extended von Karman momentum theory, free-falling wedge."""

    name = "extended-von-karman"
    description = (
        "Extended von Karman momentum theory: the paper's characteristic curves of a "
        "free-falling wedge, with Dobrovol'skaya's pile-up (default)"
    )
    curves = PAPER_CURVES
