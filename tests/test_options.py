"""The option table drives the three front ends: the case-file schema, the command line
and :class:`~hullslice.study.Study` (``hullslice.options``)."""

from __future__ import annotations

import argparse
import dataclasses

import pytest

from hullslice.case import COMMAND_KEYS, SCHEMA, load_case, write_case
from hullslice.cli import build_parser
from hullslice.cli.options import add_option
from hullslice.options import COMMANDS, OPTIONS, Option, option
from hullslice.study import Study

# study fields that are not options: where a study was read from
NOT_OPTIONS = {"case_file"}


def _subparsers() -> dict[str, argparse.ArgumentParser]:
    parser = build_parser()
    (sub,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return dict(sub.choices)


def test_every_study_field_has_one_row():
    fields = {f.name for f in dataclasses.fields(Study)} - NOT_OPTIONS
    attributes = [o.attribute for o in OPTIONS]
    assert sorted(attributes) == sorted(set(attributes))  # one row a field
    assert set(attributes) == fields


def test_study_defaults_are_the_tables():
    for f in dataclasses.fields(Study):
        if f.name in NOT_OPTIONS or f.default is dataclasses.MISSING:
            continue
        row = next(o for o in OPTIONS if o.attribute == f.name)
        assert f.default == row.study_default, f.name


def test_case_schema_is_the_table():
    assert list(SCHEMA) == [o.name for o in OPTIONS]
    assert all(SCHEMA[o.name] is o for o in OPTIONS)
    for command in COMMANDS:
        assert COMMAND_KEYS[command] == {o.name for o in OPTIONS if command in o.commands}


@pytest.mark.parametrize("command", COMMANDS)
def test_parser_is_built_from_the_table(command):
    """Each command's parser has exactly the rows its command takes (the case-file-only
    ``title`` and ``command`` aside), each with the row's flag, help and destination."""
    parser = _subparsers()[command]
    by_dest: dict[str, argparse.Action] = {}
    for a in parser._actions:  # the first of a destination: --water names a --rho
        by_dest.setdefault(a.dest, a)
    for row in OPTIONS:
        dest = "solver_option" if row.kind == "table" else row.name
        if row.cli is None or command not in row.commands:
            assert dest not in by_dest or row.name == "command", row.name
            continue
        action = by_dest[dest]
        cli = row.command_line(command)
        flags = cli.get("flags", (row.flag,))
        assert tuple(action.option_strings or (action.dest,)) == tuple(flags)
        if "{figure}" in cli["help"]:
            head = cli["help"].split("{figure}")[0]
            assert action.help.startswith(head)
        else:
            assert action.help == cli["help"]
        if row.choices:
            assert list(action.choices) == list(row.choices)
    # and nothing of the study's inputs is declared beside the table
    keys = {o.name for o in OPTIONS} | {"solver_option"}
    own = {a.dest for a in parser._actions} - keys
    assert own <= {"help", "save_case", "write_mesh", "pressures", "pressures_out",
                   "pressures_every", "frames", "frame_spacing"}, own  # fmt: skip


def test_a_row_makes_its_option():
    """A row is all an option needs: its flag, type by kind and unit, default, help."""
    row = Option("sink_limit", "number", "m/s", "a test row", 2.5, commands=("simulate",),
                 cli={"metavar": "M/S", "help": "a test row in m/s (default: 2.5)"})  # fmt: skip
    parser = argparse.ArgumentParser()
    import hullslice.options as options

    options._BY_NAME[row.name] = row
    try:
        add_option(parser, row.name, "simulate")
    finally:
        del options._BY_NAME[row.name]
    assert parser.parse_args([]).sink_limit == 2.5
    assert parser.parse_args(["--sink-limit", "4"]).sink_limit == 4.0
    with pytest.raises(SystemExit):
        parser.parse_args(["--sink-limit", "fast"])


@pytest.mark.parametrize(
    "argv",
    [
        ["force", "m.stl", "--mass", "1", "--draft", "0.03", "--velocity", "-3", "--pitch",
         "4", "--slices", "8,16", "--solver-option", "a=1", "--water", "sea"],
        ["simulate", "m.stl", "--mass", "1", "--velocity", "-3", "--t-end", "0.1",
         "--free-pitch", "--lift", "WEIGHT", "--lift-fraction", "0.9", "--at", "0.01,0.02",
         "--cg", "1,2", "--inertia", "3", "--check", "--slicing", "fixed", "--units", "MM",
         "--keep-box=-1,2,-1,1,-1,1", "--pitch-rate", "2", "--dt", "0.001"],
        ["sections", "m.stl", "--draft", "0.1", "--pitch", "2", "--slices", "12",
         "--deadrise", "keel-fit", "--length", "3", "--forward=-y", "--up=+x"],
        ["info", "m.stl", "--stations", "12", "--scale", "0.001", "--keep", "largest"],
    ],
)  # fmt: skip
def test_command_line_round_trip(argv, tmp_path):
    """A study's command line parses back to the same study, and its case file reads back
    to the same case (invariances)."""
    parser = build_parser()
    study = Study.from_args(parser.parse_args(argv))
    again = Study.from_args(parser.parse_args(study.command_line()))
    assert again == study
    case = write_case(study.to_case(), tmp_path / "case.toml")
    assert Study.from_case(load_case(case), checked=True).to_case() == study.to_case()


def test_angle_rows_name_their_unit():
    assert option("pitch").unit == "deg" and option("pitch").attribute == "pitch_deg"
    assert option("pitch_rate").unit == "deg/s"
    assert option("pitch_rate").attribute == "pitch_rate_deg_s"
