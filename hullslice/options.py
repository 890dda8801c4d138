"""The options of a study, one row each: the table the three front ends are built from.

A row (:class:`Option`) names an option once: its case-file key, its type and unit, its
default and limits, the commands that take it, what it is, and how the command line
writes it. From :data:`OPTIONS`,

- :data:`hullslice.case.SCHEMA` (the keys a case file may hold, checked by
  :func:`~hullslice.case.validate_case`) and :data:`hullslice.case.COMMAND_KEYS`,
- the command line's options (:func:`hullslice.cli.options.add_option`),
- :class:`hullslice.study.Study`'s defaults and its conversions to and from case files and
  command lines

are built, so that a new option is one row here (and a field of ``Study``, which
``tests/test_options.py`` checks against the table). Values are in the command line's
units: SI, angles in degrees (``pitch``, ``pitch_rate``; the study's fields ``pitch_deg``
and ``pitch_rate_deg_s``).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from dataclasses import field as _field
from typing import Any

from .aero import AERO_MODELS, AERO_NUMBERS
from .constants import AXES, LENGTH_UNITS, MAX_SLICES, RHO_WATER, G
from .geometry import CUTTERS
from .motion import DEFAULT_STOP_ON, MAX_FLAGGED_SHARE
from .sections import DEADRISE_ESTIMATORS, SLICINGS
from .solvers.registry import DEFAULT_SOLVER

__all__ = ["COMMANDS", "FIELD_KEYS", "OPTIONS", "Option", "option", "study_default"]

#: The computations a study can describe.
COMMANDS = ("info", "sections", "force", "simulate")

_ALL = COMMANDS
_SOLVED = ("force", "simulate")
_CUT = ("sections", "force", "simulate")
_SIM = ("simulate",)


@dataclass(frozen=True)
class Option:
    """One option of a study.

    Attributes
    ----------
    name : str
        The case-file key; the command line's option is ``--`` and the name with dashes
        (``forward_speed``: ``--forward-speed``), the parsed argument's name is the key.
    kind : str
        Its type: ``"text"``, ``"path"`` (text, a file relative to the case file),
        ``"number"`` (a float; an integer is accepted), ``"count"`` (a whole number),
        ``"counts"`` (a whole number or a list of them), ``"times"`` (a number or a list of
        numbers), ``"pair"`` (two numbers), ``"box"`` (six numbers), ``"flag"`` (true or
        false) or ``"table"``.
    unit : str
        SI unit of a number (``""`` for none).
    help : str
        What it is, in a few words: for case files' comments and messages.
    default : Any
        Value taken when the key is absent (None: absent stays absent, the study's field
        is None, or False for a flag).
    check : callable, optional
        Further condition on the (converted) value: returns a reason when the value is
        out of range, else None.
    commands : tuple of str
        The commands that take it.
    field : str
        The :class:`~hullslice.study.Study` field it fills (``""``: the name).
    choices : tuple of str
        The values a text may take (checked, case-insensitive), when they are few.
    cli : mapping, optional
        How the command line gives it: ``help`` (the ``--help`` text), ``metavar``,
        ``default`` (argparse's, when it differs), ``required``, ``flags`` (the option
        strings, when not ``--name``), ``type`` (a kind other than the row's). None: the
        option is the case file's only (``title``, ``command``).
    cli_for : mapping of str to mapping
        A command's own changes to ``cli`` (``simulate``'s initial ``--draft``).
    """

    name: str
    kind: str
    unit: str
    help: str
    default: Any = None
    check: Callable[[Any], str | None] | None = None
    commands: tuple[str, ...] = _ALL
    field: str = ""
    choices: tuple[str, ...] = ()
    cli: Mapping[str, Any] | None = _field(default_factory=dict)
    cli_for: Mapping[str, Mapping[str, Any]] = _field(default_factory=dict)

    @property
    def attribute(self) -> str:
        """The study's field of this option."""
        return self.field or self.name

    @property
    def study_default(self) -> Any:
        """The study's default: the row's, else False for a flag, () for a table, None."""
        if self.default is not None:
            return self.default
        return {"flag": False, "table": ()}.get(self.kind)

    def command_line(self, command: str | None = None) -> dict[str, Any]:
        """The command line's description of this option for ``command`` (see ``cli``)."""
        if self.cli is None:
            return {}
        out = dict(self.cli)
        out.update(self.cli_for.get(command or "", {}))
        return out

    @property
    def flag(self) -> str:
        """The command line's long option, ``--forward-speed``."""
        flags = (self.cli or {}).get("flags", ())
        longs = [f for f in flags if f.startswith("--")]
        return longs[0] if longs else "--" + self.name.replace("_", "-")


def _positive(v: float) -> str | None:
    return None if v > 0.0 else "must be positive"


def _not_negative(v: float) -> str | None:
    return None if v >= 0.0 else "must not be negative"


def _share(v: float) -> str | None:
    return None if 0.0 <= v <= 1.0 else "must be a share in [0, 1]"


def one_of(choices) -> Callable[[Any], str | None]:
    """A check that a text is one of ``choices`` (case-insensitive)."""
    names = tuple(choices)

    def check(v: str) -> str | None:
        return None if v.strip().lower() in names else f"must be one of {', '.join(names)}"

    return check


def _axis(v: str) -> str | None:
    key = v.strip().lower()
    return None if key in AXES or "+" + key in AXES else f"must be one of {', '.join(AXES)}"


def _slice_range(v: list[int]) -> str | None:
    bad = [n for n in v if not 1 <= n <= MAX_SLICES]
    if bad:
        return f"must be from 1 to {MAX_SLICES} (got {bad[0]})"
    if len(set(v)) != len(v):
        return "must not repeat a count"
    return None


def _choice(name, unit, what, choices, default=None, commands=_ALL, cli=None, **more):
    """A text of few values, checked against them."""
    return Option(name, "text", unit, what, default, one_of(choices), commands,
                  choices=tuple(choices), cli=cli, **more)  # fmt: skip


def _aero(name: str, unit: str, what: str) -> Option:
    model = "weight" if name in ("lift_fraction", "stall_deg") else "coefficients"
    default = {"wing_area": "", "wing_chord": "", "lift_fraction": " (default: 1)",
               "stall_deg": " (default: 15)", "cl_max": " (default: none)"}.get(
        name, " (default: 0)")  # fmt: skip
    in_unit = f", in {unit}" if unit else ""
    check = {"wing_area": _positive, "wing_chord": _positive, "cd": _not_negative,
             "thrust": _not_negative, "stall_deg": _positive, "cl_max": _positive}.get(
        name)  # fmt: skip
    help = f"with --lift {model}: {what}{in_unit}{default}"
    return Option(name, "number", unit, what, None, check, _SIM,
                  cli={"metavar": unit.upper() or "C", "help": help})  # fmt: skip


_SLICES_HELP = "slices over the wetted length at each instant (default: 32)"
_DRAFT_HELP = "depth of the body's lowest point below the calm water, in m"

#: Every option of a study, in the order of case files.
OPTIONS: tuple[Option, ...] = (
    Option("title", "text", "", "a name for the study, for reports", cli=None),
    _choice("command", "", "what to compute: sections, force, simulate or info",
            ("sections", "force", "simulate", "info"), cli=None),
    Option("mesh", "path", "", "the hull mesh, STL or OBJ, relative to the case file", cli={
        "flags": ("mesh",), "metavar": "MESH",
        "help": "hull mesh file: STL, OBJ or Cart3D .tri; PLY, OFF, GLB/glTF, 3MF or Gmsh .msh "
        "with pip install 'hullslice[formats]'"}),
    _choice("units", "", "length unit of the mesh", LENGTH_UNITS, cli={
        "help": "length unit of the mesh file (default: the unit the file declares, as a 3MF "
        "does, else m)"}),
    Option("forward", "text", "", "mesh axis pointing forward", None, _axis, cli={
        "metavar": "AXIS",
        "help": "mesh axis pointing forward along the body: x, y, z, or with a sign as "
        "--forward=-x (default: +x, or what the file declares)"}),
    Option("up", "text", "", "mesh axis pointing up", None, _axis, cli={
        "metavar": "AXIS",
        "help": "mesh axis pointing up: x, y, z, or with a sign as --up=-y (default: +z, or what "
        "the file declares: +y for glTF/GLB)"}),
    Option("scale", "number", "m per file unit", "scale of the mesh (not with length)",
           check=_positive, cli={"metavar": "FACTOR",
        "help": "metres per unit of the mesh file (times the --units factor when both are "
        "given), e.g. 2.56 for a model whose 14.7 units are 37.6 m (not with --length)"}),
    Option("length", "number", "m", "the body's length along forward, sets the scale",
           check=_positive, cli={"metavar": "M",
        "help": "scale the body so that its extent along --forward is M metres (after --keep; "
        "not with --scale or --units)"}),
    _choice("repair", "", "repair of an open mesh: none or close", ("none", "close"), cli={
        "help": "close: fill the holes of an open mesh (MeshFix, pip install "
        "'hullslice[repair]') and drop shells that cannot be closed, with the figures in a "
        "warning (default: none, an open mesh is refused)"}),
    Option("keep", "text", "", "bodies to keep: 'largest' or numbers from 1 as '1,3'", cli={
        "metavar": "largest|N,M",
        "help": "keep only these bodies (shells) of the mesh: largest, or numbers from 1, "
        "largest first as 'hullslice info' lists them (default: all)"}),
    Option("keep_box", "box", "m", "keep the part inside xmin, xmax, ymin, ymax, zmin, zmax",
           cli={"metavar": "XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX",
        "help": "keep the part of the body inside this box, in m, body frame after scaling; "
        "write it as --keep-box=-1,40,-2.5,2.5,-1,5"}),
    Option("no_fix", "flag", "", "make none of the safe repairs: refuse a mesh that needs one",
           cli={"help": "make none of the safe repairs (merging vertices that differ by "
        "rounding, dropping degenerate or repeated faces, re-orienting faces, ...): refuse a "
        "mesh that needs one, naming the repair"}),
    Option("mass", "number", "kg", "mass of the body", check=_positive, cli={
        "metavar": "KG", "help": "body mass in kg (for mass per metre)"}, cli_for={
        c: {"help": "body mass in kg (or --mass-distribution)"} for c in _SOLVED}),
    Option("mass_distribution", "path", "", "CSV of the mass along the body, relative to "
           "the case", cli={"metavar": "CSV",
        "help": "mass along the body instead of a uniform density: CSV with columns "
        "x,mass_per_metre (m, kg/m) or point masses x,z,mass[,length] (m, kg, m; length "
        "default a tenth of the body's length), body frame in metres after --units and axes; "
        "it must lie on the body"}),
    Option("cg", "pair", "m", "centre of gravity x, z in the body frame", cli={
        "metavar": "X,Z",
        "help": "centre of gravity x,z in m, body frame (default: from the mass distribution, "
        "or the centre of volume)"}),
    Option("inertia", "number", "kg*m^2", "pitch moment of inertia about the centre of "
           "gravity", check=_positive, cli={"metavar": "KG*M^2",
        "help": "pitch moment of inertia about the centre of gravity in kg*m^2 (default: from "
        "the mass distribution, or the mesh with uniform density)"}),
    Option("rho", "number", "kg/m^3", "water density", RHO_WATER, _positive, _SOLVED, cli={
        "metavar": "KG/M3", "help": f"water density in kg/m^3 (default: {RHO_WATER:g})"}),
    Option("g", "number", "m/s^2", "gravitational acceleration", G, _not_negative, _SOLVED,
           cli={"metavar": "M/S2",
                "help": f"gravitational acceleration in m/s^2 (default: {G:g})"}),
    Option("solver", "text", "", "name of the 2D solver", DEFAULT_SOLVER, None, _SOLVED, cli={
        "metavar": "NAME",
        "help": f"2D solver, see 'hullslice solvers' (default: {DEFAULT_SOLVER})"}),
    Option("solver_options", "table", "", "options passed to the 2D solver", None, None,
           _SOLVED, cli={"flags": ("--solver-option",), "metavar": "KEY=VALUE",
        "help": "an option of the 2D solver (repeatable); VALUE is read as JSON when it parses "
        "(numbers, [lists], true/false), else as text; SI units, e.g. froude_min=8 "
        "(smallest peak Froude number), or for --solver curves table=FILE.csv (columns "
        "z_tilde,a_tilde,v_tilde), rho=1025 (kg/m^3, the density the curves were made for), "
        "pile_up=wagner. 'hullslice solvers --format json' lists each solver's options and "
        "their defaults"}),
    _choice("deadrise", "", "local deadrise estimator", DEADRISE_ESTIMATORS, "wedge", _CUT,
            cli={"help": "local deadrise estimator: wedge (the equivalent wedge p / c), "
        "waterline-slope or keel-fit (default: wedge)"}),
    _choice("slicing", "", "how the slices are placed", SLICINGS, "wetted", _CUT, cli={
        "help": "wetted: the slices cover the wetted length at each instant (the paper's); "
        "fixed: they cover the body's length and are cut once per pitch, much faster on "
        "large meshes (default: wetted)"}),
    Option("slices", "counts", "", "slice count(s) over the wetted length", None,
           _slice_range, _CUT, cli={"type": "count", "default": 32, "metavar": "N",
                                    "help": _SLICES_HELP},
           cli_for={"sections": {"help": "number of slices over the wetted length (default: 32)"},
                    "force": {"type": "counts", "default": [16, 32, 64], "metavar": "N[,N...]",
        "help": "slice counts over the wetted length; three or more give the extrapolated "
        "force (default: 16,32,64)"}}),
    Option("draft", "number", "m", "depth of the lowest point below the water", None,
           _not_negative, _CUT, cli={"metavar": "M", "required": True, "help": _DRAFT_HELP},
           cli_for={"simulate": {"required": False, "default": 0.0,
        "help": "initial draft of the lowest point in m (default: 0, first contact)"}}),
    Option("pitch", "number", "deg", "pitch angle, positive nose up", commands=_CUT,
           field="pitch_deg", cli={"default": 0.0, "metavar": "DEG",
        "help": "pitch angle in degrees, positive nose up, about the centre of gravity "
        "(default: 0)"}),
    Option("velocity", "number", "m/s", "vertical velocity, negative down", commands=_SOLVED,
           cli={"metavar": "M/S", "required": True,
        "help": "vertical velocity in m/s, negative downward (e.g. --velocity=-3.5)"},
           cli_for={"simulate": {"required": False,
        "help": "initial vertical velocity in m/s, negative downward (free fall)"}}),
    Option("forward_speed", "number", "m/s", "horizontal speed along the body",
           commands=_SOLVED, cli={"default": 0.0, "metavar": "M/S",
        "help": "horizontal speed along the body's forward direction in m/s (default: 0)"}),
    Option("pitch_rate", "number", "deg/s", "pitch rate, positive nose up", commands=_SOLVED,
           field="pitch_rate_deg_s", cli={"default": 0.0, "metavar": "DEG/S",
        "help": "pitch rate in degrees per second, positive nose up (default: 0)"}),
    _choice("cutter", "", "how a new pitch is cut: exact or manifold3d (default: exact with "
            "free pitch, else manifold3d)", tuple(CUTTERS), commands=_SIM, cli={
        "help": "how the stations of a new pitch are cut: exact (a kernel on the body-frame "
        "mesh, without turning it; the default with --free-pitch) or manifold3d (the mesh "
        "turned to the pitch; the default otherwise, and of --kinematics); the two agree "
        "within 1e-9 of the force"}),
    Option("t_end", "number", "s", "duration of a free fall", None, _positive, _SIM, cli={
        "metavar": "S", "help": "duration of the run in s (free fall)"}),
    Option("dt", "number", "s", "time step of a free fall", None, _positive, _SIM, cli={
        "metavar": "S", "help": "time step in s (default: t-end / 1000)"}),
    Option("kinematics", "path", "", "CSV of t, draft, velocity, relative to the case",
           commands=_SIM, cli={"metavar": "CSV",
        "help": "prescribed motion: CSV with columns t (s), draft (m, positive), "
        "velocity (m/s, negative down), optionally acceleration (m/s^2, up; derived from "
        "velocity when absent), pitch_deg, pitch_rate_deg_s, forward_speed (m/s)"}),
    Option("free_pitch", "flag", "", "integrate the pitch in a free fall", commands=_SIM, cli={
        "help": "integrate the pitch from the moment about the centre of gravity (default: the "
        "pitch changes at the constant --pitch-rate)"}),
    Option("free_surge", "flag", "", "integrate the forward speed in a free fall",
           commands=_SIM, cli={"help": "integrate the forward speed from the horizontal force "
                                       "(default: constant)"}),
    Option("continue_invalid", "flag", "", "go on past the method's range in a free fall",
           commands=_SIM, cli={"help": "go on to the end when a stop rule is met, with flagged "
                                       f"values (rules: {', '.join(DEFAULT_STOP_ON)})"}),
    _choice("lift", "", "the air's forces", tuple(AERO_MODELS), commands=_SIM, cli={
        "help": "the air's forces: none (default), weight (lift equal to the weight at "
        "touchdown, scaled with the speed squared and the angle of attack) or coefficients "
        "(--wing-area, --wing-chord and the coefficients below)"}),
    *(_aero(name, unit, what) for name, unit, what in AERO_NUMBERS),
    Option("friction", "flag", "", "the water's friction on the wetted surface (ITTC-57)",
           commands=_SIM, cli={"help": "add the water's friction on the wetted surface "
                                       "(ITTC-57 line, N)"}),
    Option("check", "flag", "", "also run at half the step and twice the slices (simulate)",
           commands=_SIM, cli={"help": "also run at half the time step and at twice the "
        "slices, and report how much the peak force (%%), its time (s) and the largest pitch "
        "(deg) moved"}),
    Option("max_flagged_share", "number", "", "largest share of the force that slices "
           "outside the solver's range may carry before a run stops", MAX_FLAGGED_SHARE,
           _share, _SIM, cli={"metavar": "SHARE",
        "help": "stop when slices outside the solver's range carry more than this share of "
        f"the force, 0 to 1 (default: {MAX_FLAGGED_SHARE:g})"}),
    Option("acceleration", "number", "m/s^2", "vertical acceleration of the body, positive "
           "up, for a momentum-form solver's force (default: free in heave)",
           commands=("force",), cli={"metavar": "M/S2",
        "help": "vertical acceleration of the body in m/s^2, positive up, for a momentum-form "
        "solver's added-inertia force (default: the body free in heave, its acceleration "
        "solved with its mass and added mass); free-fall solvers do not use it"}),
    Option("stations", "count", "", "stations of the sectional area curve (info)",
           commands=("info",), cli={"default": 40, "metavar": "N",
        "help": "stations of the sectional area curve, along the body's length (default: 40)"}),
    Option("every", "count", "", "rows shown: every Nth instant, with the first and last "
           "(simulate)", None, _positive, _SIM, cli={"metavar": "N",
        "help": "give every Nth instant, with the first and the last, in the table, CSV and "
        "JSON (default: every instant in CSV and JSON, about 40 in the table)"}),
    Option("at", "times", "s", "rows shown: the instants nearest these times (simulate)",
           commands=_SIM, cli={"metavar": "S[,S...]",
        "help": "give the instants nearest these times in s, e.g. --at 0.01,0.02, in the "
        "table, CSV and JSON (a time outside the run is refused, naming its range)"}),
    _choice("format", "", "output format: table, json or csv", ("table", "json", "csv"),
            cli={"default": "table",
                 "help": "table for reading, json or csv for machines (default: table)"},
            cli_for={"run": {"default": None, "help": "output format (default: the case's)"}}),
    Option("output", "path", "", "file to write the output to, relative to the case", cli={
        "flags": ("-o", "--output"), "metavar": "PATH",
        "help": "write to this file instead of the terminal (written completely or not at "
        "all)"}, cli_for={"run": {"help": "output file (default: the case's)"}}),
    Option("plot", "path", "", "image to draw the main figure to, relative to the case", cli={
        "metavar": "PATH.png",
        "help": "also draw {figure} to this image (PNG, SVG or PDF by the extension; needs "
        "matplotlib: pip install 'hullslice[plot]')"},
           cli_for={"run": {"help": "figure file (default: the case's)"}}),
)  # fmt: skip

_BY_NAME: dict[str, Option] = {o.name: o for o in OPTIONS}


def option(name: str) -> Option:
    """The row of the case key ``name``."""
    return _BY_NAME[name]


def study_default(name: str) -> Any:
    """The study's default of the case key ``name`` (:attr:`Option.study_default`)."""
    return _BY_NAME[name].study_default


#: Study field to case key, where they differ (the angles, whose fields name the unit).
FIELD_KEYS: dict[str, str] = {o.attribute: o.name for o in OPTIONS if o.field}
