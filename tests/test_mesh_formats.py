"""Mesh formats: one body in every format loads to the same hull; Cart3D .tri is read by
hullslice with the same safety as STL and OBJ; the extra formats need trimesh or meshio
and say so when missing; the checked and repaired mesh is written back out."""

from __future__ import annotations

import contextlib
import io
import sys
import zipfile

import numpy as np
import pytest

import hullslice as hs
from hullslice.axes import axis_matrix
from hullslice.cli import main
from hullslice.errors import (
    InputError,
    MeshError,
    MissingDependencyError,
    OrientationWarning,
    UnitsWarning,
)
from hullslice.shapes import wedge_prism

from .conftest import MESHES

WEDGE = MESHES / "wedge_prism.stl"  # float32-exact coordinates: STL and GLB hold them exactly

trimesh = pytest.importorskip("trimesh")


@pytest.fixture(scope="module")
def wedge() -> hs.Hull:
    return hs.load_hull(WEDGE)


def _write(hull: hs.Hull, path) -> None:
    """``hull`` in the format of ``path``'s extension: hullslice's writer for STL, OBJ and
    TRI, trimesh for PLY, OFF, GLB, glTF and 3MF, meshio for Gmsh; a glTF +Y up and a 3MF
    in the millimetres trimesh declares, as their specifications say."""
    ext = path.suffix[1:]
    if ext in ("stl", "obj", "tri"):
        hull.save(path)
    elif ext == "msh":
        meshio = pytest.importorskip("meshio")
        meshio.Mesh(hull.vertices, [("triangle", hull.faces)]).write(
            path, file_format="gmsh", binary=True
        )
    else:
        if ext == "3mf":
            pytest.importorskip("lxml")
        v = hull.vertices
        if ext in ("glb", "gltf"):  # glTF is +Y up: the body's z up is the file's +y
            v = v @ axis_matrix("+x", "+y")
        elif ext == "3mf":  # trimesh declares millimetres
            v = v * 1000.0
        tm = trimesh.Trimesh(v, hull.faces, process=False)
        out = tm.export(file_type=ext, **({"digits": 17} if ext == "off" else {}))
        if ext == "gltf":
            tm_files = tm.export(file_type="gltf", embed_buffers=True)
            out = tm_files["model.gltf"]
        path.write_bytes(out if isinstance(out, bytes) else out.encode())


FORMATS = ["stl", "obj", "tri", "ply", "off", "glb", "gltf", "3mf", "msh"]

#: The note a format's declared convention gives on loading (glTF's +Y up, a 3MF's unit).
NOTES = {"glb": OrientationWarning, "gltf": OrientationWarning, "3mf": UnitsWarning}


def _noted(ext: str):
    return pytest.warns(NOTES[ext]) if ext in NOTES else contextlib.nullcontext()


@pytest.mark.parametrize("ext", FORMATS)
def test_every_format_loads_the_same_body(wedge, tmp_path, ext):
    path = tmp_path / f"wedge.{ext}"
    _write(wedge, path)
    with _noted(ext):
        hull = hs.load_hull(path)
    assert hull.volume == pytest.approx(wedge.volume, rel=1e-9)
    assert hull.centroid == pytest.approx(wedge.centroid, rel=1e-9, abs=1e-12)
    assert len(hull.faces) == len(wedge.faces)
    assert hull.source["repairs"] == ()


@pytest.mark.parametrize("ext", ["stl", "obj", "tri", "ply", "off", "glb", "3mf"])
def test_the_saved_mesh_reads_back_as_the_loaded_one(wedge, tmp_path, ext):
    if ext == "3mf":
        pytest.importorskip("lxml")
    path = wedge.save(tmp_path / f"out.{ext}")
    with _noted(ext):
        back = hs.load_hull(path)
    if ext == "glb":  # turned +Y up and back: the same triangles, the vertices in another order
        assert _triangles(back) == _triangles(wedge)
        return
    np.testing.assert_array_equal(back.vertices, wedge.vertices)
    np.testing.assert_array_equal(back.faces, wedge.faces)


def _triangles(hull: hs.Hull) -> list[tuple[float, ...]]:
    """The hull's triangles as corner coordinates, each from its least corner (keeping its
    orientation), sorted: equal for the same surface whatever the vertex order."""
    out = []
    for tri in hull.vertices[hull.faces].tolist():
        k = min(range(3), key=lambda i: tri[i])
        out.append(tuple(c for corner in tri[k:] + tri[:k] for c in corner))
    return sorted(out)


@pytest.mark.parametrize("ext", ["obj", "tri"])
def test_text_formats_keep_every_bit(tmp_path, ext):
    # coordinates that float32 cannot hold (tan 30 deg): OBJ and .tri keep them exactly
    hull = hs.Hull.from_arrays(*wedge_prism(length=1.3, beam=0.37, stations=7))
    back = hs.load_hull(hull.save(tmp_path / f"w.{ext}"))
    np.testing.assert_array_equal(back.vertices, hull.vertices)
    np.testing.assert_array_equal(back.faces, hull.faces)
    assert back.volume == pytest.approx(hull.volume, rel=1e-12)


def test_stl_is_binary_float32(tmp_path):
    hull = hs.Hull.from_arrays(*wedge_prism(length=1.3, beam=0.37, stations=7))
    path = hull.save(tmp_path / "w.stl")
    assert path.stat().st_size == 84 + 50 * len(hull.faces)
    back = hs.load_hull(path)
    rounded = hs.Hull.from_arrays(hull.vertices.astype(np.float32), hull.faces)
    assert back.volume == pytest.approx(rounded.volume, rel=1e-12)
    assert back.volume == pytest.approx(hull.volume, rel=1e-6)
    rows = np.lexsort(back.vertices.T), np.lexsort(rounded.vertices.T)
    np.testing.assert_array_equal(back.vertices[rows[0]], rounded.vertices[rows[1]])


def test_save_in_millimetres(wedge, tmp_path):
    back = hs.load_hull(wedge.save(tmp_path / "w.obj", units="mm"), units="mm")
    assert back.volume == pytest.approx(wedge.volume, rel=1e-12)
    assert back.bounds == pytest.approx(wedge.bounds, rel=1e-15, abs=1e-18)
    text = (tmp_path / "w.obj").read_text()
    assert "v 1000.0 " in text


def test_save_refuses_unknown_format_and_missing_folder(wedge, tmp_path):
    with pytest.raises(InputError, match=r"hullslice writes meshes as stl, obj, tri"):
        wedge.save(tmp_path / "w.step")
    with pytest.raises(InputError, match="does not exist"):
        wedge.save(tmp_path / "nope" / "w.stl")
    assert list(tmp_path.iterdir()) == []


# -- Cart3D .tri ----------------------------------------------------------------------------

CUBE_TRI = """8 12
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
1 3 2
1 4 3
5 6 7
5 7 8
1 2 6
1 6 5
2 3 7
2 7 6
3 4 8
3 8 7
4 1 5
4 5 8
"""


def test_tri_reads_openvsp_layout_with_component_numbers(tmp_path):
    path = tmp_path / "cube.tri"
    path.write_text(CUBE_TRI + "1\n" * 6 + "2\n" * 6)
    hull = hs.load_hull(path)
    assert hull.volume == pytest.approx(1.0, rel=1e-12)
    assert hull.centroid == pytest.approx([0.5, 0.5, 0.5], rel=1e-12)


def test_tri_reads_any_layout_and_no_component_numbers(tmp_path):
    path = tmp_path / "cube.tri"
    path.write_text(" ".join(CUBE_TRI.split()) + "\n")  # everything on one line
    assert hs.load_hull(path).volume == pytest.approx(1.0, rel=1e-12)


def _long(lines: int) -> str:
    """The first ``lines`` lines of the cube, its coordinates written with 12 digits."""
    rows = CUBE_TRI.splitlines()
    rows[1:9] = [" ".join(f"{float(t):.12f}" for t in r.split()) for r in rows[1:9]]
    return "\n".join(rows[:lines]) + "\n"


def _bad(text: str) -> str:
    lines = CUBE_TRI.splitlines()
    for k, v in _EDITS[text].items():
        lines[k] = v
    return "\n".join(lines) + "\n"


_EDITS = {
    "nan": {3: "1 1 nan"},
    "inf": {3: "1 1 -inf"},
    "word": {2: "1 zero 0"},
    "index": {12: "5 7 9"},
    "zero": {12: "0 7 8"},
    "float-index": {12: "5 7.0 8"},
}


@pytest.mark.parametrize(
    ("content", "message"),
    [
        (_bad("nan"), "line 4: vertex coordinate 'nan' is not finite"),
        (_bad("inf"), "line 4: vertex coordinate '-inf' is not finite"),
        (_bad("word"), "line 3: vertex coordinate 'zero' is not a number"),
        (_bad("index"), r"line 13: vertex number 9 does not exist \(the file has 8 vertices"),
        (_bad("zero"), "line 13: vertex number 0 does not exist"),
        (_bad("float-index"), "line 13: triangle corner '7.0' is not a vertex number"),
        ("8 12 3\n" + CUBE_TRI.split("\n", 1)[1], "line 1: '8 12 3' is not the header"),
        ("eight twelve\n" + CUBE_TRI.split("\n", 1)[1], "line 1: 'eight twelve' is not the"),
        ("-8 12\n" + CUBE_TRI.split("\n", 1)[1], "gives a negative count"),
        ("80000 12\n" + CUBE_TRI.split("\n", 1)[1], "the header claims 80000 vertices"),
        ("\n".join(CUBE_TRI.splitlines()[:15]) + "\n", "line 1: the header claims 8 vertices"),
        (_long(15), "ends after 18 of the 36 vertex numbers of the triangles"),
        (_long(6), "ends after 15 of the 24 vertex coordinates"),
        (CUBE_TRI + "1\n" * 5, "ends after 5 of the 12 component numbers"),
        (CUBE_TRI + "1\n" * 12 + "7\n", "line 34: '7' follows the 12 triangles' component"),
        (CUBE_TRI + "1\n" * 11 + "x\n", "line 33: component number 'x' is not a whole number"),
        ("8 12\n\0\0\0" + "0" * 200, "line 2 holds binary data"),
        ("   \n\n", "holds no values"),
    ],
)
def test_malformed_tri_is_refused_with_its_line(tmp_path, content, message):
    path = tmp_path / "bad.tri"
    path.write_text(content)
    with pytest.raises(MeshError, match=rf"'{path}' is not a valid TRI file: .*{message}"):
        hs.load_hull(path)


def test_tri_line_length_is_bounded(tmp_path):
    path = tmp_path / "long.tri"
    path.write_text("8 12\n" + "0 " * 40_000 + "\n")
    with pytest.raises(MeshError, match="line 2 is longer than 64 KiB"):
        hs.load_hull(path)


def test_tri_through_the_cli_refuses_nan_in_one_line(tmp_path, capsys):
    path = tmp_path / "bad.tri"
    path.write_text(_bad("nan"))
    assert main(["info", str(path)]) == 3
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "line 4: vertex coordinate 'nan' is not finite" in err


# -- the same checks for every format ---------------------------------------------------------


def test_an_open_ply_is_refused_like_an_open_stl(wedge, tmp_path):
    tm = trimesh.Trimesh(wedge.vertices, wedge.faces[:-1], process=False)
    (tmp_path / "open.ply").write_bytes(tm.export(file_type="ply"))
    (tmp_path / "open.stl").write_bytes(tm.export(file_type="stl"))
    with pytest.raises(MeshError, match="open") as ply:
        hs.load_hull(tmp_path / "open.ply")
    with pytest.raises(MeshError, match="open") as stl:
        hs.load_hull(tmp_path / "open.stl")
    assert str(ply.value).replace("open.ply", "X") == str(stl.value).replace("open.stl", "X")


def test_nan_in_an_off_is_refused(wedge, tmp_path):
    v = wedge.vertices.copy()
    v[3, 1] = np.nan
    (tmp_path / "nan.off").write_text(
        trimesh.Trimesh(v, wedge.faces, process=False).export(file_type="off")
    )
    with pytest.raises(MeshError, match="NaN or infinite coordinates"):
        hs.load_hull(tmp_path / "nan.off")


def test_size_limit_applies_to_extra_formats(wedge, tmp_path, monkeypatch):
    import hullslice.readers as readers

    _write(wedge, tmp_path / "w.glb")
    monkeypatch.setattr(readers, "MAX_FILE_BYTES", 100)
    with pytest.raises(MeshError, match=r"more than the .* hullslice reads"):
        hs.load_hull(tmp_path / "w.glb")


def test_units_and_axes_apply_to_extra_formats(wedge, tmp_path):
    _write(wedge, tmp_path / "w.ply")
    hull = hs.load_hull(tmp_path / "w.ply", units="mm", forward="-x")
    assert hull.volume == pytest.approx(wedge.volume * 1e-9, rel=1e-9)
    assert hull.extents == pytest.approx(wedge.extents * 1e-3, rel=1e-9)


def test_extra_format_from_an_open_file(wedge, tmp_path):
    _write(wedge, tmp_path / "w.off")
    data = (tmp_path / "w.off").read_bytes()
    hull = hs.load_hull(io.BytesIO(data), format="off")
    assert hull.volume == pytest.approx(wedge.volume, rel=1e-9)


def test_gltf_with_separate_buffers_is_refused(wedge, tmp_path):
    files = trimesh.Trimesh(wedge.vertices, wedge.faces).export(file_type="gltf")
    for name, data in files.items():
        (tmp_path / name).write_bytes(data)
    with pytest.raises(MeshError, match=r"is a separate file, .* export the mesh as \.glb"):
        hs.load_hull(tmp_path / "model.gltf")


def test_3mf_that_is_not_a_zip_or_unpacks_to_too_much(wedge, tmp_path, monkeypatch):
    pytest.importorskip("lxml")
    import hullslice.readers.extra as extra

    (tmp_path / "bad.3mf").write_bytes(b"PK not really a zip")
    with pytest.raises(MeshError, match="a 3MF is a zip archive and this one is not"):
        hs.load_hull(tmp_path / "bad.3mf")
    _write(wedge, tmp_path / "w.3mf")
    with zipfile.ZipFile(tmp_path / "w.3mf") as z:
        unpacked = sum(i.file_size for i in z.infolist())
    monkeypatch.setattr(extra, "MAX_UNPACKED_BYTES", unpacked - 1)
    with pytest.raises(MeshError, match=r"it unpacks to .* GiB, more than"):
        hs.load_hull(tmp_path / "w.3mf")


def test_garbage_in_an_extra_format_is_a_mesh_error(tmp_path):
    (tmp_path / "bad.glb").write_bytes(b"glTF" + bytes(range(200)))
    with pytest.raises(MeshError, match=r"'.*bad.glb' is not a valid GLB file: trimesh cannot"):
        hs.load_hull(tmp_path / "bad.glb")


def test_gmsh_volume_mesh_gives_its_boundary(tmp_path):
    meshio = pytest.importorskip("meshio")
    v = np.array(
        [[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0], [0, 0, 3], [2, 0, 3], [2, 1, 3], [0, 1, 3]],
        dtype=float,
    )
    # the cube split into six tetrahedra around the diagonal 0-6, some inverted
    tets = np.array(
        [[0, 1, 2, 6], [0, 2, 3, 6], [0, 3, 7, 6], [0, 7, 4, 6], [0, 4, 5, 6], [0, 5, 1, 6]]
    )
    tets[::2, [2, 3]] = tets[::2, [3, 2]]
    meshio.Mesh(v, [("tetra", tets)]).write(tmp_path / "box.msh", file_format="gmsh22")
    hull = hs.load_hull(tmp_path / "box.msh")
    assert hull.volume == pytest.approx(6.0, rel=1e-12)
    assert len(hull.faces) == 12


# -- without the extra --------------------------------------------------------------------------


@pytest.mark.parametrize(("ext", "module"), [("ply", "trimesh"), ("msh", "meshio")])
def test_missing_library_gives_the_install_hint(wedge, tmp_path, monkeypatch, capsys, ext, module):
    _write(wedge, tmp_path / f"w.{ext}")
    monkeypatch.setitem(sys.modules, module, None)  # import fails as when not installed
    with pytest.raises(MissingDependencyError, match=r"pip install 'hullslice\[formats\]'"):
        hs.load_hull(tmp_path / f"w.{ext}")
    assert main(["info", str(tmp_path / f"w.{ext}")]) == 3
    err = capsys.readouterr().err
    what = {"ply": "PLY files", "msh": "Gmsh .msh files"}[ext]
    assert err == (
        f"hullslice: error: reading {what} needs {module}: pip install "
        f"'hullslice[formats]' (or pip install {module})\n"
    )


def test_missing_lxml_for_3mf(wedge, tmp_path, monkeypatch):
    pytest.importorskip("lxml")
    _write(wedge, tmp_path / "w.3mf")
    monkeypatch.setitem(sys.modules, "lxml", None)
    with pytest.raises(MissingDependencyError, match="reading 3MF files needs lxml"):
        hs.load_hull(tmp_path / "w.3mf")


def test_own_formats_need_no_extra(wedge, tmp_path, monkeypatch):
    for ext in ("stl", "obj", "tri"):
        wedge.save(tmp_path / f"w.{ext}")
    monkeypatch.setitem(sys.modules, "trimesh", None)
    monkeypatch.setitem(sys.modules, "meshio", None)
    for ext in ("stl", "obj", "tri"):
        assert hs.load_hull(tmp_path / f"w.{ext}").volume == pytest.approx(wedge.volume, 1e-12)
    with pytest.raises(MissingDependencyError, match=r"Hull.to_trimesh needs trimesh"):
        wedge.to_trimesh()
    with pytest.raises(MissingDependencyError, match="needs trimesh"):
        wedge.save(tmp_path / "w.ply")


# -- trimesh objects ------------------------------------------------------------------------------


def test_trimesh_round_trip(wedge):
    tm = wedge.to_trimesh()
    assert isinstance(tm, trimesh.Trimesh)
    np.testing.assert_array_equal(tm.vertices, wedge.vertices)
    np.testing.assert_array_equal(tm.faces, wedge.faces)
    back = hs.Hull.from_trimesh(tm, mass=2.0, name="back")
    assert back.volume == pytest.approx(wedge.volume, rel=1e-12)
    assert back.mass == 2.0 and back.name == "back"
    tm.vertices[0] += 1.0  # a copy: the hull is unchanged
    assert wedge.vertices[0, 0] != tm.vertices[0, 0]


def test_from_trimesh_applies_units_axes_and_checks(wedge):
    tm = trimesh.Trimesh(wedge.vertices * 1000.0, wedge.faces, process=False)
    hull = hs.Hull.from_trimesh(trimesh.Scene([tm]), units="mm")
    assert hull.volume == pytest.approx(wedge.volume, rel=1e-9)
    with pytest.raises(MeshError):
        hs.Hull.from_trimesh(trimesh.Trimesh(wedge.vertices, wedge.faces[:-1], process=False))
    with pytest.raises(InputError, match=r"expected a trimesh.Trimesh"):
        hs.Hull.from_trimesh(np.zeros((3, 3)))


# -- hullslice info --write-mesh -------------------------------------------------------------------


def test_info_writes_the_repaired_mesh(tmp_path, capsys):
    out = tmp_path / "clean.obj"
    assert main(["info", str(WEDGE), "--units", "mm", "--write-mesh", str(out)]) == 0
    assert f"wrote {out}" in capsys.readouterr().err
    loaded = hs.load_hull(WEDGE, units="mm")
    back = hs.load_hull(out)
    assert back.volume == pytest.approx(loaded.volume, rel=1e-12)
    rows = np.lexsort(back.vertices.T), np.lexsort(loaded.vertices.T)
    np.testing.assert_array_equal(back.vertices[rows[0]], loaded.vertices[rows[1]])
    assert len(back.faces) == len(loaded.faces)


@pytest.mark.parametrize(
    ("target", "message"),
    [
        ("input", "it is the input mesh file and would be overwritten"),
        ("w.step", "a mesh is written as stl, obj, tri"),
        ("nofolder/w.stl", "does not exist; create it first"),
        ("same-as-output", "--output writes the same file"),
    ],
)
def test_info_write_mesh_refusals(tmp_path, capsys, target, message):
    mesh = tmp_path / "w.stl"
    mesh.write_bytes(WEDGE.read_bytes())
    extra: list[str] = []
    if target == "input":
        out = mesh
    elif target == "same-as-output":
        out = tmp_path / "o.obj"
        extra = ["-o", str(out)]
    else:
        out = tmp_path / target
    before = sorted(p.name for p in tmp_path.iterdir())
    assert main(["info", str(mesh), "--write-mesh", str(out), *extra]) == 3
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err and "(--write-mesh)" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == before
    assert mesh.read_bytes() == WEDGE.read_bytes()


# -- the conventions a file declares: a 3MF's unit, glTF's +Y up ------------------------------


def _3mf(path, unit: str | None, scale: float = 1.0):
    """The paper prism as a 3MF whose model declares ``unit`` (None: no unit attribute),
    its coordinates the prism's in metres times ``scale``."""
    pytest.importorskip("lxml")
    prism = hs.load_hull(MESHES / "paper_prism.stl")
    data = trimesh.Trimesh(prism.vertices * scale, prism.faces, process=False).export(
        file_type="3mf"
    )
    declared = b"" if unit is None else f' unit="{unit}"'.encode()
    out = io.BytesIO()
    with zipfile.ZipFile(io.BytesIO(data)) as zin, zipfile.ZipFile(out, "w") as zout:
        for item in zin.infolist():
            content = zin.read(item.filename)
            if item.filename.endswith(".model"):
                content = content.replace(b' unit="millimeter"', declared)
            zout.writestr(item, content)
    path.write_bytes(out.getvalue())
    return path


PRISM_LENGTH = 0.35  # m


@pytest.mark.parametrize(
    ("unit", "metres_per_unit"),
    [("inch", 0.0254), ("centimeter", 0.01), ("meter", 1.0), ("millimeter", 1e-3),
     (None, 1e-3), ("micron", 1e-6)],
)  # fmt: skip
def test_a_3mf_is_read_in_the_unit_it_declares(tmp_path, unit, metres_per_unit):
    # the file holds 0.35 units along x: 0.35 of its unit
    path = _3mf(tmp_path / "p.3mf", unit)
    with pytest.warns(UnitsWarning, match=f"declares its unit '{unit or 'millimeter'}'"):
        hull = hs.load_hull(path)
    assert hull.extents[0] == pytest.approx(PRISM_LENGTH * metres_per_unit, rel=1e-6)
    assert hull.source["units"] == {"inch": "in", "centimeter": "cm", "meter": "m"}.get(unit, "mm")


def test_units_given_win_over_the_3mf_unit(tmp_path):
    path = _3mf(tmp_path / "p.3mf", "inch")
    with pytest.warns(UnitsWarning, match="declares its unit 'inch'; read in m as given"):
        hull = hs.load_hull(path, units="m")
    assert hull.extents[0] == pytest.approx(PRISM_LENGTH, rel=1e-6)


def test_a_length_sets_the_size_of_a_3mf_without_a_unit_note(tmp_path):
    hull = hs.load_hull(_3mf(tmp_path / "p.3mf", "inch"), length=3.5)  # warnings are errors
    assert hull.extents[0] == pytest.approx(3.5, rel=1e-12)


def test_the_cli_reads_a_3mf_in_its_unit_and_says_so(tmp_path, capsys):
    path = _3mf(tmp_path / "p.3mf", "centimeter", scale=100.0)  # 35 cm
    assert main(["info", str(path)]) == 0
    out, err = capsys.readouterr()
    assert "declares its unit 'centimeter': read in cm (give --units to override)" in err
    assert "units cm" in out and "length 0.35 m" in out
    assert main(["info", str(path), "--units", "mm"]) == 0
    out, err = capsys.readouterr()
    assert "read in mm as given" in err and "length 0.035 m" in out


@pytest.mark.parametrize(("units", "declared", "factor"), [("m", b"meter", 1.0),
                                                           ("mm", b"millimeter", 1e3)])  # fmt: skip
def test_a_written_3mf_declares_the_unit_it_is_written_in(wedge, tmp_path, units, declared, factor):
    pytest.importorskip("lxml")
    path = wedge.save(tmp_path / "w.3mf", units=units)
    with zipfile.ZipFile(path) as z:
        model = next(z.read(n) for n in z.namelist() if n.endswith(".model"))
    assert b' unit="' + declared + b'"' in model
    other = trimesh.load(path, force="mesh")  # another reader sees the same size
    assert other.units == declared.decode()
    assert other.extents == pytest.approx(wedge.extents * factor, rel=1e-6)
    with pytest.warns(UnitsWarning):
        back = hs.load_hull(path)
    assert back.volume == pytest.approx(wedge.volume, rel=1e-6)


def test_the_cli_writes_a_3mf_in_metres_and_says_so_in_the_file(tmp_path, capsys):
    pytest.importorskip("lxml")
    out = tmp_path / "out.3mf"
    assert main(["info", str(MESHES / "paper_prism.stl"), "--write-mesh", str(out)]) == 0
    assert trimesh.load(out, force="mesh").units == "meter"


def test_a_glb_is_read_y_up(tmp_path):
    prism = hs.load_hull(MESHES / "paper_prism.stl")
    path = tmp_path / "p.glb"
    v = prism.vertices @ axis_matrix("+x", "+y")  # the prism as glTF has it: +Y up
    path.write_bytes(trimesh.Trimesh(v, prism.faces, process=False).export(file_type="glb"))
    with pytest.warns(OrientationWarning, match=r"declares up \+y \(glTF is \+Y up\)"):
        hull = hs.load_hull(path)
    assert hull.extents == pytest.approx(
        prism.extents, rel=1e-6
    )  # 0.35 x 0.2 x 0.1, not on its side
    assert hull.source["up"] == "+y" and hull.source["forward"] == "+x"
    assert _wagner(hull) == pytest.approx(_wagner(prism), rel=1e-6)
    on_its_side = hs.load_hull(path, up="+z")  # given: it wins, without a note
    assert on_its_side.extents[1] == pytest.approx(0.1, rel=1e-6)
    assert _wagner(on_its_side) < 0.5 * _wagner(prism)  # as it was read before


def _wagner(hull: hs.Hull) -> float:
    return hs.compute_force(
        hull, 0.0383, -3.4943, slices=32, solver="wagner", acceleration=0.0
    ).total


def test_a_forward_along_the_glb_up_axis_needs_the_up_too(tmp_path, wedge):
    path = wedge.save(tmp_path / "w.glb")
    with pytest.raises(InputError, match=r"forward axis 'y' is the axis the file declares up"):
        hs.load_hull(path, forward="y")
    hull = hs.load_hull(path, forward="y", up="x")  # both given: as for any format
    assert hull.volume == pytest.approx(wedge.volume, rel=1e-6)


def test_a_written_glb_is_y_up(wedge, tmp_path):
    path = wedge.save(tmp_path / "w.glb")
    other = trimesh.load(path, force="mesh")  # as another glTF reader sees it
    lo, hi = other.bounds
    # the body's z (height) is the file's +Y, its y (beam, to port) the file's -Z
    assert hi[1] - lo[1] == pytest.approx(wedge.extents[2], rel=1e-6)
    assert hi[2] - lo[2] == pytest.approx(wedge.extents[1], rel=1e-6)
    assert lo[1] == pytest.approx(wedge.bounds[0][2], rel=1e-6, abs=1e-9)
