"""``hullslice run CASE.toml``: run the study a case file describes."""

from __future__ import annotations

import argparse
import dataclasses
import shlex
from typing import Any

from ..case import load_case
from ..study import Study
from .options import add_options
from .studies import command_module


def add_parser(sub) -> None:
    p = sub.add_parser(
        "run",
        help="run a case file (TOML): mesh, mass, fluid, solver, slices, motion, outputs",
        description="Run the computation a case file describes, exactly as the command line "
        "it amounts to (every command's --save-case writes one). Paths in the case are "
        "relative to its folder. The options below override the case's outputs.",
    )
    p.add_argument("case", metavar="CASE.toml", help="the case file")
    add_options(p, "run", "format", "output", "plot")
    p.add_argument(
        "--print-command",
        action="store_true",
        help="print the command line the case amounts to, and run nothing",
    )
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    study = Study.from_case(load_case(args.case), checked=True)
    overrides: dict[str, Any] = {
        option: getattr(args, option)
        for option in ("format", "output", "plot")
        if getattr(args, option) is not None
    }
    # the case file is an input of the run, protected from its outputs like the mesh
    study = dataclasses.replace(study, case_file=args.case, **overrides)
    if args.print_command:
        print("hullslice " + " ".join(shlex.quote(a) for a in study.command_line()))
        return 0
    return command_module(study.command).run_study(study)
