"""A 2D solver run on the wetted sections, and what it returns checked.

:func:`evaluate` runs a free-fall-form solver (the force per metre of each section),
:func:`evaluate_added_mass` a momentum-form one (added mass, its rate, an extra force).
Both give the solver the wetted sections only, turn any escape from it into a
:class:`~hullslice.errors.SolverError` naming the solver, check the shapes and values of its
output, spread it over every section and flag the sections outside the method's range
(a flat bottom, the water at the chine, no mass).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..errors import HullsliceError, InputError, SolverError
from ..kernel.keel import END_FACE_SLOPE, STEEP_SLOPE
from ..limits import no_mass
from ..safety import failure, plugin_code
from ..sections import Sections
from ..solvers.base import AddedMass, MomentumFormSolver, SectionLoads, SolverBase
from ..solvers.registry import describe
from ..state import Fluid

__all__ = [
    "CHINE_REASON",
    "FACE_REASON",
    "FLAT_REASON",
    "MASSLESS_REASON",
    "MIN_DEADRISE",
    "STEEP_REASON",
    "STEEP_SLOPE",
    "evaluate",
    "evaluate_added_mass",
]

CHINE_REASON = "water at or above the section's chine/widest point"
MASSLESS_REASON = "no mass per metre at this station (the mass distribution puts none here)"
#: Smallest deadrise a solver is given, rad: a flat bottom is computed as this, flagged.
MIN_DEADRISE = float(np.radians(1.0))
FLAT_REASON = "deadrise below 1 deg (a flat bottom): computed at 1 deg, outside the wedge theory"
STEEP_REASON = (
    "keel steeper than 45 deg (a blunt bow or tail): outside the slender-body theory, "
    "computed and flagged"
)
FACE_REASON = (
    "keel on an end face or a step's face (steeper than 75 deg): not a section of the "
    "bottom, no force"
)


def _on_faces(sections: Sections, wet: np.ndarray) -> np.ndarray:
    """Wetted entries whose keel is on an end face (a transom, a blunt bow) or the face of
    a step: the keel line there is steeper than :data:`~hullslice.kernel.keel.END_FACE_SLOPE`.
    A pitched transom's face dips under the water aft of the keel's corner, and the planes
    through it cut flat-bottomed sections that are no slender body's: the 2D theory does
    not describe them, and they get no force."""
    return wet & (np.abs(sections.keel_slope) > END_FACE_SLOPE)


def _steep(sections: Sections, wet: np.ndarray) -> np.ndarray:
    """Wetted entries whose keel is steeper than 45 deg but not yet a face: a blunt bow or
    tail met at speed presses its sections down at the forward speed times that slope,
    which the 2D theory of a slender body does not describe. Computed, flagged."""
    return wet & (np.abs(sections.keel_slope) > STEEP_SLOPE)


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
        with np.errstate(all="ignore"), plugin_code(f"solver {solver.name!r}"):
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
        mpm = sections.mass_per_metre[wet]
        if np.any(np.isinf(mpm)):  # a mass so large its share per metre overflows
            i = int(np.flatnonzero(np.isinf(mpm))[0])
            raise InputError(
                f"the mass per metre at x = {sections.x[wet][i]:.6g} m overflows to infinity: "
                "the body's mass is too large for a float over its volume; give the mass in kg "
                "(a real body's is below 1e12)"
            )
        raise no_mass()
    # a wetted section that carries no mass (between a distribution's point masses, or
    # beyond its line) is in no free fall: it gets no force, flagged
    massless = wet & (sections.mass_per_metre <= 0.0)
    faces = _on_faces(sections, wet)
    wet = wet & ~massless & ~faces
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
    chine = sections.chine_wetted & ~faces
    checks = ((faces, FACE_REASON), (flat, FLAT_REASON), (chine, CHINE_REASON),
              (_steep(sections, wet), STEEP_REASON))  # fmt: skip
    _flag(valid, reason, checks)
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
    faces = _on_faces(sections, sections.wetted)
    wet = sections.wetted & ~faces
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
    chine = sections.chine_wetted & ~faces
    if getattr(solver, "models_separation", False):
        chine = np.zeros(n, dtype=bool)
    contour = diagnostics.get("contour")
    if contour is not None:  # read from its own contour: not limited by a wedge's deadrise
        flat = flat & ~(contour > 0)
    checks = ((faces, FACE_REASON), (flat, FLAT_REASON), (chine, CHINE_REASON),
              (_steep(sections, wet), STEEP_REASON))  # fmt: skip
    _flag(valid, reason, checks)
    girth = pressure = None
    if out is not None and out.girth is not None:
        girth = np.array(out.girth) if every else np.zeros(n)
        if not every:
            girth[wet] = out.girth
    if out is not None and out.pressure is not None:
        pressure = out.pressure if every else out.pressure.spread(wet)
    return AddedMass(
        m_a, rate, valid, reason, extra, diagnostics, arrays["vertical"], girth, pressure
    )


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
    if not problem:
        problem = _total_problem(loads.force_per_metre, sections, "force per metre", "N")  # type: ignore[attr-defined]
    if problem:
        # naming the plugin reads its distribution's metadata: only when there is a fault
        raise SolverError(f"solver {describe(solver)} returned {problem}")


def _total_problem(per_metre: np.ndarray, sections: Sections, what: str, unit: str) -> str:
    """What is wrong with finite per-metre values whose slices or total are not finite
    (``1e308`` N/m over 0.1 m slices): "" when nothing is."""
    with np.errstate(all="ignore"):
        per_slice = per_metre * sections.dx
        total = per_slice.sum()
        size = np.abs(per_slice).sum()
    if np.isfinite(total) and np.isfinite(size):
        return ""
    i = int(np.argmax(np.abs(per_metre)))
    return (
        f"finite {what} values whose total over the {len(sections)} slices is not a finite "
        f"number (the largest: {per_metre[i]:.6g} {unit}/m at x = {sections.x[i]:.6g} m): "
        "no load a body can take; check the solver's units, or use another solver"
    )


def _check_added_mass(solver: SolverBase, out: object, sections: Sections) -> None:
    n = len(sections)
    problem = ""
    if not isinstance(out, AddedMass):
        problem = f"{type(out).__name__}, not hullslice.AddedMass"
    else:
        for name in ("added_mass", "rate", "extra", "vertical", "valid", "reason", "girth"):
            arr = getattr(out, name)
            if arr is not None and arr.shape != (n,):
                problem = f"{name} of shape {arr.shape} for {n} sections"
                break
        else:
            if out.pressure is not None and len(out.pressure) != n:
                problem = f"pressures for {len(out.pressure)} of {n} sections"
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
        if not problem:
            for name, unit in (("added_mass", "kg"), ("rate", "kg/s"), ("extra", "N"),
                               ("vertical", "N")):  # fmt: skip
                problem = _total_problem(getattr(out, name), sections, name.replace("_", " "), unit)
                if problem:
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
