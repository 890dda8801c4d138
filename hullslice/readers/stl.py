"""STL, binary and ASCII: the triangles of a stereolithography file.

A binary STL is an 80-byte header, a little-endian uint32 triangle count, then 50 bytes per
triangle (normal, three corners as float32, a 2-byte attribute); its size must be exactly
``84 + 50 n`` bytes. Otherwise a file that starts with ``solid`` is read as ASCII, in
chunks so that memory stays bounded. A binary file's vertices are returned as float32, the
precision it stores (the hull's checks refuse a body too far from the origin for it). Every
triangle has its own three vertices (a triangle
soup): the hull's checks merge the copies.
"""

from __future__ import annotations

import re
from array import array
from typing import IO

import numpy as np

from .base import FormatError

__all__ = ["read_stl"]

#: Binary STL: an 80-byte header, a little-endian uint32 triangle count, then 50 bytes per
#: triangle (normal, three corners as float32, a 2-byte attribute).
_STL_HEAD = 84
_STL_RECORD = np.dtype([("normal", "<f4", (3,)), ("corners", "<f4", (3, 3)), ("attr", "<u2")])

_STL_VERTEX = re.compile(rb"\bvertex\s+(\S+)\s+(\S+)\s+(\S+)")


def read_stl(fh: IO[bytes], size: int) -> tuple[np.ndarray, np.ndarray]:
    """Binary or ASCII STL: a binary file's size must be exactly 84 + 50 n bytes."""
    head = fh.read(_STL_HEAD)
    claimed = int.from_bytes(head[80:84], "little") if len(head) == _STL_HEAD else None
    if claimed is not None and size == _STL_HEAD + _STL_RECORD.itemsize * claimed:
        data = np.frombuffer(fh.read(), dtype=_STL_RECORD, count=claimed)
        v = data["corners"].reshape(-1, 3).astype(np.float32)  # as stored: a copy, native order
        return v, np.arange(len(v), dtype=np.int64).reshape(-1, 3)
    binary = (
        f"as a binary STL its header claims {claimed} triangles "
        f"({_STL_HEAD + _STL_RECORD.itemsize * claimed} bytes) but the file has {size} bytes"
        if claimed is not None
        else f"at {size} bytes it is shorter than a binary STL's 84-byte header"
    )
    if not head.lstrip()[:5].lower() == b"solid":
        raise FormatError(
            f"{binary}, and it does not start with 'solid' as an ASCII STL does "
            "(a truncated file, or another format)"
        )
    return _parse_ascii_stl(fh, head, binary)


#: Bytes of an ASCII STL parsed at a time (cut at a line end): memory stays bounded.
_STL_CHUNK = 16 * 1024**2


def _parse_ascii_stl(fh: IO[bytes], head: bytes, binary: str) -> tuple[np.ndarray, np.ndarray]:
    coords = array("d")
    loops = 0
    rest = head
    while True:
        block = fh.read(_STL_CHUNK)
        data = rest + block
        if block:  # keep the last, perhaps partial, line for the next chunk
            cut = data.rfind(b"\n") + 1
            data, rest = data[:cut], data[cut:]
        if b"\0" in data:
            raise FormatError(
                f"it starts with 'solid' but holds binary data; {binary} (a truncated file?)"
            )
        data = data.lower()
        corners = _STL_VERTEX.findall(data)
        loops += data.count(b"endloop")
        try:
            coords.extend(np.array(corners, dtype=np.float64).ravel())
        except ValueError:
            bad = next(t for c in corners for t in c if not _is_float(t))
            raise FormatError(
                f"vertex coordinate {bad.decode('latin-1')!r} is not a number"
            ) from None
        if not block:
            break
    v = np.frombuffer(coords, dtype=np.float64).reshape(-1, 3).copy()
    if len(v) != 3 * loops:
        raise FormatError(
            f"ASCII STL with {len(v)} vertex lines in {loops} facets: every facet needs "
            "exactly three (a truncated or hand-edited file?)"
        )
    return v, np.arange(len(v), dtype=np.int64).reshape(-1, 3)


def _is_float(token: bytes) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True
