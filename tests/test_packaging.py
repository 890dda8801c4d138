"""The distributions' metadata: the extras, and the plugins packaged as the core is."""

from __future__ import annotations

import tomllib

import pytest

from .conftest import ROOT

CORE = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
PLUGINS = sorted((ROOT / "plugins").glob("*/pyproject.toml"))
EXTRAS = CORE["project"]["optional-dependencies"]
FEATURES = ("plot", "repair", "formats", "sweep")


def _names(requirements: list[str]) -> set[str]:
    return {r.split(";")[0].split("[")[0].split(">")[0].split("=")[0].strip() for r in requirements}


def _floor(requirements: list[str], name: str) -> str:
    (req,) = [r for r in requirements if _names([r]) == {name}]
    return req.split(">=")[1]


def test_all_is_every_feature_and_test_takes_all_and_the_type_check():
    assert EXTRAS["all"] == [f"hullslice[{','.join(FEATURES)}]"]
    assert "hullslice[all]" in EXTRAS["test"]
    # CI type-checks in the test environment: mypy at the dev extra's version, ruff not
    assert _names(EXTRAS["test"]) == {"pytest", "hypothesis", "mypy", "hullslice"}
    mypy = [r for r in EXTRAS["test"] if _names([r]) == {"mypy"}]
    assert mypy == [r for r in EXTRAS["dev"] if _names([r]) == {"mypy"}]
    assert _names(EXTRAS["dev"]) == {"ruff", "mypy"}


def test_ci_installs_the_tools_of_the_dev_extra():
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert '".[dev,test]"' in ci
    assert "ruff==" not in ci and "mypy==" not in ci  # the versions are the dev extra's


def test_the_readme_names_every_extra_and_the_copyleft_licence():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    quick = readme.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    for extra in EXTRAS:
        assert f"**`{extra}`**" in quick, extra
    assert "AGPL-3.0" in quick and "hullslice is MIT" in quick
    # and pyproject.toml says it where the extra is declared
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    assert "AGPL-3.0" in text.split("\nplot = ", 1)[1].split("\nrepair = ", 1)[0]


@pytest.mark.parametrize("path", PLUGINS, ids=lambda p: p.parent.name)
def test_a_plugin_is_packaged_as_the_core(path):
    plugin = tomllib.loads(path.read_text(encoding="utf-8"))
    project = plugin["project"]
    assert project["license"] == CORE["project"]["license"] == "MIT"  # the string, PEP 639
    assert project["requires-python"] == CORE["project"]["requires-python"]
    assert plugin["build-system"]["requires"] == CORE["build-system"]["requires"]
    core_deps = CORE["project"]["dependencies"]
    for name in _names(project["dependencies"]) - {"hullslice"}:
        assert _floor(project["dependencies"], name) == _floor(core_deps, name), name
