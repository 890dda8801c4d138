"""Where a run may write, what it must not overwrite, and how names from inputs are written.

Three rules keep a run's files safe from its inputs:

- **A case file writes only inside its own folder.** Its ``output`` and ``plot`` are
  resolved against the case's folder (symbolic links followed) and refused when they
  leave it (``../x``, an absolute path, a link to elsewhere): a case file received from
  someone else cannot write beside or above it. A path given on the command line
  (``-o``, ``--plot``) is the user's own choice and may go anywhere.
- **No output replaces an input.** Every file a run reads (the mesh, the case file, the
  kinematics and mass-distribution tables, a solver option that names a file) is compared
  with every path it writes, by identity on disk (a link or another spelling of the same
  file is the same file): see :func:`run_inputs` and :func:`check_not_an_input`.
- **Names from inputs are written escaped.** A file name or a title may hold line breaks,
  terminal escapes or markup; :func:`printable` makes it one line of visible characters,
  :func:`markdown_text` also escapes Markdown's markup, and :func:`toml_string` writes a
  TOML string that reads back as the same text.
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from .errors import CaseError, InputError

__all__ = [
    "check_not_an_input",
    "confined",
    "markdown_text",
    "printable",
    "run_inputs",
    "toml_string",
    "toml_value",
]

#: Keys of a case file naming files that a run writes (confined to the case's folder).
WRITTEN_KEYS = ("output", "plot")

#: Attributes of a parsed command line naming files that a run reads.
INPUT_ARGS = (
    ("mesh", "mesh"),
    ("case", "case"),
    ("kinematics", "kinematics"),
    ("mass_distribution", "mass distribution"),
)


def printable(text: object) -> str:
    """``text`` as one line of visible characters: every character Python does not print
    (line breaks, tabs, terminal escapes, bidirectional overrides, undecodable bytes) is
    written as its escape (``\\n``, ``\\x1b``, ``\\u202e``, ``\\udcff``), and a backslash as
    two, so that the result reads back unambiguously."""
    s = str(text)
    if s.isprintable() and "\\" not in s:
        return s
    out = []
    for ch in s:
        if ch == "\\":
            out.append("\\\\")
        elif ch.isprintable():
            out.append(ch)
        else:
            out.append(repr(ch)[1:-1] if ch not in "'\"" else ch)
    return "".join(out)


_MARKDOWN = re.compile(r"([\\`*_{}\[\]<>|&!#~])")


def markdown_text(text: object) -> str:
    """``text`` as one line of Markdown that shows it as written: :func:`printable`, and
    Markdown's markup characters (``* _ [ ] < > | & ! # ~`` and the backtick) escaped with a
    backslash, so that a title or a file name cannot end a table row, open a link or
    insert HTML."""
    return _MARKDOWN.sub(r"\\\1", printable(text).replace("\\\\", "\\"))


def markdown_fence(content: str) -> str:
    """A code fence longer than any run of backticks in ``content`` (so it cannot end early)."""
    longest = max((len(m) for m in re.findall(r"`+", content)), default=0)
    return "`" * max(3, longest + 1)


def toml_string(text: object, what: str = "a value") -> str:
    """A TOML basic string that reads back as ``text``.

    Quotes, backslashes and control characters (DEL included) are escaped; other characters
    are written as they are (TOML files are UTF-8).

    Raises
    ------
    CaseError
        ``text`` holds a lone surrogate (a file name with bytes that are not UTF-8), which
        no TOML file can hold.
    """
    s = str(text)
    out = ['"']
    for ch in s:
        code = ord(ch)
        if ch == '"':
            out.append('\\"')
        elif ch == "\\":
            out.append("\\\\")
        elif code < 0x20 or code == 0x7F:
            out.append(f"\\u{code:04X}")
        elif 0xD800 <= code <= 0xDFFF:
            raise CaseError(
                f"{what} {printable(s)!r} holds bytes that are not UTF-8 text and cannot be "
                "written to a case file: rename the file"
            )
        else:
            out.append(ch)
    out.append('"')
    return "".join(out)


def toml_value(value: Any) -> str:
    """A value as TOML text: a boolean, an integer, a finite float (always with a point or
    an exponent), a string or path (:func:`toml_string`), or a list of them.

    Raises
    ------
    CaseError
        A non-finite number, or a value of another type.
    """
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise CaseError(f"case: {value!r} cannot be written to a case file")
        text = repr(value)
        return text if any(c in text for c in ".en") else text + ".0"
    if isinstance(value, str | Path):
        return toml_string(value)
    if isinstance(value, list | tuple):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise CaseError(f"case: a value of type {type(value).__name__} cannot be written")


def confined(value: str, folder: Path, key: str, where: str) -> Path:
    """The path ``value`` of a case key that a run writes, resolved inside ``folder``.

    Parameters
    ----------
    value : str
        The path as written in the case file.
    folder : Path
        The case file's folder.
    key : str
        The key, for messages.
    where : str
        The message's prefix naming the case file.

    Raises
    ------
    CaseError
        The path is absolute, or leads out of the folder (``..``, a symbolic link).
    """
    shown = printable(value)
    if os.path.isabs(value) or Path(value).drive:
        raise CaseError(
            f"{where}key {key!r} ({shown!r}) is an absolute path: a case file writes only "
            "inside its own folder; give a path relative to it, or -o/--plot on the command "
            "line"
        )
    path = Path(os.path.normpath(Path(folder, value)))
    home = Path(os.path.realpath(folder))
    real = Path(os.path.realpath(path))
    if real != home and home not in real.parents:
        raise CaseError(
            f"{where}key {key!r} ({shown!r}) leads out of the case's folder: a case file writes "
            "only inside its own folder; give a path inside it, or -o/--plot on the command line"
        )
    return path


def _files_in(value: Any) -> Iterable[str]:
    """The strings in a solver option's value (a text, or a list of them)."""
    if isinstance(value, str | os.PathLike):
        yield os.fspath(value)
    elif isinstance(value, list | tuple):
        for v in value:
            yield from _files_in(v)


def run_inputs(args: Any) -> list[tuple[str, Path]]:
    """The files a parsed command line reads, as ``(what, path)``: the mesh, the case file,
    the kinematics and mass-distribution tables, and each solver option that names an
    existing file (a curve table)."""
    found: list[tuple[str, Path]] = []
    for attr, what in INPUT_ARGS:
        value = getattr(args, attr, None)
        if value:
            found.append((what, Path(value)))
    for key, value in getattr(args, "solver_option", None) or ():
        for text in _files_in(value):
            if text and Path(text).is_file():
                found.append((f"solver option {key}", Path(text)))
    return found


def check_not_an_input(out: str | os.PathLike, inputs: Iterable[tuple[str, Path]], option: str):
    """Refuse an output path that is one of the run's input files (by identity on disk).

    Raises
    ------
    InputError
        Naming the option, the path and which input it is.
    """
    target = Path(out)
    if not target.exists():
        return
    for what, source in inputs:
        try:
            same = source.exists() and target.samefile(source)
        except OSError:
            same = False
        if same:
            raise InputError(
                f"cannot write {printable(out)!r} ({option}): it is the input {what} file and "
                "would be overwritten; give another file"
            )
