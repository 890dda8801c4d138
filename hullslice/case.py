"""Case files: a study's inputs in a TOML file, checked against a declared schema.

A case file holds what a command line would give, so that a study can be repeated exactly::

    # paper.toml: the paper's prism at t = 0.01 s
    mesh = "paper_prism.stl"      # STL or OBJ, relative to this file
    mass = 1.0                    # kg
    draft = 0.0383                # m
    velocity = -3.4943            # m/s, negative down
    slices = [16, 32, 64]

:func:`load_case` reads one with ``tomllib`` (nothing in it is executed) and
:func:`validate_case` checks every key against :data:`SCHEMA`: an unknown key, a value of
the wrong type (a quoted number, a boolean for a number, a fractional slice count) or out
of range (a negative mass, NaN) raises a :class:`~hullslice.errors.CaseError` that names
the key, the expected type and unit, and the offending value. The keys are the rows of the
option table, :data:`hullslice.options.OPTIONS`, which the command line and
:class:`~hullslice.study.Study` are built from too. Keys are flat except
``solver_options``, a table passed to the solver as it is. Values are in the command
line's units: SI, angles in degrees (``pitch``, ``pitch_rate``).
"""

from __future__ import annotations

import difflib
import math
import os
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from .errors import CaseError
from .limits import MAX_CASE_BYTES
from .options import COMMANDS, OPTIONS, Option
from .paths import WRITTEN_KEYS, confined, printable, toml_string, toml_value
from .safety import non_finite

__all__ = [
    "COMMAND_KEYS",
    "MAX_CASE_BYTES",
    "SCHEMA",
    "Key",
    "case_command",
    "load_case",
    "validate_case",
    "write_case",
]


#: One key of a case file: a row of the option table (:class:`hullslice.options.Option`).
Key = Option

#: The keys a case file may hold, by name: every row of :data:`hullslice.options.OPTIONS`.
SCHEMA: dict[str, Key] = {o.name: o for o in OPTIONS}

_KIND_WORDS = {
    "text": "text in quotes",
    "path": "a file path in quotes",
    "number": "a number",
    "count": "a whole number",
    "counts": "a whole number or a list of whole numbers",
    "times": "a number or a list of numbers",
    "pair": "a list of two numbers",
    "box": "a list of six numbers",
    "flag": "true or false",
    "table": "a table",
}


def _describe(value: Any) -> str:
    kinds = {bool: "the boolean", str: "the text", int: "the integer", float: "the number"}
    for t, word in kinds.items():
        if type(value) is t:
            return f"{word} {value!r}"
    if isinstance(value, list):
        return f"the list {value!r}"
    if isinstance(value, dict):
        return "a table"
    return f"{type(value).__name__} {value!r}"


def _convert(key: Key, value: Any, where: str) -> Any:
    """The value of one key in its Python type, or a CaseError naming what is wrong."""
    kind = key.kind
    hint = ""
    if kind in ("text", "path"):
        ok = isinstance(value, str)
        hint = " (put text in quotes)"
    elif kind == "flag":
        ok = isinstance(value, bool)
        hint = " (write true or false without quotes)"
    elif kind == "table":
        ok = isinstance(value, dict)
    elif kind == "number":
        ok = isinstance(value, int | float) and not isinstance(value, bool)
        if isinstance(value, str):
            hint = " (write the number without quotes)"
        elif ok and not math.isfinite(value):
            ok, hint = False, " (a finite number is needed)"
    elif kind == "pair":
        ok = (
            isinstance(value, list)
            and len(value) == 2
            and all(isinstance(i, int | float) and not isinstance(i, bool) for i in value)
            and all(math.isfinite(i) for i in value)
        )
        hint = " (write e.g. [12.5, 0.3])"
    elif kind == "times":
        items = value if isinstance(value, list) else [value]
        real = [i for i in items if isinstance(i, int | float) and not isinstance(i, bool)]
        ok = bool(items) and len(real) == len(items) and all(map(math.isfinite, real))
        hint = " (write e.g. [0.01, 0.02])"
    elif kind == "box":
        ok = (
            isinstance(value, list)
            and len(value) == 6
            and all(isinstance(i, int | float) and not isinstance(i, bool) for i in value)
            and all(math.isfinite(i) for i in value)
        )
        hint = " (write e.g. [-1.0, 40.0, -2.5, 2.5, -1.0, 5.0])"
    else:  # count or counts
        items = value if kind == "counts" and isinstance(value, list) else [value]
        ok = bool(items) and all(isinstance(i, int) and not isinstance(i, bool) for i in items)
        hint = ' (write e.g. 32, not 32.0 or "32")' if items else " (give at least one count)"
    if not ok:
        unit = f" in {key.unit}" if key.unit else ""
        raise CaseError(
            f"{where}key {key.name!r} must be {_KIND_WORDS[kind]}{unit} ({key.help}), "
            f"not {_describe(value)}{hint}"
        )
    if kind == "number":
        return float(value)
    if kind == "pair":
        return (float(value[0]), float(value[1]))
    if kind == "box":
        return [float(i) for i in value]
    if kind == "table":
        return dict(value)
    if kind == "times":
        return [float(i) for i in items]
    if kind == "count":
        return int(value)
    if kind == "counts":
        return [int(i) for i in items]
    return value


def validate_case(
    case: Mapping[str, Any], *, base: str | os.PathLike | None = None, source: str = ""
) -> dict[str, Any]:
    """Check a case mapping (as ``tomllib`` gives it) against :data:`SCHEMA`.

    Parameters
    ----------
    case : mapping
        Key to value, as read from a case file.
    base : path, optional
        Folder that relative ``path`` keys (``mesh``, ``kinematics``) are resolved against
        (the case file's folder); without it they are kept as written.
    source : str
        Name of the case file, for messages.

    Returns
    -------
    dict
        Every key of the case converted to its type (numbers as float, counts as int,
        ``slices`` as a list of int, paths as :class:`~pathlib.Path`), and the defaults
        of :data:`SCHEMA` for the keys that have one and are absent.

    Raises
    ------
    CaseError
        An unknown key, no ``mesh`` (the only key every case needs), a value of the wrong
        type or out of range, a time step longer than the run, or ``forward`` and ``up``
        along one axis; the message names the key, what it must be and the value found.
    """
    where = f"case file {source!r}: " if source else "case: "
    if not isinstance(case, Mapping):
        raise CaseError(f"{where}a case is a table of keys, not {_describe(case)}")
    if "sweep" in case:
        raise CaseError(
            f"{where}it has a [sweep] table: it is a sweep of many cases; run it with "
            "'hullslice sweep CASE.toml' (or hullslice.sweep in Python)"
        )
    unknown = [k for k in case if k not in SCHEMA]
    if unknown:
        k = unknown[0]
        close = difflib.get_close_matches(str(k), list(SCHEMA), n=1)
        hint = f"did you mean {close[0]!r}? " if close else ""
        raise CaseError(f"{where}unknown key {k!r}; {hint}the keys are {', '.join(SCHEMA)}")
    out: dict[str, Any] = {}
    for name, key in SCHEMA.items():
        if name not in case:
            if key.default is not None:
                out[name] = key.default
            continue
        value = _convert(key, case[name], where)
        if key.check is not None:
            why = key.check(value)
            if why:
                unit = f" {key.unit}" if key.unit else ""
                raise CaseError(f"{where}key {name!r} ({key.help}) {why}: {value!r}{unit}")
        if key.kind == "path" and name in WRITTEN_KEYS and base is not None:
            value = confined(value, Path(base), name, where)  # a case writes in its folder
        elif key.kind == "path":
            value = Path(os.path.normpath(Path(base, value))) if base is not None else Path(value)
        if name == "solver_options":
            for k, v in value.items():
                if non_finite(v) is not None:  # NaN passes no comparison: a check switched off
                    raise CaseError(
                        f"{where}key 'solver_options': {k} = {non_finite(v)!r} is not a finite "
                        "number; give a finite value"
                    )
        if name == "solver_options" and base is not None:
            # a solver's file (a curve table) is named relative to the case, like the mesh
            value = {
                k: (
                    os.path.normpath(Path(base, v))
                    if isinstance(v, str) and Path(base, v).is_file()
                    else v
                )
                for k, v in value.items()
            }
        elif key.kind == "text" and key.check is not None:
            value = value.strip().lower()
        out[name] = value
    if "mesh" not in out:
        raise CaseError(f"{where}key 'mesh' is missing: name the hull, e.g. mesh = \"hull.stl\"")
    if "dt" in out and "t_end" in out and out["dt"] > out["t_end"]:
        raise CaseError(
            f"{where}key 'dt' ({out['dt']:g} s) is longer than the run, 't_end' "
            f"({out['t_end']:g} s): shorten it"
        )
    forward, up = out.get("forward", "+x"), out.get("up", "+z")
    if forward.lstrip("+-") == up.lstrip("+-"):
        raise CaseError(
            f"{where}keys 'forward' ({forward!r}) and 'up' ({up!r}) are the same "
            "axis: choose two different mesh axes"
        )
    return out


def load_case(path: str | os.PathLike) -> dict[str, Any]:
    """Read and check a case file (TOML).

    Parameters
    ----------
    path : path
        The case file; ``mesh`` and ``kinematics`` in it are relative to its folder.

    Returns
    -------
    dict
        The checked case, see :func:`validate_case`.

    Raises
    ------
    CaseError
        The file cannot be read as TOML (:func:`read_case_file`), or its content fails
        :func:`validate_case`.
    """
    data, p, name = read_case_file(path)
    return validate_case(data, base=p.parent, source=name)


def read_case_file(path: str | os.PathLike) -> tuple[dict[str, Any], Path, str]:
    """The TOML of a case file, unchecked: ``(data, path, printable name)``.

    Raises
    ------
    CaseError
        The file is missing, not a file, larger than :data:`MAX_CASE_BYTES`, not UTF-8
        (a byte-order mark is allowed), cannot be read, or is not valid TOML (the message
        gives the line).
    """
    p = Path(path)
    name = printable(p)
    if not p.exists():
        raise CaseError(f"case file {name!r} does not exist")
    if not p.is_file():
        raise CaseError(f"case path {name!r} is not a file: give a TOML case file")
    if p.stat().st_size > MAX_CASE_BYTES:
        raise CaseError(
            f"case file {name!r} is larger than {MAX_CASE_BYTES // 1024} KiB: a case file is a "
            "few lines of TOML"
        )
    try:
        text = p.read_bytes().decode("utf-8-sig")  # an editor may write a byte-order mark
    except UnicodeDecodeError as exc:
        raise CaseError(f"case file {name!r} is not UTF-8 text (byte {exc.start})") from None
    except OSError as exc:
        raise CaseError(f"case file {name!r} cannot be read: {exc.strerror or exc}") from None
    try:
        return tomllib.loads(text), p, name
    except tomllib.TOMLDecodeError as exc:
        raise CaseError(f"case file {name!r} is not valid TOML: {exc}") from None
    except RecursionError:
        raise CaseError(
            f"case file {name!r} nests tables or lists too deeply to be a case: a case is "
            "flat keys and one [solver_options] table"
        ) from None


#: The keys that each command takes: the rows of :data:`~hullslice.options.OPTIONS` that
#: name it (``title``, ``command`` and the mesh's keys are every command's).
COMMAND_KEYS: dict[str, set[str]] = {
    command: {o.name for o in OPTIONS if command in o.commands} for command in COMMANDS
}


def case_command(case: Mapping[str, Any]) -> str:
    """The command a checked case runs: its ``command``, or the one its keys imply."""
    if "command" in case:
        return str(case["command"])
    if "kinematics" in case or "t_end" in case:
        return "simulate"
    if "velocity" in case:
        return "force"
    if "draft" in case:
        return "sections"
    return "info"


def write_case(case: Mapping[str, Any], path: str | os.PathLike) -> Path:
    """Write a case to a TOML file, completely or not at all.

    Paths are written relative to the file's folder, so that the case can be moved with its
    files; ``solver_options`` becomes a table at the end. An ``output`` or ``plot`` outside
    the folder is left out (a comment says so): a case file writes only inside its folder.
    """
    from .atomic import write_atomic

    target = Path(path)
    folder = target.resolve().parent
    lines = ["# hullslice case file: run it with 'hullslice run " + printable(target.name) + "'"]
    table = None
    for name, value in case.items():
        if name not in SCHEMA:
            raise CaseError(f"case: unknown key {name!r}")
        if name == "solver_options":
            table = value
            continue
        if isinstance(value, Path):
            value = Path(os.path.relpath(value.resolve(), folder)).as_posix()
            if name in WRITTEN_KEYS and (value == ".." or value.startswith("../")):
                lines.append(
                    f"# {name} left out: it is outside this folder (give it on the command line)"
                )
                continue
        key = SCHEMA[name]
        unit = f" [{key.unit}]" if key.unit else ""
        lines.append(f"{name} = {toml_value(value)}  # {key.help}{unit}")
    if table:
        lines.append("")
        lines.append("[solver_options]")
        lines += [f"{toml_string(k)} = {toml_value(v)}" for k, v in table.items()]
    validate_case(tomllib.loads("\n".join(lines)))  # what is written reads back
    return write_atomic(target, "\n".join(lines) + "\n")
