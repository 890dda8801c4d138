"""Names from inputs written escaped, and the paths a case file may write (hullslice.paths)."""

from __future__ import annotations

import ast
import tomllib

import pytest
from hypothesis import given
from hypothesis import strategies as st

import hullslice as hs
from hullslice.case import write_case
from hullslice.paths import markdown_text, printable, toml_string

# any text a file name or a title can hold, lone surrogates (undecodable bytes) aside
TEXT = st.text(st.characters(exclude_categories=("Cs",)), max_size=40)


@given(TEXT)
def test_a_toml_string_reads_back_as_the_text(text):
    assert tomllib.loads(f"k = {toml_string(text)}")["k"] == text


@given(TEXT)
def test_printable_text_is_one_line_of_visible_characters(text):
    out = printable(text)
    assert out.isprintable() and "\n" not in out
    assert printable(text) == text or "\\" in out  # what changed is escaped
    # the escapes read back: a Python string literal of the same text
    assert ast.literal_eval("'" + out.replace("'", "\\'") + "'") == text


@given(TEXT)
def test_markdown_text_has_no_markup_left(text):
    out = markdown_text(text)
    assert "\n" not in out and out.isprintable()
    # every markup character is escaped: removing the escaped ones leaves none
    bare = out.replace("\\\\", "")
    for ch in "`*_[]<>|&!#~":
        assert bare.count(ch) == bare.count("\\" + ch)


def test_a_name_with_undecodable_bytes_cannot_be_written_to_a_case():
    with pytest.raises(hs.CaseError, match="holds bytes that are not UTF-8 text"):
        toml_string("hull\udcff.stl", "mesh")


def test_a_saved_case_leaves_out_an_output_outside_its_folder(tmp_path):
    # --save-case cases/c.toml with -o elsewhere: the case must not write outside its folder
    (tmp_path / "cases").mkdir()
    mesh = tmp_path / "cases" / "w.stl"
    mesh.write_text("solid x\nendsolid x\n")
    case = {
        "command": "force",
        "mesh": mesh,
        "mass": 1.0,
        "draft": 0.01,
        "velocity": -1.0,
        "output": tmp_path / "out.json",
        "plot": tmp_path / "cases" / "figure.png",
    }
    path = write_case(case, tmp_path / "cases" / "c.toml")
    loaded = hs.load_case(path)
    assert "output" not in loaded
    assert loaded["plot"] == tmp_path / "cases" / "figure.png"
    assert "# output left out: it is outside this folder" in path.read_text()
