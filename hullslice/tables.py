"""Reading the CSV tables a run takes (kinematics, mass distribution, curve tables), one way.

A table is text with a header line naming the columns, then one line of numbers per row;
blank lines and lines starting with ``#`` are skipped, and messages give a row's line
number in the file (comments counted). Text is UTF-8, with or without a byte-order mark;
UTF-16 with its byte-order mark (a spreadsheet's "Unicode text") is read too. Anything else
(Latin-1, binary data) is refused with a message that says how to save the file, and no
message quotes content of a file that does not look like a table: a path set to a system
file gets "its first line is not a header of column names", not that line.
"""

from __future__ import annotations

import csv
import math
import os
import re
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from .errors import CaseError
from .paths import printable

__all__ = ["MAX_TABLE_BYTES", "column_values", "header_text", "read_csv"]

#: Largest table read, in bytes (a million rows of kinematics is about 60 MB).
MAX_TABLE_BYTES = 256 * 1024**2

_NAME = re.compile(r"^[a-z_][a-z0-9_ ]{0,63}$")


def _decode(data: bytes, what: str, name: str) -> str:
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        try:
            return data.decode("utf-16")
        except UnicodeDecodeError:
            raise CaseError(f"{what} file {name!r} is not valid UTF-16 text") from None
    try:
        return data.decode("utf-8-sig")  # a spreadsheet's CSV may start with a byte-order mark
    except UnicodeDecodeError as exc:
        raise CaseError(
            f"{what} file {name!r} is not UTF-8 text (byte {exc.start}): save it as CSV UTF-8"
        ) from None


def read_csv(
    path: str | os.PathLike, what: str, max_rows: int | None = None, why: str = ""
) -> tuple[list[str], list[tuple[int, list[str]]]]:
    """The header (names stripped, lower case) and the rows (with their line numbers).

    Parameters
    ----------
    path : path
        The CSV file.
    what : str
        What the table is, for messages (``"kinematics"``).
    max_rows : int, optional
        Most rows the table may have (counted before any row is parsed); ``why`` says why,
        for the message.

    Raises
    ------
    CaseError
        The file is missing, not a file, larger than :data:`MAX_TABLE_BYTES`, not text in
        one of the encodings above, holds binary data, has more than ``max_rows`` rows, has
        no header line, or its header
        names a column twice (which of the two is meant cannot be known).
    """
    p = Path(path)
    name = printable(p)
    if not p.exists():
        raise CaseError(f"{what} file {name!r} does not exist")
    if not p.is_file():
        raise CaseError(f"{what} path {name!r} is not a file: give a CSV file")
    try:
        if p.stat().st_size > MAX_TABLE_BYTES:
            raise CaseError(
                f"{what} file {name!r} is larger than {MAX_TABLE_BYTES // 1024**2} MiB: "
                "not a table hullslice reads"
            )
        data = p.read_bytes()
    except OSError as exc:
        raise CaseError(f"{what} file {name!r} cannot be read: {exc.strerror or exc}") from None
    text = _decode(data, what, name)
    if "\0" in text:
        raise CaseError(f"{what} file {name!r} holds binary data: give a CSV text file")
    if max_rows is not None and text.count("\n") > max_rows:
        rows = sum(1 for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#"))
        if rows - 1 > max_rows:
            raise CaseError(
                f"{what} file {name!r} has {rows - 1} rows, more than the {max_rows} hullslice "
                f"allows{why}: give every k-th row"
            )
    numbered = [
        (i, row)
        for i, line in enumerate(text.splitlines(), start=1)
        if line.strip() and not line.lstrip().startswith("#")
        for row in csv.reader([line])
    ]
    if not numbered:
        raise CaseError(f"{what} file {name!r} is empty")
    header = [h.strip().lower() for h in numbered[0][1]]
    repeated = next((h for i, h in enumerate(header) if h and h in header[:i]), None)
    if repeated is not None and _NAME.match(repeated):
        raise CaseError(
            f"{what} file {name!r} repeats the column {repeated!r} ({header_text(header)}): "
            "give each column once"
        )
    return header, numbered[1:]


def header_text(header: Sequence[str]) -> str:
    """``its header: a, b, c`` when the first line is column names, else a description that
    quotes none of it (the file may be anything)."""
    if header and all(_NAME.match(h) for h in header) and len(header) <= 64:
        return f"its header: {', '.join(header)}"
    return "its first line is not a header of column names"


def column_values(
    rows: Sequence[tuple[int, Sequence[str]]],
    idx: Sequence[int],
    names: Sequence[str],
    where: str,
) -> np.ndarray:
    """The numbers of columns ``idx`` of each row, ``(rows, len(idx))`` float.

    Raises
    ------
    CaseError
        A row lacks a column, or a value is not a finite number; the message gives the
        line number in the file and the column.
    """
    out = np.empty((len(rows), len(idx)))
    for r, (lineno, row) in enumerate(rows):
        for c, (i, col) in enumerate(zip(idx, names, strict=True)):
            if i >= len(row):
                raise CaseError(
                    f"{where} line {lineno} has {len(row)} values: it lacks the column {col}"
                )
            try:
                value = float(row[i])
            except ValueError:
                raise CaseError(
                    f"{where} line {lineno}: {printable(row[i].strip())[:40]!r} in the column "
                    f"{col} is not a number"
                ) from None
            if not math.isfinite(value):
                raise CaseError(
                    f"{where} line {lineno}: {printable(row[i].strip())[:40]!r} in the column "
                    f"{col} is not a finite number"
                )
            out[r, c] = value
    return out
