"""The force on a hull at one state, and its convergence with the number of slices."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..convergence import Richardson, richardson
from ..errors import InputError
from ..mesh import Hull
from ..sections import Sections, _as_pose, _slice_count, cut
from ..solvers.base import MOMENTUM, SolverBase
from ..solvers.registry import get_solver
from ..state import Acceleration, Fluid, Motion, Pose
from .evaluate import evaluate
from .kinematics import section_velocity
from .momentum import held_bounded, momentum_terms, solve_bounded
from .result import ForceResult

__all__ = ["ConvergenceStudy", "compute_force", "convergence", "force_on"]


def _as_motion(motion: Motion | float) -> Motion:
    return motion if isinstance(motion, Motion) else Motion(velocity=motion)


def compute_force(
    hull: Hull,
    pose: Pose | float,
    motion: Motion | float,
    *,
    slices: int = 32,
    solver: str | SolverBase | type[SolverBase] | None = None,
    fluid: Fluid | None = None,
    deadrise: str = "wedge",
    slicing: str = "wetted",
    acceleration: Acceleration | float | None = None,
) -> ForceResult:
    """The 2D+t force on a hull at one state.

    Parameters
    ----------
    hull : Hull
        The body, with its mass.
    pose : Pose or float
        The pose (draft in m, pitch in rad), or the draft alone (level body).
    motion : Motion or float
        The motion (vertical velocity and forward speed in m/s, pitch rate in rad/s), or the
        vertical velocity alone (m/s, negative down).
    slices : int
        Number of slices over the wetted length (default 32, as everywhere).
    solver : str, Solver or Solver subclass, optional
        The 2D solver (default ``"extended-von-karman"``).
    fluid : Fluid, optional
        Water density and gravity (default 1000 kg/m^3, 9.81 m/s^2).
    deadrise : str
        Deadrise estimator (default ``"wedge"``).
    slicing : str
        ``"wetted"`` (default) or ``"fixed"``, see :data:`~hullslice.sections.SLICINGS`.
    acceleration : Acceleration or float, optional
        The body's acceleration (a float: the vertical one, m/s^2, positive up), for a
        momentum-form solver, whose force has an added-inertia part. By default the body
        is free in heave: its vertical acceleration solves ``(m + A_33) dw/dt = F0 - m g``
        with the hull's mass; pitch and forward speed are steady. Free-fall solvers do not
        use it (their force follows from each slice's own free fall).

    Returns
    -------
    ForceResult
    """
    pose, motion = _as_pose(pose), _as_motion(motion)
    fluid = fluid or Fluid()
    solver = get_solver(solver)
    if isinstance(acceleration, int | float | np.floating):
        acceleration = Acceleration(vertical=float(acceleration))
    if hull.mass is None and not (solver.kind == MOMENTUM and acceleration is not None):
        raise InputError(
            f"hull {hull.name!r} has no mass: give its mass in kg (mass=...)"
            + (" or the body's acceleration" if solver.kind == MOMENTUM else "")
        )
    sections = cut(hull, pose, slices, deadrise=deadrise, slicing=slicing)
    return force_on(
        sections, motion, solver, fluid, float(hull.cg[0]), acceleration=acceleration,
        mass=hull.mass,
    )  # fmt: skip


def force_on(
    sections: Sections,
    motion: Motion,
    solver: SolverBase,
    fluid: Fluid,
    x_cg: float,
    *,
    acceleration: Acceleration | None = None,
    mass: float | None = None,
) -> ForceResult:
    """The force on cut sections moving with ``motion`` (inputs already checked).

    A momentum-form solver's force uses the body's ``acceleration``; without one, the body
    of ``mass`` (kg) is free in heave (see :func:`compute_force`).
    """
    if solver.kind == MOMENTUM:
        terms = momentum_terms(sections, motion, solver, fluid, x_cg)  # type: ignore[arg-type]
        if acceleration is None:
            if mass is None:
                raise InputError(
                    "a momentum-form solver needs the body's acceleration or its mass (kg)"
                )
            terms, acceleration = solve_bounded(terms, mass, None, fluid.g, (True, False, False))
        else:
            terms = held_bounded(terms, acceleration)
        return terms.result(acceleration, solver, fluid, motion, x_cg)
    velocity = section_velocity(sections, motion, x_cg)
    loads = evaluate(solver, sections, velocity, fluid)
    pose = Pose(sections.draft, sections.pitch)
    return ForceResult(sections, velocity, loads, solver.name, fluid, pose, motion, x_cg)


@dataclass(frozen=True, eq=False)
class ConvergenceStudy:
    """Forces for a sequence of slice counts and their Richardson extrapolation.

    Attributes
    ----------
    results : tuple of ForceResult
        One per slice count, in the order of ``counts``.
    counts : tuple of int
        The slice counts, increasing.
    richardson : Richardson or None
        The extrapolation over the three finest counts (None with fewer than three).
    """

    results: tuple[ForceResult, ...]
    counts: tuple[int, ...]
    richardson: Richardson | None

    @property
    def forces(self) -> np.ndarray:
        """(k,) float: total force in N for each slice count."""
        return np.array([r.total for r in self.results])

    @property
    def finest(self) -> ForceResult:
        """The result with the most slices."""
        return self.results[-1]


def convergence(
    hull: Hull,
    pose: Pose | float,
    motion: Motion | float,
    *,
    slices: Sequence[int] = (16, 32, 64),
    solver: str | SolverBase | type[SolverBase] | None = None,
    fluid: Fluid | None = None,
    deadrise: str = "wedge",
    slicing: str = "wetted",
    acceleration: Acceleration | float | None = None,
) -> ConvergenceStudy:
    """Forces for several slice counts and their Richardson extrapolation (paper, Fig. 8).

    Parameters
    ----------
    slices : sequence of int
        Slice counts (default 16, 32, 64); three or more give the extrapolated force and its
        GCI band.

    Other parameters are those of :func:`compute_force`.
    """
    counts = tuple(sorted({int(n) for n in _counts(slices)}))
    solver = get_solver(solver)
    results = tuple(
        compute_force(
            hull,
            pose,
            motion,
            slices=n,
            solver=solver,
            fluid=fluid,
            deadrise=deadrise,
            slicing=slicing,
            acceleration=acceleration,
        )
        for n in counts
    )
    rich = richardson(counts, [r.total for r in results]) if len(counts) >= 3 else None
    return ConvergenceStudy(results, counts, rich)


def _counts(slices: Sequence[int] | int) -> list[int]:
    if isinstance(slices, int | np.integer):
        slices = [slices]
    out = []
    for n in slices:
        if isinstance(n, bool) or not isinstance(n, int | np.integer) or n < 1:
            raise InputError(f"slice count {n!r} is not a positive whole number (e.g. 32)")
        out.append(_slice_count(n))
    if not out:
        raise InputError("no slice count given: give one or more, e.g. 16, 32, 64")
    return out
