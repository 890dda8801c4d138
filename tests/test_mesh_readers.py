"""Mesh readers: the table of formats, and meshes given as open files."""

from __future__ import annotations

import io

import numpy as np
import pytest

import hullslice as hs
from hullslice.mesh import read_mesh
from hullslice.readers import READERS, SUPPORTED_FORMATS
from hullslice.readers import read_mesh as read_mesh_of_readers

from .conftest import MESHES
from .test_mesh_files import TETRA_OBJ

PRISM = MESHES / "paper_prism.stl"


def test_the_table_names_every_format():
    assert set(READERS) == {"stl", "obj", "tri", "ply", "off", "glb", "gltf", "3mf", "msh"}
    assert SUPPORTED_FORMATS == tuple(READERS)
    assert read_mesh is read_mesh_of_readers


def test_an_open_binary_file_gives_the_same_hull_as_its_path():
    by_path = hs.load_hull(PRISM, mass=1.0)
    with open(PRISM, "rb") as fh:
        by_file = hs.load_hull(fh, mass=1.0)
    assert by_file.name == by_path.name == "paper_prism"
    assert np.array_equal(by_file.vertices, by_path.vertices)
    assert np.array_equal(by_file.faces, by_path.faces)
    assert by_file.source == by_path.source


def test_a_file_object_without_a_name_needs_its_format():
    data = io.BytesIO(TETRA_OBJ.encode())
    with pytest.raises(hs.InputError, match="format="):
        hs.load_hull(data)
    hull = hs.load_hull(data, format="obj")
    assert hull.volume == pytest.approx(1 / 6, rel=1e-12)
    assert hull.name == "hull"


def test_the_format_given_wins_over_the_name(tmp_path):
    path = tmp_path / "tetra.txt"
    path.write_text(TETRA_OBJ)
    with pytest.raises(hs.MeshError, match="has format 'txt'"):
        hs.load_hull(path)
    assert hs.load_hull(path, format="OBJ").volume == pytest.approx(1 / 6, rel=1e-12)


def test_a_file_object_is_checked_as_a_file_is():
    with pytest.raises(hs.MeshError, match="is empty"):
        read_mesh(io.BytesIO(b""), format="stl")
    with pytest.raises(hs.MeshError, match="not a valid OBJ file: line 1"):
        read_mesh(io.BytesIO(b"v 1 2\n"), format="obj")
    # a binary STL whose header claims more than the stream holds
    head = b"x" * 80 + (2**31).to_bytes(4, "little")
    with pytest.raises(hs.MeshError, match="claims 2147483648 triangles"):
        read_mesh(io.BytesIO(head), format="stl")
    nan = "v nan 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
    with pytest.raises(hs.MeshError, match="NaN or infinite"):
        hs.load_hull(io.BytesIO(nan.encode()), format="obj")


def test_a_text_mode_file_is_refused(tmp_path):
    path = tmp_path / "tetra.obj"
    path.write_text(TETRA_OBJ)
    with open(path) as fh, pytest.raises(hs.InputError, match="binary mode"):
        hs.load_hull(fh)


class _Stream(io.RawIOBase):
    """A stream that cannot seek (a pipe)."""

    def __init__(self, data: bytes) -> None:
        self._data = io.BytesIO(data)

    def readable(self) -> bool:
        return True

    def readinto(self, b) -> int:
        chunk = self._data.read(len(b))
        b[: len(chunk)] = chunk
        return len(chunk)

    def seekable(self) -> bool:
        return False

    def tell(self) -> int:
        raise OSError("not seekable")


def test_a_stream_that_cannot_seek_is_read():
    with open(PRISM, "rb") as fh:
        data = fh.read()
    v, f = read_mesh(io.BufferedReader(_Stream(data)), format="stl")
    w, g = read_mesh(PRISM)
    assert np.array_equal(v, w) and np.array_equal(f, g)
