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

**The momentum form** (solvers of the kind ``"momentum"``). The solver gives each
section's added mass per metre ``m_a`` and its rate ``m_a' = dm_a/dp``; the force per metre
is the rate of change of the fluid's momentum at the fixed plane,

    f = d/dt [m_a (-v)] = m_a' v^2 - m_a a + extra      (N/m, positive up)

with ``dp/dt = -v``. On a section leaving the water (``v >= 0``) the flux term ``m_a' v^2``
is dropped (the flow separates; no suction), the inertia term stays. The section's
acceleration ``a = dv/dt |_X`` at the fixed plane follows from differentiating ``v`` above
(``dX_g/dt = u``, ``dZ_k/dt |_X = v``, ``ds/dt |_X = dv/dX`` with ``s = dZ_k/dX``):

    a = dw/dt + dq/dt (X - X_g + (Z_k - Z_g) s) - du/dt s + b,
    b = - q u + q (v - w) s - U q (1 + s^2) + U^2 kappa,     U = u - q (Z_k - Z_g),

with ``kappa = d^2 Z_k / dX^2`` the keel line's curvature. The first line is linear in the
body's accelerations, ``a = J . (dw/dt, dq/dt, du/dt) + b``; ``b`` holds the terms that
multiply no acceleration (the pitch rate's and the keel line's slide through the plane).
By virtual work, the generalised forces of a section force ``f`` along the penetration are
``J f``: the vertical force ``f``, the moment ``f (X - X_g + (Z_k - Z_g) s)`` (each force
applied at its keel point, normal to the keel line) and the horizontal force ``- f s``. The
added-mass matrix of the body is then ``A = sum m_a J J^T dx``, symmetric and positive
semi-definite, and the equations of motion read ``(M_body + A) q'' = Q0 + gravity`` with
``Q0 = sum J f0 dx``, ``f0 = m_a' v^2 [v < 0] - m_a b + extra`` (:class:`MomentumTerms`).
A solver's ``vertical`` force (buoyancy) is vertical whatever the keel's slope: it adds
``(1, X - X_g, 0) f_v dx`` instead.

A momentum solver that reads an entry's wetted width from the section's own contour says
so with the diagnostic ``contour`` (1): such an entry is not flagged for a deadrise below
:data:`MIN_DEADRISE`, which limits the equivalent wedge only.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import cast

import numpy as np

from .convergence import Richardson, richardson
from .errors import HullsliceError, InputError, SolverError
from .limits import no_mass
from .mesh import Hull
from .safety import failure
from .sections import Sections, _as_pose, _slice_count, cut
from .solvers.base import (
    FREE_FALL,
    MOMENTUM,
    AddedMass,
    MomentumFormSolver,
    SectionLoads,
    SolverBase,
)
from .solvers.registry import describe, get_solver
from .state import Acceleration, Fluid, Motion, Pose

__all__ = [
    "ConvergenceStudy",
    "ForceResult",
    "MomentumTerms",
    "compute_force",
    "convergence",
    "evaluate",
    "evaluate_added_mass",
    "force_on",
    "momentum_terms",
    "section_kinematics",
    "section_velocity",
]

CHINE_REASON = "water at or above the section's chine/widest point"
#: Smallest wetted length over wetted beam of a slender body (2D+t's assumption).
MIN_SLENDERNESS = 2.0
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
    x_cg : float
        Earth ``X`` of the centre of gravity, m.
    kind : str
        The solver's kind, ``"free-fall"`` or ``"momentum"``.
    acceleration : Acceleration or None
        The body's acceleration the force was formed with (momentum form), else None.
    section_acceleration : (n,) float or None
        Each section's penetration acceleration, m/s^2, positive up (momentum form).
    """

    sections: Sections
    velocity: np.ndarray
    loads: SectionLoads
    solver: str
    fluid: Fluid
    pose: Pose
    motion: Motion
    x_cg: float = 0.0
    kind: str = FREE_FALL
    acceleration: Acceleration | None = None
    section_acceleration: np.ndarray | None = None

    @property
    def force(self) -> np.ndarray:
        """(n,) float: vertical force on each slice (entry) in N, positive up."""
        return self.loads.force_per_metre * self.sections.dx

    @property
    def force_x(self) -> np.ndarray:
        """(n,) float: horizontal force on each slice in N, positive forward: the force
        normal to the keel line has a horizontal part, a vertical (hydrostatic) force of a
        momentum-form solver has none."""
        normal = self.force
        vertical = self.loads.diagnostics.get("vertical_force")
        if vertical is not None:
            normal = normal - np.nan_to_num(vertical) * self.sections.dx
        return -normal * self.sections.keel_slope

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
        """Pitch moment about the centre of gravity in N m, positive nose up.

        A free-fall force is applied halfway between its keel and the waterline, a
        momentum-form force at its keel point (see the module notes).
        """
        s = self.sections
        arm_x = s.x - self.x_cg
        keel = s.keel_z if self.kind == MOMENTUM else 0.5 * s.keel_z
        arm_z = keel - s.z_cg
        return float((arm_x * self.force - arm_z * self.force_x).sum())

    @property
    def added_mass(self) -> float:
        """Heave added mass ``sum m_a dx`` in kg (momentum form; NaN for free-fall)."""
        if self.kind != MOMENTUM:
            return float("nan")
        return float((self.loads.diagnostics["added_mass"] * self.sections.dx).sum())

    @property
    def slenderness(self) -> float:
        """Wetted length over wetted beam (the widest wetted piece at the waterline);
        ``inf`` when nothing is wetted. See :data:`MIN_SLENDERNESS`."""
        s = self.sections
        wet = s.penetration > 0
        if not wet.any():
            return float("inf")
        beam = float((s.half_beam_port + s.half_beam_stbd)[wet].max())
        return s.wetted_length / beam if beam > 0 else float("inf")

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
        if self.section_acceleration is not None:
            cols["section_acceleration"] = self.section_acceleration
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


def _readonly_velocity(velocity, n: int) -> np.ndarray:
    velocity = np.asarray(velocity, dtype=np.float64)
    if velocity.shape != (n,):
        return np.broadcast_to(velocity, (n,))
    velocity = velocity.view()  # the solver may not write into the caller's array
    velocity.flags.writeable = False
    return velocity


def _flat_clamped(sections: Sections, wet: np.ndarray) -> tuple[Sections, np.ndarray]:
    """A flat bottom (zero deadrise) has no wedge: computed at :data:`MIN_DEADRISE`."""
    flat = wet & ~(sections.deadrise >= MIN_DEADRISE)
    if flat.any():
        sections = replace(
            sections,
            deadrise=np.where(flat, MIN_DEADRISE, sections.deadrise),
            deadrise_port=np.fmax(sections.deadrise_port, MIN_DEADRISE),
            deadrise_stbd=np.fmax(sections.deadrise_stbd, MIN_DEADRISE),
        )
    return sections, flat


def _call(solver: SolverBase, method, sections: Sections, velocity, fluid: Fluid):
    """Call a solver's method on wetted sections, turning every escape into a SolverError."""
    try:
        with np.errstate(all="ignore"):
            return method(sections, velocity, fluid)
    except HullsliceError:
        raise
    except (Exception, SystemExit) as exc:  # a plugin's sys.exit() does not end hullslice
        raise SolverError(f"solver {describe(solver)} failed: {failure(exc)}") from exc


#: What a section the solver was not given (dry, or without mass) holds.
_FILL = {
    "force_per_metre": (0.0, np.float64),
    "added_mass": (0.0, np.float64),
    "rate": (0.0, np.float64),
    "extra": (0.0, np.float64),
    "vertical": (0.0, np.float64),
    "valid": (True, bool),
    "reason": ("", object),
}


def _spread(record, names, wet: np.ndarray, every: bool):
    """A solver's arrays over every section, and its diagnostics (NaN where it was not
    called): its own arrays, copied, when it was given every section."""
    n = len(wet)
    if record is not None and every:
        return {k: np.array(getattr(record, k)) for k in names}, dict(record.diagnostics)
    arrays = {k: np.full(n, _FILL[k][0], dtype=_FILL[k][1]) for k in names}
    diagnostics: dict[str, np.ndarray] = {}
    if record is not None:
        for k in names:
            arrays[k][wet] = getattr(record, k)
        for k, arr in record.diagnostics.items():
            full = np.full(n, np.nan)
            full[wet] = arr
            diagnostics[k] = full
    return arrays, diagnostics


def _flag(valid: np.ndarray, reason: np.ndarray, masks) -> None:
    for mask, why in masks:
        if mask.any():
            valid &= ~mask
            reason[mask] = [f"{r}; {why}" if r else why for r in reason[mask]]


def evaluate(
    solver: SolverBase, sections: Sections, velocity: np.ndarray, fluid: Fluid
) -> SectionLoads:
    """Run a free-fall-form solver on the wetted sections and check what it returns.

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
    velocity = _readonly_velocity(velocity, n)
    wet = sections.wetted
    if wet.any() and not np.all(np.isfinite(sections.mass_per_metre[wet])):
        raise no_mass()
    # a wetted section that carries no mass (between a distribution's point masses, or
    # beyond its line) is in no free fall: it gets no force, flagged
    massless = wet & (sections.mass_per_metre <= 0.0)
    wet = wet & ~massless
    sections, flat = _flat_clamped(sections, wet)
    loads = None
    every = bool(wet.all()) and n > 0
    if wet.any():
        sub = sections if every else sections.subset(wet)
        v_sub = velocity if every else velocity[wet]
        loads = _call(solver, solver.section_loads, sub, v_sub, fluid)  # type: ignore[attr-defined]
        _check_loads(solver, loads, sub, v_sub)
    arrays, diagnostics = _spread(loads, ("force_per_metre", "valid", "reason"), wet, every)
    force, valid, reason = arrays["force_per_metre"], arrays["valid"], arrays["reason"]
    if massless.any():
        valid[massless] = False
        reason[massless] = MASSLESS_REASON
    _flag(valid, reason, ((flat, FLAT_REASON), (sections.chine_wetted, CHINE_REASON)))
    return SectionLoads(force, valid, reason, diagnostics)


def evaluate_added_mass(
    solver: MomentumFormSolver, sections: Sections, velocity: np.ndarray, fluid: Fluid
) -> AddedMass:
    """Run a momentum-form solver on the wetted sections and check what it returns.

    Dry sections get zero added mass. A deadrise below :data:`MIN_DEADRISE` (a flat bottom)
    is given to the solver as that, flagged, and every section whose water reaches its
    chine is flagged. The body's mass is not used.

    Raises
    ------
    SolverError
        The solver raised, or returned arrays of the wrong type or shape, a negative or
        non-finite added mass, or a non-finite rate or extra force.
    """
    n = len(sections)
    velocity = _readonly_velocity(velocity, n)
    wet = sections.wetted
    sections, flat = _flat_clamped(sections, wet)
    every = bool(wet.all()) and n > 0
    out = None
    if wet.any():
        sub = sections if every else sections.subset(wet)
        v_sub = velocity if every else velocity[wet]
        out = _call(solver, solver.added_mass, sub, v_sub, fluid)
        _check_added_mass(solver, out, sub)
    names = ("added_mass", "rate", "extra", "vertical", "valid", "reason")
    arrays, diagnostics = _spread(out, names, wet, every)
    m_a, rate, extra = arrays["added_mass"], arrays["rate"], arrays["extra"]
    valid, reason = arrays["valid"], arrays["reason"]
    chine = sections.chine_wetted
    if getattr(solver, "models_separation", False):
        chine = np.zeros(n, dtype=bool)
    contour = diagnostics.get("contour")
    if contour is not None:  # read from its own contour: not limited by a wedge's deadrise
        flat = flat & ~(contour > 0)
    _flag(valid, reason, ((flat, FLAT_REASON), (chine, CHINE_REASON)))
    return AddedMass(m_a, rate, valid, reason, extra, diagnostics, arrays["vertical"])


def _check_loads(solver: SolverBase, loads: object, sections: Sections, velocity) -> None:
    problem = _loads_problem(loads, len(sections))
    if not problem and not np.all(np.isfinite(loads.force_per_metre)):  # type: ignore[attr-defined]
        fpm = loads.force_per_metre  # type: ignore[attr-defined]
        i = int(np.flatnonzero(~np.isfinite(fpm))[0])
        problem = (
            f"a non-finite force per metre for {int((~np.isfinite(fpm)).sum())}"
            f" of {len(sections)} sections (first: x = {sections.x[i]:.6g} m, penetration "
            f"{sections.penetration[i]:.6g} m, deadrise {sections.deadrise_deg[i]:.4g} deg, mass "
            f"per metre {sections.mass_per_metre[i]:.6g} kg/m, velocity {velocity[i]:.6g} m/s); "
            "check these inputs, or use another solver"
        )
    if problem:
        # naming the plugin reads its distribution's metadata: only when there is a fault
        raise SolverError(f"solver {describe(solver)} returned {problem}")


def _check_added_mass(solver: SolverBase, out: object, sections: Sections) -> None:
    n = len(sections)
    problem = ""
    if not isinstance(out, AddedMass):
        problem = f"{type(out).__name__}, not hullslice.AddedMass"
    else:
        for name in ("added_mass", "rate", "extra", "vertical", "valid", "reason"):
            shape = getattr(out, name).shape
            if shape != (n,):
                problem = f"{name} of shape {shape} for {n} sections"
                break
        else:
            for k, arr in out.diagnostics.items():
                if arr.shape != (n,):
                    problem = f"diagnostic {k!r} of shape {arr.shape} for {n} sections"
                    break
        if not problem and out.valid.dtype != bool:
            problem = f"valid of type {out.valid.dtype}, not a boolean array"
        if not problem:
            for name in ("added_mass", "rate", "extra", "vertical"):
                bad = ~np.isfinite(getattr(out, name))
                if bad.any():
                    i = int(np.flatnonzero(bad)[0])
                    problem = (
                        f"a non-finite {name.replace('_', ' ')} for {int(bad.sum())} of {n} "
                        f"sections (first: x = {sections.x[i]:.6g} m, penetration "
                        f"{sections.penetration[i]:.6g} m, deadrise "
                        f"{sections.deadrise_deg[i]:.4g} deg)"
                    )
                    break
        if not problem and np.any(out.added_mass < 0):
            i = int(np.flatnonzero(out.added_mass < 0)[0])
            problem = (
                f"a negative added mass ({out.added_mass[i]:.6g} kg/m at x = "
                f"{sections.x[i]:.6g} m, penetration {sections.penetration[i]:.6g} m): an "
                "added mass is never negative"
            )
    if problem:
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


def section_kinematics(
    sections: Sections, motion: Motion, x_cg: float, velocity: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """How each section's penetration acceleration follows from the body's.

    Parameters
    ----------
    sections : Sections
    motion : Motion
        Vertical velocity and forward speed (m/s) and pitch rate (rad/s).
    x_cg : float
        Earth ``X`` of the centre of gravity, m.
    velocity : (n,) float
        The sections' penetration velocities (:func:`section_velocity`), m/s.

    Returns
    -------
    jac : (n, 3) float
        ``da/d(dw/dt)`` (1), ``da/d(dq/dt)`` (m) and ``da/d(du/dt)`` (1): the section's
        acceleration is ``jac @ (dw/dt, dq/dt, du/dt) + bias``.
    bias : (n,) float
        The part that multiplies no acceleration, m/s^2 (see the module notes).
    """
    q, u, w = motion.pitch_rate, motion.forward_speed, motion.velocity
    slope = sections.keel_slope
    arm_z = sections.keel_z - sections.z_cg
    jac = np.empty((len(sections), 3))
    jac[:, 0] = 1.0
    jac[:, 1] = sections.x - x_cg + arm_z * slope
    jac[:, 2] = -slope
    if q == 0.0 and u == 0.0:
        return jac, np.zeros(len(sections))
    slide = u - q * arm_z
    bias = (
        -q * u
        + q * (velocity - w) * slope
        - slide * q * (1.0 + slope * slope)
        + slide * slide * cast(np.ndarray, sections.keel_curvature)
    )
    return jac, bias


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
    s = terms.sections
    weight = terms.added.added_mass * s.dx
    jac = terms.jac[:, idx] if len(idx) < 3 else terms.jac
    total = (jac * weight[:, None]).T @ jac
    rhs = jac.T @ (terms.f0 * s.dx)
    body = {0: mass, 1: inertia, 2: mass}
    for k, i in enumerate(idx):
        if body[i] is None:
            raise InputError("a free pitch needs the body's pitch inertia (kg m^2)")
        total[k, k] += body[i]
    if idx[0] == 0:
        rhs[0] -= mass * gravity
    held = [i for i in range(3) if not free[i] and acc[i] != 0.0]
    if held:  # prescribed accelerations of the other degrees of freedom
        cross = (terms.jac[:, idx] * weight[:, None]).T @ terms.jac[:, held]
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
            acceleration = solve_accelerations(terms, mass, None, fluid.g, (True, False, False))
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
