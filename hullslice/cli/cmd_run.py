"""``hullslice run CASE.toml``: run the command a case file describes."""

from __future__ import annotations

import argparse

from ..case import case_argv, load_case
from .common import FORMATS


def add_parser(sub) -> None:
    p = sub.add_parser(
        "run",
        help="run a case file (TOML): mesh, mass, fluid, solver, slices, motion, outputs",
        description="Run the computation a case file describes, exactly as the command line "
        "it amounts to (every command's --save-case writes one). Paths in the case are "
        "relative to its folder. The options below override the case's outputs.",
    )
    p.add_argument("case", metavar="CASE.toml", help="the case file")
    p.add_argument("--format", choices=FORMATS, help="output format (default: the case's)")
    p.add_argument("-o", "--output", metavar="PATH", help="output file (default: the case's)")
    p.add_argument("--plot", metavar="PATH.png", help="figure file (default: the case's)")
    p.add_argument(
        "--print-command",
        action="store_true",
        help="print the command line the case amounts to, and run nothing",
    )
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from . import build_parser

    case = load_case(args.case)
    argv = case_argv(case)
    for option in ("format", "output", "plot"):
        value = getattr(args, option)
        if value is not None:
            argv = [a for a in argv if not a.startswith(f"--{option}=")]
            argv.append(f"--{option}={value}")
    if args.print_command:
        print("hullslice " + " ".join(_quote(a) for a in argv))
        return 0
    command = build_parser().parse_args(argv)
    command.case = args.case  # an input of the run, protected from its outputs like the mesh
    return command.func(command)


def _quote(arg: str) -> str:
    import shlex

    return shlex.quote(arg)
