"""Sections in several parts: a catamaran is the sum of its floats, twin keels are flagged.

Reference: two floats moving together as one rigid body, far enough apart not to disturb
each other's flow, carry each its own share of the mass; in the 2D+t method each float's
slice is then a wedge of its own, so the pair's force is the sum of the forces on each
float alone with its share of the mass, exactly (same stations, same formulas).
"""

from __future__ import annotations

import manifold3d
import numpy as np
import pytest

import hullslice as hs
from hullslice import shapes
from hullslice.motion import simulate
from hullslice.sections import split_parts

DRAFT, VELOCITY, SLICES = 0.03, -5.0, 16


def join(*bodies):
    vs, fs, offset = [], [], 0
    for v, f in bodies:
        vs.append(v)
        fs.append(f + offset)
        offset += len(v)
    return np.vstack(vs), np.vstack(fs)


@pytest.fixture(scope="module")
def floats():
    """Two 1 m floats 0.6 m apart: 30 deg starboard, 20 deg port, keels level."""
    vs, fs = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0)
    vp, fp = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=20.0)
    # put both keels at z = 0: the draft of the pair is then the draft of each float
    vs = vs - np.array([0.0, 0.3, vs[:, 2].min()])
    vp = vp + np.array([0.0, 0.3, -vp[:, 2].min()])
    return (vs, fs), (vp, fp)


def test_a_catamaran_is_the_sum_of_its_floats(floats):
    (vs, fs), (vp, fp) = floats
    cat = hs.Hull.from_arrays(*join((vs, fs), (vp, fp)), mass=20.0, name="catamaran")
    stbd = hs.Hull.from_arrays(vs, fs)
    port = hs.Hull.from_arrays(vp, fp)
    share = {h: 20.0 * h.volume / cat.volume for h in (stbd, port)}
    assert cat.volume == pytest.approx(stbd.volume + port.volume, rel=1e-12)

    r = hs.compute_force(cat, DRAFT, VELOCITY, slices=SLICES)
    s = r.sections
    assert len(s) == 2 * SLICES and s.slice_count == SLICES
    assert list(s.part) == [0, 1] * SLICES
    assert np.array_equal(s.slice_index, np.repeat(np.arange(SLICES), 2))
    # each part is one float's section: area, penetration, half-beam, deadrise
    h30, h20 = 0.1 * np.tan(np.radians(30.0)), 0.1 * np.tan(np.radians(20.0))
    assert s.area[0::2] == pytest.approx(np.full(SLICES, 0.1 * h30), rel=1e-6)
    assert s.area[1::2] == pytest.approx(np.full(SLICES, 0.1 * h20), rel=1e-6)
    assert s.deadrise_deg[0::2] == pytest.approx(np.full(SLICES, 30.0), abs=1e-4)
    assert s.deadrise_deg[1::2] == pytest.approx(np.full(SLICES, 20.0), abs=1e-4)
    assert s.penetration == pytest.approx(np.full(2 * SLICES, DRAFT), rel=1e-6)
    assert s.half_beam[0::2] == pytest.approx(np.full(SLICES, DRAFT / np.tan(np.radians(30))))
    # the mass per metre of the whole station is the sum of the parts'
    station = np.bincount(s.slice_index, weights=s.mass_per_metre)
    assert station == pytest.approx(np.full(SLICES, 20.0 * (0.1 * h30 + 0.1 * h20) / cat.volume))

    alone = [
        hs.compute_force(h.with_mass(share[h]), DRAFT, VELOCITY, slices=SLICES)
        for h in (stbd, port)
    ]
    # manifold3d cuts in single precision relative to each hull's own size (1e-7), and the
    # steep characteristic curves amplify that in the force: 1e-5
    assert r.total == pytest.approx(alone[0].total + alone[1].total, rel=1e-5)
    assert r.force[0::2] == pytest.approx(alone[0].force, rel=1e-5)
    assert r.force[1::2] == pytest.approx(alone[1].force, rel=1e-5)
    assert list(r.valid[0::2]) == list(alone[0].valid)
    assert list(r.valid[1::2]) == list(alone[1].valid)


def test_no_half_beam_spans_both_floats(floats):
    # what one equivalent wedge over the whole section gives: the half-beam spans both
    # floats (0.3 m + half a float), a deadrise of a few degrees, a far larger force
    (vs, fs), (vp, fp) = floats
    cat = hs.Hull.from_arrays(*join((vs, fs), (vp, fp)), mass=20.0)
    s = hs.cut(cat, DRAFT, 4)
    assert s.half_beam.max() < 0.1  # each part's own half-beam, never the span of both


def test_a_free_fall_counts_slices_not_parts(floats):
    (vs, fs), (vp, fp) = floats
    cat = hs.Hull.from_arrays(*join((vs, fs), (vp, fp)), mass=20.0)
    h = simulate(cat, -5.0, 0.004, dt=1e-3, slices=8)
    assert list(h.slices) == [0, 8, 8, 8, 8]
    assert np.all(np.isfinite(h.force))


def test_twin_keels_joined_above_the_water_are_flagged():
    # one part whose bottom is a W: at this draft the water meets it in two spans
    w = [[-0.3, 0.05], [-0.2, -0.1], [-0.1, 0.0], [0.1, 0.0], [0.2, -0.1], [0.3, 0.05]]
    mesh = manifold3d.CrossSection([w]).extrude(1.0).to_mesh()
    v = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
    # extruded along the mesh z; its y is up, so its x is the body's port
    hull = hs.Hull.from_arrays(v, np.asarray(mesh.tri_verts), forward="+z", up="+y", mass=10.0)
    r = hs.compute_force(hull, 0.05, -5.0, slices=4)
    s = r.sections
    assert list(s.waterline_spans) == [2, 2, 2, 2] and list(s.part) == [0, 0, 0, 0]
    assert s.area == pytest.approx(np.full(4, 0.045), rel=1e-6)
    assert not r.valid.any() and np.isfinite(r.total)
    assert all("meets the waterline in 2 separate spans" in why for why in r.loads.reason)
    # deeper, the tunnel is under water: one span, the flag goes
    deep = hs.cut(hull, 0.12, 4)
    assert list(deep.waterline_spans) == [1, 1, 1, 1]


def test_holes_belong_to_the_part_around_them():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    hole = (square * 0.5 + 0.25)[::-1]  # clockwise
    left = square - [3.0, 0.0]
    parts = split_parts((square, left, hole))
    assert len(parts) == 2
    assert [len(p) for p in parts] == [1, 2]  # starboard (left, y < 0) first, then the holed
    assert parts[1][1] is hole
    assert split_parts((square, hole))[0] == (square, hole)
    assert split_parts(()) == [()]


def test_a_hollow_float_beside_a_solid_one():
    outer = manifold3d.Manifold.cube([1.0, 0.4, 0.2], center=True)
    inner = manifold3d.Manifold.cube([0.8, 0.2, 0.1], center=True)
    other = manifold3d.Manifold.cube([1.0, 0.4, 0.2], center=True).translate([0.0, 1.0, 0.0])
    body = (outer - inner) + other
    mesh = body.to_mesh()
    hull = hs.Hull.from_arrays(np.asarray(mesh.vert_properties)[:, :3], mesh.tri_verts)
    s = hs.cut(hull, 0.2, 2)
    assert list(s.part) == [0, 1, 0, 1]
    # hollow part: 0.4 x 0.2 less the 0.2 x 0.1 cavity; solid part: 0.4 x 0.2
    assert s.area == pytest.approx([0.06, 0.08, 0.06, 0.08], rel=1e-6)
