"""Time histories: the body's free fall, or a prescribed motion, with the 2D+t force.

Free fall integrates the vertical equation of motion of the rigid body,

    d(draft)/dt = -w,        m dw/dt = F_z(draft, w) - m g,

(``w`` the vertical velocity, negative down; ``F_z`` the 2D+t force, positive up) with the
classical fourth-order Runge-Kutta scheme at a fixed step, cutting the hull afresh at each
stage. A prescribed motion (the paper's way: kinematics from CFD or a test) evaluates the
force along a table of ``t, penetration, velocity``.

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

from .errors import CaseError, InputError
from .forces import ForceResult, _as_motion, evaluate
from .mesh import Hull
from .sections import _check_deadrise, _level_sections, _slice_count
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
}


class ForceModel:
    """The 2D+t force on a level hull as a function of draft and vertical velocity.

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
    """

    def __init__(
        self,
        hull: Hull,
        *,
        slices: int = 32,
        solver: str | Solver | type[Solver] | None = None,
        fluid: Fluid | None = None,
        deadrise: str = "wedge",
    ) -> None:
        if hull.mass is None:
            raise InputError(f"hull {hull.name!r} has no mass: give its mass in kg (mass=...)")
        self.hull = hull
        self.slices = _slice_count(slices)
        self.solver = get_solver(solver)
        self.fluid = fluid or Fluid()
        self.deadrise = _check_deadrise(deadrise)

    def __call__(self, draft: float, velocity: float) -> ForceResult:
        """The force result at a draft (m, clipped to the body's height) and velocity (m/s)."""
        draft = min(max(float(draft), 0.0), float(self.hull.extents[2]))
        sections = _level_sections(self.hull, draft, self.slices, self.deadrise)
        v = np.full(len(sections), float(velocity))
        loads = evaluate(self.solver, sections, v, self.fluid)
        return ForceResult(
            sections, v, loads, self.solver.name, self.fluid, Pose(draft), Motion(velocity)
        )


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
        Vertical velocity, m/s, negative down.
    acceleration : (k,) float
        Vertical acceleration, m/s^2, positive up (``F / m - g``).
    force : (k,) float
        2D+t vertical force, N, positive up.
    wetted_length : (k,) float
        Length of the wetted part, m.
    slices : (k,) int
        Number of wetted slices.
    valid : (k,) bool
        Every slice inside the validity range at that instant.
    chine_wetted : (k,) bool
        The water reached some section's chine at that instant.
    reason : (k,) str
        Why the instant is not valid (the reasons of its slices), ``""`` when it is.
    stop_reason : str
        ``"t_end"``, ``"end of table"`` or a key of :data:`STOP_RULES`.
    first_crossed : dict
        For each key of :data:`STOP_RULES`, the first time (s) its limit was crossed, or
        None.
    mode : str
        ``"free fall"`` or ``"prescribed"``.
    settings : dict
        The run's inputs (hull, mass, solver, fluid, slices, time step, ...).
    """

    t: np.ndarray
    penetration: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    force: np.ndarray
    wetted_length: np.ndarray
    slices: np.ndarray
    valid: np.ndarray
    chine_wetted: np.ndarray
    reason: np.ndarray
    stop_reason: str
    first_crossed: Mapping[str, float | None]
    mode: str
    settings: Mapping[str, object] = field(default_factory=dict)

    COLUMNS = (
        "t",
        "penetration",
        "velocity",
        "acceleration",
        "force",
        "wetted_length",
        "slices",
        "valid",
        "chine_wetted",
        "reason",
    )

    def __post_init__(self) -> None:
        for name in self.COLUMNS:
            arr = np.asarray(getattr(self, name))
            arr.flags.writeable = False
            object.__setattr__(self, name, arr)

    def __len__(self) -> int:
        return len(self.t)

    @property
    def peak(self) -> dict[str, float]:
        """The instant of the largest force: ``t``, ``force``, ``acceleration``, ``velocity``,
        ``penetration``."""
        i = int(np.argmax(self.force))
        return {
            "t": float(self.t[i]),
            "force": float(self.force[i]),
            "acceleration": float(self.acceleration[i]),
            "velocity": float(self.velocity[i]),
            "penetration": float(self.penetration[i]),
        }

    def columns(self) -> dict[str, np.ndarray]:
        """The per-instant arrays by name."""
        return {name: getattr(self, name) for name in self.COLUMNS}

    def at(self, t: float) -> dict[str, float]:
        """Penetration, velocity, acceleration and force interpolated linearly at time ``t``."""
        if not (self.t[0] <= t <= self.t[-1]):
            raise InputError(f"t = {t} s is outside the history ({self.t[0]} to {self.t[-1]} s)")
        return {
            k: float(np.interp(t, self.t, getattr(self, k)))
            for k in ("penetration", "velocity", "acceleration", "force", "wetted_length")
        }


class _Recorder:
    """Collects the instants of a run and applies the stop rules."""

    def __init__(self, stop_on: Iterable[str]) -> None:
        self.stop_on = _check_rules(stop_on)
        self.rows: list[tuple] = []
        self.first: dict[str, float | None] = dict.fromkeys(STOP_RULES)
        self.stop: str | None = None

    def add(self, t: float, draft: float, w: float, mass: float, r: ForceResult) -> bool:
        """Record an instant; True when a stop rule ends the run here."""
        g = r.fluid.g
        solver_invalid = ~r.loads.valid & ~r.sections.chine_wetted
        reasons = sorted({s for s in r.loads.reason if s})
        crossed = {
            "velocity": w >= 0.0,
            "chine": bool(r.sections.chine_wetted.any()),
            "validity": bool(solver_invalid.any()),
        }
        self.rows.append(
            (
                t,
                draft,
                w,
                r.total / mass - g,
                r.total,
                r.sections.wetted_length,
                int(r.sections.wetted.sum()),
                r.all_valid,
                crossed["chine"],
                "; ".join(reasons),
            )
        )
        for rule, hit in crossed.items():
            if hit and self.first[rule] is None:
                self.first[rule] = t
            if hit and rule in self.stop_on and self.stop is None:
                self.stop = rule
        return self.stop is not None

    def history(self, end: str, mode: str, settings: dict) -> History:
        cols = list(zip(*self.rows, strict=True)) if self.rows else [()] * 10
        arrays = [np.array(c, dtype=float) for c in cols[:6]]
        return History(
            *arrays,
            slices=np.array(cols[6], dtype=int),
            valid=np.array(cols[7], dtype=bool),
            chine_wetted=np.array(cols[8], dtype=bool),
            reason=np.array(cols[9], dtype=object),
            stop_reason=self.stop or end,
            first_crossed=dict(self.first),
            mode=mode,
            settings=settings,
        )


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
    slices: int = 32,
    solver: str | Solver | type[Solver] | None = None,
    fluid: Fluid | None = None,
    deadrise: str = "wedge",
    stop_on: Iterable[str] = tuple(STOP_RULES),
    progress: Callable[[float, float], None] | None = None,
) -> History:
    """The free fall of a level body into the water.

    Parameters
    ----------
    hull : Hull
        The body, with its mass.
    velocity : float
        Initial vertical velocity in m/s, negative (moving down into the water).
    t_end : float
        Duration of the run in s.
    dt : float, optional
        Time step in s (default ``t_end / 1000``).
    draft : float
        Initial draft of the lowest point in m (default 0: first contact).
    slices : int
        Slices over the wetted length at each instant (default 32).
    solver, fluid, deadrise
        As for :func:`~hullslice.forces.compute_force`.
    stop_on : iterable of str
        Stop rules that end the run (default all of :data:`STOP_RULES`); pass ``()`` to go
        on to ``t_end`` with the flagged values (the crossings are still recorded).
    progress : callable, optional
        Called as ``progress(t, t_end)`` after each step.

    Returns
    -------
    History
    """
    model = ForceModel(hull, slices=slices, solver=solver, fluid=fluid, deadrise=deadrise)
    w0 = _as_motion(velocity).velocity
    if w0 >= 0.0:
        raise InputError(
            f"initial velocity {w0:g} m/s is not downward: give a negative vertical velocity "
            "(e.g. -4 for 4 m/s into the water)"
        )
    t_end = _positive(t_end, "end time", "s")
    dt = t_end / 1000.0 if dt is None else _positive(dt, "time step", "s")
    if dt > t_end:
        raise InputError(f"time step {dt:g} s is longer than the run ({t_end:g} s): shorten it")
    d0 = Pose(draft).draft
    if d0 > hull.extents[2]:
        raise InputError(
            f"initial draft {d0:g} m is deeper than the body's height {hull.extents[2]:.6g} m"
        )
    m, g = hull.mass, model.fluid.g
    rec = _Recorder(stop_on)
    steps = math.ceil(t_end / dt - 1e-9)

    def rate(d: float, w: float, r: ForceResult | None = None) -> tuple[float, float]:
        r = r or model(d, w)
        return -w, r.total / m - g

    t, d, w = 0.0, d0, w0
    for k in range(steps + 1):
        r = model(d, w)
        if rec.add(t, d, w, m, r) or k == steps:
            break
        h = min(dt, t_end - t)
        k1 = rate(d, w, r)
        k2 = rate(d + 0.5 * h * k1[0], w + 0.5 * h * k1[1])
        k3 = rate(d + 0.5 * h * k2[0], w + 0.5 * h * k2[1])
        k4 = rate(d + h * k3[0], w + h * k3[1])
        d += h / 6.0 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        w += h / 6.0 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        t = (k + 1) * dt if k + 1 < steps else t_end
        if progress is not None:
            progress(t, t_end)
    settings = {
        "hull": hull.name,
        "mass": m,
        "initial_velocity": w0,
        "initial_draft": d0,
        "t_end": t_end,
        "dt": dt,
        "slices": model.slices,
        "solver": model.solver.name,
        "solver_options": dict(model.solver.settings),
        "rho": model.fluid.rho,
        "g": g,
        "deadrise": model.deadrise,
        "scheme": "classical Runge-Kutta, 4th order, fixed step",
        "stop_on": list(rec.stop_on),
    }
    return rec.history("t_end", "free fall", settings)


def prescribed(
    hull: Hull,
    kinematics: Mapping[str, Sequence[float]],
    *,
    slices: int = 32,
    solver: str | Solver | type[Solver] | None = None,
    fluid: Fluid | None = None,
    deadrise: str = "wedge",
    stop_on: Iterable[str] = (),
    progress: Callable[[float, float], None] | None = None,
) -> History:
    """The force along a prescribed motion (a table of ``t``, ``penetration``, ``velocity``).

    Parameters
    ----------
    hull : Hull
        The body, with its mass.
    kinematics : mapping
        Arrays ``t`` (s, increasing), ``penetration`` (m, draft of the lowest point, >= 0)
        and ``velocity`` (m/s, negative down), e.g. from :func:`read_kinematics`.
    stop_on : iterable of str
        Stop rules that end the evaluation early (default none: the whole table).

    Other parameters as for :func:`simulate`. The history's acceleration is the one the
    2D+t force implies, ``F / m - g``.
    """
    kin = _check_kinematics(kinematics, hull)
    model = ForceModel(hull, slices=slices, solver=solver, fluid=fluid, deadrise=deadrise)
    rec = _Recorder(stop_on)
    t_all = kin["t"]
    for t, d, w in zip(t_all, kin["penetration"], kin["velocity"], strict=True):
        if rec.add(float(t), float(d), float(w), hull.mass, model(d, w)):
            break
        if progress is not None:
            progress(float(t), float(t_all[-1]))
    settings = {
        "hull": hull.name,
        "mass": hull.mass,
        "slices": model.slices,
        "solver": model.solver.name,
        "solver_options": dict(model.solver.settings),
        "rho": model.fluid.rho,
        "g": model.fluid.g,
        "deadrise": model.deadrise,
        "stop_on": list(rec.stop_on),
        "rows": len(t_all),
    }
    return rec.history("end of table", "prescribed", settings)


KINEMATICS_COLUMNS = ("t", "penetration", "velocity")


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
    if np.any(p < 0):
        i = int(np.flatnonzero(p < 0)[0])
        raise CaseError(
            f"kinematics penetration at row {i + 1} is negative ({p[i]:g} m): the penetration "
            "is the depth of the lowest point below the water, >= 0"
        )
    if np.any(p > hull.extents[2]):
        i = int(np.flatnonzero(p > hull.extents[2])[0])
        raise CaseError(
            f"kinematics penetration at row {i + 1} ({p[i]:g} m) is deeper than the body's "
            f"height {hull.extents[2]:.6g} m"
        )
    return out


def read_kinematics(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """Read a kinematics table from CSV.

    The header names the columns; ``t`` (s), ``penetration`` (m, the draft of the lowest
    point, positive) and ``velocity`` (m/s, negative down) are required, other columns are
    ignored. Lines starting with ``#`` are comments.

    Returns
    -------
    dict of (k,) float arrays
        ``t``, ``penetration``, ``velocity``.
    """
    p = Path(path)
    if not p.is_file():
        raise CaseError(f"kinematics file {str(p)!r} does not exist")
    with open(p, newline="", encoding="utf-8") as fh:
        lines = [ln for ln in fh if ln.strip() and not ln.lstrip().startswith("#")]
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
    idx = [header.index(c) for c in KINEMATICS_COLUMNS]
    rows = []
    for lineno, row in enumerate(reader, start=2):
        try:
            rows.append([float(row[i]) for i in idx])
        except (ValueError, IndexError):
            raise CaseError(
                f"kinematics file {str(p)!r} line {lineno}: {','.join(row)!r} does not hold "
                "three numbers for t, penetration, velocity"
            ) from None
    arr = np.array(rows, dtype=np.float64).reshape(-1, 3)
    return {c: arr[:, i] for i, c in enumerate(KINEMATICS_COLUMNS)}
