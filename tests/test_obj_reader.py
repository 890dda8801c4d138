"""The OBJ reader's block reader against its line reader, the reader of record: the same
vertices to the bit and the same faces, or the same error, on the catalogued meshes and on
files of every form the block reader takes or hands over."""

from __future__ import annotations

import io
import random

import numpy as np
import pytest

from hullslice.readers import obj

from .conftest import MESHES

#: Lines the block reader parses itself (vertices with a w or colours, tabs, CRLF, faces
#: of 3 to 5 corners, with texture and normal indices, leading zeros, other statements).
PLAIN = [
    "v 1 2 3", "v 0.5 -1e-3 2.25", "v\t1.5 2.5 3.5", "v 1 2 3 1.0", "v +.5 5. -0",
    "v 1E+2 3e-05 7", "v 1 2 3\r", "v   4  5   6  ", "f 1 2 3", "f 1/1 2/2 3/3",
    "f 1//1 2//2 3//3 4//4", "f 1 2 3 4 5", "f\t2 3 4", "f 1 2 3\r", "f 01 2 3",
    "f 1/2/3 2/3/4 3/4/5 1/1/1", "f 1/a 2 3", "# a comment", "", "vn 0 0 1", "vt 0 1",
    "g part", "o x", "s 1", "usemtl m", "\r", "  ", "l 1 2", "mtllib a.mtl",
]  # fmt: skip
#: Lines it hands to the line reader, which reads them (negative indices, comments after a
#: statement, an indented one, nan, underscores, signs) or rejects them with the line.
HANDED_OVER = [
    "f -1 -2 -3", "f 1 2 3 # c", "v 1 2 3 # c", "  v 1 1 1", "v nan 1 2", "v inf 0 0",
    "v 1_0 2 3", "f 1_0 2 3", "f +1 2 3", "v 1 2 3 abc", "v\x1c1 2 3",
    "v 1 2", "f 1 2", "f 0 1 2", "v", "f", "v#", "f 1 2 99", "f //1 2 3", "v 1-2 3 4",
    "v 0x1p3 1 2", "f 1 2 3 x", "v 1.2.3 1 2", "f 99999999999999999 1 2", "v 1e 1 2",
]  # fmt: skip


def read(reader, data: bytes):
    try:
        return reader(io.BytesIO(data), len(data))
    except Exception as exc:  # the same error from both, as the user sees it
        return type(exc), str(exc)


def same(a, b) -> bool:
    if isinstance(a[0], type) or isinstance(b[0], type):
        return a == b
    return (
        a[0].dtype == b[0].dtype == np.float64
        and a[1].dtype == b[1].dtype == np.int64
        and a[0].shape == b[0].shape
        and np.array_equal(a[0].view(np.int64), b[0].view(np.int64))  # to the bit
        and np.array_equal(a[1], b[1])
    )


def by_blocks(fh, size):
    return obj.read_obj(fh, size)


def by_lines(fh, size):
    return obj._read_lines(fh)


def blocks(data: bytes):
    return obj._read_blocks(io.BytesIO(data), len(data))


@pytest.mark.parametrize(
    "name", ["fuselage_model.obj", "fuselage_full.obj", "airliner/airliner.obj"]
)
def test_the_catalogued_meshes_are_read_by_blocks_as_by_lines(name):
    data = (MESHES / name).read_bytes()
    assert blocks(data) is not None  # taken by the block reader
    assert same(read(by_blocks, data), read(by_lines, data))


def files(seed: int, count: int, pool: list[str]):
    rng = random.Random(seed)
    for _ in range(count):
        lines = [rng.choice(pool) for _ in range(rng.randint(1, 14))]
        head = b"\xef\xbb\xbf" if rng.random() < 0.05 else b""  # a byte-order mark
        yield head + ("\n".join(lines) + rng.choice(["", "\n", "\r\n"])).encode()


def test_plain_files_are_read_by_blocks_as_by_lines():
    taken = 0
    for data in files(1, 1500, PLAIN):
        parsed = blocks(data)
        lines = read(by_lines, data)
        if parsed is not None:
            taken += 1
            assert same(parsed, lines), data
        assert same(read(by_blocks, data), lines), data
    # all but those whose faces name vertices a file does not have
    assert taken > 300


def test_files_with_what_the_line_reader_judges_read_the_same():
    for data in files(2, 3000, PLAIN + HANDED_OVER):
        assert same(read(by_blocks, data), read(by_lines, data)), data
    for line in HANDED_OVER:  # each hands its block over, alone among plain lines
        data = f"v 0 0 0\nv 1 0 0\nv 0 1 0\n{line}\nf 1 2 3\n".encode()
        assert blocks(data) is None, line


def test_lines_across_block_ends_read_the_same(monkeypatch):
    monkeypatch.setattr(obj, "_BLOCK", 4096)  # a hundred lines a block, the last cut
    data = (MESHES / "airliner" / "airliner.obj").read_bytes().rstrip()  # no newline at the end
    assert blocks(data) is not None
    assert same(read(by_blocks, data), read(by_lines, data))
    # a file longer than its size said (grown since): read to its end all the same
    assert same(obj._read_blocks(io.BytesIO(data), 1000), read(by_lines, data))
    monkeypatch.setattr(obj, "_BLOCK", 37)  # a few lines a block
    for data in files(3, 300, PLAIN):
        assert same(read(by_blocks, data), read(by_lines, data)), data
