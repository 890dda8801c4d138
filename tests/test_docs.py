"""Every command and Python example in README.md and docs/*.md runs as it is written.

What is run, and how (the docs cannot drift from the code):

- A **command** is a line of a code block (indented or fenced) that starts with
  ``hullslice``, ``python`` or ``pip``, optionally after ``$ ``; a line ending in ``\\``
  continues on the next. A chain ``A && B`` is taken part by part.
- **Run**: each ``hullslice ...`` and ``python examples/...`` part, in a temporary folder
  holding ``meshes`` and ``plugins`` (links to the repository's) and a copy of ``examples``,
  so that every output goes there. It must exit with status 0, or 3 where the block quotes
  ``hullslice: error:`` after it.
- **Not run**: ``pip install``, ``python -m venv``, the activation and ``python -m pytest``
  (the suite runs in the environment they make); synopses, which hold placeholders in
  capitals (``MESH``, ``KG``), optional parts in brackets or a description after
  spaces; ``python benchmarks/...``
  (minutes each). Commands quoted inside prose are not run.
- **Quoted output**: after a ``$ `` command, the lines up to the next command are its
  output (``...`` leaves lines out). Every number there with three significant digits or
  more must appear in what the command printed.
- **Python**: every fenced ``python`` block is executed in the same temporary folder.
- Commands that take more than a few seconds are marked ``slow`` (see ``SLOW``).
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import shlex
import shutil
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from .conftest import ROOT

PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]

#: Commands (by their start) that take more than a few seconds: marked slow.
SLOW = (
    "hullslice sweep ",
    "python examples/sweep_envelope.py",
    "hullslice simulate meshes/fuselage_full.obj",
    "python examples/ditching.py",
    "python examples/structure_loads.py",
    "hullslice simulate meshes/fuselage_model.obj --mass 40 --velocity=-1 --t-end 0.1",
    "python examples/drop_test.py",
    "python examples/ditching_pitch.py",
)
#: Commands that read what an earlier command wrote: that one runs first.
NEEDS = {
    "python examples/sweep_envelope.py ditching.nc": (
        "hullslice sweep examples/ditching_sweep.toml -o ditching.nc"
    ),
}
#: Python blocks that take more than a few seconds (a Dask cluster): marked slow.
SLOW_PYTHON = ("Client(",)

NUMBER = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e[-+]?\d+)?(?![\w])")
PLACEHOLDER = re.compile(r"(?<![\w-])[A-Z][A-Z0-9_]*(?![a-z])")
SETUP = ("pip ", "python -m venv", ". ", "source ", "python -m pytest")
COMMAND_START = ("hullslice ", "python ", "pip ", ". ")


@dataclass
class Command:
    page: str
    line: int
    text: str
    output: list[str] = field(default_factory=list)
    quoted: bool = False  # shown with its output after "$ "

    @property
    def id(self) -> str:
        return f"{self.page}:{self.line}"


def code_blocks(text: str) -> list[tuple[int, str, list[str]]]:
    """The code blocks of a Markdown page: (first line number, language, lines)."""
    blocks: list[tuple[int, str, list[str]]] = []
    lines = text.split("\n")
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("```"):
            lang, start, body = line[3:].strip(), i + 2, []
            i += 1
            while i < len(lines) and not lines[i].startswith("```"):
                body.append(lines[i])
                i += 1
            blocks.append((start, lang, body))
        elif line.startswith("    ") and (i == 0 or not lines[i - 1].strip()):
            start, body = i + 1, []
            while i < len(lines) and (lines[i].startswith("    ") or not lines[i].strip()):
                body.append(lines[i][4:])
                i += 1
            while body and not body[-1].strip():
                body.pop()
            blocks.append((start, "", body))
            continue
        i += 1
    return blocks


def commands(page: Path) -> list[Command]:
    """The commands shown in a page's code blocks, with the output quoted after them."""
    found: list[Command] = []
    name = str(page.relative_to(ROOT))
    for start, lang, body in code_blocks(page.read_text(encoding="utf-8")):
        if lang not in ("", "console", "shell", "sh", "bash"):
            continue
        current: Command | None = None
        j = 0
        while j < len(body):
            raw = body[j]
            quoted = raw.startswith("$ ")
            line = raw[2:] if quoted else raw
            if line.startswith(COMMAND_START):
                text = line
                while text.endswith("\\") and j + 1 < len(body):
                    j += 1
                    text = text[:-1].rstrip() + " " + body[j].strip()
                current = Command(name, start + j, text, quoted=quoted)
                found.append(current)
            elif current is not None and current.quoted:
                current.output.append(raw)
            j += 1
    return found


def runnable(part: str) -> bool:
    """Whether a part of a command chain is run (see the module's docstring)."""
    if part.startswith(SETUP) or part.startswith("python benchmarks/"):
        return False
    if "[" in part or "   " in part or part.startswith("..."):
        return False
    return PLACEHOLDER.search(part) is None


def parts(command: Command) -> list[str]:
    return [p.strip() for p in command.text.split("&&")]


ALL = [c for page in PAGES for c in commands(page)]
RUN = [c for c in ALL if any(runnable(p) for p in parts(c))]


def argv(part: str) -> list[str]:
    words = shlex.split(part)
    if words[0] == "hullslice":
        return [sys.executable, "-m", "hullslice", *words[1:]]
    assert words[0] == "python", part
    return [sys.executable, *words[1:]]


@pytest.fixture
def workdir(tmp_path, monkeypatch) -> Path:
    """A folder to run the docs' commands in: their inputs linked or copied, outputs here."""
    (tmp_path / "meshes").symlink_to(ROOT / "meshes", target_is_directory=True)
    (tmp_path / "plugins").symlink_to(ROOT / "plugins", target_is_directory=True)
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def run(part: str, where: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, MPLBACKEND="Agg", COLUMNS="100")
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), env.get("PYTHONPATH")]))
    return subprocess.run(
        argv(part), cwd=where, env=env, capture_output=True, text=True, timeout=600
    )


def significant(number: str) -> int:
    digits = re.sub(r"e.*", "", number.lstrip("-")).replace(".", "").lstrip("0")
    return len(digits)


def params(items, slow_if):
    return [pytest.param(c, id=c.id, marks=[pytest.mark.slow] if slow_if(c) else []) for c in items]


@pytest.mark.parametrize("command", params(RUN, lambda c: c.text.startswith(SLOW)))
def test_a_command_in_the_docs_runs_as_shown(command: Command, workdir: Path):
    for part in parts(command):
        if not runnable(part):
            continue
        for start, earlier in NEEDS.items():
            if part.startswith(start):
                first = run(earlier, workdir)
                assert first.returncode == 0, first.stderr
        done = run(part, workdir)
        printed = done.stdout + done.stderr
        expect_error = any(line.startswith("hullslice: error:") for line in command.output[:1])
        want = 3 if expect_error else 0
        assert done.returncode == want, f"{command.id}: {part}\n{printed[-3000:]}"
        if command.quoted and command.output:
            shown = {n for line in command.output for n in NUMBER.findall(line)}
            got = set(NUMBER.findall(printed))
            missing = sorted(n for n in shown if significant(n) >= 3 and n not in got)
            assert not missing, f"{command.id}: {part}: quoted {missing}, printed:\n{printed}"


def test_the_docs_show_commands_and_run_most_of_them():
    # the extraction itself: a page reorganised so that nothing is found would pass above
    assert len(ALL) >= 20 and len(RUN) >= 12
    texts = [c.text for c in RUN]
    assert "hullslice run examples/paper.toml" in texts
    quoted = [c for c in RUN if c.quoted and c.output]
    assert len(quoted) >= 6


PYTHON = [
    (str(page.relative_to(ROOT)), start, "\n".join(body))
    for page in PAGES
    for start, lang, body in code_blocks(page.read_text(encoding="utf-8"))
    if lang == "python"
]


@pytest.mark.parametrize(
    "page, line, code",
    [
        pytest.param(*block, id=f"{block[0]}:{block[1]}",
                     marks=[pytest.mark.slow] if any(s in block[2] for s in SLOW_PYTHON) else [])
        for block in PYTHON
    ],
)  # fmt: skip
def test_a_python_block_in_the_docs_runs(page: str, line: int, code: str, workdir: Path):
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile("\n" * (line - 1) + code, page, "exec"), {"__name__": "docs"})
    assert Path.cwd() == workdir


# -- links ----------------------------------------------------------------------------------

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")


def slug(heading: str) -> str:
    """GitHub's anchor of a heading."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def anchors(page: Path) -> set[str]:
    text = page.read_text(encoding="utf-8")
    return {slug(m) for m in re.findall(r"^#{1,6} (.+)$", text, flags=re.M)}


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_relative_link_and_image_resolves(page: Path):
    text = page.read_text(encoding="utf-8")
    for target in LINK.findall(text):
        if re.match(r"[a-z]+:", target):
            continue
        path, _, anchor = target.partition("#")
        dest = (page.parent / path).resolve() if path else page
        assert dest.exists(), f"{page.name}: link to {target}: no such file"
        if anchor:
            assert anchor in anchors(dest), f"{page.name}: link to {target}: no such heading"


def test_the_front_page_links_every_docs_page():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    for page in PAGES[1:]:
        assert f"(docs/{page.name})" in readme, page.name


# -- the plugin guide -----------------------------------------------------------------------


def test_the_plugin_guide_builds_a_plugin_that_loads(tmp_path, monkeypatch, paper_hull):
    # the guide's pyproject.toml with the guide's momentum-form solver as its package,
    # installed by hand (a dist-info folder, as pip would write it) and found by name
    import importlib
    import math
    import tomllib

    import hullslice as hs
    from hullslice.solvers import registry

    guide = (ROOT / "docs" / "plugins.md").read_text(encoding="utf-8")
    project = tomllib.loads(guide.split("```toml\n", 1)[1].split("```", 1)[0])
    assert project["build-system"]["build-backend"] == "setuptools.build_meta"
    assert any(r.startswith("setuptools") for r in project["build-system"]["requires"])
    meta = project["project"]
    entry = meta["entry-points"]["hullslice.solvers"]
    assert meta["dependencies"][0].startswith("hullslice")
    (package,) = project["tool"]["setuptools"]["packages"]
    code = guide.split("**A momentum-form solver** implements", 1)[1]
    code = code.split("```python\n", 1)[1].split("```", 1)[0]
    (tmp_path / package).mkdir()
    (tmp_path / package / "__init__.py").write_text(code, encoding="utf-8")
    dist = meta["name"].replace("-", "_")
    info = tmp_path / f"{dist}-{meta['version']}.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(
        f"Metadata-Version: 2.1\nName: {meta['name']}\nVersion: {meta['version']}\n"
    )
    points = "".join(f"{k} = {v}\n" for k, v in entry.items())
    (info / "entry_points.txt").write_text("[hullslice.solvers]\n" + points)
    monkeypatch.syspath_prepend(str(tmp_path))
    importlib.invalidate_caches()
    registry.refresh()
    try:
        (name,) = entry
        mine = hs.get_solver(name, gamma=math.pi / 2)
        assert name in [i.name for i in hs.list_solvers()]
        ref = hs.compute_force(paper_hull, 0.0383, -3.4943, slices=16, solver="wagner")
        got = hs.compute_force(paper_hull, 0.0383, -3.4943, slices=16, solver=mine)
        assert got.total == pytest.approx(ref.total, rel=1e-12)
    finally:
        sys.modules.pop(package, None)
        monkeypatch.undo()
        registry.refresh()


def test_the_benchmark_without_trimesh_says_what_to_install():
    # trimesh comes with the test extra; without it the benchmark stops at once, in one line
    code = (
        "import runpy, sys; sys.modules['trimesh'] = None; "
        "sys.argv = ['benchmarks/run.py', '--quick']; "
        "runpy.run_path('benchmarks/run.py', run_name='__main__')"
    )
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), env.get("PYTHONPATH")]))
    done = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, env=env, capture_output=True, text=True, timeout=60
    )
    assert done.returncode == 1
    assert done.stdout == ""
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in done.stderr
    assert "trimesh is not installed" in lines[0] and 'pip install -e ".[test]"' in lines[0]
