"""The catalogue of bad inputs, each run through the command line, with what the user gets.

Each entry runs ``hullslice.cli.main`` in-process, with ``--format json -o OUT`` where the
command takes it:

- an **error** exits with status 2 and writes exactly one line on stderr, naming the
  problem, with no traceback; no output file (nor a temporary one) is left behind;
- a **repair** exits with status 0, shows its warning as one line on stderr, and writes a
  complete result that is checked against a reference (the clean body, a closed form);
- a **result** is a run that works although the input looks odd, checked the same way.

Entries marked as library calls (case files, before ``hullslice run`` exists) raise the
same errors from the Python API. The README's "Bad input" table is this catalogue:
``python -m tests.test_bad_input`` prints it, and a test checks that the two agree.
"""

from __future__ import annotations

import functools
import json
import struct
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import manifold3d
import numpy as np
import pytest
import trimesh

import hullslice as hs
from hullslice import shapes
from hullslice.cli import main

from .test_mesh_files import TETRA_OBJ, ascii_stl
from .test_registry import DEFAULT, ep

ROOT = Path(__file__).resolve().parents[1]

# the standard case: a 1 m prism of 30-degree wedge section, 0.2 m beam, 10 kg
MASS, DRAFT, VELOCITY, SLICES = 10.0, 0.03, -5.0, 8
H30 = 0.1 * np.tan(np.radians(30.0))  # its keel depth, m
STATE = ["--mass", "10", "--draft", "0.03", "--velocity=-5", "--slices", "8"]


# -- meshes ---------------------------------------------------------------------------------


def wedge():
    return shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0)


def box(extents=(1.0, 1.0, 1.0), center=(0.0, 0.0, 0.0)):
    b = trimesh.creation.box(extents=extents)
    b.apply_translation(center)
    return np.asarray(b.vertices), np.asarray(b.faces)


def stl(tmp: Path, name: str, v, f) -> str:
    path = tmp / name
    trimesh.Trimesh(np.asarray(v, dtype=float), np.asarray(f), process=False).export(path)
    return str(path)


def text(tmp: Path, name: str, content: str | bytes) -> str:
    path = tmp / name
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content)
    return str(path)


def join(*bodies):
    vs, fs, offset = [], [], 0
    for v, f in bodies:
        vs.append(v)
        fs.append(np.asarray(f) + offset)
        offset += len(v)
    return np.vstack(vs), np.vstack(fs)


def wedge_with(change: Callable[[np.ndarray, np.ndarray], tuple]):
    v, f = wedge()
    return change(v.copy(), f.copy())


def flip_one(v, f):
    f[5] = f[5, ::-1]
    return v, f


def degenerate(v, f):
    return v, np.vstack([f, [[0, 0, 1]]])


def repeated(v, f):
    return v, np.vstack([f, f[:3]])


def six_digit_soup(tmp: Path) -> str:
    # a CAD export: each triangle's corners computed apart (1e-6 noise), 6 digits written
    v, f = wedge()
    rng = np.random.default_rng(11)
    tri = (v[f] * (1.0 + rng.uniform(-1e-6, 1e-6, (len(f), 3, 3)))).reshape(-1, 3)
    soup = (tri, np.arange(len(tri)).reshape(-1, 3))
    return text(tmp, "six.stl", ascii_stl({"hull": soup}, ".6g"))


def catamaran():
    v, f = wedge()
    return join((v - np.array([0.0, 0.3, 0.0]), f), (v + np.array([0.0, 0.3, 0.0]), f))


def overlapping():
    # two 1 m prisms overlapping by 0.45 m: the body is one 1.55 m prism
    v, f = wedge()
    return join((v, f), (v + np.array([0.55, 0.0, 0.0]), f))


def twin_keels(tmp: Path) -> str:
    w = [[-0.3, 0.05], [-0.2, -0.1], [-0.1, 0.0], [0.1, 0.0], [0.2, -0.1], [0.3, 0.05]]
    mesh = manifold3d.CrossSection([w]).extrude(1.0).to_mesh()
    return stl(tmp, "w.stl", np.asarray(mesh.vert_properties)[:, :3], mesh.tri_verts)


def kinematics(tmp: Path, content: str | bytes) -> str:
    return text(tmp, "kin.csv", content)


# -- references --------------------------------------------------------------------------


@functools.cache
def wedge_force(mass: float = MASS) -> float:
    """The 2D+t force on the clean wedge prism in the standard state, N, with the
    coordinates an STL file stores (single precision)."""
    v, f = wedge()
    hull = hs.Hull.from_arrays(v.astype(np.float32).astype(np.float64), f, mass=mass)
    return hs.compute_force(hull, DRAFT, VELOCITY, slices=SLICES).total


def same_force(data: dict) -> None:
    # the same body as the clean file: the same force to rounding
    assert data["force"] == pytest.approx(wedge_force(), rel=1e-9)


def same_force_in_mm(data: dict) -> None:
    # the file holds the body in mm in single precision: 6e-8 relative from the metre file
    assert data["force"] == pytest.approx(wedge_force(), rel=1e-6)


def rounded_force(data: dict) -> None:
    # the corners moved by up to 1e-6 (noise) and 5e-6 (6 digits) of their coordinates:
    # the force of a body that close, within 2e-5 (it is 1.7e-6 off)
    assert data["force"] == pytest.approx(wedge_force(), rel=2e-5)


def catamaran_force(data: dict) -> None:
    # two floats moving together: each carries its own half of the mass (tests/test_parts.py)
    assert data["force"] == pytest.approx(2 * wedge_force(MASS / 2), rel=1e-5)
    assert [s["station"] for s in data["slices"]] == list(np.repeat(np.arange(SLICES), 2))
    # 10 kg over 1 m, half each
    assert [s["mass_per_metre"] for s in data["slices"]] == pytest.approx([5.0] * 2 * SLICES)
    assert data["valid"] is True


def union_sections(data: dict) -> None:
    # the union is a 1.55 m prism: one wedge section (not two added) along 1.55 m
    assert data["wetted_length"] == pytest.approx(1.55, rel=1e-7)
    assert [s["area"] for s in data["sections"]] == pytest.approx([0.1 * H30] * 4, rel=1e-6)


def tetra_sections(data: dict) -> None:
    # the section at x of the tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1): (1 - x)^2 / 2,
    # to manifold3d's single precision (1e-7 of the body's size in each coordinate)
    for s in data["sections"]:
        assert s["area"] == pytest.approx(0.5 * (1.0 - s["x"]) ** 2, rel=1e-6, abs=1e-9)


def scaled_sections(scale: float) -> Callable[[dict], None]:
    def check(data: dict) -> None:
        for s in data["sections"]:
            assert s["area"] == pytest.approx(0.1 * H30 * scale**2, rel=1e-6)
            assert s["deadrise_deg"] == pytest.approx(30.0, abs=1e-4)

    return check


def twin_keel_pieces(data: dict) -> None:
    # one entry per keel at each of the 4 stations, each with half the part's 10 kg/m
    assert [s["station"] for s in data["slices"]] == [0, 0, 1, 1, 2, 2, 3, 3]
    assert [s["mass_per_metre"] for s in data["slices"]] == pytest.approx([5.0] * 8)
    assert np.isfinite(data["force"])


def flagged_upward(data: dict) -> None:
    assert data["valid"] is False and np.isfinite(data["force"])
    assert all("section not moving down into the water" in s["reason"] for s in data["slices"])


def read_as_metres(data: dict) -> None:
    # computed as asked: a body 1000 m long, since the file was read in metres
    assert data["wetted_length"] == pytest.approx(1000.0, rel=1e-9)


# -- the catalogue --------------------------------------------------------------------------


@dataclass(frozen=True)
class Bad:
    """One bad input.

    Attributes
    ----------
    id : str
        Test id.
    input : str
        The bad input, as the README lists it.
    gets : str
        What the user gets, as the README lists it.
    argv : callable
        ``argv(tmp)`` makes the files in the folder ``tmp`` and returns the command line;
        None for a library call.
    error, warning : str
        A part of the one error line (exit 2) or of the one warning line (exit 0).
    check : callable, optional
        Checks the JSON result of a run that works.
    output : bool
        Add ``--format json -o OUT`` (the entries about ``-o`` give their own).
    call : callable, optional
        ``call(tmp)``: the library call of an entry without a command.
    """

    id: str
    input: str
    gets: str
    argv: Callable[[Path], list[str]] | None = None
    error: str = ""
    warning: str = ""
    check: Callable[[dict], None] | None = None
    output: bool = True
    call: Callable[[Path], object] | None = None


def wedge_file(tmp: Path) -> str:
    return stl(tmp, "wedge.stl", *wedge())


CATALOGUE: tuple[Bad, ...] = (
    # -- files
    Bad(
        "missing-file",
        "a mesh file that does not exist",
        "error: mesh file '...' does not exist",
        lambda t: ["sections", str(t / "nope.stl"), "--draft", "0.01"],
        error="does not exist",
    ),
    Bad(
        "directory",
        "a folder given as the mesh",
        "error: mesh path '...' is not a file",
        lambda t: ["sections", str(t), "--draft", "0.01"],
        error="is not a file",
    ),
    Bad(
        "empty-file",
        "an empty file",
        "error: mesh file '...' is empty",
        lambda t: ["sections", text(t, "empty.stl", b""), "--draft", "0.01"],
        error="is empty",
    ),
    Bad(
        "unknown-format",
        "an unknown format (`.step`, `.3mf`, ...)",
        "error: hullslice reads stl, obj: export the hull as STL or OBJ",
        lambda t: ["sections", text(t, "hull.step", "ISO-10303-21;\n"), "--draft", "0.01"],
        error="hullslice reads stl, obj",
    ),
    Bad(
        "binary-garbage",
        "binary garbage named `.stl`",
        "error: not a valid STL file: as a binary STL its header claims N triangles but the "
        "file has M bytes, and it does not start with 'solid'",
        lambda t: [
            "sections",
            text(t, "garbage.stl", np.random.default_rng(0).bytes(1000)),
            "--draft",
            "0.01",
        ],
        error="is not a valid STL file: as a binary STL its header claims",
    ),
    Bad(
        "absurd-count",
        "a binary STL whose header claims 2^31 triangles in 1 KB",
        "error: its header claims 2147483648 triangles (107 GB) but the file has 1024 bytes; "
        "nothing is allocated",
        lambda t: [
            "sections",
            text(t, "absurd.stl", b"\0" * 80 + struct.pack("<I", 2**31) + b"\1" * 940),
            "--draft",
            "0.01",
        ],
        error="claims 2147483648 triangles (107374182484 bytes) but the file has 1024 bytes",
    ),
    Bad(
        "text-not-a-mesh-stl",
        "text that is not a mesh, named `.stl`",
        "error: it does not start with 'solid' as an ASCII STL does",
        lambda t: ["sections", text(t, "notes.stl", "hull notes\n" * 20), "--draft", "0.01"],
        error="does not start with 'solid'",
    ),
    Bad(
        "text-not-a-mesh-obj",
        "text that is not a mesh, named `.obj`",
        "error: mesh file '...' holds no triangles",
        lambda t: ["sections", text(t, "notes.obj", "hull notes\n" * 20), "--draft", "0.01"],
        error="holds no triangles",
    ),
    Bad(
        "binary-obj",
        "binary data named `.obj`",
        "error: it holds binary data; an OBJ is a text file",
        lambda t: ["sections", text(t, "b.obj", b"v 0 0 0\n\0\1\2"), "--draft", "0.01"],
        error="an OBJ is a text file",
    ),
    Bad(
        "obj-index-out-of-range",
        "a face index out of range (OBJ)",
        "error: line N: a face refers to a vertex that does not exist",
        lambda t: [
            "sections",
            text(t, "bad.obj", TETRA_OBJ.replace("f 2 3 4", "f 2 3 3000000000")),
            "--draft",
            "0.01",
        ],
        error="line 8: a face refers to a vertex that does not exist (the file has 4 vertices)",
    ),
    Bad(
        "obj-index-zero",
        "a face index 0 (OBJ counts from 1)",
        "error: line N: face index 0 does not exist",
        lambda t: [
            "sections",
            text(t, "zero.obj", TETRA_OBJ.replace("f 1 3 2", "f 0 3 2")),
            "--draft",
            "0.01",
        ],
        error="line 5: face index 0 does not exist (OBJ counts vertices from 1)",
    ),
    Bad(
        "obj-materials",
        "an OBJ naming material files (`mtllib ../../etc/passwd`)",
        "result: the geometry only; no other file is opened",
        lambda t: [
            "sections",
            text(t, "m.obj", "mtllib ../../etc/passwd\nusemtl steel\n" + TETRA_OBJ),
            "--draft",
            "1",
        ],
        check=tetra_sections,
    ),
    Bad(
        "obj-not-utf8",
        "an OBJ that is not UTF-8 (a Latin-1 comment)",
        "result: read as it is; the bad bytes are in comments or names",
        lambda t: [
            "sections",
            text(t, "k.obj", ("# K\xf6ln\n" + TETRA_OBJ).encode("latin-1")),
            "--draft",
            "1",
        ],
        check=tetra_sections,
    ),
    # -- bodies that are not closed 2-manifolds
    Bad(
        "open",
        "an open mesh (holes)",
        "error: mesh '...' is open: N edges belong to a single face",
        lambda t: [
            "sections",
            stl(t, "open.stl", *wedge_with(lambda v, f: (v, f[1:]))),
            "--draft",
            "0.01",
        ],
        error="is open: 3 edges belong to a single face",
    ),
    Bad(
        "non-manifold",
        "a non-manifold mesh (an edge shared by 4 faces)",
        "error: mesh '...' is not manifold: N edges are shared by more than two faces",
        lambda t: [
            "sections",
            stl(t, "touch.stl", *join(box(center=(0, 0, 0)), box(center=(1, 1, 0)))),
            "--draft",
            "0.1",
        ],
        error="is not manifold: 1 edges are shared by more than two faces",
    ),
    Bad(
        "nan",
        "NaN coordinates",
        "error: N vertices have NaN or infinite coordinates (first: vertex i = [...])",
        lambda t: [
            "sections",
            text(t, "nan.obj", TETRA_OBJ.replace("v 0 0 1", "v 0 nan 1")),
            "--draft",
            "0.01",
        ],
        error="1 vertices have NaN or infinite coordinates (first: vertex 3 = [0.0, nan, 1.0])",
    ),
    Bad(
        "inf",
        "infinite coordinates",
        "error: the same, quoting the vertex",
        lambda t: [
            "sections",
            text(t, "inf.obj", TETRA_OBJ.replace("v 1 0 0", "v inf 0 0")),
            "--draft",
            "0.01",
        ],
        error="(first: vertex 1 = [inf, 0.0, 0.0])",
    ),
    Bad(
        "flat",
        "a flat mesh of zero volume",
        "error: mesh '...' encloses no volume: a flat or zero-thickness surface",
        lambda t: [
            "sections",
            text(t, "flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n"),
            "--draft",
            "0.01",
        ],
        error="encloses no volume",
    ),
    # -- repaired with a warning
    Bad(
        "inside-out",
        "an inside-out mesh",
        "repaired, warning: the mesh was inside out; all faces were flipped",
        lambda t: ["force", stl(t, "io.stl", *wedge_with(lambda v, f: (v, f[:, ::-1]))), *STATE],
        warning="the mesh was inside out (negative volume); all faces were flipped",
        check=same_force,
    ),
    Bad(
        "one-face-flipped",
        "one face flipped",
        "repaired, warning: re-oriented 1 faces whose winding disagreed with their neighbours",
        lambda t: ["force", stl(t, "flip.stl", *wedge_with(flip_one)), *STATE],
        warning="re-oriented 1 faces whose winding disagreed",
        check=same_force,
    ),
    Bad(
        "overlapping-shells",
        "overlapping shells",
        "repaired, warning: N shells overlap; the body is taken as their union",
        lambda t: [
            "sections",
            stl(t, "two.stl", *overlapping()),
            "--draft",
            str(H30),
            "--slices",
            "4",
        ],
        warning="2 shells overlap (their volumes add to 0.011547 m^3, their union is "
        "0.00894893 m^3); the body is taken as their union",
        check=union_sections,
    ),
    Bad(
        "soup-exact",
        "an STL triangle soup (every STL: three corners per triangle)",
        "result: identical corners merged silently",
        lambda t: ["force", wedge_file(t), *STATE],
        check=same_force,
    ),
    Bad(
        "soup-rounded",
        "an unmerged STL soup whose copies of a vertex differ by rounding (6 digits)",
        "repaired, warning: merged N vertices closer than D m to close the surface",
        lambda t: ["force", six_digit_soup(t), *STATE],
        warning="vertices closer than",
        check=rounded_force,
    ),
    Bad(
        "degenerate",
        "degenerate faces (a repeated vertex)",
        "repaired, warning: removed N degenerate faces",
        lambda t: ["force", stl(t, "deg.stl", *wedge_with(degenerate)), *STATE],
        warning="removed 1 degenerate faces (a repeated vertex)",
        check=same_force,
    ),
    Bad(
        "repeated-faces",
        "the same triangle written twice",
        "repaired, warning: removed N repeated faces",
        lambda t: ["force", stl(t, "rep.stl", *wedge_with(repeated)), *STATE],
        warning="removed 3 repeated faces",
        check=same_force,
    ),
    # -- units and scale
    Bad(
        "mm-read-as-m",
        "a mesh in mm read as metres (with a mass)",
        "warning: mass M kg in a volume of V m^3 is a density of D kg/m^3, implausible; if the "
        "mesh is in millimetres, give its units (--units mm); computed as asked",
        lambda t: [
            "force",
            stl(t, "mm.stl", wedge()[0] * 1000.0, wedge()[1]),
            "--mass",
            "10",
            "--draft",
            "0.01",
            "--velocity=-5",
            "--slices",
            "4",
        ],
        warning="if the mesh is in millimetres, give its units (units='mm', --units mm): the "
        "density is then 1732 kg/m^3",
        check=read_as_metres,
    ),
    Bad(
        "units-upper-case",
        "`--units MM`",
        "result: units are case-insensitive",
        lambda t: [
            "force",
            stl(t, "mm.stl", wedge()[0] * 1000.0, wedge()[1]),
            "--units",
            "MM",
            *STATE,
        ],
        check=same_force_in_mm,
    ),
    Bad(
        "units-unknown",
        "an unknown unit (`--units yd`)",
        "error: invalid choice: 'yd' (choose from m, cm, mm, in, ft)",
        lambda t: ["sections", wedge_file(t), "--draft", "0.01", "--units", "yd"],
        error="invalid choice: 'yd'",
    ),
    Bad(
        "tiny",
        "a tiny body (1e-9 m)",
        "result: cut as accurately as a metre-sized one",
        lambda t: [
            "sections",
            stl(t, "tiny.stl", wedge()[0] * 1e-9, wedge()[1]),
            "--draft",
            "3e-11",
            "--slices",
            "4",
        ],
        check=scaled_sections(1e-9),
    ),
    Bad(
        "huge",
        "a huge body (1e9 m)",
        "result: cut as accurately as a metre-sized one",
        lambda t: [
            "sections",
            stl(t, "huge.stl", wedge()[0] * 1e9, wedge()[1]),
            "--draft",
            "3e7",
            "--slices",
            "4",
        ],
        check=scaled_sections(1e9),
    ),
    Bad(
        "tetrahedron",
        "a single tetrahedron",
        "result: a body like any other",
        lambda t: ["sections", text(t, "t.obj", TETRA_OBJ), "--draft", "1"],
        check=tetra_sections,
    ),
    # -- several bodies
    Bad(
        "disjoint-bodies",
        "several disjoint bodies (a catamaran's two floats)",
        "result: one entry per float at each station, each with its own mass; the force is "
        "the sum of the floats'",
        lambda t: [
            "force",
            stl(t, "cat.stl", *catamaran()),
            "--mass",
            "10",
            "--draft",
            "0.03",
            "--velocity=-5",
            "--slices",
            "8",
        ],
        check=catamaran_force,
    ),
    Bad(
        "twin-keels",
        "a section meeting the water in several places (twin keels joined above it)",
        "result: one entry per wetted piece, the part's mass shared by their widths",
        lambda t: [
            "force",
            twin_keels(t),
            "--up",
            "y",
            "--forward",
            "z",
            "--mass",
            "10",
            "--draft",
            "0.05",
            "--velocity=-5",
            "--slices",
            "4",
        ],
        check=twin_keel_pieces,
    ),
    # -- values
    Bad(
        "upward-velocity-force",
        "an upward velocity at one state (`force`)",
        "result, flagged invalid: 'section not moving down into the water'",
        lambda t: ["force", wedge_file(t), *STATE, "--velocity=5"],
        check=flagged_upward,
    ),
    Bad(
        "mass-zero",
        "zero mass",
        "error: mass 0.0 kg is not positive: give the body's mass in kg",
        lambda t: ["force", wedge_file(t), *STATE, "--mass", "0"],
        error="mass 0.0 kg is not positive",
    ),
    Bad(
        "mass-negative",
        "negative mass",
        "error: the same",
        lambda t: ["force", wedge_file(t), *STATE, "--mass=-10"],
        error="mass -10.0 kg is not positive",
    ),
    Bad(
        "mass-inf",
        "`--mass inf` or `nan`",
        "error: the same",
        lambda t: ["force", wedge_file(t), *STATE, "--mass", "inf"],
        error="mass inf kg is not positive",
    ),
    Bad(
        "upward-velocity",
        "an upward initial velocity (`simulate`)",
        "error: initial velocity 4 m/s is not downward: give a negative vertical velocity",
        lambda t: ["simulate", wedge_file(t), "--mass", "10", "--velocity=4", "--t-end", "0.01"],
        error="initial velocity 4 m/s is not downward",
    ),
    Bad(
        "draft-too-deep",
        "a draft deeper than the body",
        "error: draft D m is deeper than the body's height H m",
        lambda t: ["sections", wedge_file(t), "--draft", "0.5"],
        error="draft 0.5 m is deeper than the body's height 0.057735 m",
    ),
    Bad(
        "draft-nan",
        "`--draft nan` or a negative draft",
        "error: draft nan is not a finite number: give one in m",
        lambda t: ["sections", wedge_file(t), "--draft", "nan"],
        error="draft nan is not a finite number: give one in m",
    ),
    Bad(
        "slices-zero",
        "zero slices",
        "error: argument --slices: '0' is not positive (give 1 or more)",
        lambda t: ["sections", wedge_file(t), "--draft", "0.01", "--slices", "0"],
        error="'0' is not positive (give 1 or more)",
    ),
    Bad(
        "slices-negative",
        "negative slices",
        "error: the same",
        lambda t: ["force", wedge_file(t), *STATE, "--slices=-8"],
        error="'-8' is not positive (give 1 or more)",
    ),
    Bad(
        "slices-not-whole",
        "`--slices 1e3`",
        "error: '1e3' is not a whole number",
        lambda t: ["force", wedge_file(t), *STATE, "--slices", "16,1e3"],
        error="'1e3' is not a whole number",
    ),
    Bad(
        "slices-too-many",
        "more than 100000 slices",
        "error: slice count N is more than the 100000 hullslice allows",
        lambda t: ["sections", wedge_file(t), "--draft", "0.01", "--slices", "100000000"],
        error="slice count 100000000 is more than the 100000 hullslice allows",
    ),
    Bad(
        "rho-zero",
        "`--rho 0`",
        "error: water density 0.0 kg/m^3 is not positive (try 1000)",
        lambda t: ["force", wedge_file(t), *STATE, "--rho", "0"],
        error="water density 0.0 kg/m^3 is not positive",
    ),
    Bad(
        "dt-longer-than-run",
        "a time step longer than the run",
        "error: time step 1 s is longer than the run (0.01 s): shorten it",
        lambda t: [
            "simulate",
            wedge_file(t),
            "--mass",
            "10",
            "--velocity=-5",
            "--t-end",
            "0.01",
            "--dt",
            "1",
        ],
        error="time step 1 s is longer than the run (0.01 s)",
    ),
    Bad(
        "too-many-steps",
        "a run of more than 1e6 time steps",
        "error: ... is 1e+12 steps, more than the 1000000 hullslice allows",
        lambda t: [
            "simulate",
            wedge_file(t),
            "--mass",
            "10",
            "--velocity=-5",
            "--t-end",
            "1",
            "--dt",
            "1e-12",
        ],
        error="is 1e+12 steps, more than the 1000000 hullslice allows",
    ),
    Bad(
        "step-through-the-impact",
        "a time step in which the body moves more than a tenth of its height",
        "error: time step ... moves the body D m a step, more than 0.1 of its height; give a "
        "time step below ... s",
        lambda t: [
            "simulate",
            wedge_file(t),
            "--mass",
            "10",
            "--velocity=-50",
            "--t-end",
            "0.01",
            "--dt",
            "0.001",
        ],
        error="moves the body 0.05 m a step, more than 0.1 of its height 0.057735 m",
    ),
    # -- kinematics
    Bad(
        "kinematics-missing-columns",
        "a kinematics CSV with missing columns",
        "error: kinematics file '...' lacks the column(s) penetration",
        lambda t: [
            "simulate",
            wedge_file(t),
            "--mass",
            "10",
            "--kinematics",
            kinematics(t, "t,velocity\n0,-5\n"),
        ],
        error="lacks the column(s) penetration (its header: t, velocity)",
    ),
    Bad(
        "kinematics-backwards",
        "a kinematics CSV with time going backwards",
        "error: kinematics time goes backwards or repeats at row N: sort the table by time",
        lambda t: [
            "simulate",
            wedge_file(t),
            "--mass",
            "10",
            "--kinematics",
            kinematics(t, "t,penetration,velocity\n0,0,-5\n0.002,0.01,-5\n0.001,0.005,-5\n"),
        ],
        error="time goes backwards or repeats at row 3 (t = 0.002 s, then 0.001 s)",
    ),
    Bad(
        "kinematics-binary",
        "a kinematics file that is not text",
        "error: kinematics file '...' is not UTF-8 text",
        lambda t: [
            "simulate",
            wedge_file(t),
            "--mass",
            "10",
            "--kinematics",
            kinematics(t, b"\x80\x81\x82"),
        ],
        error="is not UTF-8 text (byte 0)",
    ),
    Bad(
        "kinematics-acceleration-disagrees",
        "a kinematics CSV whose acceleration column disagrees with its velocity",
        "error: kinematics acceleration disagrees with velocity: integrated from t = ... it "
        "changes the velocity by ... m/s, the velocity column by ... m/s",
        lambda t: [
            "simulate",
            wedge_file(t),
            "--solver",
            "wagner",
            "--kinematics",
            kinematics(
                t,
                "t,penetration,velocity,acceleration\n0,0,-5,100\n0.001,0.005,-5,100\n"
                "0.002,0.01,-5,100\n",
            ),
        ],
        error="changes the velocity by 0.2 m/s, the velocity column by 0 m/s",
    ),
    Bad(
        "kinematics-too-short",
        "a prescribed motion too short to differentiate (momentum-form solver)",
        "error: the kinematics table has 2 row(s), too few to differentiate velocity in time "
        "(three at least): give more rows or an acceleration column",
        lambda t: [
            "simulate",
            wedge_file(t),
            "--solver",
            "wagner",
            "--kinematics",
            kinematics(t, "t,penetration,velocity\n0,0,-5\n0.001,0.005,-4.9\n"),
        ],
        error="has 2 row(s), too few to differentiate velocity in time",
    ),
    Bad(
        "flagged-share-out-of-range",
        "`--max-flagged-share 1.5` (or NaN)",
        "error: largest flagged share 1.5 is not in [0, 1]: give the share of the force that "
        "flagged slices may carry before a run stops (default 0.1)",
        lambda t: [
            "simulate",
            wedge_file(t),
            "--mass",
            "10",
            "--velocity=-5",
            "--t-end",
            "0.01",
            "--max-flagged-share",
            "1.5",
        ],
        error="largest flagged share 1.5 is not in [0, 1]",
    ),
    # -- solvers
    Bad(
        "unknown-solver",
        "an unknown solver",
        "error: no solver named '...' is installed; installed solvers: ...",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "nope"],
        error="no solver named 'nope'",
    ),
    Bad(
        "solver-nan",
        "a solver returning NaN",
        "error: solver '...' returned a non-finite force per metre for N of M sections "
        "(first: x, penetration, deadrise, mass per metre, velocity)",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "nan"],
        error="returned a non-finite force per metre for 8 of 8 sections (first: x = 0.0625 m",
    ),
    # -- output
    Bad(
        "output-missing-folder",
        "`-o` into a folder that does not exist",
        "error: cannot write '...': the folder '...' does not exist; create it first",
        lambda t: ["sections", wedge_file(t), "--draft", "0.01", "-o", str(t / "no" / "x.csv")],
        error="the folder",
        output=False,
    ),
    Bad(
        "output-is-a-folder",
        "`-o` onto a folder",
        "error: cannot write '...': it is a folder; give a file name in it",
        lambda t: ["sections", wedge_file(t), "--draft", "0.01", "-o", str(t)],
        error="it is a folder; give a file name in it",
        output=False,
    ),
    Bad(
        "output-is-the-input",
        "`-o` onto the input mesh",
        "error: cannot write '...': it is the input mesh file and would be overwritten",
        lambda t: ["sections", wedge_file(t), "--draft", "0.01", "-o", str(t / "wedge.stl")],
        error="it is the input mesh file and would be overwritten",
        output=False,
    ),
    # -- case files (library: hullslice.load_case)
    Bad(
        "case-unknown-key",
        "a case file with an unknown key (`load_case`)",
        "error: unknown key 'mas'; did you mean 'mass'? the keys are ...",
        call=lambda t: hs.load_case(text(t, "c.toml", "mesh = 'hull.stl'\nmas = 1.0\n")),
        error="unknown key 'mas'; did you mean 'mass'?",
    ),
    Bad(
        "case-wrong-type",
        "a case file with a value of the wrong type (`load_case`)",
        "error: key 'mass' must be a number in kg (mass of the body), not the text '1.0'",
        call=lambda t: hs.load_case(text(t, "c.toml", "mesh = 'hull.stl'\nmass = '1.0'\n")),
        error="key 'mass' must be a number in kg (mass of the body), not the text '1.0' (write "
        "the number without quotes)",
    ),
)


def kind(bad: Bad) -> str:
    return "error" if bad.error else "repair" if bad.warning else "result"


# -- running it -------------------------------------------------------------------------------


@pytest.fixture
def nan_solver_installed(fake_entry_points):
    fake_entry_points([DEFAULT, ep("nan", "tests.fake_solvers:NaNSolver")])


@pytest.mark.parametrize("bad", CATALOGUE, ids=[b.id for b in CATALOGUE])
def test_bad_input(bad: Bad, tmp_path, capsys, request):
    work = tmp_path / "in"
    work.mkdir()
    out_dir = tmp_path / "out"
    out_dir.mkdir()
    out = out_dir / "result.json"
    if bad.call is not None:
        with pytest.raises(hs.HullsliceError) as info:
            bad.call(work)
        assert bad.error in str(info.value)
        return
    if bad.id == "solver-nan":
        request.getfixturevalue("nan_solver_installed")
    argv = bad.argv(work)
    if bad.output:
        argv += ["--format", "json", "-o", str(out)]
    before = {p: p.read_bytes() for p in work.rglob("*") if p.is_file()}

    code = main(argv)
    stdout, stderr = capsys.readouterr()
    lines = stderr.splitlines()

    assert "Traceback" not in stderr
    after = {p: p.read_bytes() for p in work.rglob("*") if p.is_file()}
    assert after == before  # inputs untouched, nothing written beside them
    if bad.error:
        assert code == 2, stderr
        assert len(lines) == 1, stderr
        assert "error:" in lines[0] and bad.error in lines[0]
        assert stdout == ""
        assert list(out_dir.iterdir()) == []  # no file, complete or partial
        return
    assert code == 0, stderr
    expected = [f"wrote {out}"]
    if bad.warning:
        assert len(lines) == 2, stderr
        assert lines[0].startswith("hullslice: warning: ") and bad.warning in lines[0]
        expected.insert(0, lines[0])
    assert lines == expected
    assert [p.name for p in out_dir.iterdir()] == ["result.json"]
    data = json.loads(out.read_text())
    assert bad.check is not None
    bad.check(data)


def test_a_failure_after_the_work_leaves_no_file(tmp_path, capsys, monkeypatch):
    # the report cannot be written (disk full, ...): the target is absent, not half written
    from hullslice import report

    def fail(fh_write):
        def write(data):
            fh_write(data[: len(data) // 2])
            raise OSError(28, "No space left on device")

        return write

    real_fdopen = report.os.fdopen

    def fdopen(*args, **kw):
        fh = real_fdopen(*args, **kw)
        fh.write = fail(fh.write)
        return fh

    monkeypatch.setattr(report.os, "fdopen", fdopen)
    target = tmp_path / "force.json"
    code = main(["force", wedge_file(tmp_path), *STATE, "--format", "json", "-o", str(target)])
    _, stderr = capsys.readouterr()
    assert code == 2
    assert (
        stderr.strip() == f"hullslice: error: cannot write {str(target)!r}: No space left on device"
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["wedge.stl"]


# -- the README's table ---------------------------------------------------------------------


def readme_table() -> str:
    """The catalogue as the README's Markdown table."""
    rows = ["| Bad input | What you get |", "| --- | --- |"]
    rows += [f"| {b.input} | {b.gets} |" for b in CATALOGUE]
    return "\n".join(rows)


def test_the_readme_lists_every_bad_input():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "## Bad input" in readme
    section = readme.split("## Bad input", 1)[1].split("\n## ", 1)[0]
    assert readme_table() in section, (
        "the README's Bad input table differs from the catalogue: "
        "paste the output of 'python -m tests.test_bad_input'"
    )


def test_the_catalogue_covers_the_issue_list():
    ids = {b.id for b in CATALOGUE}
    issue = {
        "missing-file", "empty-file", "unknown-format", "binary-garbage", "text-not-a-mesh-stl",
        "open", "non-manifold", "nan", "inf", "obj-index-out-of-range", "inside-out",
        "one-face-flipped", "overlapping-shells", "soup-rounded", "degenerate", "mm-read-as-m",
        "disjoint-bodies", "mass-zero", "mass-negative", "upward-velocity", "draft-too-deep",
        "slices-zero", "slices-negative", "dt-longer-than-run", "kinematics-missing-columns",
        "kinematics-backwards", "case-unknown-key", "case-wrong-type", "solver-nan",
        "absurd-count",
    }  # fmt: skip
    assert issue <= ids
    assert len(ids) == len(CATALOGUE)
    assert {kind(b) for b in CATALOGUE} == {"error", "repair", "result"}


if __name__ == "__main__":
    print(readme_table())
