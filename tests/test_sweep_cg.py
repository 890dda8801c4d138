"""Sweeps of the centre of gravity: ``cg_x`` and ``cg_z`` (m) set one component of the case's
``cg``, and each case equals the single run with that centre of gravity exactly."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

import hullslice as hs
from hullslice.cli import main

pytest.importorskip("xarray")

ROOT = Path(__file__).resolve().parents[1]
WEDGE = ROOT / "meshes" / "wedge_prism.stl"

# a 1 m prism of 30-degree wedge section, pitched 3 degrees at 2 m/s forward, free in
# pitch: where the centre of gravity is changes the pitch moment and so the whole run
BASE = {"mesh": str(WEDGE), "mass": 10.0, "cg": [0.5, 0.05], "velocity": -4.0,
        "t_end": 0.01, "dt": 0.001, "slices": 8, "pitch": 3.0, "forward_speed": 2.0,
        "free_pitch": True}  # fmt: skip


def single(cg: tuple[float, float], velocity: float = -4.0) -> hs.History:
    """The reference: the case run alone with the centre of gravity ``cg`` (x, z in m)."""
    hull = hs.load_hull(WEDGE, mass=10.0, cg=cg)
    return hs.simulate(hull, velocity, 0.01, dt=0.001, slices=8, pitch_rad=math.radians(3.0),
                       forward_speed=2.0, free_pitch=True)  # fmt: skip


def test_a_sweep_of_cg_x_equals_single_runs_exactly():
    xs = [0.4, 0.5, 0.6]
    ds = hs.sweep(BASE, {"cg_x": xs, "velocity": [-3.0, -4.0]}, workers=1)
    assert ds["peak_force"].dims == ("cg_x", "velocity")
    assert ds["cg_x"].attrs["units"] == "m"
    assert "centre of gravity x" in ds["cg_x"].attrs["long_name"]
    peaks = set()
    for x in xs:
        for v in (-3.0, -4.0):
            ref = single((x, 0.05), v)
            point = ds.sel(cg_x=x, velocity=v)
            assert point["error"].item() == ""
            assert point["peak_force"].item() == ref.peak["force"]
            assert point["peak_moment"].item() == float(ref.moment[abs(ref.moment).argmax()])
            assert point["final_pitch_deg"].item() == math.degrees(ref.pitch[-1])
            assert point["steps"].item() == len(ref)
            peaks.add(point["peak_force"].item())
    assert len(peaks) == 6  # the centre of gravity does change the results
    # the base case keeps its own cg, the grid names the swept part
    assert json.loads(ds.attrs["base_case"])["cg"] == [0.5, 0.05]
    assert json.loads(ds.attrs["sweep"])["cg_x"] == xs


def test_a_cases_table_with_cg_columns(tmp_path):
    (tmp_path / "doe.csv").write_text("cg_x,cg_z\n0.45,0.0\n0.55,0.1\n")
    base = {k: v for k, v in BASE.items() if k != "cg"}  # both parts given by the table
    lines = [f"{k} = {json.dumps(v)}" for k, v in base.items()]
    case = tmp_path / "case.toml"
    case.write_text("\n".join([*lines, "", "[sweep]", 'cases = "doe.csv"', ""]))
    ds = hs.sweep(case, workers=1)
    assert ds["peak_force"].dims == ("case",)
    assert list(ds["cg_z"].values) == [0.0, 0.1]
    for i, cg in enumerate([(0.45, 0.0), (0.55, 0.1)]):
        assert ds["peak_force"].isel(case=i).item() == single(cg).peak["force"]


def test_the_command_line_sweep_of_cg_z_equals_the_command_line_simulate(tmp_path, capsys):
    lines = [f"{k} = {json.dumps(v)}" for k, v in BASE.items()]
    case = tmp_path / "case.toml"
    case.write_text("\n".join([*lines, "", "[sweep]", "cg_z = [0.0, 0.1]", ""]))
    out = tmp_path / "out.nc"
    assert main(["sweep", str(case), "-o", str(out), "--workers", "1"]) == 0
    from hullslice.xarray_io import read_dataset

    ds = read_dataset(out)
    assert main(["simulate", str(WEDGE), "--mass", "10", "--cg", "0.5,0.1", "--velocity=-4",
                 "--t-end", "0.01", "--dt", "0.001", "--slices", "8", "--pitch", "3",
                 "--forward-speed", "2", "--free-pitch", "--format", "json"]) == 0  # fmt: skip
    ref = json.loads(capsys.readouterr().out)
    assert ds["peak_force"].sel(cg_z=0.1).item() == ref["peak"]["force"]
    assert ds["final_pitch_deg"].sel(cg_z=0.1).item() == ref["history"]["pitch_deg"][-1]


@pytest.mark.parametrize(
    ("grid", "message"),
    [
        ({"cg_y": [0.1]}, "[sweep] unknown key 'cg_y'; did you mean 'cg_z'?"),
        ({"cg": [[0.4, 0.0]]}, "key 'cg' is not a number key of a simulate case"),
        ({"cg_x": [0.4, "front"]}, "key 'cg_x': every value must be a finite number in m"),
        ({"cg_x": [0.4, 0.4]}, "key 'cg_x' repeats a value"),
    ],
)
def test_a_bad_cg_key_is_refused_by_name(grid, message):
    with pytest.raises(hs.CaseError) as exc:
        hs.sweep(BASE, grid, workers=1)
    assert message in str(exc.value)


def test_a_part_of_cg_needs_the_other_part():
    base = {k: v for k, v in BASE.items() if k != "cg"}
    with pytest.raises(hs.CaseError, match=r"'cg_x' sets a part of the case's 'cg'.*add cg = "):
        hs.sweep(base, {"cg_x": [0.4, 0.6]}, workers=1)
    # both parts swept: no cg needed in the base case
    ds = hs.sweep(base, {"cg_x": [0.4], "cg_z": [0.05]}, workers=1)
    assert ds["peak_force"].item() == single((0.4, 0.05)).peak["force"]


def test_a_sweep_of_slice_counts_equals_single_runs_exactly():
    ds = hs.sweep(BASE, {"slices": [4, 8]}, workers=1)
    for n in (4, 8):
        point = ds.sel(slices=n)
        assert point["error"].item() == ""
        hull = hs.load_hull(WEDGE, mass=10.0, cg=(0.5, 0.05))
        ref = hs.simulate(hull, -4.0, 0.01, dt=0.001, slices=n, pitch_rad=math.radians(3.0),
                          forward_speed=2.0, free_pitch=True)  # fmt: skip
        assert point["peak_force"].item() == ref.peak["force"]
        assert point["final_slices"].item() == ref.slices[-1]


def test_a_sweep_reads_its_mesh_as_a_single_run_does(tmp_path):
    # no_fix: a mesh that needs a fix (one face wound against its neighbours) is refused by
    # a sweep as by hullslice simulate, naming the pass, and nothing is computed
    from .conftest import flipped_wedge_obj

    mesh = flipped_wedge_obj(tmp_path)
    base = {**BASE, "mesh": str(mesh), "no_fix": True}
    with pytest.raises(hs.MeshError, match="would fix it"):
        hs.sweep(base, {"velocity": [-3.0, -4.0]}, workers=1)
    with pytest.warns(hs.MeshRepairWarning, match="re-oriented 1 faces"):
        fixed = hs.sweep({**base, "no_fix": False}, {"velocity": [-3.0, -4.0]}, workers=1)
    assert (fixed["error"].values == "").all()
