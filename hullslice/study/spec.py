"""The :class:`Study`: one computation, described completely and checked once.

A study names the command (``info``, ``sections``, ``force`` or ``simulate``), the mesh and
how to read it, the mass properties, the water, the solver and its options, the slicing,
the state or the motion, and the outputs. The command line and case files both build one
(:meth:`Study.from_args`, :meth:`Study.from_case`); :meth:`Study.to_case` gives it back as a
case mapping and :meth:`Study.command_line` as the equivalent command. Angles are in degrees
here, as in case files and on the command line; :attr:`Study.pitch_rad` gives radians.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any

from ..aero import COEFFICIENTS, model_of
from ..case import COMMAND_KEYS, SCHEMA, case_command, validate_case
from ..errors import CaseError, InputError
from ..limits import check_pitch, check_slice_count
from ..options import COMMANDS, FIELD_KEYS, OPTIONS, option
from ..options import study_default as _default
from ..renamed import former_attribute
from ..state import Acceleration, Fluid, Motion, Pose

__all__ = ["COMMANDS", "Study", "StudyError"]

#: Study fields whose case key (and command-line option) differs: angles, in degrees.
_CASE_NAMES = FIELD_KEYS
_FIELD_NAMES = {v: k for k, v in _CASE_NAMES.items()}
_FLAGS = tuple(o.name for o in OPTIONS if o.kind == "flag")
COEFS = tuple(COEFFICIENTS)  # the study's fields of the aerodynamic coefficients
_PATHS = tuple(o.name for o in OPTIONS if o.kind == "path")
#: Keys whose values are sequences (kept as tuples in a study, lists in a case).
_SEQUENCES = tuple(o.name for o in OPTIONS if o.kind in ("counts", "pair", "box", "times"))


class StudyError(InputError):
    """A study that is incomplete or inconsistent (a free fall without its duration, a
    value its command does not take): the command line's usage error, exit status 2.

    Attributes
    ----------
    command : str
        The study's command, for the message's prefix on the command line.
    """

    def __init__(self, command: str, message: str) -> None:
        super().__init__(message)
        self.command = command


@dataclass(frozen=True)
class Study:
    """One computation of hullslice, checked on construction.

    Attributes
    ----------
    command : str
        ``info``, ``sections``, ``force`` or ``simulate``.
    mesh : str
        The hull mesh file (a format of :data:`hullslice.readers.SUPPORTED_FORMATS`).
    title : str, optional
        A name for the study, for reports.
    units, forward, up : str, optional
        Length unit of the mesh file and its forward and up axes (``+x``, ``-y``, ...);
        None: what the file declares, else ``m``, ``+x``, ``+z``.
    scale : float, optional
        Metres per unit of the file (not with ``length``).
    length : float, optional
        The body's length along ``forward`` in m, which sets the scale.
    repair : str, optional
        ``close`` to fill the holes of an open mesh; None or ``none``: refuse it.
    keep : str, optional
        Bodies to keep: ``largest`` or numbers from 1 as ``"1,3"``.
    keep_box : str or sequence of 6 float, optional
        The box XMIN, XMAX, YMIN, YMAX, ZMIN, ZMAX (m, body frame) whose part is kept.
    no_fix : bool
        Make none of the safe repairs of the mesh (merging, dropping degenerate faces,
        orienting, ...): a mesh that needs one is refused, naming it.
    mass : float, optional
        Mass of the body in kg.
    mass_distribution : str, optional
        CSV of the mass along the body.
    cg : (float, float), optional
        Centre of gravity x, z in m, body frame.
    inertia : float, optional
        Pitch moment of inertia about the centre of gravity in kg*m^2.
    rho, g : float
        Water density in kg/m^3 and gravitational acceleration in m/s^2.
    solver : str
        Name of the 2D solver.
    solver_options : tuple of (str, Any)
        Options passed to the solver, in order.
    deadrise, slicing, cutter : str
        Local deadrise estimator, slice placement (``wetted`` or ``fixed``) and how a new
        pitch is cut (:data:`hullslice.geometry.CUTTERS`; None: the run's default).
    slices : tuple of int, optional
        Slice count(s); one for ``sections`` and ``simulate``, one or more for ``force``
        (default: the command's, 32 or 16, 32, 64).
    draft : float, optional
        Depth of the lowest point below the water in m (``simulate``: the initial draft,
        default 0).
    pitch_deg, pitch_rate_deg_s : float, optional
        Pitch in deg (nose up) and pitch rate in deg/s (default 0).
    velocity : float, optional
        Vertical velocity in m/s, negative down (``simulate``: the initial one).
    forward_speed : float, optional
        Horizontal speed along the body in m/s (default 0).
    acceleration : float, optional
        Vertical acceleration in m/s^2, up, for a momentum-form solver's force.
    t_end, dt : float, optional
        Duration and time step of a free fall in s.
    kinematics : str, optional
        CSV of a prescribed motion (t, draft, velocity, ...).
    free_pitch, free_surge, continue_invalid : bool
        Integrate the pitch, the forward speed; go on past the stop rules.
    lift : str, optional
        The air's forces (:data:`hullslice.aero.AERO_MODELS`): ``none`` (default),
        ``weight`` (``lift_fraction`` of the weight at touchdown, held past ``stall_deg``) or
        ``coefficients`` (``wing_area`` m^2, ``wing_chord`` m, ``cl0``, ``cl_alpha``,
        ``cl_max``, ``cd``, ``cm0``, ``cm_alpha``, ``cm_q`` per rad, ``thrust`` N).
    friction : bool
        The water's friction on the wetted surface by the ITTC-57 line.
    check : bool
        Also run at half the time step and at twice the slices, and report what moved.
    max_flagged_share : float
        Largest share of the force that flagged slices may carry before a run stops.
    stations : int, optional
        Stations of the sectional area curve (``info``, default 40).
    every : int, optional
        Rows of a simulation's outputs: every Nth instant, with the first and the last
        (default: the whole run in CSV and JSON, about 40 rows in a table).
    at : tuple of float, optional
        Rows of a simulation's outputs: the instants nearest these times, s (not with
        ``every``).
    format : str, optional
        Output format: ``table``, ``json`` or ``csv``.
    output, plot : str, optional
        Files the text and the main figure are written to.
    case_file : str, optional
        The case file the study was read from (an input, never overwritten by an output).
    """

    command: str
    mesh: str
    title: str | None = None
    units: str | None = None
    forward: str | None = None
    up: str | None = None
    scale: float | None = None
    length: float | None = None
    repair: str | None = None
    keep: str | None = None
    keep_box: Any = None
    no_fix: bool = False
    mass: float | None = None
    mass_distribution: str | None = None
    cg: tuple[float, float] | None = None
    inertia: float | None = None
    rho: float = _default("rho")
    g: float = _default("g")
    solver: str = _default("solver")
    solver_options: tuple[tuple[str, Any], ...] = ()
    deadrise: str = _default("deadrise")
    slicing: str = _default("slicing")
    slices: tuple[int, ...] | None = None
    cutter: str | None = None
    draft: float | None = None
    pitch_deg: float | None = None
    velocity: float | None = None
    forward_speed: float | None = None
    pitch_rate_deg_s: float | None = None
    acceleration: float | None = None
    t_end: float | None = None
    dt: float | None = None
    kinematics: str | None = None
    free_pitch: bool = False
    free_surge: bool = False
    continue_invalid: bool = False
    max_flagged_share: float = _default("max_flagged_share")
    lift: str | None = None
    lift_fraction: float | None = None
    stall_deg: float | None = None
    wing_area: float | None = None
    wing_chord: float | None = None
    cl0: float | None = None
    cl_alpha: float | None = None
    cl_max: float | None = None
    cd: float | None = None
    cm0: float | None = None
    cm_alpha: float | None = None
    cm_q: float | None = None
    thrust: float | None = None
    friction: bool = False
    check: bool = False
    stations: int | None = None
    every: int | None = None
    at: tuple[float, ...] | None = None
    format: str | None = None
    output: str | None = None
    plot: str | None = None
    case_file: str | None = None

    def __post_init__(self) -> None:
        if self.command not in COMMANDS:
            raise InputError(
                f"study command {self.command!r} is not one of {', '.join(COMMANDS)}: "
                "choose one of them"
            )
        if isinstance(self.slices, int):
            object.__setattr__(self, "slices", (self.slices,))
        elif self.slices is not None:
            object.__setattr__(self, "slices", tuple(self.slices))
        if isinstance(self.at, int | float):
            object.__setattr__(self, "at", (float(self.at),))
        elif self.at is not None:
            object.__setattr__(self, "at", tuple(float(t) for t in self.at))
        if isinstance(self.solver_options, Mapping):
            object.__setattr__(self, "solver_options", tuple(self.solver_options.items()))
        if self.slices is not None:
            for n in self.slices:
                check_slice_count(n)
            if self.command != "force" and len(self.slices) != 1:
                self._refuse(
                    f"--slices takes one count for {self.command}, not "
                    f"{','.join(str(n) for n in self.slices)} (give e.g. 32)"
                )
        if self.stations is not None and self.stations < 1:
            self._refuse(f"--stations {self.stations!r} is not positive (give 1 or more)")
        self._check_values()
        needs = {"sections": ("draft",), "force": ("draft", "velocity")}
        missing = [n for n in needs.get(self.command, ()) if getattr(self, n) is None]
        if missing:
            self._refuse(
                "the following arguments are required: " + ", ".join("--" + n for n in missing)
            )
        if self.command == "simulate":
            self._check_motion()
            self._check_rows()
            self.aero()  # refuses a model's bad values here, before any work

    def _check_values(self) -> None:
        """The state and the water, checked by the objects the library computes with (so
        that a value is refused with one message, whichever way it was given)."""
        check_pitch(self.pitch_rad)
        if self.command in ("sections", "force") and self.draft is not None:
            Pose(self.draft, self.pitch_rad)
        if self.command == "force" and self.velocity is not None:
            Motion(self.velocity, self.horizontal_speed, self.pitch_rate_rad_s)
        if self.command == "force" and self.acceleration is not None:
            Acceleration(self.acceleration)
        if self.command in ("force", "simulate"):
            Fluid(rho=self.rho, g=self.g)

    def _refuse(self, message: str) -> None:
        raise StudyError(self.command, message)

    def _check_motion(self) -> None:
        if self.kinematics is None:
            missing = [
                o for o, v in (("--velocity", self.velocity), ("--t-end", self.t_end)) if v is None
            ]
            if missing:
                self._refuse(
                    f"a free fall needs {' and '.join(missing)} "
                    "(or give --kinematics CSV for a prescribed motion)"
                )
            return
        given = [
            opt
            for opt, value, default in (
                ("--velocity", self.velocity, None),
                ("--t-end", self.t_end, None),
                ("--dt", self.dt, None),
                ("--draft", self.draft, 0.0),
                ("--pitch", self.pitch_deg, 0.0),
                ("--forward-speed", self.forward_speed, 0.0),
                ("--pitch-rate", self.pitch_rate_deg_s, 0.0),
                ("--free-pitch", self.free_pitch, False),
                ("--free-surge", self.free_surge, False),
            )
            if value is not None and value != default
        ]
        if given:
            self._refuse(
                f"--kinematics gives the motion; leave out "
                f"{', '.join(given)} (the table's columns t, draft, velocity and "
                "optionally pitch_deg, pitch_rate_deg_s, forward_speed give it)"
            )

    def _check_rows(self) -> None:
        """``every`` and ``at``: one of them, a positive step, times inside a free fall."""
        if self.every is not None and self.every < 1:
            self._refuse(f"--every {self.every!r} is not positive (give 1 or more)")
        if self.at is None:
            return
        if self.every is not None:
            self._refuse("give --every or --at, not both")
        if not self.at:
            self._refuse("--at needs one or more times in s, e.g. --at 0.01,0.02")
        if self.kinematics is None and self.t_end is not None:
            outside = [t for t in self.at if not 0.0 <= t <= self.t_end]
            if outside:
                self._refuse(
                    f"--at {outside[0]:g} s is outside the run, from 0 to {self.t_end:g} s; "
                    "give times in that range"
                )

    # -- derived values -------------------------------------------------------------------

    @property
    def pitch_rad(self) -> float:
        """The pitch in rad (0 when not given)."""
        return 0.0 if self.pitch_deg is None else math.radians(self.pitch_deg)

    @property
    def pitch_rate_rad_s(self) -> float:
        """The pitch rate in rad/s (0 when not given)."""
        return 0.0 if self.pitch_rate_deg_s is None else math.radians(self.pitch_rate_deg_s)

    pitch = former_attribute("Study.pitch", "pitch_rad")
    pitch_rate = former_attribute("Study.pitch_rate", "pitch_rate_rad_s")

    @property
    def horizontal_speed(self) -> float:
        """The forward speed in m/s (0 when not given)."""
        return 0.0 if self.forward_speed is None else self.forward_speed

    def aero(self):
        """The aerodynamic model of this study (:func:`hullslice.aero.model_of`)."""
        coefs = {k: getattr(self, k) for k in COEFS}
        return model_of(self.lift, self.lift_fraction, coefs, self.stall_deg)

    @property
    def slice_counts(self) -> tuple[int, ...]:
        """The slice counts, the command's default when none is given."""
        default = (16, 32, 64) if self.command == "force" else (32,)
        return self.slices if self.slices is not None else default

    @property
    def options(self) -> dict[str, Any]:
        """The solver options as a dict."""
        return dict(self.solver_options)

    def for_command(self, command: str) -> Study:
        """This study's mesh, reading and mass, for another command (e.g. ``info``)."""
        keep = COMMAND_KEYS[command] | {"title", "mesh"}
        values = {f.name: getattr(self, f.name) for f in fields(self)}
        kept = {
            k: v for k, v in values.items() if _CASE_NAMES.get(k, k) in keep or k == "case_file"
        }
        return Study(command=command, **{k: v for k, v in kept.items() if k != "command"})

    # -- case files and command lines -----------------------------------------------------

    @classmethod
    def from_case(
        cls,
        case: Mapping[str, Any],
        folder: str | Path | None = None,
        *,
        checked: bool = False,
        source: str = "",
    ) -> Study:
        """The study of a case mapping.

        Parameters
        ----------
        case : mapping
            Key to value as ``tomllib`` reads a case file, checked here against
            :data:`~hullslice.case.SCHEMA` (or, with ``checked``, as
            :func:`~hullslice.load_case` returns it).
        folder : path, optional
            Folder the case's relative paths are resolved against.

        Raises
        ------
        CaseError
            A key that fails the schema, or that the case's command does not take.
        """
        if not checked:
            case = validate_case(case, base=folder, source=source)
        command = case_command(case)
        allowed = COMMAND_KEYS[command]
        extra = [k for k in case if k not in allowed and SCHEMA[k].default is None]
        extra = [k for k in extra if k not in ("title", "command", "mesh")]
        if extra:
            raise CaseError(
                f"case: key {extra[0]!r} does not apply to the command {command!r}; its keys "
                f"are {', '.join(sorted(allowed))}"
            )
        values: dict[str, Any] = {}
        for name, value in case.items():
            if name == "command" or (name not in allowed and name not in ("title", "mesh")):
                continue
            if name in _PATHS:
                value = str(value)
            elif name == "solver_options":
                value = tuple(value.items())
            elif name in _SEQUENCES:
                value = tuple(value)
            values[_FIELD_NAMES.get(name, name)] = value
        return cls(command=command, **values)

    @classmethod
    def from_args(cls, args: Any) -> Study:
        """The study of a parsed command line (an ``argparse.Namespace`` of a command).

        Options are read by their names; angles are taken in degrees, as given.

        Raises
        ------
        StudyError
            A solver option given twice.
        """
        values: dict[str, Any] = {"command": args.command}
        for o in OPTIONS:
            if o.cli is None or o.kind == "table":
                continue
            value = getattr(args, o.name, None)
            if value is not None:
                values[o.attribute] = value
        options: dict[str, Any] = {}
        for key, value in getattr(args, "solver_option", None) or ():
            if key in options:
                raise StudyError(
                    args.command,
                    f"--solver-option {key} is given twice; give each option once",
                )
            options[key] = value
        values["solver_options"] = tuple(options.items())
        values["case_file"] = getattr(args, "case", None)
        return cls(**values)

    def _case_items(self):
        """``(case key, value)`` of the keys this study's command takes, in schema order."""
        allowed = COMMAND_KEYS[self.command]
        for name in SCHEMA:
            if name in ("title", "command", "mesh") or name not in allowed:
                continue
            yield name, getattr(self, _FIELD_NAMES.get(name, name))

    def to_case(self) -> dict[str, Any]:
        """The case mapping of this study, for :func:`~hullslice.case.write_case`: the keys
        its command takes, without those left unset (paths absolute)."""
        from ..parts import parse_box

        out: dict[str, Any] = {"command": self.command, "mesh": Path(self.mesh).resolve()}
        for name, value in self._case_items():
            if name == "solver_options":
                if value:
                    out[name] = dict(value)
                continue
            if value is None or (name in _FLAGS and not value):
                continue
            if name in ("pitch", "pitch_rate") and value == 0.0:
                continue
            if name in ("slices", "cg", "at"):
                value = list(value)
            if name == "keep_box":
                box = parse_box(value)
                if box is None:
                    continue
                value = [float(x) for x in box.T.ravel()]
            if name == "repair" and value == "none":
                continue
            if name in _PATHS:
                value = Path(value).resolve()
            out[name] = value
        return out

    def command_line(self) -> list[str]:
        """The arguments of the ``hullslice`` command that computes this study."""
        argv = [self.command, str(self.mesh)]
        for name, value in self._case_items():
            flag = option(name).flag
            if value is None:
                continue
            if name in _FLAGS:
                if value:
                    argv.append(flag)
            elif name == "solver_options":
                argv += [f"{flag}={k}={json.dumps(v)}" for k, v in value]
            elif name == "cg":
                argv.append(f"--cg={value[0]!r},{value[1]!r}")
            elif name == "slices":
                argv.append(f"--slices={','.join(str(n) for n in value)}")
            elif name == "at":
                argv.append(f"--at={','.join(repr(float(t)) for t in value)}")
            elif name == "keep_box" and not isinstance(value, str):
                argv.append(f"--keep-box={','.join(repr(float(x)) for x in value)}")
            elif isinstance(value, float):
                argv.append(f"{flag}={value!r}")
            else:
                argv.append(f"{flag}={value}")
        return argv
