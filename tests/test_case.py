"""Case files: TOML read as data and checked key by key against the declared schema."""

from __future__ import annotations

from pathlib import Path

import pytest

import hullslice as hs
from hullslice.case import MAX_CASE_BYTES, SCHEMA

PAPER_CASE = """\
# the paper's prism at t = 0.01 s
title = "paper prism"
mesh = "hulls/paper_prism.stl"
units = "M"
mass = 1                 # kg, an integer is a number too
draft = 0.0383           # m
velocity = -3.4943       # m/s
slices = [16, 32, 64]
t_end = 0.03
dt = 1e-4
kinematics = "kin.csv"
continue_invalid = false
pitch = 4.5                  # deg
forward_speed = 0.0
cg = [0.17, -0.03]           # m
mass_distribution = "mass.csv"
slicing = "fixed"

[solver_options]
froude_min = 6.5
"""


def write(tmp_path: Path, text: str, name: str = "case.toml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_a_full_case_is_read_with_its_types_and_defaults(tmp_path):
    case = hs.load_case(write(tmp_path, PAPER_CASE))
    assert case["mesh"] == tmp_path / "hulls" / "paper_prism.stl"  # relative to the file
    assert case["kinematics"] == tmp_path / "kin.csv"
    assert case["units"] == "m"  # case-insensitive, normalised
    assert case["mass"] == 1.0 and isinstance(case["mass"], float)
    assert case["slices"] == [16, 32, 64]
    assert case["draft"] == 0.0383 and case["velocity"] == -3.4943
    assert case["continue_invalid"] is False
    assert case["solver_options"] == {"froude_min": 6.5}
    assert case["pitch"] == 4.5 and case["cg"] == (0.17, -0.03)
    assert case["mass_distribution"] == tmp_path / "mass.csv"
    assert case["slicing"] == "fixed"
    # defaults of the keys that have one
    assert case["rho"] == hs.RHO_WATER and case["g"] == hs.G
    assert case["deadrise"] == "wedge"
    # the mesh's axes, like its unit, default to what the file declares (else +x, +z)
    assert "forward" not in case and "up" not in case
    assert case["solver"] == "extended-von-karman"
    assert set(case) <= set(SCHEMA)


def test_one_slice_count_is_a_list_of_one():
    assert hs.validate_case({"mesh": "a.stl", "slices": 32})["slices"] == [32]


@pytest.mark.parametrize(
    ("case", "message"),
    [
        ({"mesh": "a.stl", "mas": 1.0}, "unknown key 'mas'; did you mean 'mass'?"),
        (
            {"mesh": "a.stl", "colour": "red"},
            "unknown key 'colour'; the keys are title, command, mesh",
        ),
        ({"mass": 1.0}, "key 'mesh' is missing"),
        ({"mesh": 3}, "key 'mesh' must be a file path in quotes"),
        (
            {"mesh": "a.stl", "mass": "1.0"},
            "key 'mass' must be a number in kg (mass of the body), not the text '1.0' "
            "(write the number without quotes)",
        ),
        ({"mesh": "a.stl", "mass": True}, "key 'mass' must be a number in kg"),
        ({"mesh": "a.stl", "mass": float("nan")}, "a finite number is needed"),
        ({"mesh": "a.stl", "rho": float("inf")}, "key 'rho' must be a number in kg/m^3"),
        ({"mesh": "a.stl", "mass": -1}, "key 'mass' (mass of the body) must be positive: -1.0 kg"),
        ({"mesh": "a.stl", "mass": 0.0}, "must be positive: 0.0 kg"),
        ({"mesh": "a.stl", "draft": -0.1}, "key 'draft' (depth of the lowest point below"),
        ({"mesh": "a.stl", "g": -9.81}, "key 'g' (gravitational acceleration) must not be"),
        ({"mesh": "a.stl", "slices": 32.0}, "key 'slices' must be a whole number or a list"),
        ({"mesh": "a.stl", "slices": "32"}, "not the text '32'"),
        ({"mesh": "a.stl", "slices": []}, "give at least one count"),
        ({"mesh": "a.stl", "slices": [16, 0]}, "must be from 1 to 100000 (got 0)"),
        ({"mesh": "a.stl", "slices": [16, 16]}, "must not repeat a count"),
        ({"mesh": "a.stl", "units": "yd"}, "key 'units' (length unit of the mesh) must be one"),
        ({"mesh": "a.stl", "forward": "w"}, "key 'forward' (mesh axis pointing forward)"),
        ({"mesh": "a.stl", "forward": "z"}, "'forward' ('z') and 'up' ('+z') are the same axis"),
        ({"mesh": "a.stl", "continue_invalid": "yes"}, "must be true or false"),
        ({"mesh": "a.stl", "solver_options": 3}, "key 'solver_options' must be a table"),
        ({"mesh": "a.stl", "t_end": 0.01, "dt": 0.1}, "'dt' (0.1 s) is longer than the run"),
        ({"mesh": "a.stl", "velocity": [1, 2]}, "key 'velocity' must be a number in m/s"),
        ({"mesh": "a.stl", "cg": [12.5]}, "key 'cg' must be a list of two numbers in m"),
        ({"mesh": "a.stl", "cg": [1, "2"]}, "(write e.g. [12.5, 0.3])"),
        ({"mesh": "a.stl", "inertia": 0}, "key 'inertia' (pitch moment of inertia"),
        ({"mesh": "a.stl", "slicing": "random"}, "key 'slicing' (how the slices are placed)"),
        ({"mesh": "a.stl", "deadrise": "best"}, "must be one of wedge, waterline-slope"),
        ({"mesh": "a.stl", "free_pitch": 1}, "key 'free_pitch' must be true or false"),
    ],
)
def test_bad_keys_and_values(case, message):
    with pytest.raises(hs.CaseError) as info:
        hs.validate_case(case)
    assert message in str(info.value)
    assert isinstance(info.value, hs.InputError)  # a CaseError is an input error


@pytest.mark.parametrize(
    ("content", "message"),
    [
        (None, "does not exist"),
        (b"mesh = 'a.stl'\nmass = \n", "at line 2, column 8"),
        (b"mesh = 'a.stl'\nmesh = 'b.stl'\n", "is not valid TOML"),
        (b"\xff\xfe m\x00", "is not UTF-8 text (byte 0)"),
        (b"[hull]\nmesh = 'a.stl'\n", "unknown key 'hull'"),
        (b"mesh = 'a.stl'\nmass = '2'\n", "case file '"),
    ],
)
def test_bad_case_files(tmp_path, content, message):
    path = tmp_path / "case.toml"
    if content is not None:
        path.write_bytes(content)
    with pytest.raises(hs.CaseError) as info:
        hs.load_case(path)
    assert message in str(info.value)


def test_a_folder_and_a_huge_file_are_refused(tmp_path):
    with pytest.raises(hs.CaseError, match="is not a file"):
        hs.load_case(tmp_path)
    big = write(tmp_path, "# " + "x" * MAX_CASE_BYTES + "\nmesh = 'a.stl'\n")
    with pytest.raises(hs.CaseError, match="larger than 1024 KiB"):
        hs.load_case(big)


def test_nothing_in_a_case_file_is_executed(tmp_path):
    # text that Python would run is only a string value to TOML
    marker = tmp_path / "ran"
    code = f"__import__('pathlib').Path({str(marker)!r}).touch()"
    case = hs.load_case(write(tmp_path, f"mesh = 'a.stl'\ntitle = {code!r}\n"))
    assert case["title"] == code
    assert not marker.exists()


def test_every_schema_key_has_a_documented_kind_and_unit():
    numbers = {k.name: k.unit for k in SCHEMA.values() if k.kind == "number"}
    assert numbers == {
        "scale": "m per file unit",
        "length": "m",
        "mass": "kg",
        "inertia": "kg*m^2",
        "rho": "kg/m^3",
        "g": "m/s^2",
        "draft": "m",
        "pitch": "deg",
        "velocity": "m/s",
        "forward_speed": "m/s",
        "pitch_rate": "deg/s",
        "t_end": "s",
        "dt": "s",
        "acceleration": "m/s^2",
        "max_flagged_share": "",  # a share of the force, 0 to 1
        "lift_fraction": "",  # a share of the weight, 0 to 2
        "stall_deg": "deg",
        "wing_area": "m^2",
        "wing_chord": "m",
        "cl0": "",
        "cl_alpha": "1/rad",
        "cl_max": "",
        "cd": "",
        "cm0": "",
        "cm_alpha": "1/rad",
        "cm_q": "1/rad",
        "thrust": "N",
    }
    assert all(k.help for k in SCHEMA.values())


def test_a_sweep_case_run_as_one_case_names_the_sweep_command(tmp_path):
    case = tmp_path / "sweep.toml"
    case.write_text('mesh = "m.stl"\nmass = 1.0\n\n[sweep]\nvelocity = [-1.0, -2.0]\n')
    with pytest.raises(
        hs.CaseError, match=r"has a \[sweep\] table: .* 'hullslice sweep CASE.toml'"
    ):
        hs.load_case(case)
