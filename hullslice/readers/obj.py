"""Wavefront OBJ: the vertices and faces of a text mesh file.

Only the ``v`` and ``f`` statements are read: nothing else in the file is opened (an
``mtllib``'s materials and textures are ignored) and every face forms the one body.
"""

from __future__ import annotations

import warnings
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

#: Bytes read at a time by the block reader (:func:`_read_blocks`).
_BLOCK = 1 << 22
_NL = ord("\n")


def _table(chars: bytes) -> np.ndarray:
    """A lookup of the bytes in ``chars``: True for them, by byte value."""
    out = np.zeros(256, dtype=bool)
    out[list(chars)] = True
    return out


#: The blanks ``str.split`` takes in ASCII but a newline (``bytes.split`` takes all but
#: the last four, which make a block go line by line).
_BLANK = _table(b" \t\r\x0b\x0c\x1c\x1d\x1e\x1f")
#: The byte after a statement's key: a space or a tab (a block's lines).
_GAP = _table(b" \t")
#: The bytes after ``v`` or ``f`` that make the line one the line reader must judge.
_ODD_SECOND = _table(b"\n\r\x0b\x0c\x1c\x1d\x1e\x1f#")
_INDEX_HEAD = _table(b"0123456789/")
#: What a block's vertices and faces may hold besides blanks and newlines.
_DECIMAL = _table(b"0123456789+-.eE \t\r\x0b\x0c\n")
_INDEX = _table(b"0123456789 \t\r\x0b\x0c\n")


def read_obj(fh: IO[bytes], size: int) -> tuple[np.ndarray, np.ndarray]:
    """Wavefront OBJ: the ``v`` and ``f`` statements; everything else is ignored.

    Polygons are split into fans of triangles; indices count from 1, negative ones back
    from the last vertex read so far (the OBJ rules). ``mtllib``, ``usemtl``, normals,
    texture coordinates, groups and objects are skipped: all faces form the one body.

    The file is read a block of lines at a time, each block's vertices and faces parsed
    together by numpy (:func:`_read_blocks`: the same numbers, three to four times as
    fast as line by line); a file that block reader does not take as it is (negative indices,
    continued lines, comments after a statement, anything malformed) is read again line by
    line (:func:`_read_lines`), which says what is wrong and on what line.
    """
    start = fh.tell()
    fast = _read_blocks(fh, size)
    if fast is not None:
        return fast
    fh.seek(start)
    return _read_lines(fh)


def _read_blocks(fh: IO[bytes], size: int) -> tuple[np.ndarray, np.ndarray] | None:
    """The vertices and faces of an OBJ of ``size`` bytes read :data:`_BLOCK` bytes at a
    time (whole lines): the numbers of :func:`_read_lines`, or None where a block holds
    what only that reader takes (or rejects, with its message)."""
    verts: list[np.ndarray] = []
    tris: list[np.ndarray] = []
    carry = b""
    n_verts = 0
    first = True
    left = size
    while True:
        # no more asked for than the file holds (a read sets aside what it is asked for)
        block = fh.read(min(_BLOCK, left)) if left > 0 else fh.read(1)
        left -= len(block)
        data = carry + block if carry else block
        if first and data.startswith(b"\xef\xbb\xbf"):  # a UTF-8 byte-order mark
            data = data[3:]
        first = False
        if block:  # whole lines only; the rest with the next block
            cut = data.rfind(b"\n") + 1
            body, carry = data[:cut], data[cut:]
            if len(carry) > _MAX_OBJ_LINE:
                return None
        else:
            body, carry = data, b""
        if body:
            parsed = _parse_block(body)
            if parsed is None:
                return None
            v, t = parsed
            verts.append(v)
            tris.append(t)
            n_verts += len(v)
        if not block:
            break
    v = np.concatenate(verts) if verts else np.empty((0, 3))
    f = np.concatenate(tris) if tris else np.empty((0, 3), dtype=np.int64)
    # indices count from 1, and only positive ones are taken here: from the file's start
    f -= 1
    if len(f) and (f.min() < 0 or f.max() >= n_verts):
        return None  # an index that does not exist: the line reader names its line
    return v, f


def _parse_block(body: bytes) -> tuple[np.ndarray, np.ndarray] | None:
    """A block's vertices ``(n, 3)`` and triangles ``(m, 3)`` (indices from 1), parsed by
    numpy, or None where it holds anything but plain ``v x y z [...]`` lines of decimal
    numbers and ``f i[/...] j k [...]`` lines of positive indices, other statements,
    comment lines and blank ones.

    The numbers are numpy's parse of the same text (correctly rounded, as ``float``'s);
    each token is checked to be one number (their count is the tokens'), so that numpy
    reads no token that ``float`` or ``int`` would not.
    """
    if not body.isascii() or b"\0" in body or b"\\" in body:
        return None  # text to decode, binary data or continued lines: line by line
    a = np.frombuffer(body, dtype=np.uint8)
    n = len(a)
    ends = np.flatnonzero(a == _NL)
    starts = np.concatenate(([0], ends + 1))
    size = np.diff(np.concatenate((starts, [n])))  # each line's bytes with its newline
    if size.max() > _MAX_OBJ_LINE:
        return None
    pad = np.concatenate((a, [_NL, _NL]))
    c0, c1 = pad[starts], pad[starts + 1]
    is_v = (c0 == ord("v")) & _GAP[c1]
    is_f = (c0 == ord("f")) & _GAP[c1]
    # "v" or "f" alone or before a comment or a blank the two above do not take
    if np.any(((c0 == ord("v")) | (c0 == ord("f"))) & _ODD_SECOND[c1]):
        return None
    for k in np.flatnonzero(_BLANK[c0]).tolist():  # an indented line: blank, or no
        if body[starts[k] : starts[k] + size[k]].strip():
            return None
    kind = np.repeat((is_v + 2 * is_f).astype(np.uint8), size)
    if np.any((a == ord("#")) & (kind != 0)):
        return None  # a comment after a statement
    text = a.copy()
    text[starts[is_v | is_f]] = ord(" ")  # the keys, so that the rest is numbers
    verts = _vertices(text[kind == 1], int(is_v.sum()))
    tris = _faces(text[kind == 2], int(is_f.sum()))
    if verts is None or tris is None:
        return None
    return verts, tris


def _token_counts(b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The lines' token counts in ``b`` (lines of tokens, each ending in a newline but
    perhaps the last), and the tokens' lengths."""
    blank = _BLANK[b] | (b == _NL)
    edge = np.diff(np.concatenate(([True], blank, [True])).astype(np.int8))
    first, last = np.flatnonzero(edge == -1), np.flatnonzero(edge == 1)
    line_of = np.searchsorted(np.flatnonzero(b == _NL), first)  # a token's line
    lines = int(np.count_nonzero(b == _NL)) + int(len(b) > 0 and b[-1] != _NL)
    return np.bincount(line_of, minlength=lines), last - first


def _numbers(b: np.ndarray, count: int, dtype) -> np.ndarray | None:
    """The ``count`` numbers of the text ``b``, or None where numpy reads another count or
    cannot read it."""
    with warnings.catch_warnings():  # an older numpy warns where a newer one raises
        warnings.simplefilter("error", DeprecationWarning)
        try:
            values = np.fromstring(b.tobytes(), dtype=dtype, sep=" ")
        except (ValueError, DeprecationWarning):
            return None
    return values if len(values) == count else None


def _vertices(b: np.ndarray, n: int) -> np.ndarray | None:
    if n == 0:
        return np.empty((0, 3))
    if not _DECIMAL[b].all():  # nan, inf, hexadecimal, words: line by line
        return None
    counts, _ = _token_counts(b)
    width = int(counts[0])
    if len(counts) != n or width < 3 or np.any(counts != width):
        return None
    values = _numbers(b, n * width, np.float64)
    return None if values is None else values.reshape(n, width)[:, :3].copy()


def _faces(b: np.ndarray, n: int) -> np.ndarray | None:
    if n == 0:
        return np.empty((0, 3), dtype=np.int64)
    slash = np.flatnonzero(b == ord("/"))
    if len(slash):  # "i/t/n": only i is read, and it must be there
        if not _INDEX_HEAD[b[slash - 1]].all():  # a digit before a token's first slash
            return None
        at = np.arange(len(b))
        cut = np.maximum.accumulate(np.where(b == ord("/"), at, -1))
        gap = np.maximum.accumulate(np.where(_BLANK[b] | (b == _NL), at, -1))
        b = np.where(cut > gap, np.uint8(ord(" ")), b)
    if not _INDEX[b].all():  # negative indices, signs, words: line by line
        return None
    counts, lengths = _token_counts(b)
    if len(counts) != n or counts.min() < 3 or lengths.max() > 15:
        return None
    idx = _numbers(b, int(counts.sum()), np.int64)
    if idx is None or idx.min() < 1:
        return None
    if counts.min() == counts.max():
        return _fan(idx.reshape(n, int(counts[0])))
    starts = np.concatenate(([0], np.cumsum(counts)[:-1]))
    pieces, order = [], []
    for k in np.unique(counts).tolist():
        pick = np.flatnonzero(counts == k)
        pieces.append(_fan(idx[starts[pick, None] + np.arange(k)]))
        order.append(np.repeat(pick, k - 2))
    # back in the file's order: each face's triangles together, in turn
    return np.concatenate(pieces)[np.argsort(np.concatenate(order), kind="stable")]


def _fan(corners: np.ndarray) -> np.ndarray:
    """The fans of triangles of faces of ``k`` corners each, ``(n, k)``: ``(c0, cj,
    cj+1)`` for ``j`` from 1, face by face."""
    n, k = corners.shape
    j = np.arange(1, k - 1)
    tri = np.empty((n, k - 2, 3), dtype=np.int64)
    tri[:, :, 0] = corners[:, :1]
    tri[:, :, 1] = corners[:, j]
    tri[:, :, 2] = corners[:, j + 1]
    return tri.reshape(-1, 3)


def _read_lines(fh: IO[bytes]) -> tuple[np.ndarray, np.ndarray]:
    """The OBJ reader of record, line by line into typed arrays (24 bytes a vertex or a
    triangle, less than their text): slower than :func:`_read_blocks`, and says what is
    wrong with a file, on what line."""
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
