"""The catalogue of bad inputs, each run through the command line, with what the user gets.

Each entry runs ``hullslice.cli.main`` in-process, with ``--format json -o OUT`` where the
command takes it:

- an **error** exits with status 2 (a command line that does not parse) or 3 (inputs that
  are refused) and writes exactly one line on stderr, naming the problem, with no
  traceback; no output file (nor a temporary one) is left behind;
- a **repair** exits with status 0, shows its warning as one line on stderr, and writes a
  complete result that is checked against a reference (the clean body, a closed form);
- a **result** is a run that works although the input looks odd, checked the same way.

Entries marked as library calls (case files, before ``hullslice run`` exists) raise the
same errors from the Python API. An entry about a plugin that ends or crashes its process
runs in a process of its own, with ``hullslice --isolate``; one about a sweep writes
``result.nc`` (read back with xarray). The "Bad input" table of docs/meshes.md is this catalogue:
``python -m tests.test_bad_input`` prints it, and a test checks that the two agree.
"""

from __future__ import annotations

import functools
import json
import os
import re
import signal
import struct
import subprocess
import sys
import time
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
from hullslice.safety import Terminated, _raise_terminated, terminated_cleanly

from .test_mesh_files import TETRA_OBJ, ascii_stl
from .test_registry import DEFAULT, ep

ROOT = Path(__file__).resolve().parents[1]

#: The error line of a command line that does not parse: ``hullslice COMMAND: error: ...``.
USAGE = re.compile(r"hullslice [a-z]+: error: ")

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


def open_deck(v, f):
    # one triangle of the flat deck taken away: a hole above the water
    top = np.flatnonzero(np.all(np.isclose(v[f][:, :, 2], v[:, 2].max()), axis=1))
    return v, np.delete(f, top[0], axis=0)


def three_floats():
    v, f = wedge()
    return join(*[(v + np.array([0.0, 0.3 * k, 0.0]), f) for k in range(3)])


def with_stray_shell():
    # a small box 50 m away: a part of the export that is not the hull
    return join(wedge(), box((0.01, 0.01, 0.01), (50.0, 0.0, 0.0)))


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


def scaled_back_force(data: dict) -> None:
    # the body 2.5 times larger in single precision, scaled back to 1 m: within rounding
    assert data["force"] == pytest.approx(wedge_force(), rel=1e-6)


def along_y(data: dict) -> None:
    # read as asked: 0.2 m long along x, 1 m wide; the file's extents say which is which
    assert data["length"] == pytest.approx(0.2, rel=1e-6)
    assert data["orientation"]["mesh_extents"]["y"] == pytest.approx(1.0, rel=1e-6)
    assert data["orientation"]["longest_axis"] == "y"


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
        The bad input, as docs/meshes.md lists it.
    gets : str
        What the user gets, as docs/meshes.md lists it.
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
    plugins : tuple of str
        Solvers of ``tests/fake_solvers.py`` installed for the run, by name.
    read : callable, optional
        ``read(out)``: the result at the output path for ``check`` (default: its JSON).
    status : int
        Exit status of an error: 2 for a command line that does not parse (usage), 3 for
        inputs that parse and are refused.
    more_warnings : tuple of str
        Parts of the warning lines after the first, one each, in order (a repair that
        does more than one thing).
    interrupt : int
        A signal sent to the run (in a process of its own) once its solver has started:
        the run must end with status 128 + the signal, one line, and no file.
    process : bool
        Run the command line in a process of its own (a plugin that ends or crashes its
        process), with ``--isolate`` before the command.
    printed : tuple of str
        Lines a plugin prints, expected on stderr (never on stdout) before the command's own.
    relative : bool
        Run in the output folder with the relative ``-o result.json``.
    out_name : str
        The output's file name (a sweep writes ``result.nc``).
    fixture : str
        A fixture of this module the entry needs (a Dask scheduler), set up before ``argv``.
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
    plugins: tuple[str, ...] = ()
    read: Callable[[Path], dict] | None = None
    interrupt: int = 0
    status: int = 3
    more_warnings: tuple[str, ...] = ()
    process: bool = False
    printed: tuple[str, ...] = ()
    relative: bool = False
    out_name: str = "result.json"
    fixture: str = ""


def wedge_file(tmp: Path) -> str:
    return stl(tmp, "wedge.stl", *wedge())


STATE_TOML = "mass = 10.0\ndraft = 0.03\nvelocity = -5.0\nslices = [8]\n"


def case_file(tmp: Path, extra: str = "", mesh: str = "wedge.stl") -> str:
    """A case of the standard state in ``tmp/case``, with its mesh beside it."""
    folder = tmp / "case"
    folder.mkdir(exist_ok=True)
    stl(folder, mesh, *wedge())
    return text(folder, "c.toml", f"mesh = {json.dumps(mesh)}\n{STATE_TOML}{extra}")


def result_of(tmp: Path) -> Path:
    """The output path the test gives (``OUT`` of the module's docstring)."""
    return tmp.parent / "out" / "result.json"


def link_out(tmp: Path) -> str:
    # a folder in the case's folder that is a link to a folder beside it
    (tmp / "victim").mkdir()
    path = case_file(tmp, 'output = "out/result.json"\n')
    (tmp / "case" / "out").symlink_to(tmp / "victim", target_is_directory=True)
    return path


NEWLINE_NAME = "hull\nrm -rf ~\n.stl"


def escaped_table(data: dict) -> None:
    # the name's line breaks written as \n: no line of the output is the planted one, and
    # the heading starts with the escaped name; the force is the clean wedge's
    lines = data["text"].splitlines()
    assert "rm -rf ~" not in lines and not any(ln.startswith("rm") for ln in lines)
    assert lines[0].startswith("hull\\nrm -rf ~\\n: ")
    force = next(ln for ln in lines if ln.startswith("force "))
    assert float(force.split()[1]) == pytest.approx(wedge_force(), rel=1e-4)


def read_text(out: Path) -> dict:
    return {"text": out.read_text(encoding="utf-8")}


def read_report(out: Path) -> dict:
    return {
        "md": (out / "report.md").read_text(encoding="utf-8"),
        "case": hs.load_case(out / "case.toml"),
        "results": json.loads((out / "results.json").read_text()),
    }


TITLE = 'Run 1 | <img src=x onerror=alert(1)>\n# [click](http://x) `x` "q" \\ end'


def escaped_report(data: dict) -> None:
    md = data["md"].splitlines()
    # the title is one heading line, its markup escaped; no raw HTML reaches the page
    assert md[0] == (
        r"# Run 1 \| \<img src=x onerror=alert(1)\>\\n\# \[click\](http://x) \`x\` "
        r'"q" \\ end'
    )
    assert "<img" not in data["md"].replace(r"\<img", "")
    # the inputs table keeps three cells a row, the mesh's file name escaped
    rows = [ln for ln in md if ln.startswith("| mesh |")]
    assert rows == [r"| mesh | hull\\nrm -rf \~\\n.stl |  |"]
    # case.toml reads back the same title and mesh file, and the same force
    assert data["case"]["title"] == TITLE
    assert data["case"]["mesh"].name == NEWLINE_NAME
    assert data["results"]["force"] == pytest.approx(wedge_force(), rel=1e-4)


def table_csv(tmp: Path) -> str:
    return text(tmp, "accel.csv", "accel\n100\n")


def table_force(data: dict) -> None:
    # f = M * 100 m/s^2 over the wetted 0.03 / tan(30 deg) ... : the mass per metre is 10 kg/m
    assert data["force"] == pytest.approx(10.0 * 100.0 * data["wetted_length"], rel=1e-6)


def link_to_mesh(tmp: Path) -> str:
    wedge_file(tmp)
    (tmp / "link.stl").symlink_to(tmp / "wedge.stl")
    return str(tmp / "link.stl")


def case_reading_table(tmp: Path) -> str:
    # a case in tmp/case that reads tmp/accel.csv
    table_csv(tmp)
    return case_file(tmp, 'solver = "table"\n[solver_options]\ntable = "../accel.csv"\n')


def corner_through_bottom():
    # a 1 m box whose top corner (0.5, 0.5, 0.5) is pushed down through the bottom to z = -1
    v, f = box()
    v = v.copy()
    v[np.flatnonzero((v == 0.5).all(axis=1))[0]] = [0.5, 0.5, -1.0]
    return v, f


def keel_through_deck():
    # the wedge prism with the keel of its middle stations pushed up through the deck
    v, f = wedge()
    v = v.copy()
    keel = (v[:, 2] < -0.01) & (v[:, 0] > 0.25) & (v[:, 0] < 0.75)
    v[keel, 2] = 0.05
    return v, f


def obj_text(v, f) -> str:
    rows = [f"v {x!r} {y!r} {z!r}" for x, y, z in np.asarray(v, dtype=float).tolist()]
    return "\n".join(rows + [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in f]) + "\n"


def far_open(tmp: Path) -> str:
    # the wedge without one face, 1e6 m from the origin, in double precision: a merge whose
    # distance grew with the coordinates would take every vertex for a copy of every other
    v, f = wedge()
    return text(tmp, "far.obj", obj_text(v + np.array([1e6, 0.0, 0.0]), f[1:]))


def stray_vertex(tmp: Path) -> str:
    # a closed fuselage plus one stray triangle 1e9 m away
    v, f = shapes.fuselage(stations=40, points=24)
    v = np.vstack([v, [[1e9, 0.0, 0.0], [1e9, 1.0, 0.0], [1e9, 0.0, 1.0]]])
    f = np.vstack([f, [[len(v) - 3, len(v) - 2, len(v) - 1]]])
    return stl(tmp, "stray.stl", v, f)


def nose_hole(tmp: Path) -> str:
    # the full-scale fuselage (128k faces) as an STL triangle soup without the two faces at
    # its nose tip, where many vertices lie within 4 mm: merging them once closed the hole
    v, f = shapes.fuselage(stations=400, points=160)
    tip = int(np.argmax(v[f].mean(axis=1)[:, 0]))
    nb = next(i for i in range(len(f)) if i != tip and len(set(f[i]) & set(f[tip])) == 2)
    return stl(tmp, "hole.stl", v, np.delete(f, [tip, nb], axis=0))


def continuation_obj(tmp: Path) -> str:
    # 2 MB of backslash continuation lines: one statement, read in linear time and refused
    return text(tmp, "cont.obj", TETRA_OBJ + "f 1 2 \\\n" + "3 \\\n" * 2**19)


def tiny_far_shell():
    # the wedge and a copy 1e4 times smaller 50 m behind it (well above the water)
    v, f = wedge()
    return join((v, f), (v * 1e-4 + np.array([50.0, 0.0, 0.0]), f))


def inside_out_overlap():
    # the two overlapping prisms of overlapping(), the second wound inside out: not a
    # cavity (it is not inside the first), so turned outward and united
    v, f = wedge()
    return join((v, f), (v + np.array([0.55, 0.0, 0.0]), f[:, ::-1]))


def far_open_obj(tmp: Path) -> str:
    # the wedge without one face, 1e5 m out along x, in double precision
    v, f = wedge()
    return text(tmp, "far.obj", obj_text(v + np.array([1e5, 0.0, 0.0]), f[1:]))


def far_away_shell():
    # the wedge and a 1 cm box 1e4 m ahead of it, 50 m up (out of the water)
    return join(wedge(), box((0.01, 0.01, 0.01), (1e4, 0.0, 50.0)))


def aircraft_export(tmp: Path) -> str:
    from .aircraft_export import light_aircraft

    path = tmp / "pa.stl"
    trimesh.Trimesh(*light_aircraft(), process=False).export(path)
    return str(path)


@functools.cache
def closed_fuselage_volume() -> float:
    """The volume of the aircraft export's fuselage shell without its holes, m^3 (float32
    coordinates, as the STL stores them)."""
    from .aircraft_export import closed_fuselage

    v, f = closed_fuselage()
    return hs.Hull.from_arrays(v.astype(np.float32).astype(np.float64), f).volume


def fuselage_kept(data: dict) -> None:
    # the 7 m fuselage, within 1 % of the closed shell's volume (0.016 % measured), not the
    # 1.62 m^3 wing nor the fin and antenna welded to it
    assert data["volume"] == pytest.approx(closed_fuselage_volume(), rel=0.01)
    assert data["length"] == pytest.approx(7.0, rel=1e-6)
    assert data["kept"] == [1]


def shells_listed(data: dict) -> None:
    # not loaded, described: the fuselage first (it closes alone), the inside-out wing
    # (1.2 x 9 x 0.15 m) second; the fin welded to the fuselage would be dropped
    assert data["loaded"] is False and len(data["shells"]) == 64
    first, second = data["shells"][:2]
    assert first["volume"] == pytest.approx(closed_fuselage_volume(), rel=0.01)
    assert second["inside_out"] is True
    assert second["volume"] == pytest.approx(1.2 * 9.0 * 0.15, rel=1e-6)
    assert any(s["closes"] is False and s["faces"] == 2 for s in data["shells"])


def repaired_far_force(data: dict) -> None:
    # the same force as the clean wedge (whose float32 coordinates put it 5e-8 apart)
    assert data["force"] == pytest.approx(wedge_force(), rel=1e-6)


def wedge_force_of_total_mass(data: dict) -> None:
    # the shell is dry: the wetted length is the wedge's, the force the wedge's (its mass
    # per metre from the 10 kg over both volumes: 1e-12 of it is the shell's); the cut is
    # made at the 50 m body's scale, in manifold3d's single precision: 50 times coarser
    assert data["wetted_length"] == pytest.approx(1.0, rel=1e-9)
    assert data["force"] == pytest.approx(wedge_force(), rel=1e-5)


KINEMATICS = "t,draft,velocity\n0,0,-5\n0.001,0.005,-5\n0.002,0.01,-5\n"


def kinematics_rows(data: dict) -> None:
    # the table read as written: three rows to the end, the peak at its last, 0.01 m deep
    assert data["steps"] == 3 and data["stop_reason"] == "end of table"
    assert data["peak"]["t"] == pytest.approx(0.002, abs=1e-15)
    assert data["peak"]["draft"] == pytest.approx(0.01, abs=1e-15)
    assert data["peak"]["velocity"] == -5.0


def simulate_kinematics(content: str | bytes) -> Callable[[Path], list[str]]:
    return lambda t: ["simulate", wedge_file(t), "--mass", "10", "--kinematics",
                      kinematics(t, content)]  # fmt: skip


def secret_file(tmp: Path) -> str:
    # a file that is not a table (a system file); its content must not be quoted
    (tmp / "shadow").write_text("root:$6$s3cr3tHash:19000:0:99999:7:::\n")
    path = Path(case_file(tmp))
    path.write_text('mesh = "wedge.stl"\nmass = 10.0\nkinematics = "../shadow"\n')
    return str(path)


def deep_case(tmp: Path) -> str:
    (tmp / "case").mkdir(exist_ok=True)
    return text(tmp / "case", "deep.toml", "mesh = 'w.stl'\nmass = " + "[" * 5000 + "]" * 5000)


def bom_case(tmp: Path) -> str:
    path = Path(case_file(tmp))
    path.write_bytes(b"\xef\xbb\xbf" + path.read_bytes())
    return str(path)


def output_to_device(tmp: Path) -> list[str]:
    # the output path is a link to /dev/null: written through, the link kept
    result_of(tmp).symlink_to(os.devnull)
    return ["force", wedge_file(tmp), *STATE, "-o", str(result_of(tmp))]


def read_link(out: Path) -> dict:
    return {"link": out.is_symlink(), "target": os.readlink(out) if out.is_symlink() else ""}


def still_a_link(data: dict) -> None:
    assert data == {"link": True, "target": os.devnull}


def stale_temp(tmp: Path) -> list[str]:
    # what a run killed with SIGKILL while writing leaves: a temporary file of a dead process
    out = result_of(tmp)
    (out.parent / f".{out.name}.hullslice-999999999-abcd.tmp").write_text('{"force": 1')
    return ["force", wedge_file(tmp), *STATE]


# -- hostile inputs of the second round ---------------------------------------------


def stepped_hull(tmp: Path) -> str:
    """Two 0.5 m wedge bottoms, 0.6 m apart, joined by a part whose keel is 5 cm higher
    (two steps, their faces vertical): at 3 cm draft the middle is dry. The raised part has
    stations 1 mm apart."""

    def prism(x0: float, x1: float, dz: float, stations: int = 11) -> manifold3d.Manifold:
        v, f = shapes.wedge_prism(length=x1 - x0, beam=0.2, deadrise_deg=30.0, stations=stations)
        v = v + np.array([x0 - v[:, 0].min(), 0.0, dz])
        mesh = manifold3d.Mesh(vert_properties=v.astype(np.float32), tri_verts=f.astype(np.uint32))
        return manifold3d.Manifold(mesh)

    body = (prism(0.0, 0.5, 0.0) + prism(0.5, 1.1, 0.05, 601) + prism(1.1, 1.6, 0.0)).to_mesh()
    return stl(tmp, "stepped.stl", np.asarray(body.vert_properties)[:, :3], body.tri_verts)


def stepped_force(data: dict) -> None:
    # wetted: the two 0.5 m bottoms, not the 1.6 m from bow to stern (a step's vertical
    # face is a jump of the keel line, not a ramp over the raised part's first 1 mm)
    assert data["wetted_length"] == pytest.approx(1.0, rel=1e-6)
    # the force of 1 m of the wedge prism, each metre of it carrying 10 kg / 1.6 m (all
    # three parts have the same section): the 16 slices of 0.1 m over 1.6 m, 10 of them wet
    assert data["force"] == pytest.approx(wedge_force(MASS / 1.6), rel=1e-6)
    assert sum(s["force"] != 0.0 for s in data["slices"]) == 10


def constant_force(data: dict) -> None:
    # f = M * 100 m/s^2 over the wetted 1 m, 10 kg/m: the solver's prints changed nothing
    assert data["force"] == pytest.approx(10.0 * 100.0 * data["wetted_length"], rel=1e-9)
    assert data["wetted_length"] == pytest.approx(1.0, rel=1e-6)


def kinematics_rows_file(tmp: Path, rows: int) -> str:
    # rows of a descent at 5 m/s, 0.1 ms apart (t and draft in steps of 1e-4 s and 5e-4 m)
    i = np.arange(rows)
    body = "\n".join(f"{k * 1e-4:.4f},{k * 5e-4:.4f},-5" for k in i.tolist())
    return kinematics(tmp, "t,draft,velocity\n" + body + "\n")


def many_rows(tmp: Path) -> str:
    # one row more than simulate's step limit, written fast (the same row repeated: the
    # count is refused before any row is read)
    return kinematics(tmp, "t,draft,velocity\n" + "0,0,-5\n" * 1_000_001)


SWEEP_CASE = (
    'mesh = "wedge.stl"\nmass = 10.0\nvelocity = -4.0\nt_end = 0.01\ndt = 0.001\n'
    "slices = [8]\n\n[sweep]\nvelocity = [-3.0, -4.0]\n"
)


def sweep_case(tmp: Path, grid: str = "") -> str:
    """A sweep of the wedge prism at two velocities in ``tmp/case``, or of ``grid``."""
    path = Path(case_file(tmp))
    body = SWEEP_CASE if not grid else SWEEP_CASE.split("[sweep]")[0] + "[sweep]\n" + grid
    path.write_text(body, encoding="utf-8")
    return str(path)


def sweep_out(tmp: Path) -> Path:
    return tmp.parent / "out" / "result.nc"


def resumable(tmp: Path, spoil: Callable[[Path], None] = lambda folder: None) -> list[str]:
    """A sweep's partial folder with both its cases finished, spoiled by ``spoil``, and the
    command line that resumes it."""
    case = sweep_case(tmp)
    folder = Path(str(sweep_out(tmp)) + ".partial")
    hs.sweep(case, workers=1, partial=folder)
    spoil(folder)
    return ["sweep", case, "-o", str(sweep_out(tmp)), "--workers", "1", "--resume"]


def edit_peak(folder: Path) -> None:
    # the first case's peak force set to 1e9 N in its record, the checksum left as it was
    path = folder / "case-0.json"
    data = json.loads(path.read_text())
    record = json.loads(data["record"])
    record["peak_force"] = 1e9
    data["record"] = json.dumps(record, sort_keys=True)
    path.write_text(json.dumps(data))


def malformed(folder: Path) -> None:
    # the files of a record that is no record, and of []
    (folder / "case-0.json").write_text('{"peak_force": 1}')
    (folder / "case-1.json").write_text("[]")


def read_sweep(out: Path) -> dict:
    from hullslice.xarray_io import read_dataset

    ds = read_dataset(out)
    return {"peak_force": ds["peak_force"].values.tolist(), "failed": ds.attrs["failed"]}


def sweep_peaks(data: dict) -> None:
    # each case's peak force as the case run alone by simulate (the reference, on the
    # bundled meshes/wedge_prism.stl: the same prism in single precision), none failed
    hull = hs.load_hull(ROOT / "meshes" / "wedge_prism.stl", mass=10.0)
    for v, got in zip((-3.0, -4.0), data["peak_force"], strict=True):
        ref = hs.simulate(hull, v, 0.01, dt=0.001, slices=8).peak["force"]
        assert got == pytest.approx(ref, rel=1e-6)
    assert data["failed"] == 0


#: The address of a Dask scheduler without workers, while an entry that needs it runs.
EMPTY_SCHEDULER: list[str] = []


@pytest.fixture
def empty_scheduler():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=0, processes=False, dashboard_address=None, silence_logs=50
    ) as cluster:
        EMPTY_SCHEDULER[:] = [cluster.scheduler_address]
        yield cluster.scheduler_address
        EMPTY_SCHEDULER.clear()


#: A Gmsh file of 71 bytes whose $Nodes section declares 2e9 nodes.
GMSH_2E9 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2000000000\n1 0 0 0\n$EndNodes\n"


def full_device(tmp: Path) -> list[str]:
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full on this system")
    return ["force", wedge_file(tmp), *STATE, "--format", "json", "-o", "/dev/full"]


#: A legal file name of 255 bytes (the longest most file systems take).
LONG_NAME = "r" * 250 + ".json"


def zeros_3mf(tmp: Path, name: str, mib: int, declared: int | None = None) -> str:
    """A 3MF whose model part is ``mib`` MiB of zeros (deflated to a few hundred KB), and
    whose zip directory claims ``declared`` bytes for it when given."""
    import io
    import zipfile

    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
        with z.open("3D/3dmodel.model", "w") as member:
            block = b"\0" * 2**20
            for _ in range(mib):
                member.write(block)
    data = bytearray(buf.getvalue())
    if declared is not None:  # the member's size in its local header and in the directory
        struct.pack_into("<I", data, 22, declared)
        struct.pack_into("<I", data, data.find(b"PK\x01\x02") + 24, declared)
    return text(tmp, name, bytes(data))


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
        "an unknown format (`.step`, `.iges`, ...)",
        "error: hullslice reads stl, obj, tri, ply, off, glb, gltf, 3mf, msh: export the hull "
        "as STL or OBJ, or give format=",
        lambda t: ["sections", text(t, "hull.step", "ISO-10303-21;\n"), "--draft", "0.01"],
        error="hullslice reads stl, obj, tri, ply, off, glb, gltf, 3mf, msh",
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
        "error: mesh '...' is open: N edges belong to a single face (holes in the surface); "
        "load it with --repair close",
        lambda t: [
            "sections",
            stl(t, "open.stl", *wedge_with(lambda v, f: (v, f[1:]))),
            "--draft",
            "0.01",
        ],
        error="is open: 3 edges belong to a single face (holes in the surface); load it with "
        "--repair close (repair='close')",
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
    Bad(
        "self-intersecting-box",
        "a box with a corner pushed through its bottom (closed and manifold, but passing "
        "through itself)",
        "error: mesh '...' intersects itself: at x = X m its section inside the contours is A1 "
        "m^2 but its faces enclose A2 m^2 ...; the sections add up to R times the volume",
        lambda t: ["force", stl(t, "corner.stl", *corner_through_bottom()), *STATE],
        error="intersects itself: at x = 0.492253 m its section inside the contours is 0.49997 "
        "m^2 but its faces enclose 0.250045 m^2",
    ),
    Bad(
        "self-intersecting-wedge",
        "a wedge prism whose keel is pushed through its deck",
        "error: the same",
        lambda t: ["force", stl(t, "keel.stl", *keel_through_deck()), *STATE],
        error="intersects itself",
    ),
    # -- memory and time stay in proportion to the file; a merge closes rounding, not holes
    Bad(
        "far-open-mesh",
        "an open mesh 1e6 m from the origin",
        "error: mesh '...' is open: 3 edges belong to a single face (memory as for any file: "
        "the merge never takes more than 8 pairs a vertex)",
        lambda t: ["sections", far_open(t), "--draft", "0.01"],
        error="is open: 3 edges belong to a single face",
    ),
    Bad(
        "stray-far-vertex",
        "a closed mesh with one stray triangle 1e9 m away",
        "error: the same: the stray triangle is open",
        lambda t: ["sections", stray_vertex(t), "--draft", "0.1"],
        error="is open: 3 edges belong to a single face",
    ),
    Bad(
        "hole-at-the-nose",
        "a real hole (two faces missing at a fuselage's nose tip, an STL soup)",
        "error: mesh '...' is open: 4 edges belong to a single face (no merge closes a gap "
        "larger than rounding: a merge that would collapse a face is not made)",
        lambda t: ["sections", nose_hole(t), "--draft", "0.5"],
        error="is open: 4 edges belong to a single face",
    ),
    Bad(
        "obj-continuation-lines",
        "an OBJ of 2 MB of backslash continuation lines (or one 2 MB line)",
        "error: line N: a statement longer than 1 MiB (with its continuation lines); read in "
        "linear time",
        lambda t: ["sections", continuation_obj(t), "--draft", "0.1"],
        error="a statement longer than 1 MiB (with its continuation lines)",
    ),
    Bad(
        "obj-byte-order-mark",
        "an OBJ starting with a byte-order mark",
        "result: read as without it",
        lambda t: ["sections", text(t, "bom.obj", "\ufeff" + TETRA_OBJ), "--draft", "1"],
        check=tetra_sections,
    ),
    Bad(
        "far-from-the-origin",
        "a wedge at x = 1e12 m",
        "error: mesh '...' lies 1e+12 m from the origin, N times its size: coordinates that "
        "far out do not resolve the body; move the body near the origin",
        lambda t: [
            "sections",
            stl(t, "far.stl", wedge()[0] + [1e12, 0, 0], wedge()[1]),
            "--draft",
            "0.01",
        ],
        error="lies 1e+12 m from the origin, 4.8e+12 times its size (0.208 m)",
    ),
    Bad(
        "huge-prism",
        "a prism 1e6 m long",
        "result: cut as accurately as a metre-sized one",
        lambda t: [
            "sections",
            stl(t, "long.stl", wedge()[0] * 1e6, wedge()[1]),
            "--draft",
            "3e4",
            "--slices",
            "4",
        ],
        check=scaled_sections(1e6),
    ),
    Bad(
        "tiny-far-shell",
        "a wedge and a tiny shell 50 m behind it",
        "result: the wetted length is the wedge's (the keel line is not drawn across the gap)",
        lambda t: ["force", stl(t, "shell.stl", *tiny_far_shell()), *STATE],
        check=wedge_force_of_total_mass,
    ),
    # -- tables and case files in odd encodings or shapes
    Bad(
        "csv-latin-1",
        "a kinematics CSV in Latin-1 (a `°` in a comment)",
        "error: kinematics file '...' is not UTF-8 text (byte N): save it as CSV UTF-8",
        simulate_kinematics(("# Winkel in \xb0\n" + KINEMATICS).encode("latin-1")),
        error="is not UTF-8 text (byte 12): save it as CSV UTF-8",
    ),
    Bad(
        "csv-utf-16",
        "a kinematics CSV in UTF-16 with its byte-order mark (a spreadsheet's Unicode text)",
        "result: read as written",
        simulate_kinematics(KINEMATICS.encode("utf-16")),
        check=kinematics_rows,
    ),
    Bad(
        "csv-byte-order-mark",
        "a kinematics CSV starting with a UTF-8 byte-order mark",
        "result: read as written (the first column is `t`)",
        simulate_kinematics(b"\xef\xbb\xbf" + KINEMATICS.encode()),
        check=kinematics_rows,
    ),
    Bad(
        "csv-overflow",
        "a mass distribution with values of 1e308 (or `1e999`, `inf` in any table)",
        "error: mass distribution: its total mass or moment overflows (inf kg)",
        lambda t: [
            "force",
            wedge_file(t),
            "--mass-distribution",
            text(t, "m.csv", "x,mass_per_metre\n0,10\n1e308,10\n"),
            "--draft",
            "0.03",
            "--velocity=-5",
            "--slices",
            "8",
        ],
        error="its total mass or moment overflows (inf kg)",
    ),
    Bad(
        "csv-line-numbers",
        "a bad row after comment lines",
        "error: ... line N: 'x' in the column draft is not a number (N counts every "
        "line of the file)",
        simulate_kinematics("# kinematics\n# from CFD\n" + KINEMATICS + "0.003,x,-5\n"),
        error="line 7: 'x' in the column draft is not a number",
    ),
    Bad(
        "case-path-to-system-file",
        "a case whose `kinematics` names a file that is not a table (`/etc/shadow`)",
        "error: kinematics file '...' lacks the column(s) ... (its first line is not a header "
        "of column names); nothing of the file is quoted",
        lambda t: ["run", secret_file(t)],
        error="lacks the column(s) t, draft, velocity (its first line is not a header "
        "of column names)",
    ),
    Bad(
        "case-deeply-nested",
        "a case file nested 5000 deep",
        "error: case file '...' nests tables or lists too deeply to be a case",
        lambda t: ["run", deep_case(t)],
        error="nests tables or lists too deeply to be a case",
    ),
    Bad(
        "case-byte-order-mark",
        "a case file starting with a byte-order mark",
        "result: read as without it",
        lambda t: ["run", bom_case(t)],
        check=same_force,
    ),
    Bad(
        "plot-not-a-figure",
        "`--plot out.txt` (or `.csv`)",
        "error: cannot write '...' (--plot): a figure is drawn as PNG, SVG, PDF by the file's "
        "extension; checked before any work",
        lambda t: ["force", wedge_file(t), *STATE, "--plot", str(t / "out.txt")],
        error="(--plot): a figure is drawn as PNG, SVG, PDF by the file's extension",
    ),
    Bad(
        "output-link-to-device",
        "`-o` onto a device, or a link to one (`/dev/null`)",
        "result: written through; the device or link stays as it was",
        output_to_device,
        check=still_a_link,
        output=False,
        read=read_link,
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
        status=2,
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
        "result: one entry per float at each station, each with its own mass and keel line; "
        "the force is the sum of the floats'",
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
        status=2,
    ),
    Bad(
        "slices-negative",
        "negative slices",
        "error: the same",
        lambda t: ["force", wedge_file(t), *STATE, "--slices=-8"],
        error="'-8' is not positive (give 1 or more)",
        status=2,
    ),
    Bad(
        "slices-not-whole",
        "`--slices 1e3`",
        "error: '1e3' is not a whole number",
        lambda t: ["force", wedge_file(t), *STATE, "--slices", "16,1e3"],
        error="'1e3' is not a whole number",
        status=2,
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
        "error: kinematics file '...' lacks the column(s) draft",
        lambda t: [
            "simulate",
            wedge_file(t),
            "--mass",
            "10",
            "--kinematics",
            kinematics(t, "t,velocity\n0,-5\n"),
        ],
        error="lacks the column(s) draft (its header: t, velocity)",
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
            kinematics(t, "t,draft,velocity\n0,0,-5\n0.002,0.01,-5\n0.001,0.005,-5\n"),
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
        "changes the velocity by ... m/s, the velocity column by ... m/s (the same check for "
        "the pitch rate, pitch acceleration and forward acceleration columns)",
        lambda t: [
            "simulate",
            wedge_file(t),
            "--solver",
            "wagner",
            "--kinematics",
            kinematics(
                t,
                "t,draft,velocity,acceleration\n0,0,-5,100\n0.001,0.005,-5,100\n"
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
            kinematics(t, "t,draft,velocity\n0,0,-5\n0.001,0.005,-4.9\n"),
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
        plugins=("nan",),
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
    Bad(
        "usage",
        "a command line that does not parse (`hullslice force MESH` without its state)",
        "error, exit status 2: hullslice force: error: the following arguments are required: "
        "--draft, --velocity",
        lambda t: ["force", wedge_file(t), "--mass", "10"],
        error="the following arguments are required: --draft, --velocity",
        status=2,
    ),
    # -- where a run writes: a case file only inside its folder, names escaped
    Bad(
        "case-output-outside",
        "a case file whose `output` leads out of its folder (`../victim/file`)",
        "error: key 'output' ('../victim/file') leads out of the case's folder: a case file "
        "writes only inside its own folder",
        lambda t: ["run", case_file(t, 'output = "../victim/file"\n')],
        error="key 'output' ('../victim/file') leads out of the case's folder",
        output=False,
    ),
    Bad(
        "case-output-absolute",
        "a case file whose `output` or `plot` is an absolute path",
        "error: key 'plot' ('/...') is an absolute path: a case file writes only inside its own "
        "folder",
        lambda t: ["run", case_file(t, f"plot = {json.dumps(str(t / 'victim.png'))}\n")],
        error="is an absolute path: a case file writes only inside its own folder",
        output=False,
    ),
    Bad(
        "case-output-through-link",
        "a case file whose `output` goes through a link to another folder",
        "error: the same (links are followed)",
        lambda t: ["run", link_out(t)],
        error="key 'output' ('out/result.json') leads out of the case's folder",
        output=False,
    ),
    Bad(
        "mesh-name-newline",
        "a mesh file name holding line breaks (and a shell command)",
        "result: the name written escaped (`hull\\nrm -rf ~\\n`), one line, in every output",
        lambda t: [
            "force",
            stl(t, NEWLINE_NAME, *wedge()),
            *STATE,
            "-o",
            str(result_of(t)),
        ],
        check=escaped_table,
        output=False,
        read=read_text,
    ),
    Bad(
        "report-markup",
        "a case title and mesh name holding Markdown, HTML and line breaks (`report`)",
        "result: each escaped in report.md (one heading line, table rows intact, no HTML); "
        "case.toml reads back the same text",
        lambda t: [
            "report",
            case_file(t, f"title = {json.dumps(TITLE)}\n", mesh=NEWLINE_NAME),
            "-o",
            str(result_of(t)),
        ],
        check=escaped_report,
        output=False,
        read=read_report,
    ),
    # -- no output replaces an input
    Bad(
        "run-output-is-the-case",
        "`hullslice run C.toml -o C.toml` (or `output` naming the case itself)",
        "error: cannot write '...': it is the input case file and would be overwritten",
        lambda t: ["run", case_file(t), "-o", str(t / "case" / "c.toml")],
        error="it is the input case file and would be overwritten",
        output=False,
    ),
    Bad(
        "output-is-a-solver-table",
        "`-o` naming a table a solver option reads (`--solver-option table=T.csv -o T.csv`)",
        "error: cannot write '...': it is the input solver option table file and would be "
        "overwritten",
        lambda t: [
            "force",
            wedge_file(t),
            *STATE,
            "--solver",
            "table",
            "--solver-option",
            f"table={table_csv(t)}",
            "-o",
            str(t / "accel.csv"),
        ],
        error="it is the input solver option table file and would be overwritten",
        output=False,
        plugins=("table",),
    ),
    Bad(
        "solver-table-read",
        "a solver option naming a table, with `-o` elsewhere",
        "result: the table is read, and left as it was",
        lambda t: [
            "force",
            wedge_file(t),
            *STATE,
            "--solver",
            "table",
            "--solver-option",
            f"table={table_csv(t)}",
        ],
        check=table_force,
        plugins=("table",),
    ),
    Bad(
        "output-link-to-input",
        "`-o` naming a link to the input mesh",
        "error: cannot write '...': it is the input mesh file and would be overwritten",
        lambda t: [
            "sections",
            wedge_file(t),
            "--draft",
            "0.01",
            "-o",
            link_to_mesh(t),
        ],
        error="it is the input mesh file and would be overwritten",
        output=False,
    ),
    Bad(
        "report-overwrite-input-table",
        "`report --overwrite` onto a folder that holds a table the case reads",
        "error: report folder '...' holds the input '...', and the folder is written anew",
        lambda t: [
            "report",
            case_reading_table(t),
            "-o",
            str(t),
            "--overwrite",
        ],
        error="holds the input",
        output=False,
        plugins=("table",),
    ),
    Bad(
        "stale-temp-file",
        "a temporary file left by a run killed with SIGKILL (`.NAME.hullslice-PID-....tmp`)",
        "result: removed by the next write to the same file (its process has ended)",
        stale_temp,
        check=same_force,
    ),
    # -- validity checks cannot be switched off
    Bad(
        "solver-option-nan",
        "`--solver-option froude_min=NaN` (or `Infinity`, `1e999`)",
        "error: 'froude_min=NaN': nan is not a finite number; give a finite value",
        lambda t: ["force", wedge_file(t), *STATE, "--solver-option", "froude_min=NaN"],
        error="'froude_min=NaN': nan is not a finite number",
        status=2,
    ),
    Bad(
        "solver-option-negative",
        "`--solver-option froude_min=-1`, or NaN in a case's `[solver_options]`",
        "error: solver '...' option froude_min=-1 is not a positive number: give one above 0",
        lambda t: ["force", wedge_file(t), *STATE, "--solver-option", "froude_min=-1"],
        error="option froude_min=-1 is not a positive number: give one above 0 (default 6.5)",
    ),
    Bad(
        "case-solver-option-nan",
        "a case file with `froude_min = nan` in `[solver_options]`",
        "error: key 'solver_options': froude_min = nan is not a finite number",
        lambda t: ["run", case_file(t, "[solver_options]\nfroude_min = nan\n")],
        error="key 'solver_options': froude_min = nan is not a finite number",
    ),
    Bad(
        "solver-valid-nan",
        "a solver returning `valid` as NaN",
        "error: solver '...' failed: TypeError: SectionLoads.valid must be a boolean array",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "nan-valid"],
        error="failed: TypeError: SectionLoads.valid must be a boolean array (True inside the "
        "solver's range), not float64 values such as [nan]",
        plugins=("nan-valid",),
    ),
    Bad(
        "solver-valid-text",
        "a solver returning `valid` as text",
        "error: the same",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "text-valid"],
        error="SectionLoads.valid must be a boolean array",
        plugins=("text-valid",),
    ),
    # -- faulty plugins
    Bad(
        "solver-sys-exit",
        "a solver that calls `sys.exit(0)` while it computes",
        "error: solver '...' failed: it called sys.exit(0) (SystemExit), which a solver must "
        "not do",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "exits"],
        error="solver 'exits' (tests.fake_solvers:ExitingSolver, distribution fake-plugin 1.0) "
        "failed: it called sys.exit(0) (SystemExit)",
        plugins=("exits",),
    ),
    Bad(
        "solver-system-exit-message",
        "a solver raising `SystemExit('message')`",
        "error: the same, quoting the message",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "exits-with-message"],
        error="failed: it called sys.exit('solver gave up') (SystemExit)",
        plugins=("exits-with-message",),
    ),
    Bad(
        "solver-exit-on-start",
        "a solver that calls `sys.exit(3)` when it is built",
        "error: solver '...' failed to start with options {}: it called sys.exit(3)",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "exits-on-start"],
        error="failed to start with options {}: it called sys.exit(3) (SystemExit)",
        plugins=("exits-on-start",),
    ),
    Bad(
        "solver-exit-on-import",
        "a solver plugin whose module calls `sys.exit(0)` when it is imported",
        "error: solver plugin '...' failed to load: it called sys.exit(0) (SystemExit); "
        "`hullslice solvers` lists it as broken",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "exits-on-import"],
        error="failed to load: it called sys.exit(0) (SystemExit)",
        plugins=("exits-on-import",),
    ),
    Bad(
        "solver-hangs-ctrl-c",
        "a solver that never returns, stopped with Ctrl-C (SIGINT)",
        "stopped: 'hullslice: interrupted', exit status 130, no file written",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "hangs"],
        error="hullslice: interrupted",
        plugins=("hangs",),
        interrupt=signal.SIGINT,
    ),
    Bad(
        "solver-hangs-kill",
        "a solver that never returns, stopped with `kill PID` (SIGTERM)",
        "stopped: 'hullslice: terminated', exit status 143, no file written",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "hangs"],
        error="hullslice: terminated",
        plugins=("hangs",),
        interrupt=signal.SIGTERM,
    ),
    # -- second round: silent wrong results
    Bad(
        "kinematics-draft-disagrees",
        "a kinematics CSV whose draft falls while its velocity says sinking",
        "error: kinematics draft disagrees with velocity: the velocity integrated from t = ... "
        "moves the body ... m down, the draft column by ... m (more than 2 % of the largest "
        "draft); the velocity is negative down and the draft positive down",
        simulate_kinematics("t,draft,velocity\n0,0.01,-5\n0.001,0.005,-5\n0.002,0,-5\n"),
        error="kinematics draft disagrees with velocity: the velocity integrated from t = 0 s "
        "to t = 0.002 s moves the body 0.01 m down, the draft column by -0.01 m",
    ),
    Bad(
        "kinematics-repeated-column",
        "a kinematics CSV naming a column twice (`t,draft,velocity,draft`)",
        "error: kinematics file '...' repeats the column 'draft' (its header: ...): give each "
        "column once (every table)",
        simulate_kinematics("t,draft,velocity,draft\n0,0,-5,0\n0.001,0.005,-5,0.1\n"),
        error="repeats the column 'draft' (its header: t, draft, velocity, draft): give each "
        "column once",
    ),
    Bad(
        "mass-table-both-forms",
        "a mass distribution with both `mass_per_metre` and point-mass (`z`, `mass`) columns",
        "error: mass distribution file '...' has both a mass_per_metre column (a line "
        "density) and a mass column (point masses): a table holds one form",
        lambda t: [
            "force",
            wedge_file(t),
            "--mass-distribution",
            text(t, "m.csv", "x,mass_per_metre,z,mass\n0,10,0,1\n1,10,0,1\n"),
            "--draft",
            "0.03",
            "--velocity=-5",
        ],
        error="has both a mass_per_metre column (a line density) and a mass column (point "
        "masses): a table holds one form",
    ),
    Bad(
        "solver-total-overflows",
        "a solver returning finite forces per metre (1e308 N/m) whose total is infinite",
        "error: solver '...' returned finite force per metre values whose total over the N "
        "slices is not a finite number (the largest: ...)",
        lambda t: ["force", wedge_file(t), *STATE, "--scale", "2", "--solver", "huge"],
        error="returned finite force per metre values whose total over the 8 slices is not a "
        "finite number (the largest: 1e+308 N/m at x = 0.125 m)",
        plugins=("huge",),
    ),
    Bad(
        "acceleration-overflows",
        "`--acceleration=-1e308` with a momentum solver (a force no float holds)",
        "error: the water's force at the body's acceleration (vertical -1e+308 m/s^2, ...) "
        "is not a finite number: give accelerations a body can have",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "mlm", "--acceleration=-1e308"],
        error="the water's force at the body's acceleration (vertical -1e+308 m/s^2, pitch 0 "
        "rad/s^2, forward 0 m/s^2) is not a finite number",
    ),
    Bad(
        "speed-past-sound",
        "`--forward-speed 1e308` (past the speed of sound in water)",
        "error: forward speed 1e+308 m/s is past the speed of sound in water (1481 m/s), "
        "where water is not the incompressible fluid of the method: give a speed in m/s",
        lambda t: ["force", wedge_file(t), *STATE, "--forward-speed", "1e308"],
        error="forward speed 1e+308 m/s is past the speed of sound in water (1481 m/s)",
    ),
    Bad(
        "section-past-sound",
        "`--pitch-rate 1e200` (deg/s: sections moving faster than sound in water)",
        "error: the keel of the section at x = ... m moves at ... m/s, from the body's vertical "
        "velocity ..., forward speed ... and pitch rate ...: past the speed of sound in water "
        "(1481 m/s); give a pitch rate in deg/s",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "mlm", "--pitch-rate", "1e200"],
        error="pitch rate 1e+200 deg/s: past the speed of sound in water (1481 m/s)",
    ),
    Bad(
        "stepped-hull-wetted-length",
        "a stepped hull whose middle is dry (two 0.5 m bottoms 1.6 m from bow to stern)",
        "result: wetted length 1.0 m, the wetted bottoms only (the slices still span 1.6 m)",
        lambda t: [
            "force",
            stepped_hull(t),
            "--mass",
            "10",
            "--draft",
            "0.03",
            "--velocity=-5",
            "--slices",
            "16",
        ],
        check=stepped_force,
    ),
    Bad(
        "mass-overflows",
        "`--mass 1e308` (a density no float holds)",
        "error: hull '...': mass 1e+308 kg in a volume of ... m^3 is a density that overflows "
        "a float: give the body's mass in kg",
        lambda t: ["force", wedge_file(t), "--mass", "1e308", *STATE[2:]],
        error="mass 1e+308 kg in a volume of 0.0057735 m^3 is a density that overflows a float",
    ),
    Bad(
        "resume-edited-record",
        "`sweep --resume` on a partial folder whose saved case was edited (peak force 1e9 N)",
        "repaired, warning: 1 saved case(s) in '...' failed their check (edited, malformed, or "
        "computed by another hullslice or solver version): they run again",
        lambda t: resumable(t, edit_peak),
        warning="1 saved case(s) in",
        check=sweep_peaks,
        read=read_sweep,
        output=False,
        out_name="result.nc",
    ),
    Bad(
        "resume-malformed-records",
        '`sweep --resume` on saved cases that are no records (`{"peak_force": 1}`, `[]`)',
        "repaired, warning: 2 saved case(s) in '...' failed their check ...: they run again",
        lambda t: resumable(t, malformed),
        warning="2 saved case(s) in",
        check=sweep_peaks,
        read=read_sweep,
        output=False,
        out_name="result.nc",
    ),
    # -- second round: plugins and outputs
    Bad(
        "solver-prints",
        "a solver that prints while it computes",
        "result: its lines on stderr, stdout (`--format json` without `-o`) holds the result only",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "prints"],
        printed=("debug: section_loads called",),
        check=constant_force,
        plugins=("prints",),
    ),
    Bad(
        "solver-changes-folder",
        "a solver that changes the working folder (`os.chdir('/')`), `-o result.json`",
        "result: written where the command was started (the folder is restored after each "
        "call of plugin code)",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "chdir"],
        relative=True,
        output=False,
        check=constant_force,
        plugins=("chdir",),
    ),
    Bad(
        "solver-os-exit",
        "a solver that ends its process (`os._exit(0)`), `hullslice --isolate`",
        "error: the command's process ended with status 0 while solver '...' ran before it "
        "gave its result (without `--isolate`: status 0 and no output, docs/plugins.md)",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "hard-exit"],
        error="the command's process ended with status 0 while solver 'hard-exit' ran before "
        "it gave its result",
        plugins=("hard-exit",),
        process=True,
    ),
    Bad(
        "solver-segfault",
        "a solver that crashes its process (SIGSEGV), `hullslice --isolate`",
        "error: the command's process was killed by SIGSEGV while solver '...' ran (without "
        "`--isolate`: status 139 and no message)",
        lambda t: ["force", wedge_file(t), *STATE, "--solver", "crashes"],
        error="the command's process was killed by SIGSEGV while solver 'crashes' ran",
        plugins=("crashes",),
        process=True,
    ),
    Bad(
        "gmsh-declares-more-than-it-holds",
        "a 71-byte Gmsh file whose `$Nodes` declares 2e9 nodes",
        "error: its $Nodes section declares 2000000000 nodes, at least 16000000000 bytes, but "
        "the file has 71 bytes: it is cut short, or its counts are wrong",
        lambda t: ["sections", text(t, "big.msh", GMSH_2E9), "--draft", "0.01"],
        error="its $Nodes section declares 2000000000 nodes, at least 16000000000 bytes, but "
        "the file has 71 bytes: it is cut short, or its counts are wrong",
    ),
    Bad(
        "output-full-device",
        "`-o /dev/full` (a device that takes no data)",
        "error: cannot write '/dev/full' (--output): No space left on device (`> /dev/full`: "
        "cannot write the result to stdout)",
        full_device,
        error="cannot write '/dev/full' (--output): No space left on device",
        output=False,
    ),
    Bad(
        "output-name-255-bytes",
        "`-o` a legal file name of 255 bytes",
        "result: written (its temporary carries a shortened name and a hash of it)",
        lambda t: ["force", wedge_file(t), *STATE],
        check=same_force,
        out_name=LONG_NAME,
    ),
    # -- second round: resources
    Bad(
        "sweep-too-many-cases",
        "a sweep grid of 1e6 cases (1000 velocities x 1000 pitches)",
        "error: case file '...': [sweep] has N cases (...), more than the 100000 hullslice "
        "runs in one sweep: give fewer values, or split it into sweeps",
        lambda t: [
            "sweep",
            sweep_case(
                t,
                f"velocity = {[-1.0 - k / 1000 for k in range(1000)]}\n"
                f"pitch = {[k / 1000 for k in range(1000)]}\n",
            ),
        ],
        error="[sweep] has 1000000 cases (1000 velocity x 1000 pitch), more than the 100000 "
        "hullslice runs in one sweep",
        output=False,
    ),
    Bad(
        "sweep-workers-above-cores",
        "`sweep --workers 1000` (here on a sweep resumed with every case done: no cluster)",
        "warning: workers 1000 is more than 4 per core (N cores here): the sweep starts 4 N",
        lambda t: [*resumable(t)[:-3], "--workers", "1000", "--resume"],
        warning="workers 1000 is more than 4 per core",
        check=sweep_peaks,
        read=read_sweep,
        output=False,
        out_name="result.nc",
    ),
    Bad(
        "sweep-scheduler-without-workers",
        "`sweep --scheduler ADDRESS` of a scheduler that has no workers",
        "error: the Dask scheduler at '...' has no workers (none joined within 10 s): start "
        "some ('dask worker ADDRESS'), or leave out --scheduler",
        lambda t: ["sweep", sweep_case(t), "--scheduler", EMPTY_SCHEDULER[0]],
        error="has no workers (none joined within 10 s)",
        output=False,
        fixture="empty_scheduler",
    ),
    Bad(
        "3mf-directory-understates",
        "a 3MF whose zip directory claims 100 bytes for a 64 MiB member",
        "error: ... is corrupt (Bad CRC-32 ...): a member gives other data than its directory "
        "entry says (inflated in blocks, counted: no more than the 100 bytes is inflated)",
        lambda t: ["sections", zeros_3mf(t, "lie.3mf", 64, declared=100), "--draft", "0.01"],
        error="a member gives other data than its directory entry says",
    ),
    Bad(
        "3mf-model-too-large",
        "a 3MF of 129 MiB of model XML (under the 4 GiB it may unpack to)",
        "error: its model XML is 129 MiB, more than the 128 MiB hullslice parses (about 1.5 "
        "million triangles; ...): export the mesh as binary STL, or decimate it",
        lambda t: ["sections", zeros_3mf(t, "big.3mf", 129), "--draft", "0.01"],
        error="its model XML is 129 MiB, more than the 128 MiB hullslice parses",
    ),
    Bad(
        "kinematics-too-many-rows",
        "a kinematics CSV of more rows than simulate's 1e6 steps",
        "error: kinematics file '...' has N rows, more than the 1000000 hullslice allows (the "
        "step limit of simulate): give every k-th row",
        lambda t: ["simulate", wedge_file(t), "--mass", "10", "--kinematics", many_rows(t)],
        error="has 1000001 rows, more than the 1000000 hullslice allows (the step limit of "
        "simulate; each row is one cut of the body)",
    ),
    Bad(
        "kinematics-rows-times-slices",
        "101 kinematics rows at 1e5 slices (1e7 section solutions)",
        "error: 101 kinematics rows times 100000 slices is 1.01e+07 section solutions, more "
        "than the 1e+07 hullslice allows in one run",
        lambda t: [
            "simulate",
            wedge_file(t),
            "--mass",
            "10",
            "--slices",
            "100000",
            "--kinematics",
            kinematics_rows_file(t, 101),
        ],
        error="101 kinematics rows times 100000 slices is 1.01e+07 section solutions, more "
        "than the 1e+07 hullslice allows in one run",
    ),
    Bad(
        "simulate-steps-times-slices",
        "`simulate` of 1e5 steps at 2e4 slices",
        "error: ... steps times N slices is ... section solutions, more than the 1e+07 "
        "hullslice allows in one run: give fewer slices, or fewer steps",
        lambda t: [
            "simulate",
            wedge_file(t),
            "--mass",
            "10",
            "--velocity=-5",
            "--t-end",
            "1",
            "--dt",
            "1e-5",
            "--slices",
            "20000",
        ],
        error="100000 steps times 20000 slices is 2e+09 section solutions, more than the "
        "1e+07 hullslice allows in one run",
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
    # -- scale, parts and repair of meshes as exported (tests/test_aircraft_meshes.py)
    Bad(
        "length-zero",
        "`--length 0`",
        "error: length 0.0 is not a positive number: give the body's length along --forward in m",
        lambda t: ["sections", wedge_file(t), "--draft", "0.01", "--length", "0"],
        error="length 0.0 is not a positive number: give the body's length along --forward",
    ),
    Bad(
        "length-negative",
        "a negative `--length`",
        "error: the same",
        lambda t: ["sections", wedge_file(t), "--draft", "0.01", "--length=-1"],
        error="length -1.0 is not a positive number",
    ),
    Bad(
        "scale-with-length",
        "`--scale` with `--length`",
        "error: scale 2.0 and length 1.0 m both give the mesh's size: give one of them",
        lambda t: ["sections", wedge_file(t), "--draft", "0.01", "--scale", "2", "--length", "1"],
        error="both give the mesh's size: give one of them (--scale FACTOR or --length M)",
    ),
    Bad(
        "length-with-units",
        "`--length` with `--units mm`",
        "error: length 1 m sets the mesh's size by itself; units 'mm' would be ignored",
        lambda t: ["sections", wedge_file(t), "--draft", "0.01", "--length", "1", "--units", "mm"],
        error="units 'mm' would be ignored: leave out --units, or give --scale",
    ),
    Bad(
        "length-sets-scale",
        "a model in arbitrary units, `--length 1` (its length in m)",
        "result: scaled to 1 m along --forward; the force of the body in metres",
        lambda t: [
            "force",
            stl(t, "model.stl", wedge()[0] * 2.5, wedge()[1]),
            *STATE,
            "--length",
            "1",
        ],
        check=scaled_back_force,
    ),
    Bad(
        "keep-missing-body",
        "`--keep 7` on a mesh of 3 bodies",
        "error: keep 7: mesh '...' has 3 bodies (numbered 1 to 3, largest first; 'hullslice "
        "info MESH' lists them)",
        lambda t: [
            "sections",
            stl(t, "floats.stl", *three_floats()),
            "--draft",
            "0.01",
            "--keep",
            "7",
        ],
        error="keep 7: mesh 'floats' has 3 bodies (numbered 1 to 3, largest first",
    ),
    Bad(
        "stray-shell-keep-largest",
        "a stray shell far from the hull, `--keep largest`",
        "repaired, warning: kept body 1 of 2 (...); dropped 2 (...)",
        lambda t: [
            "force",
            stl(t, "stray.stl", *with_stray_shell()),
            *STATE,
            "--keep",
            "largest",
        ],
        warning="kept body 1 of 2",
        check=same_force,
    ),
    Bad(
        "keep-box-empty",
        "a `--keep-box` that holds none of the body",
        "error: keep box ... keeps nothing of mesh '...', which spans x ... m: give a box that "
        "overlaps it",
        lambda t: ["sections", wedge_file(t), "--draft", "0.01", "--keep-box=5,6,-1,1,-1,1"],
        error="keeps nothing of mesh 'wedge', which spans x",
    ),
    Bad(
        "open-repair-close",
        "an open mesh with `--repair close` (a hole in the deck)",
        "repaired, warning: repair close: closed 1 hole (3 edges with a single face), adding "
        "A m^2 of surface; volume ...",
        lambda t: [
            "force",
            stl(t, "deck.stl", *wedge_with(open_deck)),
            *STATE,
            "--repair",
            "close",
        ],
        warning="repair close: closed 1 hole (3 edges with a single face)",
        check=same_force,
    ),
    Bad(
        "open-far-repair-close",
        "an open wedge 1e5 m from the origin with `--repair close` (OBJ, double precision)",
        "repaired, warning: repair close: closed 1 hole ...; the volume and force as at the "
        "origin (merges are relative to the body's size and edges, not to its coordinates)",
        lambda t: ["force", far_open_obj(t), *STATE, "--repair", "close"],
        warning="repair close: closed 1 hole (3 edges with a single face)",
        check=repaired_far_force,
    ),
    Bad(
        "welded-fuselage-keep-largest",
        "an open aircraft export (a holed fuselage with a fin and an antenna welded to it, an "
        "inside-out wing through it, 60 small open parts), `--repair close --keep largest`",
        "repaired, warnings: repair close: ... closed 2 shells on their own that did not "
        "close with the parts welded to them; dropped 21 of 64 shells ... (the largest: SIZE "
        "m (2 faces, 4 open edges), ...); kept body 1 of 43 (...): the fuselage",
        lambda t: ["info", aircraft_export(t), "--repair", "close", "--keep", "largest"],
        warning="closed 2 shells on their own that did not close with the parts welded to them",
        more_warnings=("kept body 1 of 43",),
        check=fuselage_kept,
    ),
    Bad(
        "open-export-info",
        "`info` on that open export, without `--repair`",
        "result: its 64 shells: faces, extent, open edges, whether `--repair close` would "
        "close each and the volume it would then enclose (numbered as `--keep` numbers them), "
        "and the views",
        lambda t: ["info", aircraft_export(t)],
        check=shells_listed,
    ),
    Bad(
        "overlapping-inside-out",
        "overlapping shells, one of them inside out",
        "repaired, warning: 1 inside-out shell (not inside another) turned outward; 2 shells "
        "overlap ...; the body is taken as their union (not the first less the second)",
        lambda t: [
            "sections",
            stl(t, "two.stl", *inside_out_overlap()),
            "--draft",
            str(H30),
            "--slices",
            "4",
        ],
        warning="1 inside-out shell (not inside another) turned outward; 2 shells overlap",
        check=union_sections,
    ),
    Bad(
        "far-away-shell",
        "a wedge and a 1 cm box 1e4 m away from it",
        "repaired, warning: mesh '...': its 2 shells spread over 1e+04 m, N times the largest "
        "(...): a part far from the body? --keep largest keeps the largest alone (it was "
        "called a flat surface)",
        lambda t: [
            "sections",
            stl(t, "far.stl", *far_away_shell()),
            "--draft",
            str(H30),
            "--slices",
            "4",
        ],
        warning="its 2 shells spread over 1e+04 m, 9.79e+03 times the largest (1.02 m across",
        check=scaled_sections(1.0),
    ),
    Bad(
        "length-along-y",
        "a hull whose length is along the file's y axis, `info` with the default `--forward x`",
        "warning: mesh '...' is longest along its y axis (L m) but --forward is +x (B m): if the "
        "body's length is along y, give --forward y (or -y)",
        lambda t: ["info", stl(t, "along_y.stl", wedge()[0][:, [1, 0, 2]], wedge()[1][:, ::-1])],
        warning="is longest along its y axis (1 m) but --forward is +x (0.2 m)",
        check=along_y,
    ),
    Bad(
        "repair-not-a-mesh",
        "`--repair close` on a file that is not a mesh",
        "error: the file's own error: it does not start with 'solid' as an ASCII STL does",
        lambda t: [
            "sections",
            text(t, "notes.stl", "hull notes\n" * 20),
            "--draft",
            "0.01",
            "--repair",
            "close",
        ],
        error="does not start with 'solid'",
    ),
)


def kind(bad: Bad) -> str:
    return "error" if bad.error else "repair" if bad.warning else "result"


# -- running it -------------------------------------------------------------------------------


#: The solvers of tests/fake_solvers.py that entries install, by name.
FAKE_SOLVERS = {
    "nan": "NaNSolver",
    "nan-valid": "NaNValidSolver",
    "text-valid": "TextValidSolver",
    "exits": "ExitingSolver",
    "exits-with-message": "ExitMessageSolver",
    "exits-on-start": "ExitOnStartSolver",
    "table": "TableSolver",
    "hangs": "HangingSolver",
    "huge": "HugeSolver",
    "prints": "PrintingSolver",
    "chdir": "ChdirSolver",
    "hard-exit": "HardExitSolver",
    "crashes": "CrashingSolver",
}


def fake_eps(names) -> list:
    return [
        DEFAULT,
        *(
            ep(n, "tests.fake_exit_on_import:Solver")
            if n == "exits-on-import"
            else ep(n, f"tests.fake_solvers:{FAKE_SOLVERS[n]}")
            for n in names
        ),
    ]


@pytest.mark.parametrize("bad", CATALOGUE, ids=[b.id for b in CATALOGUE])
def test_bad_input(bad: Bad, tmp_path, capsys, request):
    work = tmp_path / "in"
    work.mkdir()
    out_dir = tmp_path / "out"
    out_dir.mkdir()
    out = out_dir / bad.out_name
    if bad.fixture:
        request.getfixturevalue(bad.fixture)
    if bad.call is not None:
        with pytest.raises(hs.HullsliceError) as info:
            bad.call(work)
        assert bad.error in str(info.value)
        return
    if bad.plugins:
        request.getfixturevalue("fake_entry_points")(fake_eps(bad.plugins))
    argv = bad.argv(work)
    if bad.relative:
        request.getfixturevalue("monkeypatch").chdir(out_dir)
        argv += ["--format", "json", "-o", out.name]
    elif bad.output:
        argv += ["--format", "json", "-o", str(out)]
    before = {p: p.read_bytes() for p in work.rglob("*") if p.is_file()}

    if bad.interrupt or bad.process:
        code, stdout, stderr = run_interrupted(
            ["--isolate", *argv] if bad.process else argv, bad.plugins, bad.interrupt, tmp_path
        )
    else:
        code = main(argv)
        stdout, stderr = capsys.readouterr()
    lines = stderr.splitlines()

    assert "Traceback" not in stderr
    after = {p: p.read_bytes() for p in work.rglob("*") if p.is_file()}
    assert after == before  # inputs untouched, nothing written beside them
    if bad.interrupt:
        assert code == 128 + bad.interrupt, stderr
        assert lines == [bad.error] and stdout == ""
        assert list(out_dir.iterdir()) == []
        return
    if bad.error:
        assert code == bad.status, stderr
        # a usage error names the command, as argparse does; a refused input does not
        assert bool(USAGE.match(stderr)) == (bad.status == 2), stderr
        assert len(lines) == 1, stderr
        assert "error:" in lines[0] and bad.error in lines[0]
        assert stdout == ""
        assert list(out_dir.iterdir()) == []  # no file, complete or partial
        return
    assert code == 0, stderr
    expected = [*bad.printed, f"wrote {out.name if bad.relative else out}"]
    if bad.warning:
        warned = (bad.warning, *bad.more_warnings)
        assert len(lines) == len(warned) + 1 + len(bad.printed), stderr
        for line, part in zip(lines, warned, strict=False):
            assert line.startswith("hullslice: warning: ") and part in line, stderr
        expected[:0] = lines[: len(warned)]
    assert stdout == ""  # the result is in its file; a plugin's prints went to stderr
    if bad.read is not None:  # a report folder names its page
        assert lines[-1].startswith(expected[-1]), stderr
        expected[-1] = lines[-1]
    assert lines == expected
    assert [p.name for p in out_dir.iterdir()] == [bad.out_name]
    data = json.loads(out.read_text()) if bad.read is None else bad.read(out)
    assert bad.check is not None
    bad.check(data)


def run_interrupted(argv, plugins, sig: int, tmp: Path) -> tuple[int, str, str]:
    """Run the command line in a process of its own with the fake solvers ``plugins``, send
    it ``sig`` once its solver has started (none when ``sig`` is 0: the run ends by itself),
    and return its status, stdout and stderr."""
    started = tmp / "solver-started"
    program = (
        "import signal, sys\n"
        "signal.signal(signal.SIGINT, signal.default_int_handler)  # as in a terminal\n"
        "from hullslice.solvers import registry\n"
        "from tests.test_bad_input import fake_eps\n"
        f"registry.entry_points = lambda group: fake_eps({list(plugins)!r})\n"
        "registry.refresh()\n"
        "from hullslice.cli import main\n"
        "sys.exit(main(sys.argv[1:]))\n"
    )
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]),
        "HULLSLICE_TEST_HANGING": str(started),
    }
    proc = subprocess.Popen(
        [sys.executable, "-c", program, *argv],
        cwd=ROOT,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        if sig:
            deadline = time.monotonic() + 120
            while not started.exists() and proc.poll() is None and time.monotonic() < deadline:
                time.sleep(0.02)
            assert started.exists(), proc.communicate(timeout=10)
            proc.send_signal(sig)
        stdout, stderr = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()
    return proc.returncode, stdout, stderr


def test_a_failure_after_the_work_leaves_no_file(tmp_path, capsys, monkeypatch):
    # the report cannot be written (disk full, ...): the target is absent, not half written
    from hullslice import atomic as report

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
    assert code == 3
    assert (
        stderr.strip() == f"hullslice: error: cannot write {str(target)!r} (--output): No space "
        "left on device; free some space, or give a path on another disk"
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["wedge.stl"]


@pytest.mark.parametrize(
    ("stop", "line", "status"),
    [
        (KeyboardInterrupt, "hullslice: interrupted", 130),
        (Terminated, "hullslice: terminated", 143),
    ],
)
def test_a_run_stopped_while_writing_leaves_no_file(
    tmp_path, capsys, monkeypatch, stop, line, status
):
    # Ctrl-C or SIGTERM in the middle of the write: neither the target nor the temporary file
    from hullslice import atomic as report

    real_fdopen = report.os.fdopen

    def fdopen(*args, **kw):
        fh = real_fdopen(*args, **kw)

        def write(data):
            real_write(data[: len(data) // 2])
            raise stop()

        real_write, fh.write = fh.write, write
        return fh

    monkeypatch.setattr(report.os, "fdopen", fdopen)
    target = tmp_path / "force.json"
    code = main(["force", wedge_file(tmp_path), *STATE, "--format", "json", "-o", str(target)])
    assert code == status
    assert capsys.readouterr().err.splitlines() == [line]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["wedge.stl"]


def test_an_isolated_run_gives_what_the_run_gives(tmp_path):
    # --isolate: the result on stdout and the status of the run in its child; a refused
    # input is its one line and status 3, once (not repeated by the parent)
    argv = ["force", wedge_file(tmp_path), *STATE, "--format", "json"]
    code, stdout, stderr = run_interrupted(["--isolate", *argv], (), 0, tmp_path)
    assert code == 0 and stderr == ""
    assert json.loads(stdout)["force"] == pytest.approx(wedge_force(), rel=1e-9)
    code, stdout, stderr = run_interrupted(["--isolate", *argv, "--slices", "0"], (), 0, tmp_path)
    assert code == 2 and stdout == ""
    assert len(stderr.splitlines()) == 1 and USAGE.match(stderr)


def test_an_isolated_run_stopped_with_sigterm_stops_its_child(tmp_path):
    # kill PID of the parent: passed on to the child, which stops as a run does (one line,
    # status 143); the parent adds nothing
    argv = ["--isolate", "force", wedge_file(tmp_path), *STATE, "--solver", "hangs"]
    code, stdout, stderr = run_interrupted(argv, ("hangs",), signal.SIGTERM, tmp_path)
    assert (code, stdout, stderr.splitlines()) == (143, "", ["hullslice: terminated"])


def test_a_full_stdout_is_one_line(tmp_path):
    # the result printed to a device that takes no data: one line naming stdout, status 3
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full on this system")
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]),
    }
    with open("/dev/full", "w") as full:
        proc = subprocess.run(
            [sys.executable, "-m", "hullslice", "force", wedge_file(tmp_path), *STATE],
            stdout=full, stderr=subprocess.PIPE, text=True, env=env, timeout=120,
        )  # fmt: skip
    assert proc.returncode == 3
    assert proc.stderr.splitlines() == [
        "hullslice: error: cannot write the result to stdout: No space left on device; free "
        "some space, or give -o PATH"
    ]


def test_sigterm_raises_where_the_run_is(tmp_path):
    # the handler main() installs turns SIGTERM into an exception in the main thread
    with terminated_cleanly(), pytest.raises(Terminated):
        os.kill(os.getpid(), signal.SIGTERM)
        time.sleep(5)
    assert signal.getsignal(signal.SIGTERM) is not _raise_terminated


# -- the docs' table -------------------------------------------------------------------------


def readme_table() -> str:
    """The catalogue as the Markdown table of docs/meshes.md."""
    rows = ["| Bad input | What you get |", "| --- | --- |"]
    rows += [f"| {b.input} | {b.gets} |" for b in CATALOGUE]
    return "\n".join(rows)


def test_the_readme_lists_every_bad_input():
    readme = (ROOT / "docs" / "meshes.md").read_text(encoding="utf-8")
    assert "## Bad input" in readme
    section = readme.split("## Bad input", 1)[1].split("\n## ", 1)[0]
    assert readme_table() in section, (
        "the Bad input table of docs/meshes.md differs from the catalogue: "
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
    # hostile inputs: writes outside a case's folder, lost inputs, silent wrong loads,
    # memory, checks switched off, faulty plugins, and the smaller ones
    hostile = {
        "case-output-outside", "case-output-absolute", "case-output-through-link",
        "mesh-name-newline", "report-markup", "run-output-is-the-case",
        "output-is-a-solver-table", "output-link-to-input", "report-overwrite-input-table",
        "self-intersecting-box", "self-intersecting-wedge", "far-open-mesh",
        "stray-far-vertex", "obj-continuation-lines", "solver-option-nan",
        "solver-option-negative", "case-solver-option-nan", "solver-valid-nan",
        "solver-valid-text", "solver-sys-exit", "solver-system-exit-message",
        "solver-exit-on-start", "solver-hangs-ctrl-c", "solver-hangs-kill",
        "output-link-to-device", "stale-temp-file", "csv-latin-1", "csv-utf-16",
        "csv-byte-order-mark", "csv-overflow", "csv-line-numbers", "plot-not-a-figure",
        "case-deeply-nested", "case-path-to-system-file", "huge-prism", "tiny-far-shell",
        "far-from-the-origin", "obj-byte-order-mark", "case-byte-order-mark",
        "hole-at-the-nose", "usage",
    }  # fmt: skip
    assert hostile <= ids
    # real aircraft exports: welded and inside-out shells, a body far out, a far part
    exports = {
        "open-far-repair-close", "welded-fuselage-keep-largest", "open-export-info",
        "overlapping-inside-out", "far-away-shell",
    }  # fmt: skip
    assert exports <= ids
    # the second round: silent wrong results, resources, plugins and messages
    second = {
        "kinematics-draft-disagrees", "kinematics-repeated-column", "mass-table-both-forms",
        "solver-total-overflows", "stepped-hull-wetted-length", "mass-overflows",
        "resume-edited-record", "resume-malformed-records", "solver-prints",
        "solver-changes-folder", "solver-os-exit", "solver-segfault",
        "gmsh-declares-more-than-it-holds", "output-full-device", "output-name-255-bytes",
        "sweep-too-many-cases", "sweep-workers-above-cores", "sweep-scheduler-without-workers",
        "3mf-directory-understates", "3mf-model-too-large", "kinematics-too-many-rows",
        "kinematics-rows-times-slices", "simulate-steps-times-slices",
    }  # fmt: skip
    assert second <= ids
    assert len(ids) == len(CATALOGUE)
    assert {kind(b) for b in CATALOGUE} == {"error", "repair", "result"}


if __name__ == "__main__":
    print(readme_table())
