"""``hullslice solvers``: the installed 2D solvers."""

from __future__ import annotations

import argparse
from dataclasses import asdict

from ..solvers.registry import DEFAULT_SOLVER, list_solvers
from ..textout import Column, csv_text, json_text, table_text
from .common import FORMATS, emit

COLUMNS = (
    Column("name", "name"),
    Column("kind", "kind"),
    Column("status", "status"),
    Column("distribution", "distribution"),
    Column("version", "version"),
    Column("description", "description"),
)


def add_parser(sub) -> None:
    p = sub.add_parser(
        "solvers",
        help="list the installed 2D solvers",
        description="List the 2D solvers registered in the entry-point group "
        "'hullslice.solvers', with their distribution, version and status (ok, broken: "
        "fails to load, with the error; shadowed: another distribution registers the same "
        "name). The kind says which form a solver has: free-fall (the paper's: each slice in "
        "a free fall of its own, F = M (a + g) d) or momentum (added mass per metre and its "
        "rate; the body's accelerations on the left of its equations of motion). JSON and CSV "
        "also give each solver's options (--solver-option KEY=VALUE).",
    )
    p.add_argument("--format", choices=FORMATS, default="table", help="output format")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    infos = list_solvers()
    rows = []
    for info in infos:
        row = asdict(info)
        if info.status != "ok":
            row["description"] = info.error
        if info.name == DEFAULT_SOLVER and info.status == "ok":
            row["name"] = f"{info.name} (default)"
        rows.append(row)
    if args.format == "json":
        emit(args, json_text({"default": DEFAULT_SOLVER, "solvers": [asdict(i) for i in infos]}))
    elif args.format == "csv":
        keys = [
            "name",
            "kind",
            "status",
            "distribution",
            "version",
            "value",
            "description",
            "error",
            "options",
        ]
        records = [{**asdict(i), "options": " ".join(i.options)} for i in infos]
        emit(args, csv_text(keys, records))
    else:
        emit(args, table_text(COLUMNS, rows) if rows else "no solvers are installed")
    return 0
