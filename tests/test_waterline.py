"""Waterline tables: each station's wetted properties against the water's height, from affine
fits between the heights of its vertices, against a fresh evaluation at the same height.

Reference: :func:`hullslice.sections.wetted_properties` on the same outline (the path a
fresh cut takes). Between two vertex heights the waterline crosses the same edges, so the
penetration and the half-beams are affine in the height and the rest is constant: the
table must agree to rounding (1e-12 relative) wherever it serves, and decline (None) where
it cannot be exact (pieces of one part sharing its mass by width).
"""

from __future__ import annotations

from pathlib import Path

import manifold3d
import numpy as np
import pytest

import hullslice as hs
from hullslice import shapes
from hullslice.constants import TOL
from hullslice.geometry import frame
from hullslice.motion import ForceModel
from hullslice.sections import TABLE_AFTER, Outline, wetted_properties
from hullslice.slicing.fixed import fixed_cut
from hullslice.waterline import WaterlineTable

MESHES = Path(__file__).resolve().parents[1] / "meshes"
FIELDS = ("half_beam", "half_beam_port", "half_beam_stbd", "y_keel", "part_half_beam",
          "mass_share")  # fmt: skip


def outline_of(hull, pitch_deg, n):
    fr = frame(hull, np.radians(pitch_deg))
    tol = TOL.coordinate * hull.size
    outline, _, c0 = fixed_cut(fr, n, tol).window(fr)
    assert c0 == 0 and outline.n_stations == n
    return outline, tol, fr


def levels(outline, fr, count=60):
    """Heights from below the keel to above the deck: on vertex heights exactly, just
    beside them, and in between."""
    rng = np.random.default_rng(7)
    z = np.unique(outline.za)
    picks = rng.choice(z, size=min(count // 3, len(z)), replace=False)
    span = fr.highest - fr.lowest
    between = rng.uniform(fr.lowest - 0.05 * span, fr.highest + 0.05 * span, count // 3)
    beside = picks + rng.choice([-1.0, 1.0], size=len(picks)) * 1e-9 * span
    return np.sort(np.concatenate([picks, between, beside]))


def compare(table, outline, level, tol, deadrise):
    got = table.at(level, 0, outline.n_stations)
    if got is None:
        return False
    ref = wetted_properties(outline, level, tol, deadrise)
    np.testing.assert_array_equal(got["station"], ref["station"])
    np.testing.assert_array_equal(got["chine_wetted"], ref["chine_wetted"])
    np.testing.assert_array_equal(got["area"], ref["area"])
    # the penetration as a fresh evaluation computes it: to the last bit
    np.testing.assert_array_equal(got["penetration"], ref["penetration"])
    size = max(float(np.ptp(outline.za)), 1.0)
    for key in FIELDS:
        np.testing.assert_allclose(
            got[key], ref[key], rtol=1e-12, atol=1e-12 * size, err_msg=f"{key} at {level!r}"
        )
    # angles from ratios of lengths: a rounding error of a half-beam c is a part 1e-16
    # size / c of it; 1e-9 (the bound the cached path keeps to) from a micrometre up
    c = np.minimum(ref["half_beam_port"], ref["half_beam_stbd"])
    wide = c > 1e-6 * size
    for key in ("deadrise", "deadrise_port", "deadrise_stbd"):
        np.testing.assert_allclose(got[key][wide], ref[key][wide], rtol=1e-9, atol=0)
    return True


def wedge_hull():
    return hs.load_hull(MESHES / "wedge_prism.stl", mass=1.0)


def fuselage_hull():
    return hs.load_hull(MESHES / "fuselage_model.obj", mass=60.0)


def asymmetric_hull():
    v, f = shapes.asymmetric_wedge_prism()
    return hs.Hull.from_arrays(v, f, mass=5.0)


def round_hull(points=180):
    v, f = shapes.circular_cylinder(points=points)
    return hs.Hull.from_arrays(v, f, mass=5.0)


@pytest.mark.parametrize("deadrise", ["wedge", "waterline-slope"])
@pytest.mark.parametrize(
    "make, pitch_deg, n",
    [
        (wedge_hull, 0.0, 8),
        (wedge_hull, 5.0, 8),
        (asymmetric_hull, 3.0, 6),
        (round_hull, 0.0, 4),
        (fuselage_hull, 6.0, 24),
    ],
)
def test_table_agrees_with_a_fresh_evaluation(make, pitch_deg, n, deadrise):
    hull = make()
    outline, tol, fr = outline_of(hull, pitch_deg, n)
    table = None
    declined = []
    for level in levels(outline, fr):
        if table is None or level > table.top:
            table = WaterlineTable.of(outline, level, tol, deadrise, budget=10**8)
        if not compare(table, outline, level, tol, deadrise):
            declined.append(level)
    # one part per section: the table serves every height but those within a fifth of the
    # tolerance above a keel vertex, where the waterline's ends count as a flat keel and
    # the keel's lateral position moves with the water
    z = np.unique(outline.za)
    for level in declined:
        i = np.searchsorted(z, level) - 1
        assert 0.0 < level - z[i] <= tol / 5 * (1 + 1e-9)


def test_the_paper_prism_against_its_fresh_evaluation(paper_hull):
    outline, tol, fr = outline_of(paper_hull, 0.0, 32)
    table = WaterlineTable.of(outline, 0.0, tol, "wedge")  # covers up to the chines
    assert table.top >= fr.lowest + 0.09
    for level in np.linspace(fr.lowest + 1e-4, fr.lowest + 0.09, 23):
        assert compare(table, outline, level, tol, "wedge")


def test_a_catamaran_is_tabulated_per_float():
    vs, fs = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0)
    vp, fp = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=20.0)
    vs = vs - np.array([0.0, 0.3, vs[:, 2].min()])
    vp = vp + np.array([0.0, 0.3, -vp[:, 2].min() + 0.01])  # port keel 1 cm higher
    hull = hs.Hull.from_arrays(np.vstack([vs, vp]), np.vstack([fs, fp + len(vs)]), mass=2.0)
    outline, tol, fr = outline_of(hull, 0.0, 4)
    table = WaterlineTable.of(outline, fr.highest, tol, "wedge")
    served = [compare(table, outline, h, tol, "wedge") for h in levels(outline, fr)]
    assert all(served)  # separate parts carry their own mass: constant shares


def catamaran_hull():
    vs, fs = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0)
    vp, fp = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=20.0)
    vs = vs - np.array([0.0, 0.3, vs[:, 2].min()])
    vp = vp + np.array([0.0, 0.3, -vp[:, 2].min() + 0.01])
    return hs.Hull.from_arrays(np.vstack([vs, vp]), np.vstack([fs, fp + len(vs)]), mass=2.0)


@pytest.mark.parametrize("deadrise", ["wedge", "waterline-slope"])
@pytest.mark.parametrize(
    "make, pitch_deg, n",
    [(fuselage_hull, 6.0, 24), (catamaran_hull, 0.0, 4), (asymmetric_hull, 3.0, 6)],
)
def test_stations_at_levels_of_their_own_are_as_each_alone(make, pitch_deg, n, deadrise):
    # at_each (the partial slices' stations, each at its own water) against at, station by
    # station: the same entries, in the same order, to the last bit
    outline, tol, fr = outline_of(make(), pitch_deg, n)
    table = WaterlineTable.of(outline, fr.highest, tol, deadrise, budget=10**8)
    rng = np.random.default_rng(3)
    served = 0
    for _ in range(40):
        stations = rng.integers(0, n, size=int(rng.integers(1, 5)))
        lv = rng.uniform(fr.lowest, min(table.top, fr.highest), size=len(stations))
        alone = [table.at(float(h), int(k), int(k) + 1) for k, h in zip(stations, lv, strict=True)]
        got = table.at_each(stations, lv)
        if any(a is None for a in alone):
            assert got is None
            continue
        served += 1
        assert set(got) == set(alone[0]) - {"area"}
        for key in got:
            want = np.concatenate([a[key] if key != "station" else a[key] + j
                                   for j, a in enumerate(alone)])  # fmt: skip
            np.testing.assert_array_equal(got[key], want, err_msg=key)
    assert served > 20
    assert table.at_each(np.array([0]), np.array([table.top + 1.0])) is None


def test_twin_keels_of_one_part_are_left_to_the_fresh_evaluation():
    # a W bottom: between its keels' and its middle's heights the water meets one part in
    # two pieces, which share the part's mass by their widths (not constant): declined
    w = [[-0.3, 0.05], [-0.2, -0.1], [-0.1, 0.0], [0.1, 0.0], [0.2, -0.1], [0.3, 0.05]]
    mesh = manifold3d.CrossSection([w]).extrude(1.0).to_mesh()
    v = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
    hull = hs.Hull.from_arrays(v, np.asarray(mesh.tri_verts), forward="+z", up="+y", mass=10.0)
    outline, tol, fr = outline_of(hull, 0.0, 4)
    table = WaterlineTable.of(outline, fr.highest, tol, "wedge")
    keel = fr.lowest
    assert table.at(keel + 0.05, 0, 4) is None  # two pieces, shares by width
    assert compare(table, outline, keel + 0.15, tol, "wedge")  # one piece again
    assert compare(table, outline, keel - 0.01, tol, "wedge")  # dry


def test_above_its_top_a_table_declines(paper_hull):
    outline, tol, fr = outline_of(paper_hull, 0.0, 8)
    table = WaterlineTable.of(outline, fr.lowest + 0.01, tol, "wedge")
    assert table.top > fr.lowest + 0.01
    assert table.at(table.top + 1e-6, 0, 8) is None
    assert compare(table, outline, table.top, tol, "wedge")


def evaluate_often(hull, deadrise, drafts):
    model = ForceModel(hull, slices=32, slicing="fixed", deadrise=deadrise)
    fresh = ForceModel(hull, slices=32, slicing="fixed", deadrise=deadrise, cache=False)
    motion = hs.Motion(-3.0)
    for d in drafts:
        a, b = model(hs.Pose(d), motion), fresh(hs.Pose(d), motion)
        assert a.total == pytest.approx(b.total, rel=1e-12)
    store = fixed_cut(frame(hull, 0.0), 32, TOL.coordinate * hull.size)
    assert store.evaluations >= len(drafts)  # the store the model used, not a new one
    return store


def test_tables_are_made_for_time_histories_only(paper_hull):
    hull = paper_hull.with_mass(1.0)  # frames of its own
    drafts = np.linspace(0.01, 0.03, 3 * TABLE_AFTER)
    store = evaluate_often(hull, "wedge", drafts[: TABLE_AFTER - 1])
    assert not store.tables  # a few evaluations: none (it would cost more than it saves)
    store = evaluate_often(hull, "wedge", drafts)
    assert store.tables["wedge"].top >= drafts[-1] + frame(hull, 0.0).lowest


def test_keel_fit_is_not_tabulated(paper_hull):
    # its slopes are ratios of cubics in the height: the fixed slicing evaluates it afresh
    hull = paper_hull.with_mass(1.0)
    store = evaluate_often(hull, "keel-fit", np.linspace(0.01, 0.03, 3 * TABLE_AFTER))
    assert "keel-fit" not in store.tables


def wavy_hull(points=1200):
    """A bottom of 12 waves (one part, many pieces at mid-height), finely sampled."""
    y = np.linspace(-0.3, 0.3, points)
    bottom = np.stack([y, -0.1 + 0.01 * np.cos(2 * np.pi * 12 * y / 0.6)], axis=1)
    section = np.vstack([bottom, [[0.3, 0.05], [-0.3, 0.05]]])  # counter-clockwise
    mesh = manifold3d.CrossSection([section]).extrude(1.0).to_mesh()
    v = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
    return hs.Hull.from_arrays(v, np.asarray(mesh.tri_verts), forward="+z", up="+y", mass=10.0)


def test_a_costly_table_is_not_made():
    # one part meeting the water in many pieces needs every edge under the water in
    # every interval: with the water over the waves, a table would evaluate millions of
    # edges; the fresh evaluation serves instead
    hull = wavy_hull()
    outline, tol, fr = outline_of(hull, 0.0, 3)
    assert len(outline.za) > 3000
    high = fr.lowest + 0.05
    assert WaterlineTable.of(outline, high, tol, "wedge") is None
    low = WaterlineTable.of(outline, fr.lowest + 0.001, tol, "wedge")  # a little: fits
    assert low is not None and low.top < high
    store = evaluate_often(hull, "wedge", np.linspace(0.045, 0.05, 2 * TABLE_AFTER))
    assert fr.lowest + 0.045 <= store.too_high["wedge"][1] <= high
    assert "wedge" not in store.tables


def test_simple_stations_evaluate_few_edges():
    # a round bottom meets every waterline in two edges: a table evaluates those and the
    # keel's, not every edge under the water: 720 points, some 1,400 intervals per
    # station, within a budget of 50,000 edges (all edges under the water: over a million)
    hull = round_hull(points=720)
    outline, tol, fr = outline_of(hull, 0.0, 3)
    table = WaterlineTable.of(outline, fr.highest, tol, "wedge", budget=50_000)
    assert table is not None and table.top >= fr.highest
    for level in np.linspace(fr.lowest + 0.01, fr.highest - 0.01, 9):
        assert compare(table, outline, level, tol, "wedge")


def test_empty_sections_are_dry_at_every_height():
    # a station beyond the body's ends has no contour: one dry interval
    square = np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])
    outline = Outline.of([(), (square,)], 1e-6)
    table = WaterlineTable.of(outline, 0.0, 1e-6, "wedge")
    for level in (-2.0, 0.0, 0.5):
        assert compare(table, outline, level, 1e-6, "wedge")
    assert table.at(0.5, 0, 2)["penetration"] == pytest.approx([0.0, 1.5], abs=1e-15)


def test_a_part_in_two_pieces_is_left_to_the_fresh_evaluation():
    # a symmetric W in one part: the pieces' widths keep their ratio, so their mass shares
    # do not change, but the submerged edges each piece gets (and so its keel) move with
    # the water: the table declines every interval where the part is in two pieces
    w = np.array([[-0.5, -0.2], [-0.4, -0.2], [-0.1, 0.1], [0.1, 0.1], [0.4, -0.2],
                  [0.5, -0.2], [0.2, 0.3], [-0.2, 0.3]])  # fmt: skip
    outline = Outline.of([(w,)], 1e-4)
    table = WaterlineTable.of(outline, 0.25, 1e-4, "wedge")  # up to 0.7
    assert table.at(-0.15, 0, 1) is None
    for level in (-0.25, -0.2, 0.15, 0.25):  # dry, and one piece above the W's middle
        assert compare(table, outline, level, 1e-4, "wedge")


def test_pieces_come_in_order_along_the_waterline():
    # a V with a bulb under water to its left: the bulb's left end is fixed, the V's moves
    # with the water; the entries are ordered by their left ends, as a fresh evaluation
    v = np.array([[0.0, 0.0], [0.5, 0.5], [-0.5, 0.5]])
    bulb = np.array([[-0.1, -0.3], [0.1, -0.3], [0.1, -0.2], [-0.1, -0.2]])
    outline = Outline.of([(v, bulb)], 1e-4)
    table = WaterlineTable.of(outline, 0.4, 1e-4, "wedge")
    for level in (0.05, 0.15, 0.3):
        assert compare(table, outline, level, 1e-4, "wedge")


@pytest.mark.parametrize("deadrise", ["wedge", "waterline-slope", "keel-fit"])
@pytest.mark.parametrize("make, pitch_deg, n", [(fuselage_hull, 6.0, 24), (round_hull, 0.0, 4),
                                                (asymmetric_hull, 3.0, 6)])  # fmt: skip
def test_one_evaluation_of_many_stations_at_their_own_levels_is_each_alone(
    make, pitch_deg, n, deadrise
):
    # stations taken from an outline (repeated, out of order), each at its own water:
    # every station's properties the very same as its evaluation alone
    outline, tol, fr = outline_of(make(), pitch_deg, n)
    rng = np.random.default_rng(3)
    picks = rng.integers(0, n, 3 * n)
    at = rng.uniform(fr.lowest, fr.highest, len(picks))
    both = wetted_properties(outline.take(picks), at, tol, deadrise)
    for j, (k, level) in enumerate(zip(picks.tolist(), at.tolist(), strict=True)):
        alone = wetted_properties(outline.window(k, k + 1), level, tol, deadrise)
        mine = both["station"] == j
        for key, val in alone.items():
            got = both[key][j : j + 1] if key == "area" else both[key][mine]
            want = val if key != "station" else val + j
            np.testing.assert_array_equal(got, want, err_msg=f"{key} of station {k}")


@pytest.mark.parametrize("lead", [False, True])
def test_an_outlines_stations_taken_are_each_its_own(lead):
    # stations taken (repeated, out of order; or every one in order and then a few more,
    # as a window and its moved slices' sources are): each station of the result, read
    # alone, the very same arrays as the outline's station it was taken of
    outline, _, _ = outline_of(fuselage_hull(), 6.0, 24)
    n = outline.n_stations
    rng = np.random.default_rng(5)
    picks = rng.integers(0, n, 3)
    picks = np.concatenate([np.arange(n), picks]) if lead else rng.integers(0, n, 2 * n)
    got = outline.take(picks)
    assert got.n_stations == len(picks)
    assert np.array_equal(got.start, np.searchsorted(got.station, np.arange(len(picks) + 1)))
    for j, k in enumerate(picks.tolist()):
        mine, theirs = got.window(j, j + 1), outline.window(k, k + 1)
        for name in Outline.__dataclass_fields__:
            np.testing.assert_array_equal(
                getattr(mine, name), getattr(theirs, name), err_msg=f"{name} of station {k}"
            )


def test_break_points_a_rounding_apart_make_a_table_all_the_same():
    # the generic fuselage (128k faces) held at 5 deg and cut by the exact kernel: one
    # station has two vertices whose heights are a rounding apart. The table's samples of
    # that interval fell on a break point, where some of the edges it had chosen met the
    # water a rounding above and some a rounding below: a piece opened that none closed
    # (IndexError in building the table). That interval is now left untabulated, and the
    # run agrees with the same run cut by manifold3d to the cuts' rounding (manifold3d
    # rounds its sections to a grid of 1e-8 of the cutter's size: 7.7e-9 of the peak here)
    v, f = shapes.fuselage()
    hull = hs.Hull.from_arrays(v, f, mass=30000.0)
    kw = dict(dt=2e-4, pitch_deg=5.0, forward_speed=60.0, slices=64, slicing="fixed",
              free_pitch=False, stop_on=(), solver="zarnick")  # fmt: skip
    exact = hs.simulate(hull, -1.5, 0.02, cutter="exact", **kw)
    reference = hs.simulate(hull.with_mass(hull.mass), -1.5, 0.02, cutter="manifold3d", **kw)
    assert len(exact) == len(reference) == 101
    peak = float(np.max(np.abs(reference.force)))
    assert np.max(np.abs(np.asarray(exact.force) - reference.force)) <= 2e-8 * peak
