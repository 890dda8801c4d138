"""Time histories: the body's free motion, or a prescribed motion, with the 2D+t force.

Free motion integrates the rigid body's equations in the vertical plane,

    dZ_g/dt = w,               m dw/dt = F_z - m g,
    d(theta)/dt = q,           I dq/dt = M_y            (free pitch),
    dX_g/dt = u,               m du/dt = F_x            (free surge),

(``w`` vertical velocity, negative down; ``theta`` pitch, nose up; ``u`` forward speed;
``F_z``, ``F_x``, ``M_y`` the 2D+t force and moment about the centre of gravity, see
:mod:`hullslice.forces`) with the classical fourth-order Runge-Kutta scheme at a fixed step,
cutting the hull afresh at each stage. Without free pitch the pitch changes at the given
constant rate (zero by default); without free surge the forward speed is constant. A level
vertical fall is the special case of the paper. A prescribed motion (the paper's way:
kinematics from CFD or a test) evaluates the force along a table of ``t, penetration,
velocity`` (and optionally pitch and forward speed).

A run ends at its end time, or earlier by one of the stop rules of :data:`STOP_RULES`; the
:class:`History` records which rule ended it and the first time each limit was crossed.
"""

from __future__ import annotations

import csv
import math
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .constants import MAX_STEPS
from .errors import CaseError, InputError
from .forces import ForceResult, force_on
from .geometry import frame
from .mesh import Hull
from .sections import (
    _check_deadrise,
    _check_slicing,
    _height_at,
    _slice_count,
    sections_at,
)
from .solvers.base import Solver
from .solvers.registry import get_solver
from .state import Fluid, Motion, Pose

__all__ = [
    "STOP_RULES",
    "ForceModel",
    "History",
    "prescribed",
    "read_kinematics",
    "simulate",
]

#: Why a run may end before its end time, and what each limit means.
STOP_RULES: dict[str, str] = {
    "velocity": "the body stopped sinking (vertical velocity >= 0)",
    "chine": "the water reached a section's chine or deck (its widest point)",
    "validity": "a slice left the 2D solver's range of validity",
    "pitch": "the pitch reached 80 deg, past what a 2D+t model describes (a run always ends there)",
}

#: Largest pitch a run may reach, rad.
MAX_PITCH = math.radians(80.0)


class _PitchLimit(Exception):
    """The pitch reached :data:`MAX_PITCH` during a run."""


#: Largest part of the body's height it may move in one time step of a free fall.
MAX_STEP_TRAVEL = 0.1


class ForceModel:
    """The 2D+t force and moment on a hull as a function of its pose and motion.

    Parameters
    ----------
    hull : Hull
        The body, with its mass.
    slices : int
        Slices over the wetted length (default 32).
    solver : str, Solver or Solver subclass, optional
        The 2D solver (default ``"extended-von-karman"``).
    fluid : Fluid, optional
        Water density and gravity.
    deadrise : str
        Deadrise estimator (default ``"wedge"``).
    slicing : str
        ``"wetted"`` (default) or ``"fixed"`` (cut once per pitch and reused), see
        :data:`~hullslice.sections.SLICINGS`.
    cache : bool
        Reuse the fixed slicing's cut (default); False cuts afresh at every call, for
        checking that both give the same numbers.
    """

    def __init__(
        self,
        hull: Hull,
        *,
        slices: int = 32,
        solver: str | Solver | type[Solver] | None = None,
        fluid: Fluid | None = None,
        deadrise: str = "wedge",
        slicing: str = "wetted",
        cache: bool = True,
    ) -> None:
        if hull.mass is None:
            raise InputError(f"hull {hull.name!r} has no mass: give its mass in kg (mass=...)")
        self.hull = hull
        self.slices = _slice_count(slices)
        self.solver = get_solver(solver)
        self.fluid = fluid or Fluid()
        self.deadrise = _check_deadrise(deadrise)
        self.slicing = _check_slicing(slicing)
        self.cache = bool(cache)

    def __call__(self, pose: Pose, motion: Motion) -> ForceResult:
        """The force result at a pose (its draft clipped to the body's height) and motion."""
        height = _height_at(self.hull, pose.pitch)
        if pose.draft > height:
            pose = Pose(height, pose.pitch)
        sections = sections_at(
            self.hull, pose, self.slices, self.deadrise, slicing=self.slicing, cache=self.cache
        )
        return force_on(sections, motion, self.solver, self.fluid, float(self.hull.cg[0]))

    def settings(self) -> dict[str, object]:
        """The model's inputs, for a history's settings."""
        return {
            "hull": self.hull.name,
            "mass": self.hull.mass,
            "slices": self.slices,
            "solver": self.solver.name,
            "solver_options": dict(self.solver.settings),
            "rho": self.fluid.rho,
            "g": self.fluid.g,
            "deadrise": self.deadrise,
            "slicing": self.slicing,
        }

    def draft(self, z_cg: float, pitch: float) -> float:
        """The draft (m, >= 0) of the body with its centre of gravity at height ``z_cg`` (m)."""
        return max(0.0, -(frame(self.hull, pitch).lowest + z_cg))


@dataclass(frozen=True, eq=False)
class History:
    """A time history of the body's motion and the force on it.

    Attributes
    ----------
    t : (k,) float
        Time in s (0 at the start of the run).
    penetration : (k,) float
        Draft of the body's lowest point below the water, m (positive).
    velocity : (k,) float
        Vertical velocity of the centre of gravity, m/s, negative down.
    acceleration : (k,) float
        Vertical acceleration of the centre of gravity, m/s^2, positive up (``F / m - g``).
    force : (k,) float
        2D+t vertical force, N, positive up.
    pitch : (k,) float
        Pitch in rad, nose up.
    pitch_rate : (k,) float
        Pitch rate in rad/s.
    forward_speed : (k,) float
        Forward speed in m/s.
    force_x : (k,) float
        Horizontal force, N, positive forward.
    moment : (k,) float
        Pitch moment about the centre of gravity, N m, nose up.
    wetted_length : (k,) float
        Length of the wetted part, m.
    slices : (k,) int
        Number of wetted slices (a slice with two wetted parts, a catamaran's floats,
        counts once).
    valid : (k,) bool
        Every slice inside the validity range at that instant.
    valid_share : (k,) float
        Share of the force (sum of the slices' absolute forces) carried by valid slices.
    chine_wetted : (k,) bool
        The water reached some section's chine at that instant.
    reason : (k,) str
        Why the instant is not valid (the reasons of its slices), ``""`` when it is.
    footprint : (k, 2) float
        Earth ``X`` (m) of the aft and fore ends of the wetted part.
    stop_reason : str
        ``"t_end"``, ``"end of table"`` or a key of :data:`STOP_RULES`.
    first_crossed : dict
        For each key of :data:`STOP_RULES`, the first time (s) its limit was crossed, or
        None.
    mode : str
        ``"free fall"``, ``"free motion"`` or ``"prescribed"``.
    settings : dict
        The run's inputs (hull, mass, solver, fluid, slices, time step, ...).
    """

    t: np.ndarray
    penetration: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    force: np.ndarray
    pitch: np.ndarray
    pitch_rate: np.ndarray
    forward_speed: np.ndarray
    force_x: np.ndarray
    moment: np.ndarray
    wetted_length: np.ndarray
    slices: np.ndarray
    valid: np.ndarray
    valid_share: np.ndarray
    chine_wetted: np.ndarray
    reason: np.ndarray
    footprint: np.ndarray
    stop_reason: str
    first_crossed: Mapping[str, float | None]
    mode: str
    settings: Mapping[str, object] = field(default_factory=dict)

    ARRAYS = (
        "t",
        "penetration",
        "velocity",
        "acceleration",
        "force",
        "pitch",
        "pitch_rate",
        "forward_speed",
        "force_x",
        "moment",
        "wetted_length",
        "slices",
        "valid",
        "valid_share",
        "chine_wetted",
        "reason",
        "footprint",
    )

    #: The columns of :meth:`columns`, in order (SI; angles in degrees as named).
    COLUMNS = (
        "t",
        "penetration",
        "velocity",
        "acceleration",
        "force",
        "pitch_deg",
        "pitch_rate_deg_s",
        "forward_speed",
        "force_x",
        "moment",
        "wetted_length",
        "x_aft",
        "x_fore",
        "slices",
        "valid",
        "valid_share",
        "chine_wetted",
        "reason",
    )

    def __post_init__(self) -> None:
        for name in self.ARRAYS:
            arr = np.asarray(getattr(self, name))
            arr.flags.writeable = False
            object.__setattr__(self, name, arr)

    def __len__(self) -> int:
        return len(self.t)

    @property
    def peak(self) -> dict[str, float]:
        """The instant of the largest force: ``t``, ``force``, ``acceleration``, ``velocity``,
        ``penetration``, ``pitch_deg``, ``moment``."""
        i = int(np.argmax(self.force))
        return {
            "t": float(self.t[i]),
            "force": float(self.force[i]),
            "acceleration": float(self.acceleration[i]),
            "velocity": float(self.velocity[i]),
            "penetration": float(self.penetration[i]),
            "pitch_deg": float(np.degrees(self.pitch[i])),
            "moment": float(self.moment[i]),
        }

    def columns(self) -> dict[str, np.ndarray]:
        """The per-instant arrays by the names of :attr:`COLUMNS`."""
        cols = {name: getattr(self, name) for name in self.ARRAYS if name != "footprint"}
        cols["pitch_deg"] = np.degrees(cols.pop("pitch"))
        cols["pitch_rate_deg_s"] = np.degrees(cols.pop("pitch_rate"))
        cols["x_aft"] = self.footprint[:, 0] if len(self) else np.empty(0)
        cols["x_fore"] = self.footprint[:, 1] if len(self) else np.empty(0)
        return {name: cols[name] for name in self.COLUMNS}

    def to_xarray(self):
        """The history as an ``xarray.Dataset`` along ``t``, with units (needs xarray)."""
        from hullslice.xarray_io import history_to_xarray

        return history_to_xarray(self)

    def to_dataframe(self):
        """The history as a ``pandas.DataFrame`` indexed by ``t``, with units in ``attrs``."""
        from hullslice.xarray_io import history_to_dataframe

        return history_to_dataframe(self)

    def at(self, t: float) -> dict[str, float]:
        """The numeric columns interpolated linearly at time ``t`` (s)."""
        if not (self.t[0] <= t <= self.t[-1]):
            raise InputError(f"t = {t} s is outside the history ({self.t[0]} to {self.t[-1]} s)")
        cols = self.columns()
        skip = ("t", "slices", "valid", "valid_share", "chine_wetted", "reason")
        return {k: float(np.interp(t, self.t, v)) for k, v in cols.items() if k not in skip}


class _Recorder:
    """Collects the instants of a run and applies the stop rules."""

    def __init__(self, stop_on: Iterable[str]) -> None:
        self.stop_on = _check_rules(stop_on)
        self.rows: list[dict] = []
        self.first: dict[str, float | None] = dict.fromkeys(STOP_RULES)
        self.stop: str | None = None

    def add(
        self,
        t: float,
        r: ForceResult,
        hull: Hull,
        acceleration: float,
        draft: float | None = None,
    ) -> bool:
        """Record an instant; True when a stop rule ends the run here. ``draft`` is the
        body's own when the force was computed at a draft clipped to its height."""
        solver_invalid = ~r.loads.valid & ~r.sections.chine_wetted
        reasons = sorted({part for text in r.loads.reason if text for part in text.split("; ")})
        w = r.motion.velocity
        crossed = {
            "velocity": w >= 0.0,
            "chine": bool(r.sections.chine_wetted.any()),
            "validity": bool(solver_invalid.any()),
        }
        s = r.sections
        wet = s.penetration > 0
        if wet.any():
            fp = (float((s.x - s.dx / 2)[wet].min()), float((s.x + s.dx / 2)[wet].max()))
        else:
            fp = (math.nan, math.nan)
        self.rows.append(
            {
                "t": t,
                "penetration": r.pose.draft if draft is None else draft,
                "velocity": w,
                "acceleration": acceleration,
                "force": r.total,
                "pitch": r.pose.pitch,
                "pitch_rate": r.motion.pitch_rate,
                "forward_speed": r.motion.forward_speed,
                "force_x": r.total_x,
                "moment": r.moment,
                "wetted_length": s.wetted_length,
                "slices": len(np.unique(s.station[wet])),
                "valid": r.all_valid,
                "valid_share": _valid_share(r),
                "chine_wetted": crossed["chine"],
                "reason": "; ".join(reasons),
                "footprint": fp,
            }
        )
        for rule, hit in crossed.items():
            if hit and self.first[rule] is None:
                self.first[rule] = t
            if hit and rule in self.stop_on and self.stop is None:
                self.stop = rule
        return self.stop is not None

    def end(self, rule: str, t: float) -> None:
        """End the run here by ``rule`` (a limit the run cannot go past)."""
        self.first[rule] = t if self.first[rule] is None else self.first[rule]
        self.stop = self.stop or rule

    def history(self, end: str, mode: str, settings: dict) -> History:
        def col(name, dtype):
            return np.array([row[name] for row in self.rows], dtype=dtype)

        dtypes = {"slices": int, "valid": bool, "chine_wetted": bool, "reason": object}
        arrays = {name: col(name, dtypes.get(name, float)) for name in History.ARRAYS}
        arrays["footprint"] = arrays["footprint"].reshape(-1, 2)
        return History(
            **arrays,
            stop_reason=self.stop or end,
            first_crossed=dict(self.first),
            mode=mode,
            settings=settings,
        )


def _valid_share(r: ForceResult) -> float:
    """Share of the slices' absolute forces carried by valid slices (1 with no force)."""
    size = np.abs(r.force)
    total = size.sum()
    return float(size[r.loads.valid].sum() / total) if total > 0 else 1.0


def _check_rules(stop_on: Iterable[str]) -> tuple[str, ...]:
    rules = tuple(stop_on)
    unknown = [r for r in rules if r not in STOP_RULES]
    if unknown:
        raise InputError(f"unknown stop rule {unknown[0]!r}: choose from {', '.join(STOP_RULES)}")
    return rules


def _positive(value: float, what: str, unit: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what} {value!r} is not a number (in {unit})") from None
    if not (math.isfinite(v) and v > 0.0):
        raise InputError(f"{what} {value!r} {unit} is not positive")
    return v


def simulate(
    hull: Hull,
    velocity: float,
    t_end: float,
    *,
    dt: float | None = None,
    draft: float = 0.0,
    pitch: float = 0.0,
    forward_speed: float = 0.0,
    pitch_rate: float = 0.0,
    free_pitch: bool = False,
    free_surge: bool = False,
    slices: int = 32,
    solver: str | Solver | type[Solver] | None = None,
    fluid: Fluid | None = None,
    deadrise: str = "wedge",
    slicing: str = "wetted",
    stop_on: Iterable[str] = tuple(STOP_RULES),
    progress: Callable[[float, float], None] | None = None,
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
    pitch : float
        Initial pitch in rad, nose up (default 0).
    forward_speed : float
        Initial forward speed in m/s (default 0).
    pitch_rate : float
        Initial pitch rate in rad/s, nose up (default 0); kept constant unless
        ``free_pitch``.
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
        Stop rules that end the run (default all of :data:`STOP_RULES`); pass ``()`` to go
        on to ``t_end`` with the flagged values (the crossings are still recorded).
    progress : callable, optional
        Called as ``progress(t, t_end)`` after each step.

    Returns
    -------
    History
    """
    model = ForceModel(
        hull, slices=slices, solver=solver, fluid=fluid, deadrise=deadrise, slicing=slicing
    )
    w0 = float(Motion(velocity, forward_speed, pitch_rate).velocity)
    if w0 >= 0.0:
        raise InputError(
            f"initial velocity {w0:g} m/s is not downward: give a negative vertical velocity "
            "(e.g. -4 for 4 m/s into the water)"
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
    if pose0.draft > height:
        raise InputError(
            f"initial draft {pose0.draft:g} m is deeper than the body's height {height:.6g} m"
        )
    m, g = hull.mass, model.fluid.g
    inertia = hull.pitch_inertia if free_pitch else None
    q0 = float(pitch_rate)

    def state_pose(y) -> tuple[Pose, Motion]:
        z, th, u, w, q = y
        if abs(th) >= MAX_PITCH:
            raise _PitchLimit
        return Pose(model.draft(z, th), th), Motion(w, u, q)

    def rate(y, r: ForceResult | None = None):
        if r is None:
            r = model(*state_pose(y))
        w, q = y[3], y[4]
        dq = r.moment / inertia if free_pitch else 0.0
        du = r.total_x / m if free_surge else 0.0
        return np.array([w, q, du, r.total / m - g, dq]), r

    y = np.array([frame(hull, pose0.pitch).z_cg(pose0.draft), pose0.pitch, forward_speed, w0, q0])
    rec = _Recorder(stop_on)
    steps = math.ceil(t_end / dt - 1e-9)
    t = 0.0
    for k in range(steps + 1):
        try:
            k1, r = rate(y)
        except _PitchLimit:  # past what the model describes: the run ends, whatever stop_on
            rec.end("pitch", t)
            break
        if rec.add(t, r, hull, k1[3], model.draft(y[0], y[1])) or k == steps:
            break
        h = min(dt, t_end - t)
        try:
            k2, _ = rate(y + 0.5 * h * k1)
            k3, _ = rate(y + 0.5 * h * k2)
            k4, _ = rate(y + h * k3)
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
        "stop_on": list(rec.stop_on),
    }
    return rec.history("t_end", "free fall" if level else "free motion", settings)


def prescribed(
    hull: Hull,
    kinematics: Mapping[str, Sequence[float]],
    *,
    slices: int = 32,
    solver: str | Solver | type[Solver] | None = None,
    fluid: Fluid | None = None,
    deadrise: str = "wedge",
    slicing: str = "wetted",
    stop_on: Iterable[str] = (),
    progress: Callable[[float, float], None] | None = None,
) -> History:
    """The force along a prescribed motion.

    Parameters
    ----------
    hull : Hull
        The body, with its mass.
    kinematics : mapping
        Arrays ``t`` (s, increasing), ``penetration`` (m, draft of the lowest point, >= 0)
        and ``velocity`` (m/s, vertical velocity of the centre of gravity, negative down),
        optionally ``pitch_deg`` (nose up), ``pitch_rate_deg_s`` and ``forward_speed``
        (m/s); e.g. from :func:`read_kinematics`.
    stop_on : iterable of str
        Stop rules that end the evaluation early (default none: the whole table).

    Other parameters as for :func:`simulate`. The history's acceleration is the one the
    2D+t force implies, ``F / m - g``.
    """
    kin = _check_kinematics(kinematics, hull)
    model = ForceModel(
        hull, slices=slices, solver=solver, fluid=fluid, deadrise=deadrise, slicing=slicing
    )
    rec = _Recorder(stop_on)
    t_all = kin["t"]
    g = model.fluid.g
    for i, t in enumerate(t_all):
        pose = Pose(kin["penetration"][i], math.radians(kin["pitch_deg"][i]))
        motion = Motion(
            kin["velocity"][i], kin["forward_speed"][i], math.radians(kin["pitch_rate_deg_s"][i])
        )
        r = model(pose, motion)
        if rec.add(float(t), r, hull, r.total / hull.mass - g):
            break
        if progress is not None:
            progress(float(t), float(t_all[-1]))
    settings = {
        **model.settings(),
        "stop_on": list(rec.stop_on),
        "rows": len(t_all),
    }
    return rec.history("end of table", "prescribed", settings)


KINEMATICS_COLUMNS = ("t", "penetration", "velocity")
#: Optional kinematics columns and their value when absent.
KINEMATICS_OPTIONAL = {"pitch_deg": 0.0, "pitch_rate_deg_s": 0.0, "forward_speed": 0.0}


def _check_kinematics(kin: Mapping[str, Sequence[float]], hull: Hull) -> dict[str, np.ndarray]:
    missing = [c for c in KINEMATICS_COLUMNS if c not in kin]
    if missing:
        raise CaseError(
            f"kinematics lack the column(s) {', '.join(missing)}: give t (s), penetration (m, "
            "positive down) and velocity (m/s, negative down)"
        )
    out = {c: np.asarray(kin[c], dtype=np.float64).ravel() for c in KINEMATICS_COLUMNS}
    n = len(out["t"])
    if n == 0:
        raise CaseError("the kinematics table has no rows")
    for c, default in KINEMATICS_OPTIONAL.items():
        out[c] = np.asarray(kin[c], dtype=np.float64).ravel() if c in kin else np.full(n, default)
    for c, a in out.items():
        if len(a) != n:
            raise CaseError(f"kinematics column {c!r} has {len(a)} values, t has {n}")
        if not np.all(np.isfinite(a)):
            i = int(np.flatnonzero(~np.isfinite(a))[0])
            raise CaseError(f"kinematics column {c!r} row {i + 1} is not a finite number")
    back = np.flatnonzero(np.diff(out["t"]) <= 0)
    if len(back):
        i = int(back[0])
        raise CaseError(
            f"kinematics time goes backwards or repeats at row {i + 2} "
            f"(t = {out['t'][i]:g} s, then {out['t'][i + 1]:g} s): sort the table by time"
        )
    p = out["penetration"]
    steep = np.flatnonzero(np.abs(out["pitch_deg"]) >= 80.0)
    if len(steep):
        i = int(steep[0])
        raise CaseError(
            f"kinematics pitch at row {i + 1} ({out['pitch_deg'][i]:g} deg) is too steep for a "
            "2D+t model: keep it between -80 and 80 deg"
        )
    if np.any(p < 0):
        i = int(np.flatnonzero(p < 0)[0])
        raise CaseError(
            f"kinematics penetration at row {i + 1} is negative ({p[i]:g} m): the penetration "
            "is the depth of the lowest point below the water, >= 0"
        )
    heights = np.array([_height_at(hull, math.radians(th)) for th in out["pitch_deg"]])
    if np.any(p > heights):
        i = int(np.flatnonzero(p > heights)[0])
        raise CaseError(
            f"kinematics penetration at row {i + 1} ({p[i]:g} m) is deeper than the body's "
            f"height {heights[i]:.6g} m"
        )
    return out


def read_kinematics(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """Read a kinematics table from CSV.

    The header names the columns; ``t`` (s), ``penetration`` (m, the draft of the lowest
    point, positive) and ``velocity`` (m/s, negative down) are required; ``pitch_deg``
    (nose up), ``pitch_rate_deg_s`` and ``forward_speed`` (m/s) are read when present;
    other columns are ignored. Lines starting with ``#`` are comments.

    Returns
    -------
    dict of (k,) float arrays
        ``t``, ``penetration``, ``velocity`` and the optional columns present.
    """
    p = Path(path)
    if not p.exists():
        raise CaseError(f"kinematics file {str(p)!r} does not exist")
    if not p.is_file():
        raise CaseError(f"kinematics path {str(p)!r} is not a file: give a CSV file")
    try:
        # utf-8-sig: a spreadsheet's CSV may start with a byte-order mark
        text = p.read_bytes().decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise CaseError(
            f"kinematics file {str(p)!r} is not UTF-8 text (byte {exc.start}): give a CSV "
            "file with the columns t, penetration, velocity"
        ) from None
    except OSError as exc:
        raise CaseError(
            f"kinematics file {str(p)!r} cannot be read: {exc.strerror or exc}"
        ) from None
    if "\0" in text:
        raise CaseError(f"kinematics file {str(p)!r} holds binary data: give a CSV text file")
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    reader = csv.reader(lines)
    try:
        header = [h.strip().lower() for h in next(reader)]
    except StopIteration:
        raise CaseError(f"kinematics file {str(p)!r} is empty") from None
    missing = [c for c in KINEMATICS_COLUMNS if c not in header]
    if missing:
        raise CaseError(
            f"kinematics file {str(p)!r} lacks the column(s) {', '.join(missing)} "
            f"(its header: {', '.join(header)}); it needs t, penetration, velocity"
        )
    names = [*KINEMATICS_COLUMNS, *(c for c in KINEMATICS_OPTIONAL if c in header)]
    idx = [header.index(c) for c in names]
    rows = []
    for lineno, row in enumerate(reader, start=2):
        try:
            rows.append([float(row[i]) for i in idx])
        except (ValueError, IndexError):
            raise CaseError(
                f"kinematics file {str(p)!r} line {lineno}: {','.join(row)!r} does not hold "
                f"numbers for {', '.join(names)}"
            ) from None
    arr = np.array(rows, dtype=np.float64).reshape(-1, len(names))
    return {c: arr[:, i] for i, c in enumerate(names)}
