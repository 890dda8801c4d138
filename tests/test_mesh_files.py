"""Reading untrusted mesh files: geometry only, nothing executed, nothing else opened, memory
in proportion to the file."""

from __future__ import annotations

import struct
import sys
import time
import tracemalloc

import numpy as np
import pytest
import trimesh

import hullslice as hs
from hullslice import shapes
from hullslice.mesh import read_mesh

from .conftest import MESHES

# a closed tetrahedron, faces outward: volume 1/6 m^3
TETRA_V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
TETRA_F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
TETRA_OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"


def ascii_stl(solids: dict[str, tuple[np.ndarray, np.ndarray]], fmt: str = ".17g") -> str:
    """An ASCII STL with one ``solid`` block per entry, coordinates written with ``fmt``."""
    lines = []
    for name, (v, f) in solids.items():
        lines.append(f"solid {name}")
        for tri in np.asarray(v)[np.asarray(f)]:
            lines += ["  facet normal 0 0 0", "    outer loop"]
            lines += ["      vertex " + " ".join(format(c, fmt) for c in p) for p in tri]
            lines += ["    endloop", "  endfacet"]
        lines.append(f"endsolid {name}")
    return "\n".join(lines) + "\n"


# -- what the guards cost: nothing in proportion to a lie ----------------------------------


def test_a_binary_stl_claiming_2_31_triangles_in_1_kb_is_refused_at_once(tmp_path):
    path = tmp_path / "absurd.stl"
    path.write_bytes(b"\0" * 80 + struct.pack("<I", 2**31) + b"\1" * 940)
    tracemalloc.start()
    t0 = time.perf_counter()
    try:
        with pytest.raises(hs.MeshError) as info:
            read_mesh(path)
        elapsed = time.perf_counter() - t0
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert "header claims 2147483648 triangles (107374182484 bytes) but the file has 1024" in str(
        info.value
    )
    assert peak < 1024**2  # bytes: the 107 GB the header claims are never asked for
    assert elapsed < 1.0


def test_an_obj_with_an_absurd_index_is_refused_without_allocating(tmp_path):
    path = tmp_path / "absurd.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3000000000\n")
    tracemalloc.start()
    try:
        with pytest.raises(hs.MeshError, match="line 4: a face refers to a vertex that does not"):
            read_mesh(path)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 1024**2
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n")
    with pytest.raises(hs.MeshError, match="line 4: face index 99999999999999999999999 does"):
        read_mesh(path)


# -- nothing else is opened, nothing is executed -------------------------------------------

_EVENTS: list[tuple[str, tuple]] | None = None
_WATCHED = ("open", "exec", "compile", "subprocess.Popen", "os.system", "socket.connect")


def _audit(event: str, args: tuple) -> None:
    if _EVENTS is not None and event in _WATCHED:
        _EVENTS.append((event, args))


sys.addaudithook(_audit)  # permanent for the process, but records only inside `watched`


def watched(fn):
    """Run ``fn`` and return what it opened, executed or started, from the audit events."""
    global _EVENTS
    _EVENTS = []
    try:
        fn()
        return list(_EVENTS)
    finally:
        _EVENTS = None


def test_an_obj_naming_material_files_loads_its_geometry_only(tmp_path):
    (tmp_path / "sub").mkdir()
    # a material file that exists beside it, naming a texture: neither may be opened
    (tmp_path / "sub" / "hull.mtl").write_text("newmtl steel\nmap_Kd secret.png\n")
    (tmp_path / "sub" / "secret.png").write_bytes(b"\x89PNG")
    obj = tmp_path / "sub" / "hull.obj"
    obj.write_text("mtllib ../../etc/passwd\nmtllib hull.mtl\nusemtl steel\n" + TETRA_OBJ)
    hs.load_hull(MESHES / "wedge_prism.stl")  # imports done before watching
    hull = None

    def load():
        nonlocal hull
        hull = hs.load_hull(obj)

    events = watched(load)
    opened = [str(args[0]) for event, args in events if event == "open"]
    assert opened == [str(obj)]
    assert [e for e, _ in events if e != "open"] == []
    assert hull.volume == pytest.approx(1 / 6, rel=1e-12)


def test_a_python_payload_in_a_mesh_file_is_only_text(tmp_path):
    marker = tmp_path / "ran"
    payload = f"__import__('pathlib').Path({str(marker)!r}).touch()"
    obj = tmp_path / "hull.obj"
    obj.write_text(f"# {payload}\no {payload}\ng {payload}\n" + TETRA_OBJ)
    stl = tmp_path / "hull.stl"
    stl.write_text(ascii_stl({payload: (TETRA_V, TETRA_F)}))
    for path in (obj, stl):
        events = watched(lambda p=path: hs.load_hull(p))
        assert [e for e, _ in events if e != "open"] == []
        assert hs.load_hull(path).volume == pytest.approx(1 / 6, rel=1e-12)
    assert not marker.exists()


# -- STL ----------------------------------------------------------------------------------


def test_ascii_stl_with_two_solids_is_one_body_of_two_parts(tmp_path):
    v, f = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0)
    path = tmp_path / "catamaran.stl"
    shift = np.array([0.0, 0.3, 0.0])
    path.write_text(ascii_stl({"port": (v + shift, f), "starboard": (v - shift, f)}))
    hull = hs.load_hull(path)
    assert hull.volume == pytest.approx(2 * 0.1 * 0.1 * np.tan(np.radians(30)), rel=1e-12)


def test_a_binary_stl_whose_header_starts_with_solid_is_binary(tmp_path):
    v, f = shapes.wedge_prism()
    data = bytearray(trimesh.Trimesh(v, f, process=False).export(file_type="stl"))
    data[:80] = b"solid exported by a CAD tool".ljust(80, b" ")
    path = tmp_path / "cad.stl"
    path.write_bytes(bytes(data))
    assert hs.load_hull(path).volume == pytest.approx(0.1 * 0.1 * np.tan(np.radians(30)))


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            "solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n",
            "ASCII STL with 2 vertex lines in 1 facets: every facet needs exactly three",
        ),
        (
            "solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
            "vertex 0 one 0\nendloop\nendfacet\nendsolid\n",
            "vertex coordinate 'one' is not a number",
        ),
        ("solid x\n\0\0\0binary", "starts with 'solid' but holds binary data"),
        ("hello, this is not a mesh\n" * 10, "does not start with 'solid'"),
        ("x" * 50, "at 50 bytes it is shorter than a binary STL's 84-byte header"),
    ],
)
def test_malformed_stl(tmp_path, text, message):
    path = tmp_path / "bad.stl"
    path.write_text(text)
    with pytest.raises(hs.MeshError) as info:
        read_mesh(path)
    assert message in str(info.value)
    assert str(path) in str(info.value)


# -- OBJ ----------------------------------------------------------------------------------


def test_obj_polygons_are_split_into_triangles(tmp_path):
    # a unit cube of quads, with texture and normal indices, groups and comments
    path = tmp_path / "cube.obj"
    path.write_text(
        "# cube\no cube\n"
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "vt 0 0\nvn 0 0 1\ng bottom\nf 1/1/1 4/1/1 3/1/1 2/1/1\ng rest\nf 5//1 6//1 7//1 8//1\n"
        "f 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf -8 -4 -1 -5  # relative indices: 1 5 8 4\n"
    )
    v, f = read_mesh(path)
    assert v.shape == (8, 3) and f.shape == (12, 3)
    assert hs.load_hull(path).volume == pytest.approx(1.0, rel=1e-12)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "line 4: face index 0 does not exist"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "line 4: a face refers to a vertex that"),
        ("v 0 0 0\nv 1 0 0\nv 0 1\nf 1 2 3\n", "line 3: 'v 0 1' is not a vertex 'v x y z'"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "line 4: 'f 1 2' has fewer than three corners"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", "line 4: face corner 'x' is not a vertex index"),
        ("v 0 0 0\nf 1 1 1\0\n", "line 2 holds binary data; an OBJ is a text file"),
        ("v 0 0 0\nv 1 0 0\n", "holds no triangles"),
    ],
)
def test_malformed_obj(tmp_path, text, message):
    path = tmp_path / "bad.obj"
    path.write_text(text)
    with pytest.raises(hs.MeshError) as info:
        read_mesh(path)
    assert message in str(info.value)


def test_obj_that_is_not_utf8_loads(tmp_path):
    path = tmp_path / "latin1.obj"
    path.write_bytes(("# Rumpf aus Stahl, entworfen in K\xf6ln\n" + TETRA_OBJ).encode("latin-1"))
    assert hs.load_hull(path).volume == pytest.approx(1 / 6, rel=1e-12)


def test_an_unreadable_file_is_an_error_not_a_crash(tmp_path, monkeypatch):
    import hullslice.readers as readers_module

    path = tmp_path / "locked.obj"
    path.write_text(TETRA_OBJ)

    def denied(*args, **kw):
        raise PermissionError(13, "Permission denied", str(args[0]))

    monkeypatch.setattr(readers_module, "open", denied, raising=False)
    with pytest.raises(hs.MeshError, match=r"locked.obj' cannot be read: Permission denied"):
        hs.load_hull(path)


def test_an_ascii_stl_read_in_small_chunks_is_the_same(tmp_path, monkeypatch):
    import hullslice.readers.stl as stl_module

    v, f = shapes.wedge_prism()
    path = tmp_path / "wedge.stl"
    path.write_text(ascii_stl({"hull": (v, f)}))
    whole = read_mesh(path)
    monkeypatch.setattr(stl_module, "_STL_CHUNK", 7)  # cuts inside every line
    chunked = read_mesh(path)
    assert np.array_equal(whole[0], chunked[0]) and np.array_equal(whole[1], chunked[1])
    assert np.array_equal(whole[0], v[f].reshape(-1, 3))
