"""Options and helpers shared by the commands."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..constants import LENGTH_UNITS, RHO_WATER, G
from ..errors import InputError
from ..mesh import Hull, load_hull
from ..report import write_atomic
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


def lower(text: str) -> str:
    """A case-insensitive choice: ``MM`` is ``mm``."""
    return text.strip().lower()


def add_mesh_options(p: argparse.ArgumentParser, mass_required: bool = False) -> None:
    p.add_argument("mesh", metavar="MESH", help="hull mesh file, STL or OBJ")
    g = p.add_argument_group("mesh options")
    g.add_argument(
        "--units",
        default="m",
        type=lower,
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
    """The hull of the command line's mesh options (the output path is checked first)."""
    check_output(args)
    return load_hull(args.mesh, units=args.units, forward=args.forward, up=args.up, mass=args.mass)


def check_output(args: argparse.Namespace) -> None:
    """Refuse an ``--output`` that cannot be written, before any work is done."""
    out = getattr(args, "output", None)
    if not out:
        return
    target = Path(out)
    if target.is_dir():
        raise InputError(f"cannot write {out!r}: it is a folder; give a file name in it")
    if not (target.parent if str(target.parent) else Path(".")).is_dir():
        raise InputError(
            f"cannot write {out!r}: the folder {str(target.parent)!r} does not exist; create it "
            "first"
        )
    for option in ("mesh", "kinematics"):
        source = getattr(args, option, None)
        if source and target.exists() and Path(source).exists() and target.samefile(source):
            raise InputError(
                f"cannot write {out!r}: it is the input {option} file and would be overwritten; "
                "give another output file"
            )


def fluid(args: argparse.Namespace) -> Fluid:
    return Fluid(rho=args.rho, g=args.g)


def emit(args: argparse.Namespace, text: str) -> None:
    """Print the command's output, or write it to ``--output``."""
    if getattr(args, "output", None):
        check_output(args)
        try:
            write_atomic(args.output, text)
        except OSError as exc:
            raise InputError(f"cannot write {args.output!r}: {exc.strerror or exc}") from None
        print(f"wrote {args.output}", file=sys.stderr)
    else:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")
