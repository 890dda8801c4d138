"""Open, multi-shell exports as modelling tools write them, and repairs that do not depend
on where the body lies.

The aircraft export is generated (``tests/aircraft_export.py``): a 7 m fuselage shell with
three holes, a fin sheet welded to it along one edge, an antenna welded at one vertex, a
closed wing wound inside out through it, and 60 small open parts. The reference is the
same fuselage shell without its holes.
"""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest
import trimesh

import hullslice as hs
from hullslice.cli import main

from .aircraft_export import LENGTH, closed_fuselage, light_aircraft
from .test_bad_input import DRAFT, SLICES, VELOCITY, obj_text, text, wedge


def _load_quietly(path, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hs.MeshRepairWarning)
        return hs.load_hull(path, **kw)


@pytest.mark.parametrize("offset", [1e3, 1e5])
def test_an_open_wedge_far_from_the_origin_repairs_as_at_the_origin(tmp_path, offset):
    # the wedge prism without one face (OBJ, double precision): the fill closes the hole;
    # no keel vertex is merged "by rounding" with one 0.1 m away because the coordinates
    # are large (the merge distance once grew with them: volume -3.3 %, force +2 % at 1e5)
    pytest.importorskip("pymeshfix")
    v, f = wedge()
    near = text(tmp_path, "near.obj", obj_text(v, f[1:]))
    far = text(tmp_path, "far.obj", obj_text(v + np.array([offset, 0.0, 0.0]), f[1:]))
    a = _load_quietly(near, repair="close", mass=10.0)
    b = _load_quietly(far, repair="close", mass=10.0)
    # the clean wedge's volume: half its 0.2 m beam times its keel depth, 1 m long
    assert a.volume == pytest.approx(0.1 * 0.1 * np.tan(np.radians(30.0)), rel=1e-12)
    assert b.volume == pytest.approx(a.volume, rel=1e-9)
    fa = hs.compute_force(a, DRAFT, VELOCITY, slices=SLICES).total
    fb = hs.compute_force(b, DRAFT, VELOCITY, slices=SLICES).total
    assert fb == pytest.approx(fa, rel=1e-9)


def test_a_merge_that_moves_a_vertex_by_a_fair_part_of_its_edge_is_not_made():
    # two copies of the wedge's keel end 1e-5 of the size apart (inside the ladder), on a
    # mesh whose edges there are 1.5e-4 m long: a move of 7 % of the edge is not rounding
    from hullslice.topology import merge_close

    v = np.array([[0.0, 0.0, 0.0], [1.5e-4, 0.0, 0.0], [0.0, 1.5e-4, 0.0], [1e-5, 0.0, 0.0]])
    f = np.array([[0, 1, 2], [3, 2, 1]])
    assert merge_close(v, f, 2e-5) is None
    # 1e-7 apart: under 5 % of the edge, a copy that differs by rounding
    v[3] = [1e-7, 0.0, 0.0]
    merged = merge_close(v, f, 2e-5)
    assert merged is not None and merged[2] == 1


# a short ditching of the 7 m fuselage: 1200 kg, 4 degrees nose up, 35 m/s forward, 6 m/s
# down, 50 ms (the peak comes at 15 ms)
DITCHING = ["--mass", "1200", "--velocity=-6", "--pitch", "4", "--forward-speed", "35",
            "--t-end", "0.05", "--dt", "1e-3", "--slices", "16"]  # fmt: skip


@pytest.fixture(scope="module")
def export(tmp_path_factory):
    """The aircraft export as a binary STL, and the closed fuselage shell alone."""
    folder = tmp_path_factory.mktemp("export")
    trimesh.Trimesh(*light_aircraft(), process=False).export(folder / "pa.stl")
    trimesh.Trimesh(*closed_fuselage(), process=False).export(folder / "fuselage.stl")
    return folder


def test_repair_close_keep_largest_keeps_the_fuselage_of_a_multi_shell_export(export, capsys):
    pytest.importorskip("pymeshfix")
    reference = hs.load_hull(export / "fuselage.stl")
    out = export / "info.json"
    code = main(["info", str(export / "pa.stl"), "--repair", "close", "--keep", "largest",
                 "--format", "json", "-o", str(out)])  # fmt: skip
    err = capsys.readouterr().err
    assert code == 0, err
    data = json.loads(out.read_text())
    # the fuselage, not the 1.62 m^3 wing (inside out), nor the antenna or the fin welded
    # to it: its volume within 1 % of the closed shell alone (0.016 % measured)
    assert data["volume"] == pytest.approx(reference.volume, rel=0.01)
    assert data["length"] == pytest.approx(LENGTH, rel=1e-6)
    assert data["height"] == pytest.approx(reference.extents[2], rel=1e-6)
    # the fuselage did not close with the fin and antenna welded to it: closed on its own
    assert "closed 2 shells on their own that did not close with the parts welded to them" in err
    # the largest part dropped is named with its size: the fin, 0.5 m high, 2 faces
    assert "the largest: 0.13 x 0.0457 x 0.5 m (2 faces, 4 open edges)" in err
    assert "turned 1 inside-out shell outward" in err


def test_the_repaired_export_ditches_to_its_end_as_the_fuselage_alone(export, capsys):
    pytest.importorskip("pymeshfix")
    runs = {}
    for name, extra in (("pa", ["--repair", "close", "--keep", "largest"]), ("fuselage", [])):
        out = export / f"{name}.json"
        code = main(["simulate", str(export / f"{name}.stl"), *extra, *DITCHING,
                     "--format", "json", "-o", str(out)])  # fmt: skip
        err = capsys.readouterr().err
        assert code == 0, err
        runs[name] = json.loads(out.read_text())
    pa, alone = runs["pa"], runs["fuselage"]
    assert pa["stop_reason"] == "t_end" and pa["history"]["t"][-1] == pytest.approx(0.05)
    assert pa["steps"] == alone["steps"] == 51
    # the peak force as on the closed fuselage alone (8e-5 apart: the fills of the windows
    # and hatch, above the water, and the closing's rounding)
    assert pa["peak"]["force"] == pytest.approx(alone["peak"]["force"], rel=1e-3)
    assert pa["peak"]["t"] == pytest.approx(alone["peak"]["t"], abs=1e-12)


def test_info_lists_the_shells_of_the_open_export_without_repair(export, capsys):
    pytest.importorskip("pymeshfix")
    reference = hs.load_hull(export / "fuselage.stl")
    out = export / "shells.json"
    views = export / "views.png"
    code = main(["info", str(export / "pa.stl"), "--format", "json", "-o", str(out),
                 "--plot", str(views)])  # fmt: skip
    err = capsys.readouterr().err
    assert code == 0, err
    assert "warning" not in err and "error" not in err  # nothing refused, nothing repaired
    data = json.loads(out.read_text())
    assert data["loaded"] is False and data["open_edges"] == 662
    assert data["nonmanifold_edges"] == 1  # the fin's edge on the crown
    shells = data["shells"]
    # 64 shells: the fuselage, antenna and fin apart (welded), the wing, 60 small parts
    assert len(shells) == 64
    fuselage, wing = shells[0], shells[1]
    assert fuselage["number"] == 1 and fuselage["closes"] is True
    assert fuselage["volume"] == pytest.approx(reference.volume, rel=0.01)
    # its three holes' rims: the faces whose centre is within a hole's radius are missing
    assert fuselage["open_edges"] == 31
    np.testing.assert_allclose(fuselage["extents"], reference.extents, rtol=1e-6)
    # the closed wing, inside out: 1.2 x 9 x 0.15 m
    assert wing["number"] == 2 and wing["inside_out"] is True and wing["open_edges"] == 0
    assert wing["volume"] == pytest.approx(1.2 * 9.0 * 0.15, rel=1e-6)  # float32 STL
    # the fin would be dropped: 2 faces, 4 open edges, 0.5 m high
    fin = next(s for s in shells if s["number"] is None and s["faces"] == 2)
    assert fin["closes"] is False and fin["open_edges"] == 4
    assert fin["extents"][2] == pytest.approx(0.5, abs=1e-3)  # and the skin edge's 0.3 mm slope
    # the numbers are those --repair close --keep N gives: body 2 is the wing
    hull = _load_quietly(export / "pa.stl", repair="close", keep=2)
    assert hull.volume == pytest.approx(wing["volume"], rel=1e-9)
    assert views.stat().st_size > 10_000


def test_the_views_of_an_open_mesh_are_its_faces_outline(export):
    pytest.importorskip("matplotlib")
    from hullslice import plots
    from hullslice.survey import survey_mesh

    s = survey_mesh(export / "pa.stl")
    fig = plots.plot_views(s, "+x", "+z")
    tri = s.vertices[s.faces]
    # side (x, z), front (y, z) and top (x, y), in the figure's order: each outline spans
    # the box of the faces seen in that view (a face seen edge-on has no outline)
    for ax, (i, j) in zip(fig.axes[:3], [(0, 2), (1, 2), (0, 1)], strict=True):
        p = tri[:, :, [i, j]]
        d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
        seen = p[d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0] != 0.0].reshape(-1, 2)
        (patch,) = ax.patches
        pts = patch.get_path().vertices
        np.testing.assert_allclose(pts.min(axis=0), seen.min(axis=0), atol=1e-6 * 10)
        np.testing.assert_allclose(pts.max(axis=0), seen.max(axis=0), atol=1e-6 * 10)
    plots._pyplot().close(fig)


def test_info_without_pymeshfix_says_which_shells_are_unknown(export, capsys, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "pymeshfix", None)
    out = export / "unknown.json"
    code = main(["info", str(export / "pa.stl"), "--format", "json", "-o", str(out)])
    assert code == 0, capsys.readouterr().err
    shells = json.loads(out.read_text())["shells"]
    # only the wing was closed before: it alone is numbered
    assert [s["number"] for s in shells if s["number"] is not None] == [1]
    assert shells[0]["volume"] == pytest.approx(1.2 * 9.0 * 0.15, rel=1e-6)
    assert {s["closes"] for s in shells[1:]} == {None}
    code = main(["info", str(export / "pa.stl")])
    assert "pip install 'hullslice[repair]'" in capsys.readouterr().out
