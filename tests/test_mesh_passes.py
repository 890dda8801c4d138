"""The checks and safe fixes every hull goes through, and ``fix=False`` to refuse a fix."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import hullslice as hs
from hullslice.cli import main
from hullslice.repair import PASSES, check_and_repair

from .conftest import MESHES
from .test_mesh import box, write


def test_every_pass_has_a_name_and_says_what_it_does():
    names = [p.name for p in PASSES]
    assert len(set(names)) == len(names)
    assert all(p.doc for p in PASSES)
    fixes = [p.name for p in PASSES if p.fixes]
    assert fixes == [
        "drop degenerate faces",
        "drop repeated faces",
        "merge close vertices",
        "orient faces",
        "turn outward",
        "union overlapping shells",
    ]


def _needing(kind: str):
    v, f = box()
    if kind == "drop degenerate faces":
        return v, np.vstack([f, [[0, 0, 1]]])
    if kind == "drop repeated faces":
        return v, np.vstack([f, f[:1]])
    if kind == "merge close vertices":
        soup = v[f].reshape(-1, 3) + 1e-12 * np.arange(3 * len(f))[:, None]
        return soup, np.arange(len(soup)).reshape(-1, 3)
    if kind == "orient faces":
        g = f.copy()
        g[0] = g[0, ::-1]
        return v, g
    if kind == "turn outward":
        return v, f[:, ::-1]
    raise AssertionError(kind)


@pytest.mark.parametrize(
    "kind",
    ["drop degenerate faces", "drop repeated faces", "merge close vertices", "orient faces",
     "turn outward"],
)  # fmt: skip
def test_a_mesh_needing_a_fix_is_fixed_or_refused(kind):
    v, f = _needing(kind)
    with pytest.warns(hs.MeshRepairWarning):
        fixed = hs.Hull.from_arrays(v, f)
    assert fixed.volume == pytest.approx(1.0)
    assert fixed.source["repairs"]
    with pytest.raises(hs.MeshError, match=f"the pass '{kind}' would fix it"):
        hs.Hull.from_arrays(v, f, fix=False)


def test_a_clean_mesh_loads_the_same_without_fixes():
    with warnings.catch_warnings():
        warnings.simplefilter("error", hs.MeshRepairWarning)
        a = hs.load_hull(MESHES / "paper_prism.stl", mass=1.0, fix=False)
    b = hs.load_hull(MESHES / "paper_prism.stl", mass=1.0)
    assert np.array_equal(a.vertices, b.vertices) and np.array_equal(a.faces, b.faces)
    assert a.source == b.source


def test_checks_run_without_fixes():
    v, f = box()
    with pytest.raises(hs.MeshError, match="is open"):
        hs.Hull.from_arrays(v, f[1:], fix=False)
    bad = v.copy()
    bad[0, 0] = np.nan
    with pytest.raises(hs.MeshError, match="NaN or infinite"):
        check_and_repair(bad, f, "box", fix=False)


def test_the_notes_are_the_warnings_in_order():
    v, f = box()
    f = np.vstack([f, [[0, 0, 1]], f[:1]])[:, ::-1]
    with pytest.warns(hs.MeshRepairWarning) as record:
        _, _, _, notes = check_and_repair(v, f, "box")
    assert [str(w.message) for w in record] == [f"mesh 'box': {n}" for n in notes]
    assert [n.split()[0] for n in notes] == ["removed", "removed", "the"]


def test_no_fix_on_the_command_line(tmp_path, capsys):
    v, f = box()
    path = write(tmp_path, "flipped.stl", v, f[:, ::-1])
    argv = ["sections", str(path), "--mass", "500", "--draft", "0.1", "--slices", "4"]
    assert main(argv) == 0
    assert "inside out" in capsys.readouterr().err
    assert main([*argv, "--no-fix"]) != 0
    assert "'turn outward' would fix it" in capsys.readouterr().err


@pytest.mark.parametrize("n", [1, 3, 17])
def test_shell_sizes_are_each_shells_box_corner_by_corner(n):
    from hullslice.topology import shell_sizes

    rng = np.random.default_rng(n)
    v = rng.normal(size=(500, 3)) * [30.0, 4.0, 3.0]
    f = rng.integers(0, 500, size=(2000, 3))
    labels = rng.integers(0, n, size=2000)
    # the reference: every corner taken into its shell's box one at a time
    lo, hi = np.full((n, 3), np.inf), np.full((n, 3), -np.inf)
    for face, label in zip(f, labels, strict=True):
        for corner in v[face]:
            lo[label] = np.minimum(lo[label], corner)
            hi[label] = np.maximum(hi[label], corner)
    assert np.array_equal(shell_sizes(v, f, labels, n), np.linalg.norm(hi - lo, axis=1))
    # a label with no face: an empty box, infinitely large
    sizes = shell_sizes(v, f, labels, n + 1)
    assert np.array_equal(sizes[:n], np.linalg.norm(hi - lo, axis=1)) and sizes[n] == np.inf


@pytest.mark.parametrize("top", [10, 1000, 2**21, 2**21 + 5])
def test_repeated_faces_are_found_by_packed_indices_as_by_rows(top, monkeypatch):
    """Faces' indices packed into one integer (below 2**21 vertices) against the rows'
    exact grouping: the same faces kept, the same count dropped."""
    from hullslice import topology

    rng = np.random.default_rng(top)
    f = rng.integers(0, top, size=(3000, 3))
    f = np.concatenate([f, f[rng.integers(0, 3000, 200)][:, [1, 2, 0]], f[:40]]).astype(np.int32)
    packed = topology.drop_repeated_faces(f)
    monkeypatch.setattr(topology, "group", lambda key: (_ for _ in ()).throw(AssertionError))
    if top <= 2**21:
        with pytest.raises(AssertionError):  # the packed path was the one taken
            topology.drop_repeated_faces(f)
    monkeypatch.undo()
    r = np.argmin(f, axis=1)
    rolled = f[np.arange(len(f))[:, None], (r[:, None] + np.arange(3)) % 3]
    unique, inverse = topology.unique_rows(rolled.astype(np.float64))
    first = np.full(len(unique), len(f))
    np.minimum.at(first, inverse, np.arange(len(f)))
    assert packed[1] == len(f) - len(unique) > 0
    assert np.array_equal(packed[0], f[np.sort(first)])
