"""The README's Python examples run as they are written (the docs cannot drift from the code)."""

from __future__ import annotations

import contextlib
import io
import os

from .conftest import ROOT


def test_the_python_api_example_runs(monkeypatch):
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    code = readme.split("## Python API", 1)[1].split("```python\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(ROOT)  # its paths are relative to the repository
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "README.md", "exec"), {"__name__": "readme"})
    printed = out.getvalue()
    assert os.getcwd() == str(ROOT)
    assert "momentum" in printed and "free-fall" in printed
