"""Without an optional extra, every command that needs it says in one line what to install
and exits with status 3, before any work and before any file is written.

Each extra is taken away in a fresh interpreter (tests/without_extras.py: an import hook
refuses its modules, and the commands' computations are replaced by one that fails, so that
a command reaching its work before its check says so). The expected line is the hint of
:func:`hullslice.extras.need`.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

import hullslice as hs
from hullslice.extras import EXTRAS

from .conftest import MESHES, ROOT

HELPER = Path(__file__).with_name("without_extras.py")
PRISM = str(MESHES / "paper_prism.stl")
DIRTY = str(MESHES / "dirty" / "dirty_aircraft.stl")
PAPER_CASE = str(ROOT / "examples" / "paper.toml")
SWEEP_CASE = """mesh = "{mesh}"
mass = 10.0
velocity = -4.0
t_end = 0.01
dt = 0.001
slices = 8
{extra}
[sweep]
mass = [8.0, 12.0]
"""


def without(modules: str, argvs: list[list[str]], cwd: Path) -> list[dict]:
    """Run the command lines in a fresh interpreter where ``modules`` cannot be imported."""
    done = subprocess.run(
        [sys.executable, str(HELPER), modules, json.dumps(argvs)],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def hint(what: str, module: str, extra: str) -> str:
    return (
        f"hullslice: error: {what} needs {module}: pip install 'hullslice[{extra}]' "
        f"(or pip install {module})\n"
    )


def check(results: list[dict], expected: list[str], argvs, folder: Path, before: set) -> None:
    for got, want, argv in zip(results, expected, argvs, strict=True):
        assert got["err"] == want, (argv, got["err"])
        assert got["code"] == 3 and got["out"] == "", argv
    assert set(folder.iterdir()) == before  # no output, no temporary file, no report folder


def sweep_case(tmp: Path, extra: str = "", mesh: Path = MESHES / "wedge_prism.stl") -> str:
    path = tmp / "sweep.toml"
    path.write_text(SWEEP_CASE.format(mesh=mesh, extra=extra))
    return str(path)


def test_every_module_of_every_extra_is_in_pyproject():
    text = (ROOT / "pyproject.toml").read_text()
    assert set(EXTRAS) <= {"plot", "repair", "formats", "sweep"}
    for extra, modules in EXTRAS.items():
        block = text.split(f"\n{extra} = [", 1)[1].split("]\n", 1)[0]
        for module in modules:
            assert module in block, (extra, module)


def test_without_matplotlib_every_figure_is_refused_first(tmp_path):
    argvs = [
        ["info", PRISM, "--plot", "x.png"],
        ["sections", PRISM, "--draft", "0.03", "--slices", "8", "--plot", "x.png"],
        ["force", PRISM, "--mass", "1", "--draft", "0.03", "--velocity=-3", "--plot", "x.png"],
        ["simulate", PRISM, "--mass", "1", "--velocity=-4", "--t-end", "0.004", "--plot", "x.png"],
        ["run", PAPER_CASE, "--plot", "x.png"],
        ["report", PAPER_CASE, "-o", "report"],
    ]
    before = set(tmp_path.iterdir())
    results = without("matplotlib", argvs, tmp_path)
    expected = [hint("--plot", "matplotlib", "plot")] * 5 + [hint("a report", "matplotlib", "plot")]
    check(results, expected, argvs, tmp_path, before)


def test_without_pymeshfix_repair_close_is_refused_first(tmp_path):
    argvs = [
        ["info", DIRTY, "--repair", "close"],
        ["force", DIRTY, "--repair", "close", "--mass", "9000", "--draft", "0.3",
         "--velocity=-2"],
        ["sweep", sweep_case(tmp_path, 'repair = "close"'), "--workers", "1"],
    ]  # fmt: skip
    before = set(tmp_path.iterdir())
    results = without("pymeshfix", argvs, tmp_path)
    expected = [hint("--repair close", "pymeshfix", "repair")] * 2 + [
        hint('repair = "close"', "pymeshfix", "repair")
    ]
    check(results, expected, argvs, tmp_path, before)


def test_without_the_formats_extra_its_meshes_are_refused_first(tmp_path):
    wedge = hs.load_hull(MESHES / "wedge_prism.stl")
    for ext in ("ply", "off", "glb", "3mf"):
        wedge.save(tmp_path / f"w.{ext}")
    (tmp_path / "w.msh").write_bytes(b"$MeshFormat\n")  # refused before it is read
    argvs = [
        ["info", "w.ply"],
        ["info", "w.msh"],
        ["info", PRISM, "--write-mesh", "out.off"],
        ["sweep", sweep_case(tmp_path, mesh=tmp_path / "w.glb"), "--workers", "1"],
    ]
    before = set(tmp_path.iterdir())
    results = without("trimesh,meshio", argvs, tmp_path)
    expected = [
        hint("reading PLY files", "trimesh", "formats"),
        hint("reading Gmsh .msh files", "meshio", "formats"),
        hint("writing OFF files", "trimesh", "formats"),
        hint("reading GLB files", "trimesh", "formats"),
    ]
    check(results, expected, argvs, tmp_path, before)
    # a 3MF also needs lxml and networkx, read or written
    argvs = [["info", "w.3mf"], ["info", PRISM, "--write-mesh", "out.3mf"]]
    results = without("lxml", argvs, tmp_path)
    expected = [
        hint("reading 3MF files", "lxml", "formats"),
        hint("writing 3MF files", "lxml", "formats"),
    ]
    check(results, expected, argvs, tmp_path, before)


@pytest.mark.parametrize(
    ("modules", "args", "what", "module"),
    [
        ("xarray", [], "a sweep", "xarray"),
        ("distributed", [], "a sweep", "distributed"),
        ("distributed", ["--scheduler", "tcp://127.0.0.1:1"], "a sweep", "distributed"),
        ("h5netcdf", ["-o", "out.nc"], "netCDF output", "h5netcdf"),
        ("zarr", ["-o", "out.zarr"], "Zarr output", "zarr"),
        ("pyarrow", ["-o", "out.parquet"], "Parquet output", "pyarrow"),
    ],
)
def test_without_the_sweep_extra_a_sweep_is_refused_first(tmp_path, modules, args, what, module):
    argvs = [["sweep", sweep_case(tmp_path), *args]]
    before = set(tmp_path.iterdir())
    results = without(modules, argvs, tmp_path)
    check(results, [hint(what, module, "sweep")], argvs, tmp_path, before)


def test_with_every_extra_the_helper_reaches_the_work(tmp_path):
    """The helper's stand-in for the work is reached when nothing is missing: the tests
    above would see it if a check came after the work."""
    argvs = [["info", PRISM, "--plot", "x.png"]]
    (got,) = without("openplaning", argvs, tmp_path)
    assert got["code"] == 1 and "RuntimeError: work started" in got["err"]
