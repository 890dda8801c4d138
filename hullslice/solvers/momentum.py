"""Von Karman's momentum theory in closed form, and the pile-up laws it is used with.

:class:`MomentumSolver` is the base of the analytic 2D solvers (the ``von-karman`` and
``wagner`` plugins). It is a **momentum-form** solver: it gives each section's added mass
per metre ``m_a = rho pi c^2 / 2``, with the wetted half-width ``c = gamma p / tan(beta)``
per side, and its rate ``dm_a/dp``; hullslice forms the force ``m_a' v^2 - m_a a`` and puts
the added mass on the left of the body's equations of motion (:mod:`hullslice.forces`).
The pile-up law ``gamma(beta)`` is its option ``pile_up``, shared by every momentum solver.

:class:`FreeFallMomentumSolver` is the same theory in the paper's **free-fall form** (the
free fall that each slice is in, and ``F = M (a + g) d``), kept to compare the two forms on
the same theory; the derivation below is that of the free-fall form.

Derivation
----------
A 2D wedge of deadrise ``beta`` and mass per metre ``M`` (kg/m) enters water of density
``rho`` with vertical velocity ``v < 0``; its keel is ``p > 0`` below the calm water. The
water rises along the wedge (pile-up), so the wetted half-width is ``c = gamma p / tan(beta)``
(``gamma = 1``: von Karman, no pile-up; ``gamma = pi / 2``: Wagner). The added mass per
metre is that of a flat plate of half-width ``c``,

    m_a = rho pi c^2 / 2 = rho pi gamma^2 p^2 / (2 tan^2(beta)).

With gravity neglected during the impact, the vertical momentum of wedge and water is
conserved, ``(M + m_a) v = M v_z0``: the slice is in the free fall of initial velocity

    v_z0 = v (M + m_a) / M.

Differentiating ``(M + m_a) v = const`` in time, with ``dp/dt = -v`` and
``dm_a/dt = rho pi gamma^2 p (dp/dt) / tan^2(beta)``,

    (M + m_a) dv/dt = -v dm_a/dt = rho pi gamma^2 p v^2 / tan^2(beta),

so the deceleration of that free fall, positive upward, is

    a = rho pi gamma^2 p v^2 / (tan^2(beta) (M + m_a)),

and the force per metre on the slice is ``M (a + g)`` (paper, Eq. 12). Along the free fall,
``v = M v_z0 / (M + m_a)`` gives ``a(p) = 2 k p M^2 v_z0^2 / (M + k p^2)^3`` with
``k = rho pi gamma^2 / (2 tan^2(beta))``; it peaks where ``k p^2 = M / 5``, at

    z* = tan(beta) sqrt(2 M / (5 pi rho gamma^2)),    v_z* = 5/6 v_z0,
    a_max = v_z0^2 (5/6)^3 gamma / tan(beta) sqrt(2 pi rho / (5 M)),

the paper's Eq. 2 (:func:`~hullslice.solvers.peaks.peak_values`). In the scaled variables of
Eq. 3 the theory's characteristic curves are ``v~ = 1 / (1 + pi rho z~^2 / 2)`` and
``a~ = -pi rho z~ v~^3`` (:func:`momentum_curves`).

Range of validity
-----------------
The closed form holds at any penetration, so unlike fitted curves it has no ``z~`` range.
Its limits are those of the model: the section moves down into the water (``v < 0``; a
section rising out of the water is left behind by the separated flow and gets no force);
gravity is negligible during the impact, ``Fr* = |v_z*| / sqrt(g z*) > 6.5`` (paper, after
Eq. 2; :func:`~hullslice.solvers.peaks.peak_froude`); and the wetted half-width with the
pile-up, ``gamma p / tan(beta)``, stays inside the section (the spray root has not reached
the chine, after which the flow separates and the added mass stops growing as assumed).
The calm-water line reaching the chine is flagged by hullslice itself for every solver;
the pile-up makes the spray root get there earlier, so this solver flags it from the
section's widest point. Both pile-up laws are small-deadrise theories: von Karman's
underestimates and Wagner's overestimates the peak of a wedge of large deadrise (compare
Dobrovol'skaya's ``gamma_D``, 1.054 at 45 deg).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from numbers import Real
from typing import Any, ClassVar

import numpy as np

from ..errors import InputError
from ..sections import Sections
from ..state import Fluid
from .base import AddedMass, MomentumFormSolver, SectionLoads, Solver, SolverBase, join_reasons
from .contour import SECTION_METHODS, contour_half_widths
from .curves import CharacteristicCurves
from .peaks import peak_froude
from .pileup import (
    PILE_UP_LAWS,
    PileUp,
    dobrovolskaya_pile_up,
    pile_up_law,
    von_karman_pile_up,
    wagner_pile_up,
)
from .section_parts import piece_half_widths

__all__ = [
    "PILE_UP_LAWS",
    "FreeFallMomentumSolver",
    "MomentumSolver",
    "PileUp",
    "PileUpOptions",
    "chine_half_width",
    "dobrovolskaya_pile_up",
    "momentum_curves",
    "pile_up_law",
    "von_karman_pile_up",
    "wagner_pile_up",
]


def chine_half_width(sections: Sections) -> np.ndarray:
    """Half the width, at its widest point, of the separate part of the section that each
    entry belongs to (one float of a catamaran), in m; where several entries share a part
    (floats joined by a tunnel roof in one closed surface), of each one's own bottom
    (:func:`~hullslice.solvers.section_parts.piece_half_widths`)."""
    return piece_half_widths(sections)


def momentum_curves(
    rho: float = 1000.0, z_min: float | None = None, points: int = 2001
) -> CharacteristicCurves:
    """The characteristic curves of von Karman's momentum theory, as a table.

    In the scaled variables of the paper's Eq. 3 the closed form is
    ``v~ = 1 / (1 + pi rho z~^2 / 2)`` and ``a~ = -pi rho z~ v~^3``, whatever the pile-up
    law (it is inside ``z~``). A table of them fed to a curve solver reproduces a
    :class:`MomentumSolver` with the same pile-up, to the table's interpolation error.

    Parameters
    ----------
    rho : float
        Water density in kg/m^3 (default 1000).
    z_min : float, optional
        Lowest ``z~`` of the table (default: four times the peak's, ``-4 sqrt(2 / (5 pi
        rho))``).
    points : int
        Number of rows, evenly spaced in ``z~`` (default 2001).
    """
    if z_min is None:
        z_min = -4.0 * math.sqrt(2.0 / (5.0 * math.pi * rho))
    z = np.linspace(z_min, 0.0, points)
    v = 1.0 / (1.0 + np.pi * rho * z**2 / 2.0)
    a = -np.pi * rho * z * v**3
    return CharacteristicCurves(
        table=np.column_stack([z, a, v]),
        rho=rho,
        source=f"von Karman momentum theory, closed form, rho = {rho:g} kg/m^3",
    )


class PileUpOptions(SolverBase):
    """The options the solvers of momentum theory share, read once when one is made.

    ``pile_up`` is the pile-up law (:func:`pile_up_law`, used by :meth:`pile_up`) and
    ``froude_min``, when the solver has that option, a positive finite number.
    """

    def __init__(self, **options: Any) -> None:
        super().__init__(**options)
        self._law = pile_up_law(self.settings["pile_up"])
        if "froude_min" in self.options:
            self.settings["froude_min"] = _positive_option(self, "froude_min")

    def pile_up(self, deadrise: np.ndarray) -> np.ndarray:
        """Pile-up coefficient ``gamma`` for deadrise angles in rad (the option ``pile_up``)."""
        return self._law(deadrise)


class FreeFallMomentumSolver(PileUpOptions, Solver):
    """Von Karman's momentum theory in closed form, in the paper's free-fall form.

    Subclasses set :attr:`~hullslice.Solver.name` and :attr:`~hullslice.Solver.description`;
    the pile-up law is the option ``pile_up`` (or override :meth:`pile_up`). The derivation
    and the range of validity are in the docstring of :mod:`hullslice.solvers.momentum`.

    Parameters
    ----------
    pile_up : str or float, optional
        The pile-up law, see :func:`pile_up_law` (default ``"von-karman"``).
    froude_min : float, optional
        Smallest peak Froude number ``Fr*`` inside the range (default 6.5, the paper's).

    Notes
    -----
    Diagnostics, per section: ``gamma`` (pile-up coefficient), ``added_mass`` (kg/m),
    ``v_z0`` (m/s, initial velocity of the slice's free fall), ``acceleration`` (m/s^2,
    upward), ``froude`` (``Fr*``), ``wetted_half_width`` (m, ``gamma p / tan(beta)``),
    ``chine_half_width`` (m).
    """

    options: ClassVar[Mapping[str, Any]] = {"pile_up": "von-karman", "froude_min": 6.5}

    def section_loads(self, sections: Sections, velocity: np.ndarray, fluid: Fluid) -> SectionLoads:
        n = len(sections)
        M = sections.mass_per_metre
        p = sections.penetration
        beta = sections.deadrise
        v = np.broadcast_to(np.asarray(velocity, dtype=np.float64), (n,))
        tb = np.tan(beta)
        gam = np.broadcast_to(np.asarray(self.pile_up(beta), dtype=np.float64), (n,))
        k = fluid.rho * np.pi * gam**2 / 2.0  # m_a = k p^2 / tan^2(beta)
        added = k * p**2 / tb**2
        v0 = v * (M + added) / M  # momentum: (M + m_a) v = M v_z0
        a = 2.0 * k * p * v**2 / (M * tb**2 + k * p**2)  # = rho pi g^2 p v^2 / (tb^2 (M+m_a))
        force = M * (a + fluid.g)  # Eq. 12, per metre
        # a section moving up is leaving the water: no free fall, the flow separates
        force = np.where(v < 0.0, force, 0.0)
        froude = peak_froude(v0, M, beta, gam, fluid.rho, fluid.g)
        wet_half = gam * p / tb
        chine = chine_half_width(sections)
        fr_min = float(self.settings["froude_min"])
        reason = join_reasons(
            n,
            [
                (v >= 0.0, "section not moving down into the water (no force)"),
                (froude <= fr_min, f"Fr* <= {fr_min:g} (gravity not negligible)"),
                (
                    wet_half > chine,
                    "spray root past the chine (gamma p / tan(beta) > the section's half-width)",
                ),
            ],
        )
        return SectionLoads(
            force_per_metre=force,
            valid=reason == "",
            reason=reason,
            diagnostics={
                "gamma": gam,
                "added_mass": added,
                "v_z0": v0,
                "acceleration": a,
                "froude": froude,
                "wetted_half_width": wet_half,
                "chine_half_width": chine,
            },
        )


def _positive_option(solver: Any, key: str, *, allow_zero: bool = False) -> float:
    """A solver's numeric option, checked: finite and positive (or zero where allowed)."""
    value = solver.settings[key]
    ok = isinstance(value, Real) and not isinstance(value, bool)
    v = float(value) if ok else math.nan
    if not (math.isfinite(v) and (v > 0.0 or (allow_zero and v == 0.0))):
        what = "zero or positive" if allow_zero else "positive"
        raise InputError(
            f"solver {solver.name!r}: option {key}={value!r} is not a {what} finite number "
            f"(default {type(solver).options[key]!r})"
        )
    return v


#: Default smallest section Froude number |v| / sqrt(g p) of the momentum solvers.
SECTION_FROUDE_MIN = 2.0


class MomentumSolver(PileUpOptions, MomentumFormSolver):
    """Von Karman's momentum theory in closed form, momentum form, with a pile-up law.

    The wetted half-width of each side of a section is ``c = gamma p / tan(beta)`` (its
    own deadrise), the added mass per metre is a flat plate's of the wetted width,

        m_a = rho pi (c_port + c_stbd)^2 / 8        (= rho pi c^2 / 2 when symmetric),

    and its rate ``dm_a/dp = rho pi (c_port + c_stbd) (gamma / tan(beta_port) +
    gamma / tan(beta_stbd)) / 4``. At constant speed ``V`` from first contact this gives
    ``f = rho pi gamma^2 V^3 t / tan^2(beta)`` per metre: von Karman's force (``gamma = 1``)
    and Wagner's (``gamma = pi / 2``, ``rho pi^3 V^3 t / (4 tan^2 beta)``).

    Once the spray root reaches the chine on a side (``c`` beyond the half-width of the
    section's part at its widest, ``part_half_beam``), that side's ``c`` stays at the chine
    and stops growing (``dc/dp = 0``): the added mass keeps its chine value and the section
    is flagged (the flow separates; no drag is modelled here).

    Subclasses set :attr:`~hullslice.SolverBase.name`,
    :attr:`~hullslice.SolverBase.description` and a default for the option ``pile_up``.

    Parameters
    ----------
    pile_up : str or float, optional
        The pile-up law: ``"wagner"`` (``pi / 2``), ``"von-karman"`` (1),
        ``"dobrovolskaya"`` (the paper's ``-0.0114 beta_deg + 1.5669``) or a number (see
        :func:`pile_up_law`).
    section_method : str, optional
        How the wetted half-width is found (:data:`~hullslice.solvers.contour.SECTION_METHODS`):
        ``"auto"`` (default: the closed form where a section is a wedge, its own contour
        elsewhere, by Wagner's condition with ``pile_up="wagner"`` or the calm-water
        crossing with ``"von-karman"``; another pile-up law takes the equivalent wedge
        everywhere), ``"wedge"`` or ``"contour"``. The diagnostic ``contour`` says which
        (1: from the contour). See :mod:`hullslice.solvers.contour`.
    froude_min : float, optional
        Smallest section Froude number ``Fr = |v| / sqrt(g p)`` inside the range (default
        2.0). The section's own velocity and depth give it: for a wedge the hydrostatic
        force over the impact force is ``tan(beta) / (pi gamma^2 Fr^2)``, so ``Fr > 2``
        keeps it below 3 % (Wagner's pile-up) or 8 % (von Karman's) up to 45 deg.

    Notes
    -----
    Diagnostics, per section: ``gamma``, ``wetted_half_width`` (m, the mean of the two
    sides, capped at the chine), ``chine_half_width`` (m), ``froude`` (``|v| / sqrt(g p)``).
    """

    options: ClassVar[Mapping[str, Any]] = {
        "pile_up": "von-karman",
        "froude_min": SECTION_FROUDE_MIN,
        "section_method": "auto",
    }

    def __init__(self, **options: Any) -> None:
        super().__init__(**options)  # pile_up and froude_min (PileUpOptions)
        method = self.settings["section_method"]
        if method not in SECTION_METHODS:
            raise InputError(
                f"solver {self.name!r}: option section_method={method!r} is unknown; choose "
                f"one of {', '.join(SECTION_METHODS)}"
            )
        spec = self.settings["pile_up"]
        self._contour_law = spec.strip().lower() if isinstance(spec, str) else None
        if self._contour_law not in ("wagner", "von-karman"):
            if method == "contour":
                raise InputError(
                    f"solver {self.name!r}: section_method=contour needs pile_up=wagner "
                    f"(Wagner's condition) or von-karman (the calm-water crossing), not "
                    f"{spec!r}; use section_method=wedge for another pile-up"
                )
            self._contour_law = None  # another law: the equivalent wedge everywhere

    def _half_widths(self, sections: Sections, gam: np.ndarray):
        """Per side, the wetted half-width ``c`` and ``dc/dp`` (NaN: past the chine), and
        the entries computed from their contour."""
        p = sections.penetration
        c_sides, dc_sides = [], []
        for beta in (sections.deadrise_port, sections.deadrise_stbd):
            dc = gam / np.tan(beta)  # dc/dp of a wedge side
            c_sides.append(dc * p)
            dc_sides.append(dc)
        method = self.settings["section_method"]
        used = np.zeros(len(p), dtype=bool)
        if method != "wedge" and self._contour_law is not None and len(p):
            c_ct, dc_ct, used = contour_half_widths(sections, self._contour_law, method)
            for k in range(2):
                c_sides[k] = np.where(used, c_ct[k], c_sides[k])
                dc_sides[k] = np.where(used, dc_ct[k], dc_sides[k])
        return c_sides, dc_sides, used

    def momentum_terms(self, sections: Sections, fluid: Fluid) -> dict[str, np.ndarray]:
        """The closed form's arrays for wetted sections: ``added_mass`` (kg/m), ``rate``
        (kg/m^2), ``past_chine`` (bool, either side), ``gamma``, ``wetted_half_width`` and
        ``chine_half_width`` (m), ``contour`` (bool). For solvers built on this one."""
        n = len(sections)
        gam = np.asarray(self.pile_up(sections.deadrise), dtype=np.float64)
        if gam.shape != (n,):
            gam = np.broadcast_to(gam, (n,))
        chine = chine_half_width(sections)
        c_raw, dc_raw, contour = self._half_widths(sections, gam)
        c_sides, dc_sides = [], []
        for c, dc in zip(c_raw, dc_raw, strict=True):
            # NaN: the contour's spray root past the side's extent; and once the calm water
            # is at the section's widest point, the wetted width stays there
            past = ~(c <= chine) | sections.chine_wetted
            c_sides.append(np.where(past, chine, c))
            dc_sides.append(np.where(past, 0.0, dc))
        width = c_sides[0] + c_sides[1]
        k = fluid.rho * np.pi / 8.0
        return {
            "added_mass": k * width**2,
            "rate": 2.0 * k * width * (dc_sides[0] + dc_sides[1]),
            "past_chine": (dc_sides[0] == 0.0) | (dc_sides[1] == 0.0),
            "gamma": gam,
            "wetted_half_width": width / 2.0,
            "chine_half_width": chine,
            "contour": contour,
        }

    def added_mass(self, sections: Sections, velocity: np.ndarray, fluid: Fluid) -> AddedMass:
        n = len(sections)
        p = sections.penetration
        v = np.asarray(velocity, dtype=np.float64)
        t = self.momentum_terms(sections, fluid)
        froude = np.abs(v) / np.sqrt(fluid.g * p) if fluid.g > 0 else np.full(n, np.inf)
        fr_min = self.settings["froude_min"]
        reason = join_reasons(
            n,
            [
                (froude <= fr_min, f"Fr = |v| / sqrt(g p) <= {fr_min:g} (gravity not negligible)"),
                (
                    t["past_chine"],
                    "spray root past the chine: added mass kept at its chine value "
                    "(flow separation not modelled)",
                ),
            ],
        )
        return AddedMass(
            added_mass=t["added_mass"],
            rate=t["rate"],
            valid=reason == "",
            reason=reason,
            diagnostics={
                "gamma": t["gamma"],
                "wetted_half_width": t["wetted_half_width"],
                "chine_half_width": t["chine_half_width"],
                "froude": froude,
                "contour": t["contour"].astype(np.float64),
            },
        )
