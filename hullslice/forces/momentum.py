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
from ..state import Acceleration, Fluid, Motion, Pose
from .evaluate import evaluate_added_mass
from .kinematics import section_kinematics, section_velocity
from .result import ForceResult

__all__ = ["MomentumTerms", "momentum_terms", "solve_accelerations"]


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
        ``m_a' v^2 [v < 0] - m_a bias + extra``.
    """

    sections: Sections
    velocity: np.ndarray
    added: AddedMass
    jac: np.ndarray
    bias: np.ndarray
    f0: np.ndarray

    @property
    def matrix(self) -> np.ndarray:
        """(3, 3) added-mass matrix ``sum m_a J J^T dx`` in the order (heave, pitch,
        surge): kg, kg m, kg m^2."""
        w = self.added.added_mass * self.sections.dx
        return (self.jac * w[:, None]).T @ self.jac

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
        m_a = self.added.added_mass
        force = self.f0 - m_a * (self.jac @ acc)
        diagnostics = {
            **self.added.diagnostics,
            "added_mass": m_a,
            "added_mass_rate": self.added.rate,
            "extra_force": cast(np.ndarray, self.added.extra),
            "vertical_force": cast(np.ndarray, self.added.vertical),
        }
        loads = SectionLoads(force, self.added.valid, self.added.reason, diagnostics)
        s = self.sections
        pose = Pose(s.draft, s.pitch)
        return ForceResult(
            s, self.velocity, loads, solver.name, fluid, pose, motion, x_cg, MOMENTUM,
            acceleration, a_n,
        )  # fmt: skip


def momentum_terms(
    sections: Sections, motion: Motion, solver: MomentumFormSolver, fluid: Fluid, x_cg: float
) -> MomentumTerms:
    """The momentum form's terms at one pose and motion (see :class:`MomentumTerms`)."""
    velocity = section_velocity(sections, motion, x_cg)
    added = evaluate_added_mass(solver, sections, velocity, fluid)
    jac, bias = section_kinematics(sections, motion, x_cg, velocity)
    flux = np.where(velocity < 0.0, added.rate * velocity * velocity, 0.0)
    f0 = flux - added.added_mass * bias + added.extra + added.vertical
    return MomentumTerms(sections, velocity, added, jac, bias, f0)


def solve_accelerations(
    terms: MomentumTerms,
    mass: float,
    inertia: float | None,
    gravity: float,
    free: tuple[bool, bool, bool],
    fixed: Acceleration | None = None,
    when: str = "",
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
    rhs = terms.generalized[idx]  # a vertical force (buoyancy) acts vertically, not normal
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
