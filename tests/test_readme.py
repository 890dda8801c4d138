"""The README is a front page: its quick start is CI's, and the API page's example runs as it
is written (tests/test_docs.py runs every command and block of every page)."""

from __future__ import annotations

import contextlib
import io
import os

from .conftest import ROOT

TEST_COMMAND = (
    'pip install -e ".[test]" -e plugins/von-karman -e plugins/wagner -e plugins/curves '
    "-e plugins/zarnick -e plugins/mlm && python -m pytest"
)


def quick_start() -> list[str]:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    section = readme.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    return [line[4:] for line in section.split("\n") if line.startswith("    ")]


def test_the_quick_start_is_two_commands_and_the_second_is_what_ci_runs():
    first, second = quick_start()
    assert second == TEST_COMMAND
    assert TEST_COMMAND in (ROOT / ".ci" / "run").read_text(encoding="utf-8").splitlines()
    # the first makes a virtual environment, installs the figures' extra and every plugin,
    # and runs the paper's case
    steps = [s.strip() for s in first.split("&&")]
    assert steps[0].startswith("python -m venv ") and "activate" in steps[1]
    assert '".[plot]"' in steps[2]
    for plugin in ("von-karman", "wagner", "curves", "zarnick"):
        assert f"-e plugins/{plugin}" in steps[2]
    assert steps[-1] == "hullslice run examples/paper.toml"


def test_the_front_page_quotes_the_papers_case():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    for figure in ("147.9106 N", "147.7947 N", "137.9688 N", "docs/paper_convergence.png"):
        assert figure in readme


def test_the_python_api_example_runs(monkeypatch):
    page = (ROOT / "docs" / "api.md").read_text(encoding="utf-8")
    code = page.split("```python\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(ROOT)  # its paths are relative to the repository
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "docs/api.md", "exec"), {"__name__": "readme"})
    printed = out.getvalue()
    assert os.getcwd() == str(ROOT)
    assert "momentum" in printed and "free-fall" in printed
