"""Equations of motion and their integration: free motion and prescribed motion.

Free motion integrates the rigid body's equations in the vertical plane,

    dZ_g/dt = w,        d(theta)/dt = q,        dX_g/dt = u,
    (M_body + A) (dw/dt, dq/dt, du/dt) = (F_z - m g, M_y, F_x)

(``w`` vertical velocity, negative down; ``theta`` pitch, nose up; ``u`` forward speed;
``F_z``, ``F_x``, ``M_y`` the 2D+t force and moment about the centre of gravity, see
:mod:`hullslice.forces`; ``M_body = diag(m, I, m)``) with the classical fourth-order
Runge-Kutta scheme at a fixed step, cutting the hull afresh at each stage. Pitch (``dq/dt``)
is free with ``free_pitch`` and surge (``du/dt``) with ``free_surge``; otherwise the pitch
changes at the given constant rate and the forward speed is constant.

``A`` is the added-mass matrix of a **momentum-form** solver, assembled from the sections
at every stage and solved with the body's mass matrix (no lag from the last step, no
iteration); a singular or indefinite matrix is an :class:`~hullslice.errors.InputError`
naming the time. Gravity acts on the body here, never in the water force. A **free-fall**
solver (the paper's) has no added mass: ``A = 0`` and ``F_z`` already holds each slice's
free fall (Eq. 12). A level vertical fall is the special case of the paper.

A prescribed motion (the paper's way: kinematics from CFD or a test) evaluates the force
along a table of ``t, draft, velocity`` (and optionally the accelerations, pitch and
forward speed, :mod:`hullslice.motion.kinematics`); a momentum-form solver's force then uses
the table's accelerations and does not depend on the body's mass.

A run ends at its end time, or earlier by one of the stop rules of
:data:`~hullslice.motion.history.STOP_RULES`; the :class:`History` records which rule
ended it and the first time each limit was crossed.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import cast

import numpy as np

from ..aero import Aerodynamics, aero_model
from ..constants import MAX_SLICE_STEPS, MAX_STEPS
from ..errors import InputError
from ..forces import solve_bounded
from ..forces.friction import Friction
from ..forces.friction import friction as wall_friction
from ..forces.momentum import calm_girth
from ..geometry import frame
from ..mesh import Hull
from ..renamed import renamed_keywords
from ..sections import _height_at
from ..solvers.base import SolverBase
from ..state import Fluid, Motion, Pose
from .history import DEFAULT_STOP_ON, MAX_FLAGGED_SHARE, MAX_PITCH, History
from .kinematics import check_kinematics, kinematics_accelerations
from .model import ForceModel
from .recorder import Recorder

__all__ = ["ForceModel", "prescribed", "simulate"]


class _PitchLimit(Exception):
    """The pitch reached :data:`MAX_PITCH` during a run."""


#: Largest part of the body's height it may move in one time step of a free fall.
MAX_STEP_TRAVEL = 0.1


def _positive(value: float, what: str, unit: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what} {value!r} is not a number (in {unit})") from None
    if not (math.isfinite(v) and v > 0.0):
        raise InputError(f"{what} {value!r} {unit} is not positive")
    return v


def _in_rad(rad: float, deg: float | None, rad_name: str, deg_name: str) -> float:
    """An angle given in rad or in degrees (not both), in rad."""
    if deg is None:
        return rad
    if rad != 0.0:
        raise InputError(f"give {rad_name}= or {deg_name}=, not both")
    try:
        return math.radians(float(deg))
    except (TypeError, ValueError):
        raise InputError(f"{deg_name} {deg!r} is not a number (in deg)") from None


@renamed_keywords(pitch="pitch_rad", pitch_rate="pitch_rate_rad_s")
def simulate(
    hull: Hull,
    velocity: float,
    t_end: float,
    *,
    dt: float | None = None,
    draft: float = 0.0,
    pitch_rad: float = 0.0,
    forward_speed: float = 0.0,
    pitch_rate_rad_s: float = 0.0,
    pitch_deg: float | None = None,
    pitch_rate_deg_s: float | None = None,
    free_pitch: bool = False,
    free_surge: bool = False,
    slices: int = 32,
    solver: str | SolverBase | type[SolverBase] | None = None,
    fluid: Fluid | None = None,
    deadrise: str = "wedge",
    slicing: str = "wetted",
    stop_on: Iterable[str] = DEFAULT_STOP_ON,
    max_flagged_share: float = MAX_FLAGGED_SHARE,
    progress: Callable[[float, float], None] | None = None,
    aero: Aerodynamics | str | None = None,
    friction: bool = False,
    sections_every: int = 0,
    cutter: str | None = None,
) -> History:
    """The free motion of a body entering the water.

    Parameters
    ----------
    hull : Hull
        The body, with its mass (and, for free pitch, its pitch inertia).
    velocity : float
        Initial vertical velocity of the centre of gravity in m/s, negative (moving down).
    t_end : float
        Duration of the run in s.
    dt : float, optional
        Time step in s (default ``t_end / 1000``). A step in which the body could move
        more than :data:`MAX_STEP_TRAVEL` of its height is refused: the run would step
        through the impact.
    draft : float
        Initial draft of the lowest point in m (default 0: first contact).
    pitch_rad : float
        Initial pitch in rad, nose up (default 0). Formerly ``pitch=`` (deprecated).
    forward_speed : float
        Initial forward speed in m/s (default 0).
    pitch_rate_rad_s : float
        Initial pitch rate in rad/s, nose up (default 0); kept constant unless
        ``free_pitch``. Formerly ``pitch_rate=`` (deprecated).
    pitch_deg, pitch_rate_deg_s : float, optional
        The initial pitch (deg) and pitch rate (deg/s) in degrees instead, as on the command
        line; give each angle in one unit only.
    free_pitch : bool
        Integrate the pitch from the moment about the centre of gravity.
    free_surge : bool
        Integrate the forward speed from the horizontal force (default: constant).
    slices : int
        Slices over the wetted length at each instant (default 32), or over the body's
        length with ``slicing="fixed"``.
    solver, fluid, deadrise, slicing
        As for :func:`~hullslice.forces.compute_force`; ``slicing="fixed"`` cuts the hull
        once per pitch and is much faster on large meshes.
    stop_on : iterable of str
        Stop rules that end the run (default :data:`DEFAULT_STOP_ON`: all of
        :data:`STOP_RULES` but ``slender``); pass ``()`` to go on to ``t_end`` with the
        flagged values (the crossings are still recorded).
    max_flagged_share : float
        The ``validity`` rule ends the run once slices outside the solver's range carry more
        than this share of the force (sum of the slices' absolute forces; default
        :data:`MAX_FLAGGED_SHARE`, 0.1).
    progress : callable, optional
        Called as ``progress(t, t_end)`` after each step.
    aero : Aerodynamics or str, optional
        The air's forces on the body (:mod:`hullslice.aero`): a model, or ``"weight"``
        (lift equal to the weight at touchdown) or ``"none"`` (default).
    friction : bool
        Add the water's friction on the wetted surface by the ITTC-57 line (default
        False; :mod:`hullslice.forces.friction`).
    sections_every : int
        Keep the slices of every Nth instant, with the last, in :attr:`History.sections`
        for the structural loads (:meth:`History.face_pressures`,
        :meth:`History.frame_loads`); default 0, none.
    cutter : str, optional
        How the stations of each pitch are cut (:data:`~hullslice.geometry.CUTTERS`): by
        the exact kernel of :mod:`hullslice.planecut` without turning the mesh
        (``"exact"``, the default with ``free_pitch``: every stage is a new pitch), or by
        manifold3d on the mesh turned to the pitch (``"manifold3d"``, the default at a
        held pitch, cut once).

    Returns
    -------
    History
    """
    model = ForceModel(
        hull, slices=slices, solver=solver, fluid=fluid, deadrise=deadrise, slicing=slicing,
        cutter=("exact" if free_pitch else "manifold3d") if cutter is None else cutter,
    )  # fmt: skip
    pitch = _in_rad(pitch_rad, pitch_deg, "pitch_rad", "pitch_deg")
    pitch_rate = _in_rad(pitch_rate_rad_s, pitch_rate_deg_s, "pitch_rate_rad_s", "pitch_rate_deg_s")
    w0 = float(Motion(velocity, forward_speed, pitch_rate).velocity)
    air0 = aero_model(aero)
    if w0 > 0.0 or (w0 == 0.0 and air0.name == "none"):
        raise InputError(
            f"initial velocity {w0:g} m/s is not downward: give a negative vertical velocity "
            "(e.g. -4 for 4 m/s into the water)"
            + ("" if w0 > 0.0 else ", or the air's lift that holds the body (aero=...)")
        )
    t_end = _positive(t_end, "end time", "s")
    dt = t_end / 1000.0 if dt is None else _positive(dt, "time step", "s")
    if dt > t_end:
        raise InputError(f"time step {dt:g} s is longer than the run ({t_end:g} s): shorten it")
    pose0 = Pose(draft, pitch)
    height = _height_at(hull, pose0.pitch)
    travel = abs(w0) * dt  # the water slows the body down: its first step is its longest
    if travel > MAX_STEP_TRAVEL * height:
        raise InputError(
            f"time step {dt:g} s at {w0:g} m/s moves the body {travel:.3g} m a step, more than "
            f"{MAX_STEP_TRAVEL:g} of its height {height:.6g} m: the run would step through the "
            f"impact; give a time step below {MAX_STEP_TRAVEL * height / abs(w0):.3g} s"
        )
    ratio = t_end / dt
    if not ratio <= MAX_STEPS:  # also catches an overflow to inf
        raise InputError(
            f"time step {dt:g} s over {t_end:g} s is {ratio:.3g} steps, more than the "
            f"{MAX_STEPS} hullslice allows: give a longer time step (an impact is resolved "
            "with a few hundred)"
        )
    _check_work(ratio, slices, f"{ratio:.6g} steps")
    if pose0.draft > height:
        raise InputError(
            f"initial draft {pose0.draft:g} m is deeper than the body's height {height:.6g} m"
        )
    m, g = hull.mass, model.fluid.g
    inertia = hull.pitch_inertia if free_pitch else None
    q0 = float(pitch_rate)
    free = (True, bool(free_pitch), bool(free_surge))
    clock = [0.0]
    air_model = air0.start(cast(float, m), g, pose0.pitch, float(forward_speed), w0)
    x_cg = float(hull.cg[0])

    def outside(y, sections, girth) -> tuple[np.ndarray, dict[str, float]]:
        """The air's and the friction's (vertical force, moment, horizontal force)."""
        th, u, w, q = y[1], y[2], y[3], y[4]
        air = air_model.forces(th, u, w, q)
        fr = wall_friction(sections, girth, u, model.fluid) if friction else Friction()
        ext = np.array([air.force_z, air.moment + fr.moment, air.force_x + fr.force_x])
        return ext, {"air_force": air.force_z, "air_force_x": air.force_x,
                     "air_moment": air.moment, "friction": fr.force_x}  # fmt: skip

    def state_pose(y) -> tuple[Pose, Motion]:
        z, th, u, w, q = y
        if abs(th) >= MAX_PITCH:
            raise _PitchLimit
        return Pose(model.draft(z, th), th), Motion(w, u, q)

    def rate(y, record: bool = True):
        """The state's rate, and the force result, outside forces and the model's draft of
        the state (None where the model was not asked for it) when ``record`` (else only
        what the rate needs: a free-fall solver's sums)."""
        w, q = y[3], y[4]
        if not (record or friction or model.momentum):  # the sums alone
            z, th, u = y[0], y[1], y[2]
            if abs(th) >= MAX_PITCH:
                raise _PitchLimit
            total, moment, total_x = model.totals_at(z, th, w, u, q)
            ext, parts = outside(y, None, None)
            dq = (moment + ext[1]) / inertia if free_pitch else 0.0
            du = (total_x + ext[2]) / m if free_surge else 0.0
            return np.array([w, q, du, (total + ext[0]) / m - g, dq]), (None, parts, None)
        r, draft = None, None
        if not model.momentum:  # a new pitch's result in one call where it serves
            if abs(y[1]) >= MAX_PITCH:
                raise _PitchLimit
            got = model.result_at(y[0], y[1], w, y[2], q)
            if got is not None:
                r, draft = got[0], got[1].draft
        if r is None:
            pose, motion = state_pose(y)
            if model.momentum:  # the added mass on the left, solved at this stage
                terms = model.terms(pose, motion)
                ext, parts = outside(y, terms.sections, calm_girth(terms.sections))
                terms, acc = solve_bounded(
                    terms, cast(float, m), inertia, g, free, when=f"at t = {clock[0]:.6g} s",
                    external=(float(ext[0]), float(ext[1]), float(ext[2])),
                )  # fmt: skip
                r = terms.result(acc, model.solver, model.fluid, motion, x_cg)
                return np.array([w, q, acc.forward, acc.vertical, acc.pitch]), (r, parts, None)
            r = model(pose, motion)
        total, moment, total_x = r.total, r.moment, r.total_x
        ext, parts = outside(y, r.sections, calm_girth(r.sections) if friction else None)
        dq = (moment + ext[1]) / inertia if free_pitch else 0.0
        du = (total_x + ext[2]) / m if free_surge else 0.0
        return np.array([w, q, du, (total + ext[0]) / m - g, dq]), (r, parts, draft)

    y = np.array([frame(hull, pose0.pitch).z_cg(pose0.draft), pose0.pitch, forward_speed, w0, q0])
    rec = Recorder(stop_on, max_flagged_share, sections_every)
    steps = math.ceil(t_end / dt - 1e-9)
    t = 0.0
    for k in range(steps + 1):
        clock[0] = t
        try:
            k1, (r, parts, draft) = rate(y)
        except _PitchLimit:  # past what the model describes: the run ends, whatever stop_on
            rec.end("pitch", t)
            break
        if draft is None:  # the model's draft of the state (given with a one-call result)
            draft = model.draft(y[0], y[1])
        if rec.add(t, r, k1[3], draft, parts) or k == steps:
            break
        h = min(dt, t_end - t)
        try:
            clock[0] = t + 0.5 * h
            k2, _ = rate(y + 0.5 * h * k1, False)
            k3, _ = rate(y + 0.5 * h * k2, False)
            clock[0] = t + h
            k4, _ = rate(y + h * k3, False)
        except _PitchLimit:
            rec.end("pitch", t)
            break
        y = y + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        t = (k + 1) * dt if k + 1 < steps else t_end
        if progress is not None:
            progress(t, t_end)
    level = pose0.pitch == 0.0 and q0 == 0.0 and forward_speed == 0.0 and not free_pitch
    settings = {
        **model.settings(),
        "initial_velocity": w0,
        "initial_draft": pose0.draft,
        "initial_pitch_deg": math.degrees(pose0.pitch),
        "forward_speed": float(forward_speed),
        "pitch_rate_deg_s": math.degrees(q0),
        "free_pitch": bool(free_pitch),
        "free_surge": bool(free_surge),
        "pitch_inertia": inertia,
        "cg": [float(hull.cg[0]), float(hull.cg[2])],
        "t_end": t_end,
        "dt": dt,
        "scheme": "classical Runge-Kutta, 4th order, fixed step",
        **air_model.settings(),
        "friction": "ITTC-57" if friction else "none",
        "stop_on": list(rec.stop_on),
        "max_flagged_share": rec.max_flagged_share,
    }
    return rec.history("t_end", "free fall" if level else "free motion", settings)


def _check_work(steps: float, slices: object, what: str) -> None:
    """Refuse a run of more than :data:`~hullslice.constants.MAX_SLICE_STEPS` slices times
    steps (or rows), before any cut."""
    if not isinstance(slices, int) or isinstance(slices, bool) or slices < 1:
        return  # the force model refuses it with its own message
    work = steps * slices
    if work > MAX_SLICE_STEPS:
        raise InputError(
            f"{what} times {slices} slices is {work:.3g} section solutions, more than the "
            f"{MAX_SLICE_STEPS:.0e} hullslice allows in one run (hours of work on a fine "
            f"mesh): give fewer slices, or fewer steps (at most {MAX_SLICE_STEPS // slices} "
            f"with {slices} slices)"
        )


def prescribed(
    hull: Hull,
    kinematics: Mapping[str, Sequence[float] | np.ndarray],
    *,
    slices: int = 32,
    solver: str | SolverBase | type[SolverBase] | None = None,
    fluid: Fluid | None = None,
    deadrise: str = "wedge",
    slicing: str = "wetted",
    stop_on: Iterable[str] = (),
    max_flagged_share: float = MAX_FLAGGED_SHARE,
    progress: Callable[[float, float], None] | None = None,
    sections_every: int = 0,
    cutter: str = "manifold3d",
) -> History:
    """The force along a prescribed motion.

    Parameters
    ----------
    hull : Hull
        The body; its mass is needed by free-fall solvers only.
    kinematics : mapping
        Arrays ``t`` (s, increasing), ``draft`` (m, draft of the lowest point, >= 0) and
        ``velocity`` (m/s, vertical velocity of the centre of gravity, negative down),
        optionally ``acceleration`` (m/s^2, up), ``pitch_rad`` (rad, nose up),
        ``pitch_rate_rad_s`` (rad/s), ``pitch_acceleration_rad_s2`` (rad/s^2),
        ``forward_speed`` (m/s) and ``forward_acceleration`` (m/s^2); e.g. from
        :func:`read_kinematics`. The angles may be given in degrees instead (``pitch_deg``,
        ``pitch_rate_deg_s``, ``pitch_acceleration_deg_s2``); the former keys
        ``penetration``, ``pitch``, ``pitch_rate`` and ``pitch_acceleration`` (rad) are
        deprecated. A momentum-form
        solver takes the body's accelerations from the table, or from the derivatives of
        its velocities (:mod:`hullslice.motion.kinematics`).
    stop_on : iterable of str
        Stop rules that end the evaluation early (default none: the whole table).
    cutter : str
        How the table's pitches are cut (:data:`hullslice.geometry.CUTTERS`; default
        ``"manifold3d"``; ``"exact"`` cuts each new pitch without turning the hull).

    Other parameters as for :func:`simulate`. The history's acceleration is the prescribed
    one with a momentum-form solver, and the one the 2D+t force implies, ``F / m - g``,
    with a free-fall solver.
    """
    kin = check_kinematics(kinematics, hull)
    rec = Recorder(stop_on, max_flagged_share, sections_every)
    _check_work(len(kin["t"]), slices, f"{len(kin['t'])} kinematics rows")
    model = ForceModel(
        hull,
        slices=slices,
        solver=solver,
        fluid=fluid,
        deadrise=deadrise,
        slicing=slicing,
        need_mass=False,
        cutter=cutter,
    )
    accelerations = kinematics_accelerations(kin) if model.momentum else None
    t_all = kin["t"]
    g = model.fluid.g
    for i, t in enumerate(t_all):
        pose = Pose(kin["draft"][i], kin["pitch_rad"][i])
        motion = Motion(kin["velocity"][i], kin["forward_speed"][i], kin["pitch_rate_rad_s"][i])
        if accelerations is not None:
            r = model(pose, motion, accelerations[i])
            acc = accelerations[i].vertical
        else:
            r = model(pose, motion)
            acc = r.total / cast(float, hull.mass) - g
        if rec.add(float(t), r, acc):
            break
        if progress is not None:
            progress(float(t), float(t_all[-1]))
    settings = {
        **model.settings(),
        "stop_on": list(rec.stop_on),
        "max_flagged_share": rec.max_flagged_share,
        "rows": len(t_all),
    }
    return rec.history("end of table", "prescribed", settings)
