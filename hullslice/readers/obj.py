"""Wavefront OBJ: the vertices and faces of a text mesh file.

Only the ``v`` and ``f`` statements are read: nothing else in the file is opened (an
``mtllib``'s materials and textures are ignored) and every face forms the one body.
"""

from __future__ import annotations

from array import array
from typing import IO

import numpy as np

from .base import FormatError

__all__ = ["read_obj"]

#: Longest OBJ statement read, in bytes (with its continuation lines): a vertex or a face
#: of a few thousand corners is far shorter; a longer one is not geometry, and reading it
#: whole would cost memory out of proportion.
_MAX_OBJ_LINE = 1024**2

#: Largest vertex index an OBJ face may hold (more vertices than any file can hold).
_MAX_INDEX = 2**40


def read_obj(fh: IO[bytes], size: int) -> tuple[np.ndarray, np.ndarray]:
    """Wavefront OBJ: the ``v`` and ``f`` statements; everything else is ignored.

    Polygons are split into fans of triangles; indices count from 1, negative ones back
    from the last vertex read so far (the OBJ rules). ``mtllib``, ``usemtl``, normals,
    texture coordinates, groups and objects are skipped: all faces form the one body. The
    file is read line by line into typed arrays (24 bytes a vertex or a triangle, less
    than their text).
    """
    verts = array("d")
    tris = array("q")
    tri_lines = array("q")
    pending: list[str] = []  # the pieces of a statement continued over several lines
    pending_bytes = 0
    lines = iter(lambda: fh.readline(_MAX_OBJ_LINE + 1), b"")
    for lineno, raw in enumerate(lines, start=1):
        if b"\0" in raw:
            raise FormatError(f"line {lineno} holds binary data; an OBJ is a text file")
        pending_bytes += len(raw)
        if pending_bytes > _MAX_OBJ_LINE:
            raise FormatError(
                f"line {lineno}: a statement longer than {_MAX_OBJ_LINE // 1024**2} MiB (with "
                "its continuation lines); an OBJ statement is a vertex or a face"
            )
        if lineno == 1 and raw.startswith(b"\xef\xbb\xbf"):  # a UTF-8 byte-order mark
            raw = raw[3:]
        line = raw.decode("utf-8", errors="replace").rstrip("\r\n")
        if line.endswith("\\"):  # continued on the next line
            pending.append(line[:-1])
            continue
        if pending:
            line = " ".join([*pending, line])  # joined once: linear in the statement's length
            pending.clear()
        pending_bytes = 0
        parts = line.split("#", 1)[0].split()
        if not parts:
            continue
        key = parts[0]
        if key == "v":
            try:
                verts.extend([float(t) for t in parts[1:4]] if len(parts) >= 4 else ())
            except ValueError:
                raise FormatError(
                    f"line {lineno}: {line.strip()[:60]!r} is not a vertex 'v x y z'"
                ) from None
            if len(parts) < 4:
                raise FormatError(f"line {lineno}: {line.strip()[:60]!r} is not a vertex 'v x y z'")
        elif key == "f":
            if len(parts) < 4:
                raise FormatError(
                    f"line {lineno}: {line.strip()[:60]!r} has fewer than three corners"
                )
            idx = []
            n_verts = len(verts) // 3
            for token in parts[1:]:
                try:
                    i = int(token.split("/", 1)[0])
                except ValueError:
                    raise FormatError(
                        f"line {lineno}: face corner {token[:30]!r} is not a vertex index"
                    ) from None
                if i == 0 or abs(i) > _MAX_INDEX:
                    raise FormatError(
                        f"line {lineno}: face index {i} does not exist (OBJ counts vertices "
                        "from 1); the file is corrupt"
                    )
                idx.append(i - 1 if i > 0 else n_verts + i)
            for k in range(1, len(idx) - 1):
                tris.extend((idx[0], idx[k], idx[k + 1]))
                tri_lines.append(lineno)
    v = np.frombuffer(verts, dtype=np.float64).reshape(-1, 3)
    f = np.frombuffer(tris, dtype=np.int64).reshape(-1, 3)
    bad = (f < 0) | (f >= len(v))
    if bad.any():
        k = int(np.flatnonzero(bad.any(axis=1))[0])
        raise FormatError(
            f"line {tri_lines[k]}: a face refers to a vertex that does not exist (the file "
            f"has {len(v)} vertices); the file is corrupt"
        )
    return v.copy(), f.copy()
