"""The package's shape: layers that import downward only, no import cycle, small modules.

Every import in the package is read from the source (lazy ones inside functions included),
each module is mapped to its layer by :data:`LAYERS`, and the tests check that no module
imports from a layer above its own, that the import graph has no cycle, and that no module
is longer than :data:`MAX_MODULE_LINES`. A new module needs a row in :data:`LAYERS`.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "hullslice"

MAX_MODULE_LINES = 500

# Module (or package prefix) -> layer. A module may import from its own layer or below.
# The longest matching prefix wins.
LAYERS: dict[str, int] = {
    # 0 base: errors, units, limits, paths and files, labelled-array conversion
    "hullslice._version": 0,
    "hullslice.errors": 0,
    "hullslice.constants": 0,
    "hullslice.limits": 0,
    "hullslice.reduce": 0,
    "hullslice.safety": 0,
    "hullslice.paths": 0,
    "hullslice.atomic": 0,
    "hullslice.tables": 0,
    "hullslice.state": 0,
    "hullslice.convergence": 0,
    "hullslice.xarray_io": 0,
    "hullslice.caching": 0,
    "hullslice.progress": 0,
    "hullslice.renamed": 0,
    "hullslice.extras": 0,
    # 1 kernel: pure numpy on 2D contours and waterlines
    "hullslice.kernel": 1,
    # 2 mesh: the body, its files, repair and mass
    "hullslice.mesh": 2,
    "hullslice.axes": 2,
    "hullslice.topology": 2,
    "hullslice.readers": 2,
    "hullslice.repair": 2,
    "hullslice.integrity": 2,
    "hullslice.parts": 2,
    "hullslice.prepare": 2,
    "hullslice.orientation": 2,
    "hullslice.mass": 2,
    "hullslice.shapes": 2,
    "hullslice.survey": 2,
    # 3 cut: frames, caches of cuts, the slicing API
    "hullslice.planecut": 3,
    "hullslice.planecut_loops": 3,
    "hullslice.stage_kit": 3,
    "hullslice.contour_loops": 3,
    "hullslice.planecut_numpy": 3,
    "hullslice.wetted_loops": 3,
    "hullslice.keel_loops": 3,
    "hullslice.side_loops": 3,
    "hullslice.frame_loops": 3,
    "hullslice.outline_loops": 3,
    "hullslice.index_loops": 3,
    "hullslice.held_loops": 3,
    "hullslice.slices_loops": 3,
    "hullslice.loops_layout": 3,
    "hullslice.geometry": 3,
    "hullslice.regions": 3,
    "hullslice.waterline": 3,
    "hullslice.sections": 3,
    "hullslice.slicing": 3,
    # 4 the 2D solvers and their registry
    "hullslice.solvers": 4,
    # 5 forces on the body
    "hullslice.forces": 5,
    "hullslice.aero": 5,
    "hullslice.loads": 5,
    # 6 motion in time
    "hullslice.motion": 6,
    # 7 studies: the option table, one computation, case files, sweeps
    "hullslice.study": 7,
    "hullslice.options": 7,
    "hullslice.case": 7,
    "hullslice.sweeps": 7,
    # 8 output and the command line
    "hullslice.textout": 8,
    "hullslice.plots": 8,
    "hullslice.testing": 8,
    "hullslice.cli": 8,
    "hullslice.__main__": 8,
    # 9 the package's front door
    "hullslice": 9,
}


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


MODULES = {_module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def _imports(name: str, path: Path) -> set[str]:
    """Modules of the package that ``name`` imports, anywhere in its source."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    out: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names if a.name.split(".")[0] == "hullslice")
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] != "hullslice":
                continue
            for alias in node.names:  # ``from . import plots`` imports a module
                sub = f"{target}.{alias.name}"
                out.add(sub if sub in MODULES else target)
    out.discard(name)
    return out


GRAPH = {name: _imports(name, path) for name, path in MODULES.items()}


def layer(name: str) -> int:
    # the package's front door is its own row only: every other module needs a row
    rows = (k for k in LAYERS if name == k or (k != "hullslice" and name.startswith(k + ".")))
    best = max(rows, key=len, default=None)
    if best is None:
        raise KeyError(f"module {name} has no layer: add it to LAYERS in {__file__}")
    return LAYERS[best]


@pytest.mark.parametrize("name", sorted(MODULES))
def test_every_module_has_a_layer(name):
    assert layer(name) >= 0


def test_imports_go_downward_only():
    upward = [
        f"{mod} (layer {layer(mod)}) imports {dep} (layer {layer(dep)})"
        for mod, deps in GRAPH.items()
        for dep in sorted(deps)
        if dep in MODULES and layer(dep) > layer(mod)
    ]
    assert upward == [], "\n".join(upward)


def test_no_import_cycle():
    # Tarjan's strongly connected components over the whole graph, lazy imports included.
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    cycles: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in GRAPH.get(v, ()):
            if w not in MODULES:
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                cycles.append(sorted(comp))

    for v in MODULES:
        if v not in index:
            visit(v)
    assert cycles == [], f"import cycles: {cycles}"


@pytest.mark.parametrize("name", sorted(MODULES))
def test_module_is_small(name):
    lines = MODULES[name].read_text(encoding="utf-8").count("\n")
    assert lines <= MAX_MODULE_LINES, f"{name} has {lines} lines (at most {MAX_MODULE_LINES})"


def test_the_walker_sees_lazy_imports():
    # forces/result.py converts to xarray inside a method: the walker must see that import.
    assert "hullslice.xarray_io" in GRAPH["hullslice.forces.result"]


def test_a_module_without_a_row_has_no_layer():
    with pytest.raises(KeyError, match="add it to LAYERS"):
        layer("hullslice.a_module_nobody_placed")
