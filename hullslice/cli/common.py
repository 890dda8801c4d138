"""Options and helpers shared by the commands."""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any

from ..constants import LENGTH_UNITS, RHO_WATER, G
from ..errors import InputError
from ..mesh import Hull, load_hull
from ..report import write_atomic
from ..solvers.base import Solver
from ..solvers.registry import DEFAULT_SOLVER, get_solver
from ..state import Fluid

FORMATS = ("table", "json", "csv")


class UsageError(Exception):
    """A command-line usage error (one line, exit status 2)."""


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
        return key, json.loads(value)
    except json.JSONDecodeError:
        return key, value


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


def solver(args: argparse.Namespace) -> Solver:
    """The solver named by ``--solver``, built with the ``--solver-option`` values."""
    options: dict[str, Any] = {}
    for key, value in args.solver_option:
        if key in options:
            raise UsageError(
                f"hullslice {args.command}: error: --solver-option {key} is given twice; "
                "give each option once"
            )
        options[key] = value
    return get_solver(args.solver, **options)


def solver_label(args: argparse.Namespace) -> str:
    """The solver's name with the options given on the command line, for table headers."""
    if not args.solver_option:
        return args.solver
    opts = ", ".join(f"{k}={json.dumps(v)}" for k, v in args.solver_option)
    return f"{args.solver} ({opts})"


def add_mesh_options(p: argparse.ArgumentParser, mass_required: bool = False) -> None:
    p.add_argument("mesh", metavar="MESH", help="hull mesh file, STL or OBJ")
    g = p.add_argument_group("mesh options")
    g.add_argument(
        "--units",
        default="m",
        choices=list(LENGTH_UNITS),
        help="length unit of the mesh file (default: m)",
    )
    g.add_argument(
        "--forward",
        default="+x",
        metavar="AXIS",
        help="mesh axis pointing forward along the body: x, y, z, or with a sign as "
        "--forward=-x (default: +x)",
    )
    g.add_argument(
        "--up",
        default="+z",
        metavar="AXIS",
        help="mesh axis pointing up: x, y, z, or with a sign as --up=-y (default: +z)",
    )
    g.add_argument(
        "--mass",
        type=number("kg"),
        metavar="KG",
        required=mass_required,
        help="body mass in kg" + ("" if mass_required else " (needed for mass per metre)"),
    )


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
        "--g",
        type=number("m/s^2"),
        default=G,
        metavar="M/S2",
        help=f"gravitational acceleration in m/s^2 (default: {G:g})",
    )


def add_output_options(p: argparse.ArgumentParser) -> None:
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
        metavar="PATH",
        help="write to this file instead of the terminal (written completely or not at all)",
    )


def load(args: argparse.Namespace) -> Hull:
    return load_hull(args.mesh, units=args.units, forward=args.forward, up=args.up, mass=args.mass)


def fluid(args: argparse.Namespace) -> Fluid:
    return Fluid(rho=args.rho, g=args.g)


def emit(args: argparse.Namespace, text: str) -> None:
    """Print the command's output, or write it to ``--output``."""
    if getattr(args, "output", None):
        try:
            write_atomic(args.output, text)
        except FileNotFoundError as exc:
            raise InputError(f"cannot write {args.output!r}: {exc}") from None
        print(f"wrote {args.output}", file=sys.stderr)
    else:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")
