"""From sections and their velocities to the force on the body (paper, Eq. 12).

``F_z = sum_j F^j``, ``F^j = f^j d^j`` with ``f^j`` the force per metre the 2D solver gives
for slice ``j`` and ``d^j`` its thickness. Dry slices (zero penetration) carry no force.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .convergence import Richardson, richardson
from .errors import HullsliceError, InputError, SolverError
from .mesh import Hull
from .sections import Sections, _as_pose, _slice_count, cut
from .solvers.base import SectionLoads, Solver
from .solvers.registry import describe, get_solver
from .state import Fluid, Motion, Pose

__all__ = ["ConvergenceStudy", "ForceResult", "compute_force", "convergence", "evaluate"]

CHINE_REASON = "water at or above the section's chine/widest point"
SPANS_REASON = (
    "the section meets the waterline in {n} separate spans (keels joined above the water): "
    "one equivalent wedge does not describe it"
)


@dataclass(frozen=True, eq=False)
class ForceResult:
    """The 2D+t force on a body at one state, per slice and in total.

    Attributes
    ----------
    sections : Sections
        The slices.
    velocity : (n,) float
        Penetration velocity of each slice in m/s (negative down).
    loads : SectionLoads
        The solver's output for every slice (zero force on dry slices); ``valid`` and
        ``reason`` include the geometric checks (chine wetted).
    solver : str
        Name of the solver used.
    fluid : Fluid
    pose : Pose
    motion : Motion
    """

    sections: Sections
    velocity: np.ndarray
    loads: SectionLoads
    solver: str
    fluid: Fluid
    pose: Pose
    motion: Motion

    @property
    def force(self) -> np.ndarray:
        """(n,) float: force on each slice in N, positive up."""
        return self.loads.force_per_metre * self.sections.dx

    @property
    def total(self) -> float:
        """Total vertical force in N, positive up (Eq. 12)."""
        return float(self.force.sum())

    @property
    def valid(self) -> np.ndarray:
        """(n,) bool: slices inside the method's validity range."""
        return self.loads.valid

    @property
    def all_valid(self) -> bool:
        """True when every slice is inside the validity range."""
        return bool(self.loads.valid.all())

    def __len__(self) -> int:
        return len(self.sections)

    def columns(self) -> dict[str, np.ndarray]:
        """Per-slice columns by name, SI units (deadrise in degrees)."""
        s = self.sections
        cols = {
            "x": s.x,
            "part": s.part,
            "dx": s.dx,
            "penetration": s.penetration,
            "velocity": self.velocity,
            "half_beam": s.half_beam,
            "deadrise_deg": s.deadrise_deg,
            "area": s.area,
            "mass_per_metre": s.mass_per_metre,
            "force_per_metre": self.loads.force_per_metre,
            "force": self.force,
        }
        cols.update(self.loads.diagnostics)
        cols["valid"] = self.loads.valid
        cols["reason"] = self.loads.reason
        return cols


def _as_motion(motion: Motion | float) -> Motion:
    return motion if isinstance(motion, Motion) else Motion(velocity=motion)


def evaluate(
    solver: Solver, sections: Sections, velocity: np.ndarray, fluid: Fluid
) -> SectionLoads:
    """Run a solver on the wetted sections and check what it returns.

    Dry sections get zero force. The result covers every section; its ``valid`` and
    ``reason`` include the geometric checks that the water is below each section's chine
    and meets each section in one span (see ``Sections.waterline_spans``). Floating-point
    warnings inside the solver are silenced: what it returns is checked instead.

    Raises
    ------
    SolverError
        The solver raised, or returned arrays of the wrong type, shape or non-finite forces;
        the message names the solver and its distribution.
    """
    n = len(sections)
    velocity = np.broadcast_to(np.asarray(velocity, dtype=np.float64), (n,))
    wet = sections.wetted
    if wet.any() and not np.all(np.isfinite(sections.mass_per_metre[wet])):
        raise InputError("the hull has no mass: give its mass in kg (mass=...)")
    force = np.zeros(n)
    valid = np.ones(n, dtype=bool)
    reason = np.full(n, "", dtype=object)
    diagnostics: dict[str, np.ndarray] = {}
    if wet.any():
        sub = sections if wet.all() else sections.subset(wet)
        try:
            with np.errstate(all="ignore"):
                loads = solver.section_loads(sub, velocity[wet], fluid)
        except HullsliceError:
            raise
        except Exception as exc:
            raise SolverError(
                f"solver {describe(solver)} failed: {type(exc).__name__}: {exc}"
            ) from exc
        _check_loads(solver, loads, sub, velocity[wet])
        force[wet] = loads.force_per_metre
        valid[wet] = loads.valid
        reason[wet] = loads.reason
        for k, arr in loads.diagnostics.items():
            full = np.full(n, np.nan)
            full[wet] = arr
            diagnostics[k] = full
    chine = sections.chine_wetted
    split = sections.waterline_spans > 1
    for i in np.flatnonzero(chine | split):
        why = [reason[i]] if reason[i] else []
        if chine[i]:
            why.append(CHINE_REASON)
        if split[i]:
            why.append(SPANS_REASON.format(n=int(sections.waterline_spans[i])))
        reason[i] = "; ".join(why)
    valid &= ~(chine | split)
    return SectionLoads(force, valid, reason, diagnostics)


def _check_loads(solver: Solver, loads: object, sections: Sections, velocity) -> None:
    who = describe(solver)
    n = len(sections)
    if not isinstance(loads, SectionLoads):
        raise SolverError(
            f"solver {who} returned {type(loads).__name__}, not hullslice.SectionLoads"
        )
    for name in ("force_per_metre", "valid", "reason"):
        shape = np.shape(getattr(loads, name))
        if shape != (n,):
            raise SolverError(f"solver {who} returned {name} of shape {shape} for {n} sections")
    for k, arr in loads.diagnostics.items():
        if np.shape(arr) != (n,):
            raise SolverError(
                f"solver {who} returned diagnostic {k!r} of shape {np.shape(arr)} for {n} sections"
            )
    try:
        bad = ~np.isfinite(np.asarray(loads.force_per_metre, dtype=np.float64))
    except (TypeError, ValueError):
        raise SolverError(f"solver {who} returned a force per metre that is not numbers") from None
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise SolverError(
            f"solver {who} returned a non-finite force per metre for {int(bad.sum())} of {n} "
            f"sections (first: x = {sections.x[i]:.6g} m, penetration "
            f"{sections.penetration[i]:.6g} m, deadrise {sections.deadrise_deg[i]:.4g} deg, "
            f"mass per metre {sections.mass_per_metre[i]:.6g} kg/m, velocity "
            f"{velocity[i]:.6g} m/s); check these inputs, or use another solver"
        )


def compute_force(
    hull: Hull,
    pose: Pose | float,
    motion: Motion | float,
    *,
    slices: int = 64,
    solver: str | Solver | type[Solver] | None = None,
    fluid: Fluid | None = None,
    deadrise: str = "wedge",
) -> ForceResult:
    """The 2D+t force on a level hull moving vertically.

    Parameters
    ----------
    hull : Hull
        The body, with its mass.
    pose : Pose or float
        The pose, or the draft in m (depth of the lowest point below the water).
    motion : Motion or float
        The motion, or the vertical velocity in m/s (negative down).
    slices : int
        Number of slices over the wetted length (default 64).
    solver : str, Solver or Solver subclass, optional
        The 2D solver (default ``"extended-von-karman"``).
    fluid : Fluid, optional
        Water density and gravity (default 1000 kg/m^3, 9.81 m/s^2).
    deadrise : str
        Deadrise estimator (default ``"wedge"``).

    Returns
    -------
    ForceResult
    """
    pose, motion = _as_pose(pose), _as_motion(motion)
    fluid = fluid or Fluid()
    solver = get_solver(solver)
    if hull.mass is None:
        raise InputError(f"hull {hull.name!r} has no mass: give its mass in kg (mass=...)")
    sections = cut(hull, pose, slices, deadrise=deadrise)
    velocity = np.full(len(sections), motion.velocity)
    loads = evaluate(solver, sections, velocity, fluid)
    return ForceResult(sections, velocity, loads, solver.name, fluid, pose, motion)


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
    solver: str | Solver | type[Solver] | None = None,
    fluid: Fluid | None = None,
    deadrise: str = "wedge",
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
        compute_force(hull, pose, motion, slices=n, solver=solver, fluid=fluid, deadrise=deadrise)
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
