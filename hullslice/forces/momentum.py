"""The momentum form: a solver's added mass on the left of the body's equations of motion.

:func:`momentum_terms` gathers a momentum-form solver's output at one pose and motion
(:class:`MomentumTerms`); :func:`solve_accelerations` solves
``(M_body + A) q'' = Q0 - m g e_z`` for the body's accelerations; the force follows once
they are known (:meth:`MomentumTerms.result`). See the notes of :mod:`hullslice.forces`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import cast

import numpy as np

from ..errors import InputError
from ..sections import Sections
from ..solvers.base import MOMENTUM, AddedMass, MomentumFormSolver, SectionLoads, SolverBase
from ..solvers.section_parts import submerged_widths
from ..state import Acceleration, Fluid, Motion, Pose
from .evaluate import evaluate_added_mass
from .kinematics import section_kinematics, section_velocity
from .result import ForceResult, SectionPressureResult

__all__ = [
    "MomentumTerms",
    "calm_girth",
    "held_bounded",
    "momentum_terms",
    "solve_accelerations",
    "solve_bounded",
]


@dataclass(frozen=True, eq=False)
class MomentumTerms:
    """A momentum-form solver's output at one pose and motion, before the body's
    accelerations are known.

    Attributes
    ----------
    sections : Sections
    velocity : (n,) float
        Penetration velocities, m/s.
    added : AddedMass
        The solver's added mass, rate and extra force, every section (zero where dry).
    jac : (n, 3) float
    bias : (n,) float
        The section acceleration is ``jac @ (dw/dt, dq/dt, du/dt) + bias`` (m/s^2).
    f0 : (n,) float
        Force per metre with the body at rest in acceleration, N/m:
        ``m_a' v^2 [v < 0] - m_a bias + extra``; on a limited section, the bound.
    carried : (n,) float
        Added mass per metre that follows the body's acceleration, kg/m: the solver's,
        or, for a solver whose load is the positive part of its pressure, that of the
        points where the pressure is positive.
    loaded : (n, 2, k) bool or None
        The points of the solver's pressures that carry load (None: all of them).
    lower : (n,) float
        The least force per metre the water can give each section, N/m: the suction
        limit of the fluid (``p_atm - p_vapour``) times the section's wetted width (the
        vertical force of that suction on the whole wetted bottom), negated.
    limited : (n,) bool
        Sections whose force is held at ``lower``: the water cannot follow them (it
        cavitates), so their added mass leaves the equations of motion.
    """

    sections: Sections
    velocity: np.ndarray
    added: AddedMass
    jac: np.ndarray
    bias: np.ndarray
    f0: np.ndarray
    lower: np.ndarray
    limited: np.ndarray
    carried: np.ndarray
    loaded: np.ndarray | None = None

    @property
    def inertia(self) -> np.ndarray:
        """(n,) added mass per metre that follows the body's acceleration, kg/m (zero on
        limited sections)."""
        return np.where(self.limited, 0.0, self.carried)

    @property
    def matrix(self) -> np.ndarray:
        """(3, 3) added-mass matrix ``sum m_a J J^T dx`` in the order (heave, pitch,
        surge): kg, kg m, kg m^2."""
        w = self.inertia * self.sections.dx
        return (self.jac * w[:, None]).T @ self.jac

    def force(self, acceleration: Acceleration) -> np.ndarray:
        """(n,) force per metre normal to the keel line at the body's acceleration, N/m."""
        with np.errstate(over="ignore", invalid="ignore"):  # result() names a non-finite one
            return self.f0 - self.inertia * (self.jac @ np.asarray(acceleration.as_array()))

    def with_limited(self, limited: np.ndarray) -> MomentumTerms:
        """The same terms with the force of the sections ``limited`` held at the bound."""
        limited = np.asarray(limited, dtype=bool)
        f0 = np.where(limited, self.lower, self.f0)
        return MomentumTerms(
            self.sections, self.velocity, self.added, self.jac, self.bias, f0, self.lower,
            limited, self.carried, self.loaded,
        )  # fmt: skip

    @property
    def generalized(self) -> np.ndarray:
        """(3,) generalised forces (N, N m, N) with no body acceleration: ``sum J f0 dx``
        for the force normal to the keel line, and the vertical force's own heave force
        and moment ``(X - X_g)`` (no surge)."""
        s = self.sections
        vertical = cast(np.ndarray, self.added.vertical) * s.dx
        q = self.jac.T @ (self.f0 * s.dx - vertical)
        q[0] += vertical.sum()
        q[1] += (self.jac[:, 1] - (s.keel_z - s.z_cg) * s.keel_slope) @ vertical
        return q

    def result(
        self,
        acceleration: Acceleration,
        solver: SolverBase,
        fluid: Fluid,
        motion: Motion,
        x_cg: float,
    ) -> ForceResult:
        """The force result once the body's acceleration is known."""
        acc = np.asarray(acceleration.as_array())
        a_n = self.jac @ acc + self.bias
        force = self.force(acceleration)
        if not np.isfinite(force).all() or not np.isfinite(force @ self.sections.dx):
            raise InputError(
                f"the water's force at the body's acceleration (vertical {acc[0]:g} m/s^2, "
                f"pitch {acc[1]:g} rad/s^2, forward {acc[2]:g} m/s^2) is not a finite "
                "number: give accelerations a body can have, in m/s^2 and rad/s^2"
            )
        diagnostics = {
            **self.added.diagnostics,
            "added_mass": self.carried,
            "added_mass_rate": self.added.rate,
            "extra_force": cast(np.ndarray, self.added.extra),
            "vertical_force": cast(np.ndarray, self.added.vertical),
            "suction_bound": self.lower,
            "suction_limited": self.limited.astype(np.float64),
        }
        loads = SectionLoads(force, self.added.valid, self.added.reason, diagnostics)
        s = self.sections
        pose = Pose(s.draft, s.pitch)
        pressures = None
        if self.added.pressure is not None:
            p = self.added.pressure.pressure(self.velocity, a_n)
            if self.loaded is not None:
                p = np.where(self.loaded, p, 0.0)
            below = (p < -fluid.suction_limit).any(axis=(1, 2)) & ~self.limited
            p = np.maximum(p, -fluid.suction_limit)  # the water cavitates first
            p = np.where(self.limited[:, None, None], -fluid.suction_limit, p)
            pressures = SectionPressureResult(self.added.pressure, p, below)
        return ForceResult(
            s, self.velocity, loads, solver.name, fluid, pose, motion, x_cg, MOMENTUM,
            acceleration, a_n, pressures,
        )  # fmt: skip


def momentum_terms(
    sections: Sections, motion: Motion, solver: MomentumFormSolver, fluid: Fluid, x_cg: float
) -> MomentumTerms:
    """The momentum form's terms at one pose and motion (see :class:`MomentumTerms`)."""
    velocity = section_velocity(sections, motion, x_cg)
    added = evaluate_added_mass(solver, sections, velocity, fluid)
    jac, bias = section_kinematics(sections, motion, x_cg, velocity)
    flux = np.where(velocity < 0.0, added.rate * velocity * velocity, 0.0)
    carried, loaded = added.added_mass, None
    if getattr(solver, "positive_pressure", False) and added.pressure is not None:
        # the load of the points whose pressure is positive at the body's rest; the body's
        # own acceleration then acts on the added mass of those points, its pressure of
        # either sign (the suction bound holds a pull the water cannot give). A section
        # leaving the water (no v^2 term) has at rest its kinematic acceleration's
        # pressure alone, of one sign: it carries its whole added mass where that is
        # not negative (as an entering section does as its speed goes to zero, so that
        # the load is continuous as the section turns), none where it is
        pts = added.pressure
        p0 = pts.pressure(velocity, bias)
        leaving = (velocity >= 0.0)[:, None, None]
        loaded = np.where(leaving, p0 >= 0.0, p0 > 0.0)
        flux = (np.where(loaded, p0, 0.0) * pts.weight).sum(axis=(1, 2))
        # no side's added mass is negative, as the solver's own (clipped at zero): on a
        # steep side the coefficient is negative near the keel (Logvinovich's f - h term)
        per_side = (np.where(loaded, pts.acceleration_coefficient, 0.0) * pts.weight).sum(axis=2)
        carried = np.maximum(per_side, 0.0).sum(axis=1)
        f0 = flux + added.extra + added.vertical
    else:
        f0 = flux - added.added_mass * bias + added.extra + added.vertical
    # a pressure no lower than -p_lim over the bottom pulls a section down by at most
    # p_lim times the bottom's horizontal breadth (the solver's loaded breadth where it
    # gives one), not its girth: the wetted bottom's breadth under the calm water
    width = added.girth if added.girth is not None else submerged_widths(sections)
    lower = -fluid.suction_limit * np.where(sections.wetted, width, 0.0)
    terms = MomentumTerms(
        sections, velocity, added, jac, bias, f0, lower, f0 < lower, carried, loaded,
    )  # fmt: skip
    return terms.with_limited(terms.limited)


def calm_girth(sections: Sections) -> np.ndarray:
    """(n,) each section's wetted girth as the chords from its keel to the calm water on
    both sides, m (a wedge's girth exactly; a round section's a little short of it)."""
    p = np.asarray(sections.penetration, dtype=np.float64)
    port = np.maximum(np.asarray(sections.half_beam_port, dtype=np.float64), 0.0)
    stbd = np.maximum(np.asarray(sections.half_beam_stbd, dtype=np.float64), 0.0)
    return np.hypot(port, p) + np.hypot(stbd, p)


#: Most rounds of the suction bound's active set in :func:`solve_bounded`.
MAX_BOUND_ROUNDS = 20


def solve_bounded(
    terms: MomentumTerms,
    mass: float,
    inertia: float | None,
    gravity: float,
    free: tuple[bool, bool, bool],
    fixed: Acceleration | None = None,
    when: str = "",
    external: tuple[float, float, float] = (0.0, 0.0, 0.0),
) -> tuple[MomentumTerms, Acceleration]:
    """The body's accelerations with every section's force at or above its suction bound.

    Sections whose force would fall below the bound (``terms.lower``) at the solved
    accelerations are held at it and their added mass leaves the equations, and the
    accelerations are solved again, until no more sections fall below (an active set that
    only grows, so it ends). Returns the terms with their limited sections and the
    accelerations; the arguments are those of :func:`solve_accelerations`.
    """
    acc = solve_accelerations(terms, mass, inertia, gravity, free, fixed, when, external)
    for _ in range(MAX_BOUND_ROUNDS):
        below = ~terms.limited & (terms.force(acc) < terms.lower)
        if not below.any():
            break
        terms = terms.with_limited(terms.limited | below)
        acc = solve_accelerations(terms, mass, inertia, gravity, free, fixed, when, external)
    return terms, acc


def held_bounded(terms: MomentumTerms, acceleration: Acceleration) -> MomentumTerms:
    """The terms at a body acceleration that is given (not solved): the sections whose
    force falls below its bound there are held at it."""
    below = ~terms.limited & (terms.force(acceleration) < terms.lower)
    return terms.with_limited(terms.limited | below) if below.any() else terms


def solve_accelerations(
    terms: MomentumTerms,
    mass: float,
    inertia: float | None,
    gravity: float,
    free: tuple[bool, bool, bool],
    fixed: Acceleration | None = None,
    when: str = "",
    external: tuple[float, float, float] = (0.0, 0.0, 0.0),
) -> Acceleration:
    """The body's accelerations from ``(M_body + A) q'' = Q0 - m g e_z`` over its free
    degrees of freedom (heave, pitch, surge); the others take ``fixed`` (default zero).

    Parameters
    ----------
    terms : MomentumTerms
    mass : float
        Mass of the body, kg.
    inertia : float or None
        Pitch moment of inertia about the centre of gravity, kg m^2 (for a free pitch).
    gravity : float
        m/s^2.
    free : (bool, bool, bool)
        Whether heave, pitch and surge are free.
    external : (float, float, float)
        Forces on the body besides the water's and gravity (the air's, friction): vertical
        force (N), pitch moment (N m) and horizontal force (N).

    Raises
    ------
    InputError
        The matrix of the free degrees of freedom is singular or not positive definite;
        the message names the stage ``when``.
    """
    idx = [i for i in range(3) if free[i]]
    acc = [0.0, 0.0, 0.0] if fixed is None else list(fixed.as_array())
    if not idx:
        return fixed or Acceleration()
    total = terms.matrix[np.ix_(idx, idx)]
    rhs = (terms.generalized + np.asarray(external, dtype=np.float64))[idx]
    body = {0: mass, 1: inertia, 2: mass}
    for k, i in enumerate(idx):
        if body[i] is None:
            raise InputError("a free pitch needs the body's pitch inertia (kg m^2)")
        total[k, k] += body[i]
    if idx[0] == 0:
        rhs[0] -= mass * gravity
    held = [i for i in range(3) if not free[i] and acc[i] != 0.0]
    if held:  # prescribed accelerations of the other degrees of freedom
        cross = terms.matrix[np.ix_(idx, held)]
        rhs -= cross @ np.array([acc[i] for i in held])
    if len(idx) == 1:
        ok = bool(total[0, 0] > 0.0 and np.isfinite(total[0, 0]))
        solved = rhs / total[0, 0] if ok else rhs
    else:
        try:
            np.linalg.cholesky(total)
            ok = bool(np.all(np.isfinite(total)))
        except np.linalg.LinAlgError:
            ok = False
        solved = np.linalg.solve(total, rhs) if ok else rhs
    if not ok:
        raise InputError(
            f"the mass matrix of the free motion (body plus added mass) is singular or not "
            f"positive definite{' ' + when if when else ''} (its diagonal: "
            f"{', '.join(f'{d:.6g}' for d in np.diag(total))}): check the body's mass and "
            "pitch inertia"
        )
    for k, i in enumerate(idx):
        acc[i] = float(solved[k])
    return Acceleration(*acc)
