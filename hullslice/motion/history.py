"""The time history of a run, and the rules that may end it early."""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ..forces import MIN_SLENDERNESS
from ..limits import MAX_PITCH
from ..loads import FacePeak, FacePressures, FrameLoads, SectionRecord, face_pressures
from ..loads.frames import frame_loads, frame_stations

__all__ = [
    "DEFAULT_STOP_ON",
    "MAX_FLAGGED_SHARE",
    "MAX_PITCH",
    "STEP_CHANGE_WARN",
    "STOP_RULES",
    "History",
]

#: Why a run may end before its end time, and what each limit means.
STOP_RULES: dict[str, str] = {
    "velocity": "the body stopped sinking (vertical velocity >= 0) in a vertical entry; "
    "with forward speed a ditching goes on (see 'left')",
    "left": "the body left the water after its first contact (no slice wetted, rising)",
    "settled": "the body settled in the water: over the last 0.25 s its vertical velocity "
    "stayed within 0.05 m/s, its pitch rate within 0.5 deg/s and its vertical acceleration "
    "within 0.1 m/s^2 (floating, or a steady run-out)",
    "chine": "the water reached a section's chine or deck (its widest point)",
    "validity": "slices outside the 2D solver's range of validity carry more than the "
    "allowed share of the force",
    "pitch": "the pitch reached 80 deg, past what a 2D+t model describes (a run always ends there)",
    "slender": f"the wetted length fell below {MIN_SLENDERNESS:g} times the wetted beam: the "
    "body is not slender there, as 2D+t assumes",
}

#: The stop rules a run applies by default (``slender`` is recorded, not applied).
DEFAULT_STOP_ON: tuple[str, ...] = ("velocity", "left", "settled", "chine", "validity", "pitch")

#: The ``settled`` rule: the window (s) and the largest vertical velocity (m/s), pitch rate
#: (rad/s) and vertical acceleration (m/s^2) in it.
SETTLE_WINDOW, SETTLE_VELOCITY, SETTLE_PITCH_RATE, SETTLE_ACCELERATION = (
    0.25,
    0.05,
    math.radians(0.5),
    0.1,
)

#: A force that changes by more than this share of its peak in one step is not resolved
#: in time: the summary says so (halve the step, or run --check).
STEP_CHANGE_WARN = 0.1

#: The history's forces from outside the water's 2D+t force (the air, friction).
OUTSIDE = ("air_force", "air_force_x", "air_moment", "friction")

#: Default largest share of the force (sum of the slices' absolute forces) that slices
#: outside the solver's range may carry before the ``validity`` rule ends a run.
MAX_FLAGGED_SHARE = 0.1


@dataclass(frozen=True, eq=False)
class History:
    """A time history of the body's motion and the force on it.

    Attributes
    ----------
    t : (k,) float
        Time in s (0 at the start of the run).
    draft : (k,) float
        Draft of the body's lowest point below the water, m (positive). Formerly
        ``penetration``, still readable under that name (deprecated).
    velocity : (k,) float
        Vertical velocity of the centre of gravity, m/s, negative down.
    acceleration : (k,) float
        Vertical acceleration of the centre of gravity, m/s^2, positive up (``F / m - g``).
    force : (k,) float
        2D+t vertical force, N, positive up.
    pitch : (k,) float
        Pitch in rad, nose up (:attr:`pitch_deg` in degrees).
    pitch_rate : (k,) float
        Pitch rate in rad/s (:attr:`pitch_rate_deg_s` in degrees per second).
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
        Share of the force (sum of the slices' absolute forces) carried by valid slices;
        :attr:`flagged_share` is the rest.
    chine_wetted : (k,) bool
        The water reached some section's chine at that instant.
    reason : (k,) str
        Why the instant is not valid (the reasons of its slices), ``""`` when it is.
    footprint : (k, 2) float
        Earth ``X`` (m) of the aft and fore ends of the wetted part.
    added_mass : (k,) float
        Heave added mass ``sum m_a dx`` of a momentum-form solver, kg (NaN for free-fall
        solvers).
    slenderness : (k,) float
        Wetted length over wetted beam (``inf`` when nothing is wetted).
    suction_share : (k,) float
        Share of the wetted length whose force is held at the water's suction bound
        (:attr:`hullslice.Fluid.suction_limit`: the water cavitates or ventilates there);
        0 for solvers that bound no suction.
    air_force, air_force_x : (k,) float
        The air's vertical and horizontal forces on the body, N (zero without an
        aerodynamic model, :mod:`hullslice.aero`).
    air_moment : (k,) float
        The air's pitch moment about the centre of gravity, N m, nose up.
    friction : (k,) float
        The water's friction on the wetted surface along the body, N, positive forward
        (zero unless asked for).
    stop_reason : str
        ``"t_end"``, ``"end of table"`` or a key of :data:`STOP_RULES`.
    first_crossed : dict
        For each key of :data:`STOP_RULES`, the first time (s) its limit was crossed, or
        None.
    mode : str
        ``"free fall"``, ``"free motion"`` or ``"prescribed"``.
    settings : dict
        The run's inputs (hull, mass, solver, fluid, slices, time step, ...).
    sections : tuple of SectionRecord
        The slices of every kept instant (``sections_every`` of :func:`simulate`), for the
        structural loads (:meth:`face_pressures`, :meth:`frame_loads`); empty by default.
    """

    t: np.ndarray
    draft: np.ndarray
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
    added_mass: np.ndarray
    slenderness: np.ndarray
    suction_share: np.ndarray
    air_force: np.ndarray
    air_force_x: np.ndarray
    air_moment: np.ndarray
    friction: np.ndarray
    stop_reason: str
    first_crossed: Mapping[str, float | None]
    mode: str
    settings: Mapping[str, object] = field(default_factory=dict)
    sections: tuple[SectionRecord, ...] = ()

    ARRAYS = (
        "t",
        "draft",
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
        "added_mass",
        "slenderness",
        "suction_share",
        "air_force",
        "air_force_x",
        "air_moment",
        "friction",
    )

    #: The columns of :meth:`columns`, in order (SI; angles in degrees as named).
    COLUMNS = (
        "t",
        "draft",
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
        "added_mass",
        "slenderness",
        "suction_share",
        "air_force",
        "air_force_x",
        "air_moment",
        "friction",
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
    def flagged_share(self) -> np.ndarray:
        """(k,) float: share of the force carried by slices outside the solver's range."""
        return 1.0 - self.valid_share

    @property
    def max_flagged_share(self) -> float:
        """The largest :attr:`flagged_share` of the run (0 for an empty history)."""
        return float(self.flagged_share.max()) if len(self) else 0.0

    @property
    def peak(self) -> dict[str, float | bool]:
        """The instant of the largest force: ``t``, ``force``, ``acceleration``, ``velocity``,
        ``draft`` (m), ``pitch_deg``, ``moment``: the names of the command line's outputs;
        and ``at_end``, True when it is the last sample of a run of several while the force
        is still rising (the load's peak may lie beyond the run)."""
        i = int(np.argmax(self.force))
        last = len(self) - 1
        at_end = bool(last > 0 and i == last and self.force[last] > self.force[last - 1])
        return {
            "t": float(self.t[i]),
            "force": float(self.force[i]),
            "acceleration": float(self.acceleration[i]),
            "velocity": float(self.velocity[i]),
            "draft": float(self.draft[i]),
            "pitch_deg": float(np.degrees(self.pitch[i])),
            "moment": float(self.moment[i]),
            "at_end": at_end,
        }

    @property
    def step_change(self) -> dict[str, float]:
        """The largest change of the force between two consecutive samples, as a share of
        the peak force (``share``), and the time it ends at (``t``): a run whose force jumps
        by a large share in one step does not resolve its load in time (see
        :data:`STEP_CHANGE_WARN`)."""
        f = np.asarray(self.force, dtype=np.float64)
        peak = float(f.max()) if len(f) else 0.0
        if len(f) < 2 or not peak > 0.0:
            return {"share": 0.0, "t": math.nan}
        jumps = np.abs(np.diff(f))
        i = int(np.argmax(jumps))
        return {"share": float(jumps[i] / peak), "t": float(self.t[i + 1])}

    @property
    def horizontal(self) -> dict[str, float]:
        """The largest horizontal load against the motion: the water's force along the
        body, the air's and the friction together, ``force`` (N, positive: a
        deceleration), its ``t`` (s) and ``g``, the deceleration of the body's mass in g
        (``mass`` from the settings; NaN without it)."""
        total = np.asarray(self.force_x) + np.asarray(self.air_force_x) + np.asarray(self.friction)
        if not len(total):
            return {"force": 0.0, "t": math.nan, "g": math.nan}
        i = int(np.argmin(total))
        mass = self.settings.get("mass")
        g = self.settings.get("g", 9.81)
        decel = -float(total[i])
        in_g = decel / (float(mass) * float(g)) if mass and g else math.nan  # type: ignore[arg-type]
        return {"force": decel, "t": float(self.t[i]), "g": in_g}

    @property
    def pitch_deg(self) -> np.ndarray:
        """(k,) float: the pitch in degrees, nose up (:attr:`pitch` in rad)."""
        return np.degrees(self.pitch)

    @property
    def pitch_rate_deg_s(self) -> np.ndarray:
        """(k,) float: the pitch rate in degrees per second (:attr:`pitch_rate` in rad/s)."""
        return np.degrees(self.pitch_rate)

    @property
    def penetration(self) -> np.ndarray:
        """(k,) float: the draft, m. Deprecated: use :attr:`draft`."""
        warnings.warn(
            "History.penetration is deprecated: use History.draft (the body's draft, m)",
            DeprecationWarning,
            stacklevel=2,
        )
        return self.draft

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
        from ..xarray_io import history_to_xarray

        return history_to_xarray(self)

    def to_dataframe(self):
        """The history as a ``pandas.DataFrame`` indexed by ``t``, with units in ``attrs``."""
        from ..xarray_io import history_to_dataframe

        return history_to_dataframe(self)

    def face_pressures(self, hull) -> Iterator[FacePressures]:
        """The pressure on every face of ``hull``'s mesh at each kept instant, one instant
        at a time (:func:`hullslice.loads.face_pressures`; memory for one instant only).

        Raises
        ------
        InputError
            The run kept no sections (run with ``sections_every``), or its solver gives no
            pressures.
        """
        self._need_sections("face pressures")
        if not any(rec.has_pressures for rec in self.sections):
            loaded = [rec for rec in self.sections if np.any(rec.force)]
            face_pressures(hull, (loaded or self.sections)[0])  # raises, naming the fix
        return (face_pressures(hull, rec) for rec in self.sections)

    def peak_face_pressures(self, hull) -> tuple[np.ndarray, np.ndarray]:
        """Each face's largest pressure over the kept instants (Pa) and its time (s; NaN
        on a face that stays dry)."""
        peak = FacePeak(len(hull.faces))
        for fp in self.face_pressures(hull):
            peak.add(fp)
        return peak.pressure, peak.t

    def frame_loads(self, hull, frames=None, *, spacing: float | None = None) -> FrameLoads:
        """The loads of the frame bays at each kept instant (:mod:`hullslice.loads.frames`).

        Parameters
        ----------
        hull : Hull
            The body of the run.
        frames : sequence of float, optional
            The frames' stations along the body's ``x``, m.
        spacing : float, optional
            Or a frame at every multiple of this (m).
        """
        self._need_sections("frame loads")
        bounds = (float(hull.bounds[0, 0]), float(hull.bounds[1, 0]))
        x = frame_stations(bounds, frames, spacing)
        return frame_loads(self.sections, x, bounds, hull.cg)

    def _need_sections(self, what: str) -> None:
        if not self.sections:
            raise InputError(
                f"{what} need the run's sections, which it did not keep: run it with "
                "sections_every=N (--pressures-out on the command line)"
            )

    def at(self, t: float) -> dict[str, float]:
        """The numeric columns interpolated linearly at time ``t`` (s)."""
        if not (self.t[0] <= t <= self.t[-1]):
            raise InputError(f"t = {t} s is outside the history ({self.t[0]} to {self.t[-1]} s)")
        cols = self.columns()
        skip = ("t", "slices", "valid", "valid_share", "chine_wetted", "reason", "slenderness")
        return {k: float(np.interp(t, self.t, v)) for k, v in cols.items() if k not in skip}


def check_share(value: float) -> float:
    """A largest flagged share, checked: a number in [0, 1]."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"largest flagged share {value!r} is not a number in [0, 1]") from None
    if not 0.0 <= v <= 1.0:  # NaN fails too
        raise InputError(
            f"largest flagged share {value!r} is not in [0, 1]: give the share of the force "
            f"that flagged slices may carry before a run stops (default {MAX_FLAGGED_SHARE:g})"
        )
    return v


def _check_rules(stop_on: Iterable[str]) -> tuple[str, ...]:
    rules = tuple(stop_on)
    unknown = [r for r in rules if r not in STOP_RULES]
    if unknown:
        raise InputError(f"unknown stop rule {unknown[0]!r}: choose from {', '.join(STOP_RULES)}")
    return rules
