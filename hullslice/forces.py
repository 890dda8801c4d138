"""From sections and their velocities to the force on the body (paper, Eq. 12).

``F_z = sum_j F^j``, ``F^j = f^j d^j`` with ``f^j`` the force per metre the 2D solver gives
for slice ``j`` and ``d^j`` its thickness. Dry slices (zero penetration) carry no force.

**Penetration velocity of a section.** The planes of the slices are fixed in the earth. A
body point at ``r`` from the centre of gravity moves at ``dX/dt = u - q (Z - Z_g)``,
``dZ/dt = w + q (X - X_g)`` (``u`` forward speed, ``w`` vertical velocity, ``q`` pitch rate,
nose up positive). The keel height ``Z_k(X, t)`` at a fixed plane changes as the body point
at the keel moves up or down and as the keel line slides through the plane:

    v = dZ_k/dt |_X = w + q (X - X_g) - (u - q (Z_k - Z_g)) dZ_k/dX

With no pitch rate and no forward speed, ``v = w``. A body moving forward with its keel
rising towards the bow (``dZ_k/dX > 0``, nose up) pushes each plane's section down.

**Horizontal force and pitch moment.** The slice force acts normal to the keel line (the
pressure on the body's bottom), so it has a horizontal part ``F_x^j = -F^j dZ_k/dX`` (a
drag when the keel rises forward). The pitch moment about the centre of gravity, nose up
positive, is ``sum_j (X^j - X_g) F^j - (Z^j - Z_g) F_x^j``, each force applied at its
station halfway between the keel and the waterline. Friction is not modelled.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from .convergence import Richardson, richardson
from .errors import HullsliceError, InputError, SolverError
from .mesh import Hull
from .sections import Sections, _as_pose, _slice_count, cut
from .solvers.base import SectionLoads, Solver
from .solvers.registry import describe, get_solver
from .state import Fluid, Motion, Pose

__all__ = [
    "ConvergenceStudy",
    "ForceResult",
    "compute_force",
    "convergence",
    "evaluate",
    "force_on",
    "section_velocity",
]

CHINE_REASON = "water at or above the section's chine/widest point"
MASSLESS_REASON = "no mass per metre at this station (the mass distribution puts none here)"
#: Smallest deadrise a solver is given, rad: a flat bottom is computed as this, flagged.
MIN_DEADRISE = float(np.radians(1.0))
FLAT_REASON = "deadrise below 1 deg (a flat bottom): computed at 1 deg, outside the wedge theory"


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
    x_cg: float = 0.0

    @property
    def force(self) -> np.ndarray:
        """(n,) float: vertical force on each slice (entry) in N, positive up."""
        return self.loads.force_per_metre * self.sections.dx

    @property
    def force_x(self) -> np.ndarray:
        """(n,) float: horizontal force on each slice in N, positive forward."""
        return -self.force * self.sections.keel_slope

    @property
    def total(self) -> float:
        """Total vertical force in N, positive up (Eq. 12)."""
        return float(self.force.sum())

    @property
    def total_x(self) -> float:
        """Total horizontal force in N, positive forward."""
        return float(self.force_x.sum())

    @property
    def moment(self) -> float:
        """Pitch moment about the centre of gravity in N m, positive nose up."""
        s = self.sections
        arm_x = s.x - self.x_cg
        arm_z = 0.5 * s.keel_z - s.z_cg
        return float((arm_x * self.force - arm_z * self.force_x).sum())

    @property
    def station_force(self) -> np.ndarray:
        """(s,) float: vertical force on each station (its pieces added), N."""
        s = self.sections
        return np.bincount(s.station, weights=self.force, minlength=s.n_stations)

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

    def to_xarray(self):
        """The per-slice results as an ``xarray.Dataset`` with units (needs xarray)."""
        from .xarray_io import force_to_xarray

        return force_to_xarray(self)

    def to_dataframe(self):
        """The per-slice results as a ``pandas.DataFrame``, units in ``attrs``."""
        from .xarray_io import force_to_dataframe

        return force_to_dataframe(self)

    def columns(self) -> dict[str, np.ndarray]:
        """Per-slice columns by name, SI units (deadrise in degrees)."""
        s = self.sections
        cols = {
            "station": s.station,
            "x": s.x,
            "dx": s.dx,
            "penetration": s.penetration,
            "velocity": self.velocity,
            "half_beam": s.half_beam,
            "deadrise_deg": s.deadrise_deg,
            "deadrise_port_deg": np.degrees(s.deadrise_port),
            "deadrise_stbd_deg": np.degrees(s.deadrise_stbd),
            "keel_slope": s.keel_slope,
            "area": s.area,
            "mass_per_metre": s.mass_per_metre,
            "force_per_metre": self.loads.force_per_metre,
            "force": self.force,
            "force_x": self.force_x,
        }
        cols.update(self.loads.diagnostics)
        cols["valid"] = self.loads.valid
        cols["reason"] = self.loads.reason
        return cols


def _as_motion(motion: Motion | float) -> Motion:
    return motion if isinstance(motion, Motion) else Motion(velocity=motion)


def section_velocity(sections: Sections, motion: Motion, x_cg: float) -> np.ndarray:
    """Penetration velocity of each section in m/s, negative down (see the module notes).

    Parameters
    ----------
    sections : Sections
    motion : Motion
        Vertical velocity and forward speed of the centre of gravity (m/s), pitch rate
        (rad/s).
    x_cg : float
        Earth ``X`` of the centre of gravity, m.
    """
    q, u = motion.pitch_rate, motion.forward_speed
    arm_x = sections.x - x_cg
    arm_z = sections.keel_z - sections.z_cg
    return motion.velocity + q * arm_x - (u - q * arm_z) * sections.keel_slope


def evaluate(
    solver: Solver, sections: Sections, velocity: np.ndarray, fluid: Fluid
) -> SectionLoads:
    """Run a solver on the wetted sections and check what it returns.

    Dry sections, and wetted ones that carry no mass, get zero force; a deadrise below
    :data:`MIN_DEADRISE` (a flat bottom) is given to the solver as that. The result covers
    every section; its ``valid`` and ``reason`` include these geometric checks and that the
    water is below each section's chine.
    Floating-point warnings inside the solver are silenced: what it returns is checked.

    Raises
    ------
    SolverError
        The solver raised, or returned arrays of the wrong type, shape or non-finite forces;
        the message names the solver and its distribution.
    """
    n = len(sections)
    velocity = np.asarray(velocity, dtype=np.float64)
    if velocity.shape != (n,):
        velocity = np.broadcast_to(velocity, (n,))
    else:  # the solver may not write into the caller's array
        velocity = velocity.view()
        velocity.flags.writeable = False
    wet = sections.wetted
    if wet.any() and not np.all(np.isfinite(sections.mass_per_metre[wet])):
        raise InputError("the hull has no mass: give its mass in kg (mass=...)")
    force = np.zeros(n)
    valid = np.ones(n, dtype=bool)
    reason = np.full(n, "", dtype=object)
    diagnostics: dict[str, np.ndarray] = {}
    # a wetted section that carries no mass (between a distribution's point masses, or
    # beyond its line) is in no free fall: it gets no force, flagged
    massless = wet & (sections.mass_per_metre <= 0.0)
    if massless.any():
        wet = wet & ~massless
        valid[massless] = False
        reason[massless] = MASSLESS_REASON
    # a flat bottom (zero deadrise) has no wedge: computed at the smallest deadrise, flagged
    flat = wet & ~(sections.deadrise >= MIN_DEADRISE)
    if flat.any():
        sections = replace(
            sections,
            deadrise=np.where(flat, MIN_DEADRISE, sections.deadrise),
            deadrise_port=np.fmax(sections.deadrise_port, MIN_DEADRISE),
            deadrise_stbd=np.fmax(sections.deadrise_stbd, MIN_DEADRISE),
        )
    if wet.any():
        every = bool(wet.all())
        sub = sections if every else sections.subset(wet)
        try:
            with np.errstate(all="ignore"):
                loads = solver.section_loads(sub, velocity if every else velocity[wet], fluid)
        except HullsliceError:
            raise
        except Exception as exc:
            raise SolverError(
                f"solver {describe(solver)} failed: {type(exc).__name__}: {exc}"
            ) from exc
        _check_loads(solver, loads, sub, velocity if every else velocity[wet])
        if every:  # the solver's arrays cover every section (none massless)
            force = np.array(loads.force_per_metre)
            valid = np.array(loads.valid)
            reason = np.array(loads.reason)
            diagnostics = dict(loads.diagnostics)
        else:
            force[wet] = loads.force_per_metre
            valid[wet] = loads.valid
            reason[wet] = loads.reason
            for k, arr in loads.diagnostics.items():
                full = np.full(n, np.nan)
                full[wet] = arr
                diagnostics[k] = full
    for mask, why in ((flat, FLAT_REASON), (sections.chine_wetted, CHINE_REASON)):
        if mask.any():
            valid &= ~mask
            reason[mask] = [f"{r}; {why}" if r else why for r in reason[mask]]
    return SectionLoads(force, valid, reason, diagnostics)


def _check_loads(solver: Solver, loads: object, sections: Sections, velocity) -> None:
    problem = _loads_problem(loads, len(sections))
    if not problem and not np.all(np.isfinite(loads.force_per_metre)):
        i = int(np.flatnonzero(~np.isfinite(loads.force_per_metre))[0])
        problem = (
            f"a non-finite force per metre for {int((~np.isfinite(loads.force_per_metre)).sum())}"
            f" of {len(sections)} sections (first: x = {sections.x[i]:.6g} m, penetration "
            f"{sections.penetration[i]:.6g} m, deadrise {sections.deadrise_deg[i]:.4g} deg, mass "
            f"per metre {sections.mass_per_metre[i]:.6g} kg/m, velocity {velocity[i]:.6g} m/s); "
            "check these inputs, or use another solver"
        )
    if problem:
        # naming the plugin reads its distribution's metadata: only when there is a fault
        raise SolverError(f"solver {describe(solver)} returned {problem}")


def _loads_problem(loads: object, n: int) -> str:
    """What is wrong with a solver's output for ``n`` sections ("" when nothing is)."""
    if not isinstance(loads, SectionLoads):
        return f"{type(loads).__name__}, not hullslice.SectionLoads"
    # SectionLoads made its fields arrays (float forces and diagnostics): shapes are left
    for name in ("force_per_metre", "valid", "reason"):
        shape = getattr(loads, name).shape
        if shape != (n,):
            return f"{name} of shape {shape} for {n} sections"
    for k, arr in loads.diagnostics.items():
        if arr.shape != (n,):
            return f"diagnostic {k!r} of shape {arr.shape} for {n} sections"
    return ""


def compute_force(
    hull: Hull,
    pose: Pose | float,
    motion: Motion | float,
    *,
    slices: int = 32,
    solver: str | Solver | type[Solver] | None = None,
    fluid: Fluid | None = None,
    deadrise: str = "wedge",
    slicing: str = "wetted",
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

    Returns
    -------
    ForceResult
    """
    pose, motion = _as_pose(pose), _as_motion(motion)
    fluid = fluid or Fluid()
    solver = get_solver(solver)
    if hull.mass is None:
        raise InputError(f"hull {hull.name!r} has no mass: give its mass in kg (mass=...)")
    sections = cut(hull, pose, slices, deadrise=deadrise, slicing=slicing)
    return force_on(sections, motion, solver, fluid, float(hull.cg[0]))


def force_on(
    sections: Sections, motion: Motion, solver: Solver, fluid: Fluid, x_cg: float
) -> ForceResult:
    """The force on cut sections moving with ``motion`` (inputs already checked)."""
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
    solver: str | Solver | type[Solver] | None = None,
    fluid: Fluid | None = None,
    deadrise: str = "wedge",
    slicing: str = "wetted",
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
