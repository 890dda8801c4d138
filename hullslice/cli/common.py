"""Options and helpers shared by the commands."""

from __future__ import annotations

import argparse
import json
from typing import Any

from ..constants import LENGTH_UNITS, RHO_SEA, RHO_WATER, G
from ..safety import non_finite
from ..solvers.registry import DEFAULT_SOLVER
from ..study import Study

# the commands' output helpers, given here with the option helpers
from .outputs import (  # noqa: F401
    FIGURE_FORMATS,
    Extra,
    Outcome,
    check_distinct,
    check_extras,
    check_output,
    check_path,
    compute,
    emit,
    finish,
    out_path,
    write_error,
    write_together,
)

FORMATS = ("table", "json", "csv")


class UsageError(Exception):
    """A command-line usage error (one line, exit status 2, as argparse's own)."""


def positive_int(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"{text!r} is not positive (give 1 or more)")
    return n


def slice_list(text: str) -> list[int]:
    """``"16,32,64"`` to ``[16, 32, 64]``."""
    parts = [p.strip() for p in text.split(",") if p.strip()]
    if not parts:
        raise argparse.ArgumentTypeError("give one or more slice counts, e.g. 16,32,64")
    out = [positive_int(p) for p in parts]
    if len(set(out)) != len(out):
        raise argparse.ArgumentTypeError(f"slice counts {text!r} repeat a value")
    return out


def number(unit: str):
    def parse(text: str) -> float:
        try:
            return float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a number (in {unit})") from None

    parse.__name__ = f"number in {unit}"
    return parse


def lower(text: str) -> str:
    """A case-insensitive choice: ``MM`` is ``mm``."""
    return text.strip().lower()


def solver_option(text: str) -> tuple[str, Any]:
    """``"KEY=VALUE"`` to ``(KEY, value)``, the value read as JSON when it parses, else text.

    ``rho=1025`` gives the number 1025, ``a_coeffs=[0, -3000]`` a list, ``pile_up=wagner``
    and ``table=curves.csv`` the text as it is.
    """
    key, sep, value = text.partition("=")
    key = key.strip()
    if not sep or not key:
        raise argparse.ArgumentTypeError(
            f"{text!r} is not KEY=VALUE (e.g. --solver-option pile_up=wagner)"
        )
    try:
        parsed = json.loads(value)
    except json.JSONDecodeError:
        return key, value
    bad = non_finite(parsed)
    if bad is not None:  # NaN would pass every comparison's test: a check switched off
        raise argparse.ArgumentTypeError(
            f"{text!r}: {bad!r} is not a finite number; give a finite value"
        )
    return key, parsed


def add_solver_options(g: argparse._ArgumentGroup) -> None:
    """``--solver NAME`` and the repeatable ``--solver-option KEY=VALUE``."""
    g.add_argument(
        "--solver",
        default=DEFAULT_SOLVER,
        metavar="NAME",
        help=f"2D solver, see 'hullslice solvers' (default: {DEFAULT_SOLVER})",
    )
    g.add_argument(
        "--solver-option",
        type=solver_option,
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="an option of the 2D solver (repeatable); VALUE is read as JSON when it parses "
        "(numbers, [lists], true/false), else as text; SI units, e.g. froude_min=8 "
        "(smallest peak Froude number), or for --solver curves table=FILE.csv (columns "
        "z_tilde,a_tilde,v_tilde), rho=1025 (kg/m^3, the density the curves were made for), "
        "pile_up=wagner. 'hullslice solvers --format json' lists each solver's options and "
        "their defaults",
    )


def solver_label(study: Study) -> str:
    """The solver's name with the options given, for table headers."""
    if not study.solver_options:
        return study.solver
    opts = ", ".join(f"{k}={json.dumps(v)}" for k, v in study.solver_options)
    return f"{study.solver} ({opts})"


def add_mesh_options(p: argparse.ArgumentParser, mass_required: bool = False) -> None:
    p.add_argument(
        "mesh",
        metavar="MESH",
        help="hull mesh file: STL, OBJ or Cart3D .tri; PLY, OFF, GLB/glTF, 3MF or Gmsh .msh "
        "with pip install 'hullslice[formats]'",
    )
    g = p.add_argument_group("mesh options")
    g.add_argument(
        "--units",
        default=None,
        type=lower,
        choices=list(LENGTH_UNITS),
        help="length unit of the mesh file (default: the unit the file declares, as a 3MF "
        "does, else m)",
    )
    g.add_argument(
        "--forward",
        default=None,
        metavar="AXIS",
        help="mesh axis pointing forward along the body: x, y, z, or with a sign as "
        "--forward=-x (default: +x, or what the file declares)",
    )
    g.add_argument(
        "--up",
        default=None,
        metavar="AXIS",
        help="mesh axis pointing up: x, y, z, or with a sign as --up=-y (default: +z, or what "
        "the file declares: +y for glTF/GLB)",
    )
    add_shape_options(g)
    m = p.add_argument_group("mass")
    m.add_argument(
        "--mass",
        type=number("kg"),
        metavar="KG",
        help="body mass in kg"
        + (" (or --mass-distribution)" if mass_required else " (for mass per metre)"),
    )
    m.add_argument(
        "--mass-distribution",
        metavar="CSV",
        help="mass along the body instead of a uniform density: CSV with columns "
        "x,mass_per_metre (m, kg/m) or point masses x,z,mass[,length] (m, kg, m; length "
        "default a tenth of the body's length), body frame in metres after --units and axes; "
        "it must lie on the body",
    )
    m.add_argument(
        "--cg",
        type=pair("m"),
        metavar="X,Z",
        help="centre of gravity x,z in m, body frame (default: from the mass distribution, "
        "or the centre of volume)",
    )
    m.add_argument(
        "--inertia",
        type=number("kg*m^2"),
        metavar="KG*M^2",
        help="pitch moment of inertia about the centre of gravity in kg*m^2 (default: from "
        "the mass distribution, or the mesh with uniform density)",
    )


def add_shape_options(g) -> None:
    """``--scale``, ``--length``, ``--repair``, ``--keep`` and ``--keep-box``
    (:mod:`hullslice.prepare`)."""
    g.add_argument(
        "--scale",
        type=number("m per file unit"),
        metavar="FACTOR",
        help="metres per unit of the mesh file (times the --units factor when both are "
        "given), e.g. 2.56 for a model whose 14.7 units are 37.6 m (not with --length)",
    )
    g.add_argument(
        "--length",
        type=number("m"),
        metavar="M",
        help="scale the body so that its extent along --forward is M metres (after --keep; "
        "not with --scale or --units)",
    )
    g.add_argument(
        "--repair",
        type=lower,
        choices=["none", "close"],
        default=None,
        help="close: fill the holes of an open mesh (MeshFix, pip install "
        "'hullslice[repair]') and drop shells that cannot be closed, with the figures in a "
        "warning (default: none, an open mesh is refused)",
    )
    g.add_argument(
        "--no-fix",
        action="store_true",
        help="make none of the safe repairs (merging vertices that differ by rounding, "
        "dropping degenerate or repeated faces, re-orienting faces, ...): refuse a mesh "
        "that needs one, naming the repair",
    )
    g.add_argument(
        "--keep",
        metavar="largest|N,M",
        help="keep only these bodies (shells) of the mesh: largest, or numbers from 1, "
        "largest first as 'hullslice info' lists them (default: all)",
    )
    g.add_argument(
        "--keep-box",
        metavar="XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX",
        help="keep the part of the body inside this box, in m, body frame after scaling; "
        "write it as --keep-box=-1,40,-2.5,2.5,-1,5",
    )


def pair(unit: str):
    def parse(text: str) -> tuple[float, float]:
        parts = text.split(",")
        try:
            if len(parts) != 2:
                raise ValueError
            return float(parts[0]), float(parts[1])
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{text!r} is not two numbers X,Z (in {unit}), e.g. 16.5,1.2"
            ) from None

    parse.__name__ = f"pair in {unit}"
    return parse


def add_section_options(g) -> None:
    """``--deadrise ESTIMATOR`` and ``--slicing wetted|fixed``."""
    from ..sections import DEADRISE_ESTIMATORS, SLICINGS

    g.add_argument(
        "--deadrise",
        choices=list(DEADRISE_ESTIMATORS),
        default="wedge",
        help="local deadrise estimator: wedge (the equivalent wedge p / c), waterline-slope "
        "or keel-fit (default: wedge)",
    )
    g.add_argument(
        "--slicing",
        choices=list(SLICINGS),
        default="wetted",
        help="wetted: the slices cover the wetted length at each instant (the paper's); "
        "fixed: they cover the body's length and are cut once per pitch, much faster on "
        "large meshes (default: wetted)",
    )


def add_pose_options(g, pitch_rate: bool = True, forward_speed: bool = True) -> None:
    """Pitch (and optionally forward speed and pitch rate) options, in degrees and m/s."""
    g.add_argument(
        "--pitch",
        type=number("deg"),
        default=0.0,
        metavar="DEG",
        help="pitch angle in degrees, positive nose up, about the centre of gravity (default: 0)",
    )
    if forward_speed:
        g.add_argument(
            "--forward-speed",
            type=number("m/s"),
            default=0.0,
            metavar="M/S",
            help="horizontal speed along the body's forward direction in m/s (default: 0)",
        )
    if pitch_rate:
        g.add_argument(
            "--pitch-rate",
            type=number("deg/s"),
            default=0.0,
            metavar="DEG/S",
            help="pitch rate in degrees per second, positive nose up (default: 0)",
        )


#: Waters by name, kg/m^3.
WATERS = {"sea": RHO_SEA, "fresh": RHO_WATER}


def water(text: str) -> float:
    """An argparse type: a water by name (:data:`WATERS`) or a density in kg/m^3."""
    key = text.strip().lower()
    if key in WATERS:
        return WATERS[key]
    try:
        return number("kg/m^3")(text)
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(
            f"{text!r} is neither sea, fresh nor a density in kg/m^3"
        ) from None


def add_fluid_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("water")
    g.add_argument(
        "--rho",
        type=number("kg/m^3"),
        default=RHO_WATER,
        metavar="KG/M3",
        help=f"water density in kg/m^3 (default: {RHO_WATER:g})",
    )
    g.add_argument(
        "--water",
        dest="rho",
        type=water,
        metavar="sea|fresh",
        help=f"the water by name: sea ({RHO_SEA:g} kg/m^3, for a ditching) or fresh "
        f"({RHO_WATER:g} kg/m^3), or a density in kg/m^3",
    )
    g.add_argument(
        "--g",
        type=number("m/s^2"),
        default=G,
        metavar="M/S2",
        help=f"gravitational acceleration in m/s^2 (default: {G:g})",
    )


def add_output_options(p: argparse.ArgumentParser, plot: str = "") -> None:
    g = p.add_argument_group("output")
    g.add_argument(
        "--format",
        choices=FORMATS,
        default="table",
        help="table for reading, json or csv for machines (default: table)",
    )
    g.add_argument(
        "-o",
        "--output",
        type=out_path(),
        metavar="PATH",
        help="write to this file instead of the terminal (written completely or not at all)",
    )
    if plot:
        g.add_argument(
            "--plot",
            type=out_path(),
            metavar="PATH.png",
            help=f"also draw {plot} to this image (PNG, SVG or PDF by the extension; needs "
            "matplotlib: pip install 'hullslice[plot]')",
        )
    g.add_argument(
        "--save-case",
        type=out_path(),
        metavar="PATH.toml",
        help="also write the case this command amounts to, for 'hullslice run' to repeat it",
    )
