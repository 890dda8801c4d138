"""Cart3D ``.tri`` (as OpenVSP exports it): the vertices and triangles of a text mesh file.

The ASCII format is a header ``nVerts nTris``, then ``nVerts`` vertices ``x y z``, then
``nTris`` triangles ``i j k`` (vertex numbers counted from 1), then optionally ``nTris``
component numbers (read and ignored: every triangle forms the one body). Values are
separated by blanks and line ends, one vertex or triangle a line as OpenVSP writes them,
but any layout is read. Nothing may follow the component numbers.

The header's counts are checked against the file's size before anything is allocated, so
that memory stays in proportion to the file; a malformed value is refused with its line.
"""

from __future__ import annotations

import math
from typing import IO

import numpy as np

from .base import FormatError

__all__ = ["read_tri"]

#: Longest line read, in bytes: a vertex or a triangle is far shorter.
_MAX_TRI_LINE = 64 * 1024

#: Fewest bytes a vertex or a triangle takes in the file (``0 0 0`` and a line end).
_MIN_RECORD_BYTES = 6


def read_tri(fh: IO[bytes], size: int) -> tuple[np.ndarray, np.ndarray]:
    """Cart3D ASCII ``.tri``: header ``nVerts nTris``, vertices, triangles (numbered from
    1), optional component numbers; a value that is malformed, not finite or out of range
    is refused with its line number."""
    lines = _numbered_lines(fh)
    lineno, first = _first_values(lines)
    # the header is the first two values; a third on their line alone is not (a .triq's)
    nv, nt = _header(first if len(first) <= 3 else first[:2], lineno, size)
    rest = first[2:] if len(first) > 3 else []
    coords = np.empty(3 * nv, dtype=np.float64)
    tris = np.empty(3 * nt, dtype=np.int64)
    sections = (
        ("vertex coordinates", coords, 3 * nv, _coordinate),
        ("vertex numbers of the triangles", tris, 3 * nt, _vertex_number(nv)),
    )
    for what, out, n, parse in sections:
        k = 0
        while k < n:
            if not rest:
                nxt = next(lines, None)
                if nxt is None:
                    raise FormatError(
                        f"the file ends after {k} of the {n} {what} its header claims (line "
                        f"1: {nv} vertices, {nt} triangles); a truncated file?"
                    )
                lineno, rest = nxt
                continue
            take, rest = rest[: n - k], rest[n - k :]
            out[k : k + len(take)] = [parse(t, lineno) for t in take]
            k += len(take)
    _component_numbers(lines, rest, lineno, nt)
    return coords.reshape(-1, 3), tris.reshape(-1, 3) - 1


def _numbered_lines(fh: IO[bytes]):
    """``(line number, values)`` of each line with values."""
    for lineno, raw in enumerate(iter(lambda: fh.readline(_MAX_TRI_LINE + 1), b""), start=1):
        if len(raw) > _MAX_TRI_LINE:
            raise FormatError(
                f"line {lineno} is longer than {_MAX_TRI_LINE // 1024} KiB; a Cart3D .tri holds "
                "one vertex or triangle a line"
            )
        if b"\0" in raw:
            raise FormatError(
                f"line {lineno} holds binary data: export the ASCII (text) Cart3D .tri, not the "
                "binary one"
            )
        values = raw.split()
        if values:
            yield lineno, values


def _first_values(lines) -> tuple[int, list[bytes]]:
    first = next(lines, None)
    if first is None:
        raise FormatError("it holds no values; a Cart3D .tri starts with 'nVerts nTris'")
    return first


def _header(values: list[bytes], lineno: int, size: int) -> tuple[int, int]:
    text = _shown(b" ".join(values))
    if len(values) != 2:
        raise FormatError(
            f"line {lineno}: {text!r} is not the header 'nVerts nTris' (two whole numbers)"
        )
    try:
        nv, nt = int(values[0]), int(values[1])
    except ValueError:
        raise FormatError(
            f"line {lineno}: {text!r} is not the header 'nVerts nTris' (two whole numbers)"
        ) from None
    if nv < 0 or nt < 0:
        raise FormatError(f"line {lineno}: the header {text!r} gives a negative count")
    if _MIN_RECORD_BYTES * (nv + nt) > size:
        raise FormatError(
            f"line {lineno}: the header claims {nv} vertices and {nt} triangles, more than a "
            f"file of {size} bytes holds (a truncated file, or another format)"
        )
    return nv, nt


def _coordinate(token: bytes, lineno: int) -> float:
    try:
        x = float(token)
    except ValueError:
        raise FormatError(
            f"line {lineno}: vertex coordinate {_shown(token)!r} is not a number"
        ) from None
    if not math.isfinite(x):
        raise FormatError(
            f"line {lineno}: vertex coordinate {_shown(token)!r} is not finite; fix the export"
        )
    return x


def _vertex_number(nv: int):
    def parse(token: bytes, lineno: int) -> int:
        try:
            i = int(token)
        except ValueError:
            raise FormatError(
                f"line {lineno}: triangle corner {_shown(token)!r} is not a vertex number"
            ) from None
        if not 1 <= i <= nv:
            raise FormatError(
                f"line {lineno}: vertex number {i} does not exist (the file has {nv} vertices, "
                "numbered from 1); the file is corrupt"
            )
        return i

    return parse


def _component_numbers(lines, rest: list[bytes], lineno: int, nt: int) -> None:
    """Read the optional component numbers (whole numbers, one a triangle) and refuse
    anything after them."""
    k = 0
    while True:
        for token in rest:
            if k == nt:
                raise FormatError(
                    f"line {lineno}: {_shown(token)!r} follows the {nt} triangles' component "
                    "numbers; a Cart3D .tri ends there"
                )
            try:
                int(token)
            except ValueError:
                raise FormatError(
                    f"line {lineno}: component number {_shown(token)!r} is not a whole number"
                ) from None
            k += 1
        nxt = next(lines, None)
        if nxt is None:
            break
        lineno, rest = nxt
    if 0 < k < nt:
        raise FormatError(
            f"the file ends after {k} of the {nt} component numbers (one a triangle); a "
            "truncated file?"
        )


def _shown(token: bytes) -> str:
    return token.decode("utf-8", errors="replace")[:40]
