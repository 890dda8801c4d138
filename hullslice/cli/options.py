"""The command line's options of a study, built from the option table.

:func:`add_option` adds the option of one row of :data:`hullslice.options.OPTIONS` to a
parser (or one of its groups), for one command: its flag, its type from the row's kind
and unit, its choices, default, metavar and help. The commands place the rows in their
groups; what each option is, is said once, in the table.
"""

from __future__ import annotations

from typing import Any

from ..options import option
from ..paths import WRITTEN_KEYS
from .argtypes import lower, number, pair, positive_int, slice_list, solver_option, times
from .outputs import out_path

__all__ = ["add_option", "add_options", "argument_type"]


def argument_type(kind: str, unit: str, name: str = "") -> Any:
    """The argparse type of an option of this kind and unit (None: the text as it is)."""
    if kind == "number":
        return number(unit)
    if kind == "count":
        return positive_int
    if kind == "counts":
        return slice_list
    if kind == "times":
        return times
    if kind == "pair":
        return pair(unit)
    if kind == "table":
        return solver_option
    if kind == "path" and name in WRITTEN_KEYS:
        return out_path()
    return None


def add_option(group, name: str, command: str, **figure: str) -> None:
    """Add the option of the case key ``name`` to ``group`` (a parser or an argument
    group), as ``command`` takes it; ``figure`` fills the help's ``{figure}``."""
    row = option(name)
    cli = row.command_line(command)
    kind = cli.get("type", row.kind)
    flags = cli.get("flags", ("--" + name.replace("_", "-"),))
    kwargs: dict[str, Any] = {"help": cli["help"].format(**figure) if figure else cli["help"]}
    if kind == "flag":
        kwargs["action"] = "store_true"
    else:
        kind_type = argument_type(kind, row.unit, name)
        if row.choices:
            kind_type, kwargs["choices"] = lower, list(row.choices)
        if kind_type is not None:
            kwargs["type"] = kind_type
        if "metavar" in cli:
            kwargs["metavar"] = cli["metavar"]
    if kind == "table":
        kwargs.update(action="append", default=[], dest="solver_option")
    elif "default" in cli:
        kwargs["default"] = cli["default"]
    elif row.default is not None and kind != "flag":
        kwargs["default"] = row.default
    if flags[0].startswith("-"):
        if cli.get("required"):
            kwargs["required"] = True
        if kind not in ("flag", "table") and flags[-1].lstrip("-").replace("-", "_") != name:
            kwargs["dest"] = name
    group.add_argument(*flags, **kwargs)


def add_options(group, command: str, *names: str) -> None:
    """:func:`add_option` for each of ``names``, in order."""
    for name in names:
        add_option(group, name, command)
