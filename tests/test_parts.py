"""Sections in several parts: a catamaran is the sum of its floats.

Reference: two floats moving together as one rigid body, far enough apart not to disturb
each other's flow, carry each its own share of the mass (its volume's, the density being
uniform); in the 2D+t method each float's slice is then a wedge of its own, so the pair's
force is the sum of the forces on each float alone with its share of the mass (same
stations, same formulas).
"""

from __future__ import annotations

import manifold3d
import numpy as np
import pytest

import hullslice as hs
from hullslice import shapes
from hullslice.motion import simulate

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
    assert len(s) == 2 * SLICES and s.n_stations == SLICES
    assert np.array_equal(s.station, np.repeat(np.arange(SLICES), 2))
    # each entry is one float's section: penetration, half-beam, deadrise
    assert s.deadrise_deg[0::2] == pytest.approx(np.full(SLICES, 30.0), abs=1e-4)
    assert s.deadrise_deg[1::2] == pytest.approx(np.full(SLICES, 20.0), abs=1e-4)
    assert s.penetration == pytest.approx(np.full(2 * SLICES, DRAFT), rel=1e-6)
    assert s.half_beam[0::2] == pytest.approx(np.full(SLICES, DRAFT / np.tan(np.radians(30))))
    # each float carries its own mass: its section's area times the density
    h30, h20 = 0.1 * np.tan(np.radians(30.0)), 0.1 * np.tan(np.radians(20.0))
    rho_b = 20.0 / cat.volume
    assert s.mass_per_metre[0::2] == pytest.approx(np.full(SLICES, rho_b * 0.1 * h30), rel=1e-6)
    assert s.mass_per_metre[1::2] == pytest.approx(np.full(SLICES, rho_b * 0.1 * h20), rel=1e-6)

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


def test_a_dry_float_keeps_its_mass(floats):
    # lift the port float by 2 cm: at 1 cm draft only the starboard float is wet, and it
    # carries its own mass, not the pair's
    (vs, fs), (vp, fp) = floats
    cat = hs.Hull.from_arrays(*join((vs, fs), (vp + np.array([0.0, 0.0, 0.02]), fp)), mass=20.0)
    s = hs.cut(cat, 0.01, 4)
    assert len(s) == 4  # one wetted piece per station
    h30 = 0.1 * np.tan(np.radians(30.0))
    assert s.mass_per_metre == pytest.approx(np.full(4, 20.0 / cat.volume * 0.1 * h30), rel=1e-6)


def test_a_free_fall_counts_slices_not_parts(floats):
    (vs, fs), (vp, fp) = floats
    cat = hs.Hull.from_arrays(*join((vs, fs), (vp, fp)), mass=20.0)
    h = simulate(cat, -5.0, 0.004, dt=1e-3, slices=8)
    assert list(h.slices) == [0, 8, 8, 8, 8]
    assert np.all(np.isfinite(h.force))


def test_twin_keels_joined_above_the_water_share_their_part_by_width():
    # one part whose bottom is a W: at this draft the water meets it in two pieces
    w = [[-0.3, 0.05], [-0.2, -0.1], [-0.1, 0.0], [0.1, 0.0], [0.2, -0.1], [0.3, 0.05]]
    mesh = manifold3d.CrossSection([w]).extrude(1.0).to_mesh()
    v = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
    # extruded along the mesh z; its y is up, so its x is the body's port
    hull = hs.Hull.from_arrays(v, np.asarray(mesh.tri_verts), forward="+z", up="+y", mass=10.0)
    s = hs.cut(hull, 0.05, 4)
    assert list(s.station) == [0, 0, 1, 1, 2, 2, 3, 3]
    # symmetric: half the section's mass each (area 0.045 m^2, density 10 / 0.045)
    assert s.mass_per_metre == pytest.approx(np.full(8, 5.0), rel=1e-6)
    assert s.y_keel[0::2] == pytest.approx(np.full(4, -0.2), abs=1e-6)


def test_a_hollow_float_beside_a_solid_one_carries_its_own_area():
    outer = manifold3d.Manifold.cube([1.0, 0.4, 0.2], center=True)
    inner = manifold3d.Manifold.cube([0.8, 0.2, 0.1], center=True)
    other = manifold3d.Manifold.cube([1.0, 0.4, 0.2], center=True).translate([0.0, 1.0, 0.0])
    mesh = ((outer - inner) + other).to_mesh()
    hull = hs.Hull.from_arrays(np.asarray(mesh.vert_properties)[:, :3], mesh.tri_verts, mass=1.0)
    s = hs.cut(hull, 0.05, 2)
    # hollow part: 0.4 x 0.2 less the 0.2 x 0.1 cavity; solid part: 0.4 x 0.2
    rho_b = 1.0 / hull.volume
    assert list(s.station) == [0, 0, 1, 1]
    assert s.mass_per_metre == pytest.approx(rho_b * np.array([0.06, 0.08, 0.06, 0.08]))


def test_a_float_under_water_beside_one_at_the_waterline_keeps_its_entry(floats):
    # the port float 2 cm lower than the starboard one's deck: at the starboard float's
    # full draft the port float is under water altogether, the starboard one is crossed
    (vs, fs), (vp, fp) = floats
    h30 = 0.1 * np.tan(np.radians(30.0))
    low = vp - np.array([0.0, 0.0, 0.02 + (0.1 * np.tan(np.radians(20.0)))])
    cat = hs.Hull.from_arrays(*join((vs, fs), (low, fp)), mass=20.0)
    s = hs.cut(cat, cat.extents[2] - 0.005, 4)
    assert list(s.station) == [0, 0, 1, 1, 2, 2, 3, 3]
    assert np.all(s.penetration > 0.0)
    # the mass is all there: sum of M dx over the entries is the body's
    assert float((s.mass_per_metre * s.dx).sum()) == pytest.approx(20.0, rel=1e-6)
    assert s.mass_per_metre[0::2] == pytest.approx(np.full(4, 20.0 / cat.volume * 0.1 * h30))


def test_a_section_under_water_beyond_its_widest_point_keeps_its_keel():
    # a square section turned 30 degrees: near full immersion the water meets it in a short
    # span around its top corner, while its keel (the bottom corner) lies far to one side
    import trimesh
    from scipy.spatial.transform import Rotation

    b = trimesh.creation.box(extents=(1.0, 1.0, 1.0))
    v = Rotation.from_euler("x", 30.0, degrees=True).apply(np.asarray(b.vertices))
    hull = hs.Hull.from_arrays(v, np.asarray(b.faces), mass=500.0)
    draft = 0.95 * hull.extents[2]
    s = hs.cut(hull, draft, 4)
    assert s.penetration == pytest.approx(np.full(4, draft), rel=1e-6)
    assert s.mass_per_metre == pytest.approx(np.full(4, 500.0), rel=1e-6)
    assert s.chine_wetted.all()  # beyond the widest point: flagged, not passed as valid


@pytest.mark.parametrize("solver", ["mlm", "zarnick", "wagner", "von-karman"])
def test_a_catamaran_is_the_sum_of_its_floats_for_each_momentum_solver(floats, solver):
    # the same reference as above, for the solvers that read each entry's own contour
    # (mlm samples each side of a float out to its own edge, not across to the other
    # float: before, its side reached over the gap, 7.8 N/m of 3.7 kN/m apart); the
    # acceleration prescribed, so that each float alone moves as the pair does
    (vs, fs), (vp, fp) = floats
    cat = hs.Hull.from_arrays(*join((vs, fs), (vp, fp)), mass=20.0)
    kw = dict(slices=SLICES, solver=solver, slicing="fixed", acceleration=0.0)
    r = hs.compute_force(cat, DRAFT, VELOCITY, **kw)
    alone = [
        hs.compute_force(h.with_mass(20.0 * h.volume / cat.volume), DRAFT, VELOCITY, **kw)
        for h in (hs.Hull.from_arrays(vs, fs), hs.Hull.from_arrays(vp, fp))
    ]
    assert r.force[0::2] == pytest.approx(alone[0].force, rel=1e-7)
    assert r.force[1::2] == pytest.approx(alone[1].force, rel=1e-7)


def _alone(cat, parts, draft_of, motion, **kw):
    """Each part alone with its share of the pair's mass, at the pose that puts it where
    it is in the pair (pitch 0: its own draft from its own lowest point)."""
    out = []
    for v, f in parts:
        one = hs.Hull.from_arrays(v, f)
        one = one.with_mass(20.0 * one.volume / cat.volume)
        out.append(hs.compute_force(one, hs.Pose(draft_of(v), 0.0), motion, **kw))
    return out


def _sloping_pair(rise):
    """Floats 0.4 m wide (both stay wet, neither goes under) 0.6 m apart: 30 deg
    starboard with a level keel at 0, 20 deg port with its keel at ``rise (x - 1) - 0.01``
    (rising forward by ``rise`` over its 1 m)."""
    vs, fs = shapes.wedge_prism(length=1.0, beam=0.4, deadrise_deg=30.0)
    vp, fp = shapes.wedge_prism(length=1.0, beam=0.4, deadrise_deg=20.0)
    vs = vs - np.array([0.0, 0.3, vs[:, 2].min()])
    vp = vp + np.array([0.0, 0.3, -vp[:, 2].min()])
    vp[:, 2] += rise * (vp[:, 0] - vp[:, 0].max()) - 0.01
    return (vs, fs), (vp, fp)


def _pair_and_alone(rise, solver, slicing, draft=0.07):
    """The pair at 10 m/s forward and each float alone where it is in the pair (its
    share of the mass, the acceleration prescribed)."""
    (vs, fs), (vp, fp) = _sloping_pair(rise)
    cat = hs.Hull.from_arrays(*join((vs, fs), (vp, fp)), mass=20.0)
    low = min(vs[:, 2].min(), vp[:, 2].min())
    motion = hs.Motion(-3.0, 10.0, 0.0)
    kw = dict(slices=SLICES, solver=solver, slicing=slicing, acceleration=0.0)
    r = hs.compute_force(cat, hs.Pose(draft, 0.0), motion, **kw)
    alone = _alone(cat, [(vs, fs), (vp, fp)], lambda v: draft - (v[:, 2].min() - low),
                   motion, **kw)  # fmt: skip
    return r, alone


@pytest.mark.parametrize("slicing", ["fixed", "wetted"])
@pytest.mark.parametrize("solver", ["mlm", "zarnick"])
def test_a_piece_above_a_lower_one_keeps_its_own_keel(slicing, solver):
    # the port float deeper everywhere, its keel sloping 0.03; the starboard float's
    # level. With forward speed a section's penetration rate is w - U * slope: on the
    # body's one keel line the level float took the other's slope (zarnick 10 % high on
    # the pair at 10 m/s, examples/pieces.py). Each float alone is the reference, as above
    r, (stbd, port) = _pair_and_alone(0.03, solver, slicing)
    s = r.sections
    assert len(s) == 2 * SLICES and np.all(s.penetration > 0)
    assert s.keel_slope[0::2] == pytest.approx(np.zeros(SLICES), abs=1e-12)
    assert s.keel_slope[1::2] == pytest.approx(np.full(SLICES, 0.03), abs=1e-9)
    assert s.keel_curvature == pytest.approx(np.zeros(2 * SLICES), abs=1e-9)
    assert s.keel_z[0::2] == pytest.approx(-s.penetration[0::2], abs=1e-12)
    assert r.force[0::2] == pytest.approx(stbd.force, rel=1e-8)
    assert r.force[1::2] == pytest.approx(port.force, rel=1e-8)


@pytest.mark.parametrize("solver", ["mlm", "zarnick"])
def test_where_two_pieces_keels_cross_each_keeps_its_own(solver):
    # the port float's keel falls forward and crosses the level one's at x = 2/3: aft of
    # it the port float is above the body's keel line, forward of it the starboard one.
    # On that one line the float above it took the other's slope, and the float on it the
    # line's kink near the crossing as curvature (the pair 2.8 % high by zarnick, 7.0 %
    # by mlm, examples/pieces.py); each on its own line, the pair is the sum of the
    # floats alone
    r, (stbd, port) = _pair_and_alone(-0.03, solver, "fixed")
    s = r.sections
    assert len(s) == 2 * SLICES and np.all(s.penetration > 0)
    assert s.keel_curvature == pytest.approx(np.zeros(2 * SLICES), abs=1e-9)
    assert r.force[0::2] == pytest.approx(stbd.force, rel=1e-8)
    assert r.force[1::2] == pytest.approx(port.force, rel=1e-8)


def test_a_piece_above_another_takes_its_own_keel_curvature():
    # a float with a parabolic rocker z = a (x - 0.5)^2 beside a lower level float: the
    # body's keel line there is the level float's (slope and curvature 0); the rocker's
    # entries take its own line's, the same as the rocker alone gives at the same place,
    # about its closed form 2 a (x - 0.5) and 2 a
    a, n = 0.04, 16
    x = np.linspace(0.0, 1.0, 81)
    v0, _ = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0)
    corners = v0[:3, 1:]  # the section's corners, counter-clockwise seen from the bow
    sections = corners[None, :, :] + np.stack(
        [np.zeros_like(x), a * (x - 0.5) ** 2], axis=1
    )[:, None, :]  # fmt: skip
    vr, fr = shapes.prism_from_sections(x, sections)
    vr = vr + np.array([0.0, 0.3, -vr[:, 2].min()])  # its keel at 0 amidships
    vl, fl = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=20.0)
    vl = vl + np.array([0.0, -0.3, -vl[:, 2].min() - 0.005])
    body = hs.Hull.from_arrays(*join((vl, fl), (vr, fr)), mass=20.0)
    alone = hs.Hull.from_arrays(vr, fr, mass=20.0 * hs.Hull.from_arrays(vr, fr).volume
                                / body.volume)  # fmt: skip
    for slicing in ("fixed", "wetted"):
        s = hs.cut(body, hs.Pose(0.03, 0.0), n, slicing=slicing)
        r = hs.cut(alone, hs.Pose(0.025, 0.0), n, slicing=slicing)
        rocker = s.y_keel > 0
        assert rocker.sum() == n and len(r) == n
        np.testing.assert_allclose(s.x[rocker], r.x, rtol=0, atol=1e-12)
        np.testing.assert_allclose(s.keel_slope[rocker], r.keel_slope, rtol=0, atol=1e-12)
        np.testing.assert_allclose(s.keel_curvature[rocker], r.keel_curvature, rtol=0,
                                   atol=1e-12)  # fmt: skip
        assert s.keel_slope[~rocker] == pytest.approx(np.zeros(n), abs=1e-12)
        assert s.keel_curvature[~rocker] == pytest.approx(np.zeros(n), abs=1e-12)
        assert s.keel_z[rocker] == pytest.approx(-s.penetration[rocker], abs=1e-12)
        # the closed form, on 80 facets: the chord to a's facets' rounding, the curvature
        # averaged over the window (half the float's beam) where it lies on the body
        inside = np.abs(r.x - 0.5) < 0.45
        assert r.keel_slope == pytest.approx(2 * a * (r.x - 0.5), abs=2e-4)
        assert r.keel_curvature[inside] == pytest.approx(np.full(inside.sum(), 2 * a),
                                                         rel=0.02)  # fmt: skip


def test_the_curvature_window_is_half_the_widest_pieces_beam(floats):
    # 2D+t resolves a section's flow no finer along the body than its own width: for
    # separate floats that is a float's, not the span across both (0.2 m floats 0.6 m
    # apart: 0.8 m across)
    from hullslice.slicing.assemble import keel_window

    (vs, fs), (vp, fp) = floats
    cat = hs.Hull.from_arrays(*join((vs, fs), (vp, fp)), mass=20.0)
    assert cat.extents[1] == pytest.approx(0.8, rel=1e-12)
    assert keel_window(cat) == pytest.approx(0.1, rel=1e-12)
    one = hs.Hull.from_arrays(vs, fs)
    assert keel_window(one) == pytest.approx(0.5 * one.extents[1], rel=1e-12)


@pytest.mark.parametrize("pitch_deg", [-3.0, 0.0, 4.0, 12.0])
def test_a_pieces_keel_line_by_the_loops_is_numpys(pitch_deg, monkeypatch):
    # a piece's line is made as the body's: by the keel line's loops (here as Python, and
    # compiled where numba is installed) from this thread's last order of the piece's
    # ends, or by numpy's lower envelope; the same line either way
    from hullslice import geometry, planecut_loops
    from hullslice.slicing.own_keel import pieces

    (vs, fs), (vp, fp) = _sloping_pair(-0.03)
    pair = hs.Hull.from_arrays(*join((vs, fs), (vp, fp)), mass=20.0)
    parts = pieces(pair)
    assert parts.n == 2
    pitch = np.radians(pitch_deg)
    monkeypatch.setattr(geometry, "loops_in_use", lambda name: None)
    want = [geometry.keel_line_of(pair, pitch, e, k) for k, e in enumerate(parts.edges)]
    paths = [lambda name: planecut_loops.LOOPS[name]]
    if planecut_loops.available():
        paths.append(planecut_loops.compiled)
    for path in paths:
        monkeypatch.setattr(geometry, "loops_in_use", path)
        for _ in range(2):  # a fresh order, then the one the first call left
            for k, e in enumerate(parts.edges):
                got = geometry.keel_line_of(pair, pitch, e, k)
                np.testing.assert_allclose(got.x, want[k].x, rtol=0, atol=1e-13 * pair.size)
                np.testing.assert_allclose(got.z, want[k].z, rtol=0, atol=1e-13 * pair.size)


def _extruded(section) -> hs.Hull:
    mesh = manifold3d.CrossSection([section]).extrude(1.0).to_mesh()
    v = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
    # extruded along the mesh z; its y is up, so its x is the body's port
    return hs.Hull.from_arrays(v, np.asarray(mesh.tri_verts), forward="+z", up="+y")


@pytest.mark.parametrize("solver", ["mlm", "zarnick", "wagner", "von-karman"])
def test_floats_joined_by_a_tunnel_roof_are_each_a_float_of_their_own(solver):
    # one closed surface: two 20-degree floats 0.5 m wide, keels 1 m apart, their knuckles
    # 0.091 m up, a tunnel roof between them 0.3 m up. Below the roof each float's bottom
    # ends at its own knuckles (the tunnel's walls above them), not at the pair's outer
    # sides: the pair carries twice one float alone, before and after the knuckles
    b, zk = 0.25, 0.25 * np.tan(np.radians(20.0))
    pair = _extruded([
        [0.5, 0.0], [0.75, zk], [0.75, 0.5], [-0.75, 0.5], [-0.75, zk], [-0.5, 0.0],
        [-0.25, zk], [-0.25, 0.3], [0.25, 0.3], [0.25, zk],
    ])  # fmt: skip
    one = _extruded([[0.0, 0.0], [b, zk], [b, 0.5], [-b, 0.5], [-b, zk]])
    kw = {"slices": 2, "solver": solver, "acceleration": 0.0, "fluid": hs.Fluid(1000.0, 0.0)}
    for draft in (0.03, 0.06, 0.15, 0.25):
        both = hs.compute_force(pair, draft, VELOCITY, **kw)
        alone = hs.compute_force(one, draft, VELOCITY, **kw)
        assert len(both.sections) == 2 * len(alone.sections)
        assert both.total == pytest.approx(2.0 * alone.total, rel=1e-6), draft
        assert both.loads.valid.all() == alone.loads.valid.all()
