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


# -- the precision a file stores, against the body's size ------------------------------------


def _prism(offset: float = 0.0, scale: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    from hullslice.shapes import wedge_prism

    v, f = wedge_prism(length=1.0, beam=0.2, deadrise_deg=30, stations=11)
    return v * scale + offset, f


def _binary_stl(path, v: np.ndarray, f: np.ndarray):
    from hullslice.readers.stl import _STL_RECORD

    data = np.zeros(len(f), dtype=_STL_RECORD)
    data["corners"] = v[f]
    path.write_bytes(b"\0" * 80 + len(f).to_bytes(4, "little") + data.tobytes())
    return path


def _wagner(hull: hs.Hull) -> float:
    return hs.compute_force(hull, 0.02, -3.0, slices=16, solver="wagner", acceleration=0.0).total


def test_a_binary_stl_is_read_as_the_float32_it_stores():
    v, f = read_mesh(PRISM)
    assert v.dtype == np.float32 and f.dtype == np.int64


def test_a_float32_file_far_out_for_its_size_is_refused_with_the_figures(tmp_path):
    # 1e5 m out, a 1 m wedge's float32 coordinates step by 7.8 mm: its force was 15 % off
    path = _binary_stl(tmp_path / "far.stl", *_prism(1e5))
    with pytest.raises(hs.MeshError) as err:
        hs.load_hull(path)
    text = str(err.value)
    for part in ("lies 1e+05 m from the origin", "(1.02 m)", "float32", "step by 0.00781 m",
                 "0.0076 of its size", "near the origin", "double precision"):  # fmt: skip
        assert part in text


def test_a_centimetre_body_a_kilometre_out_is_refused(tmp_path):
    # it lost 7 % of its volume on loading
    path = _binary_stl(tmp_path / "cm.stl", *_prism(1000.0, scale=0.01))
    with pytest.raises(hs.MeshError, match=r"0\.006 of its size"):
        hs.load_hull(path)


def test_a_float32_file_within_the_limit_warns_and_keeps_its_force(tmp_path):
    # 1e3 m out: a step of 6e-5 of the size, the force within 0.1 % of the one at the origin
    at_origin = _wagner(hs.load_hull(_binary_stl(tmp_path / "a.stl", *_prism())))
    with pytest.warns(hs.HullsliceWarning, match="6e-05 of its size"):
        hull = hs.load_hull(_binary_stl(tmp_path / "b.stl", *_prism(1000.0)))
    assert _wagner(hull) == pytest.approx(at_origin, rel=1e-3)


def test_a_float32_file_near_the_origin_loads_silently(tmp_path):
    hull = hs.load_hull(_binary_stl(tmp_path / "near.stl", *_prism(10.0)))  # warnings are errors
    assert hull.volume == pytest.approx(0.2 * 0.1 * np.tan(np.radians(30)) / 2, rel=1e-4)


def test_the_same_offset_in_double_precision_loads(tmp_path):
    v, f = _prism(1e5)
    path = tmp_path / "far.obj"
    hs.Hull.from_arrays(v, f).save(path)  # every bit of float64
    assert hs.load_hull(path).volume == pytest.approx(hs.Hull.from_arrays(*_prism()).volume)


def test_the_precision_refusal_is_one_line_from_the_cli(tmp_path, capsys):
    from hullslice.cli import main

    path = _binary_stl(tmp_path / "far.stl", *_prism(1e5))
    assert main(["info", str(path)]) != 0
    err = capsys.readouterr().err.strip()
    assert err.startswith("hullslice: error: mesh 'far' lies 1e+05 m from the origin")
    assert "\n" not in err and "Traceback" not in err


def _obj(path, v: np.ndarray, f: np.ndarray, digits: int):
    lines = [f"v {x:.{digits}f} {y:.{digits}f} {z:.{digits}f}" for x, y, z in v]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in f]
    path.write_text("\n".join(lines) + "\n")
    return path


def test_a_text_file_written_with_too_few_digits_is_warned_about(tmp_path):
    prism = hs.load_hull(PRISM)
    path = _obj(tmp_path / "r.obj", prism.vertices * 0.03, prism.faces, 3)  # 1.2 cm, 3 decimals
    with pytest.warns(hs.HullsliceWarning) as caught:
        hs.load_hull(path)  # the rounding also made faces degenerate: they are dropped
    texts = [str(w.message) for w in caught]
    assert any("look rounded to 0.001 m, 0.083 of its size" in t for t in texts)


def test_a_text_file_on_a_grid_by_design_is_not_warned_about(tmp_path):
    # a box drawn on a 0.1 m grid: its values are exact, not rounded
    v = np.array([[x, y, z] for x in (0.0, 1.0) for y in (-0.2, 0.2) for z in (0.0, 0.1)])
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])  # fmt: skip
    hull = hs.load_hull(_obj(tmp_path / "box.obj", v, f, 1))
    assert hull.volume == pytest.approx(0.04, rel=1e-12)


def test_a_text_file_with_enough_digits_is_not_warned_about(tmp_path):
    prism = hs.load_hull(PRISM)
    hs.load_hull(_obj(tmp_path / "r.obj", prism.vertices, prism.faces, 5))


# -- an empty path ----------------------------------------------------------------------------


@pytest.mark.parametrize("path", ["", "  "])
def test_an_empty_path_is_refused_in_one_line(path):
    with pytest.raises(hs.MeshError, match=r"^mesh path is empty: give the path of a mesh file$"):
        hs.load_hull(path)


def test_an_empty_path_from_the_cli(capsys):
    from hullslice.cli import main

    assert main(["info", ""]) != 0
    err = capsys.readouterr().err
    assert err == "hullslice: error: mesh path is empty: give the path of a mesh file\n"
