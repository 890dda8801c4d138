"""Von Karman's momentum theory in closed form, and the pile-up laws it is used with.

:class:`MomentumSolver` is the base of the analytic 2D solvers (the ``von-karman`` and
``wagner`` plugins): a subclass gives only the pile-up coefficient ``gamma(beta)``. It uses
the theory in the same inverse form as the default solver (the free fall that each slice is
in, and ``F = M (a + g) d``), so that every solver is comparable on the same body.

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

the paper's Eq. 2 (:func:`~hullslice.solvers.karman.peak_values`). In the scaled variables of
Eq. 3 the theory's characteristic curves are ``v~ = 1 / (1 + pi rho z~^2 / 2)`` and
``a~ = -pi rho z~ v~^3`` (:func:`momentum_curves`).

Range of validity
-----------------
The closed form holds at any penetration, so unlike fitted curves it has no ``z~`` range.
Its limits are those of the model: the section moves down into the water (``v < 0``; a
section rising out of the water is left behind by the separated flow and gets no force);
gravity is negligible during the impact, ``Fr* = |v_z*| / sqrt(g z*) > 6.5`` (paper, after
Eq. 2; :func:`~hullslice.solvers.karman.peak_froude`); and the wetted half-width with the
pile-up, ``gamma p / tan(beta)``, stays inside the section (the spray root has not reached
the chine, after which the flow separates and the added mass stops growing as assumed).
The calm-water line reaching the chine is flagged by hullslice itself for every solver;
the pile-up makes the spray root get there earlier, so this solver flags it from the
section's widest point. Both pile-up laws are small-deadrise theories: von Karman's
underestimates and Wagner's overestimates the peak of a wedge of large deadrise (compare
Dobrovol'skaya's ``gamma_D``, 1.054 at 45 deg).
"""

from __future__ import annotations

import abc
import math
from collections.abc import Callable, Mapping
from numbers import Real
from typing import Any, ClassVar

import numpy as np

from ..errors import InputError
from ..sections import Sections
from ..state import Fluid
from .base import SectionLoads, Solver, join_reasons
from .karman import CharacteristicCurves, dobrovolskaya_pile_up, peak_froude

__all__ = [
    "PILE_UP_LAWS",
    "MomentumSolver",
    "chine_half_width",
    "momentum_curves",
    "pile_up_law",
    "von_karman_pile_up",
    "wagner_pile_up",
]

PileUp = Callable[[np.ndarray], np.ndarray]


def von_karman_pile_up(deadrise: np.ndarray) -> np.ndarray:
    """Von Karman's pile-up coefficient: ``gamma = 1`` (no pile-up); ``deadrise`` in rad."""
    return np.ones_like(np.asarray(deadrise, dtype=np.float64))


def wagner_pile_up(deadrise: np.ndarray) -> np.ndarray:
    """Wagner's pile-up coefficient: ``gamma = pi / 2`` (small deadrise); ``deadrise`` in rad."""
    return np.full_like(np.asarray(deadrise, dtype=np.float64), np.pi / 2)


#: Pile-up laws by name: ``gamma(deadrise in rad)``.
PILE_UP_LAWS: Mapping[str, PileUp] = {
    "dobrovolskaya": dobrovolskaya_pile_up,
    "wagner": wagner_pile_up,
    "von-karman": von_karman_pile_up,
}


def pile_up_law(spec: str | float) -> PileUp:
    """A pile-up law from its name (a key of :data:`PILE_UP_LAWS`) or a constant ``gamma``.

    Parameters
    ----------
    spec : str or float
        ``"dobrovolskaya"`` (``-0.0114 beta_deg + 1.5669``), ``"wagner"`` (``pi / 2``),
        ``"von-karman"`` (1), or a positive number used for every deadrise.

    Returns
    -------
    callable
        ``gamma(deadrise)`` with ``deadrise`` in rad.

    Raises
    ------
    InputError
        An unknown name, or a number that is not positive and finite.
    """
    if isinstance(spec, str):
        law = PILE_UP_LAWS.get(spec.strip().lower())
        if law is None:
            raise InputError(
                f"pile-up law {spec!r} is unknown: give one of {', '.join(PILE_UP_LAWS)} or a "
                "positive number (the constant gamma)"
            )
        return law
    if isinstance(spec, bool) or not isinstance(spec, Real):
        raise InputError(
            f"pile-up {spec!r} is neither a law's name ({', '.join(PILE_UP_LAWS)}) nor a number"
        )
    gamma = float(spec)
    if not (math.isfinite(gamma) and gamma > 0.0):
        raise InputError(f"pile-up coefficient {spec!r} is not a positive number (e.g. 1.5708)")

    def constant(deadrise: np.ndarray) -> np.ndarray:
        return np.full_like(np.asarray(deadrise, dtype=np.float64), gamma)

    constant.__doc__ = f"Constant pile-up coefficient gamma = {gamma:g}."
    return constant


def chine_half_width(sections: Sections) -> np.ndarray:
    """Half the width, at its widest point, of the separate part of the section that each
    entry belongs to (one float of a catamaran), in m."""
    return np.asarray(sections.part_half_beam, dtype=np.float64)


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


class MomentumSolver(Solver):
    """Von Karman's momentum theory in closed form, with a pile-up law, in inverse form.

    Subclasses set :attr:`~hullslice.Solver.name` and :attr:`~hullslice.Solver.description`
    and implement :meth:`pile_up`. The derivation and the range of validity are in the
    docstring of :mod:`hullslice.solvers.momentum`.

    Parameters
    ----------
    froude_min : float, optional
        Smallest peak Froude number ``Fr*`` inside the range (default 6.5, the paper's).

    Notes
    -----
    Diagnostics, per section: ``gamma`` (pile-up coefficient), ``added_mass`` (kg/m),
    ``v_z0`` (m/s, initial velocity of the slice's free fall), ``acceleration`` (m/s^2,
    upward), ``froude`` (``Fr*``), ``wetted_half_width`` (m, ``gamma p / tan(beta)``),
    ``chine_half_width`` (m).
    """

    options: ClassVar[Mapping[str, Any]] = {"froude_min": 6.5}

    @abc.abstractmethod
    def pile_up(self, deadrise: np.ndarray) -> np.ndarray:
        """Pile-up coefficient ``gamma`` for deadrise angles in rad."""

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
