"""The keel line's wetted range, found from its first and last points under the water,
against a brute force over all its points and crossings of the water's height."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from hypothesis import given
from hypothesis import strategies as st

import hullslice as hs
from hullslice.geometry import KeelLine


def brute_force(x: np.ndarray, z: np.ndarray, level: float):
    """Every point under the level and every crossing of it: their lowest and highest x."""
    xs = [xi for xi, zi in zip(x, z, strict=True) if zi < level]
    for i in range(len(x) - 1):
        if (z[i] < level) != (z[i + 1] < level):
            t = (level - z[i]) / (z[i + 1] - z[i])
            xs.append(x[i] + t * (x[i + 1] - x[i]))
    return (min(xs), max(xs)) if xs else None


heights = st.floats(-1.0, 1.0, allow_nan=False)


@given(
    steps=st.lists(st.floats(1e-3, 1.0), min_size=1, max_size=25),
    z=st.lists(heights, min_size=26, max_size=26),
    level=heights,
)
def test_wetted_range_matches_the_brute_force(steps, z, level):
    x = np.concatenate([[0.0], np.cumsum(steps)])
    zz = np.asarray(z[: len(x)])
    got = KeelLine(x, zz).below(level)
    want = brute_force(x, zz, level)
    if want is None:
        assert got is None
    else:
        assert got is not None
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12)


def test_a_keel_under_the_water_everywhere_is_wetted_end_to_end():
    line = KeelLine(np.array([0.0, 1.0, 2.0]), np.array([-0.3, -0.5, -0.2]))
    assert line.below(0.0) == (0.0, 2.0)
    assert line.below(-0.4) == pytest.approx((0.5, 4.0 / 3.0), abs=1e-15)
    assert line.below(-0.6) is None


def test_a_body_of_two_parts_wetted_only_forward_of_the_gap_between_them():
    # two 2 x 1 x 1 boxes one behind the other, 1 m apart, the aft one 0.2 m higher: at a
    # draft of 0.1 m only the forward box is wet, over its 2 m length (the keel line has no
    # point in the gap between them, so its crossing of the water is at the forward box)
    aft = trimesh.creation.box(extents=(2.0, 1.0, 1.0))
    aft.apply_translation((0.0, 0.0, 0.7))
    fore = trimesh.creation.box(extents=(2.0, 1.0, 1.0))
    fore.apply_translation((3.0, 0.0, 0.5))
    both = trimesh.util.concatenate([aft, fore])
    hull = hs.Hull.from_arrays(both.vertices, both.faces, mass=1000.0)
    for slicing in ("wetted", "fixed"):
        s = hs.cut(hull, 0.1, slices=8, slicing=slicing)
        assert s.wetted_length == pytest.approx(2.0, rel=1e-9)
        assert np.all(s.x[s.penetration > 0] > 2.0)
        r = hs.compute_force(hull, 0.1, -1.0, slices=8, slicing=slicing)
        assert np.isfinite(r.total) and r.total > 0.0


def lowest_brute_force(a: np.ndarray, b: np.ndarray, x: float) -> float:
    """The lowest height over ``x`` of the segments from ``a`` to ``b``, one at a time."""
    best = np.inf
    for (xa, za), (xb, zb) in zip(a, b, strict=True):
        if min(xa, xb) <= x <= max(xa, xb):
            z = min(za, zb) if xb == xa else za + (x - xa) / (xb - xa) * (zb - za)
            best = min(best, z)
    return best


coordinate = st.integers(-20, 20).map(lambda k: k / 8)  # ties between ends, vertical ones


@given(
    ends=st.lists(
        st.tuples(coordinate, coordinate, coordinate, coordinate), min_size=1, max_size=30
    )
)
def test_lower_envelope_at_its_points_is_the_lowest_segment(ends):
    # the envelope holds, at each of its points, the lowest of the segments over it (and
    # is infinitely high where none is: a gap between parts)
    from hullslice.kernel.envelope import lower_envelope

    e = np.array(ends, dtype=np.float64)
    a, b = e[:, :2], e[:, 2:]
    line, every = lower_envelope(a, b), lower_envelope(a, b, every_pair)
    np.testing.assert_array_equal(_bits(line.x), _bits(every.x))
    np.testing.assert_array_equal(_bits(line.z), _bits(every.z))
    want = np.array([lowest_brute_force(a, b, x) for x in line.x])
    np.testing.assert_allclose(line.z, want, rtol=0.0, atol=1e-12)
    ends_x = np.unique(np.concatenate([a[:, 0], b[:, 0]]))
    assert set(ends_x.tolist()) <= set(line.x.tolist())


def outline_edges_brute_force(hull, edge_on: bool = False) -> set:
    """Every edge whose two faces do not both face port or both starboard (a normal's y
    component of one sign, or zero), but for those between two edge-on faces (unless
    ``edge_on``), as a set of sorted vertex pairs."""
    v, f = hull.vertices, hull.faces
    ny = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])[:, 1]
    faces_of: dict[tuple[int, int], list[int]] = {}
    for i, tri in enumerate(f.tolist()):
        for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            faces_of.setdefault((min(a, b), max(a, b)), []).append(i)
    out = set()
    for (a, b), (f1, f2) in faces_of.items():
        if np.sign(ny[f1]) * np.sign(ny[f2]) <= 0 and (edge_on or ny[f1] != 0 or ny[f2] != 0):
            out.add(
                (tuple(v[a]), tuple(v[b]))
                if tuple(v[a]) < tuple(v[b])
                else (tuple(v[b]), tuple(v[a]))
            )
    return out


@pytest.mark.parametrize(
    "body",
    [
        "fuselage_model.obj",
        "paper_prism.stl",
        "box",  # faces edge-on to the side view (top, bottom, ends): ny = 0
        "tilted sphere",
    ],
)
def test_the_outline_edges_are_every_edge_between_port_and_starboard_faces(body):
    from hullslice.geometry import silhouette_edges

    from .conftest import ROOT

    if body == "box":
        mesh = trimesh.creation.box((1.0, 0.4, 0.3))
    elif body == "tilted sphere":
        mesh = trimesh.creation.icosphere(3)
        mesh.apply_transform(trimesh.transformations.rotation_matrix(0.3, (1.0, 0.2, 0.5)))
    if body in ("box", "tilted sphere"):
        hull = hs.Hull.from_arrays(mesh.vertices, mesh.faces)
    else:
        hull = hs.load_hull(ROOT / "meshes" / body)
    a, b = silhouette_edges(hull)
    got = {
        (tuple(p), tuple(q)) if tuple(p) < tuple(q) else (tuple(q), tuple(p))
        for p, q in zip(a, b, strict=True)
    }
    assert len(got) == len(a) > 0
    assert got == outline_edges_brute_force(hull)


def _box_with_a_fanned_bottom(x_fan: float) -> trimesh.Trimesh:
    """A 2 x 0.5 x 0.3 m box whose bottom is a fan about a vertex inside it, at ``x_fan``."""
    corners = [[x, y, z] for z in (0.0, 0.3) for y in (0.5, 1.0) for x in (0.0, 2.0)]
    v = np.array([*corners, [x_fan, 0.75, 0.0]])
    f = [[4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4], [2, 6, 7], [2, 7, 3], [0, 4, 6],
         [0, 6, 2], [1, 3, 7], [1, 7, 5], [8, 1, 0], [8, 3, 1], [8, 2, 3], [8, 0, 2]]  # fmt: skip
    mesh = trimesh.Trimesh(v, f, process=False)
    mesh.fix_normals()
    return mesh


def _edge_on_bodies(body: str):
    from .conftest import ROOT

    if body == "fuselage_model.obj":
        return hs.load_hull(ROOT / "meshes" / body)
    if body == "box":
        mesh = trimesh.creation.box((1.0, 0.4, 0.3))
    elif body == "capped cylinder":  # flat ends of fans of faces, along x
        mesh = trimesh.creation.cylinder(0.2, 2.0, sections=48)
        mesh.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, (0, 1, 0)))
    else:  # a fanned flat bottom beside a box pitched 20 deg: their bottoms cross
        other = trimesh.creation.box((2.0, 0.5, 0.3))
        other.apply_translation((1.0, -0.75, 0.15))
        turn = trimesh.transformations.rotation_matrix(np.radians(20.0), (0, 1, 0), (1, 0, 0))
        other.apply_transform(turn)
        mesh = trimesh.util.concatenate([_box_with_a_fanned_bottom(0.9), other])
    return hs.Hull.from_arrays(mesh.vertices, mesh.faces, mass=1.0)


@pytest.mark.parametrize(
    "body", ["fuselage_model.obj", "box", "capped cylinder", "fanned bottom beside a crossing"]
)
def test_the_edges_between_edge_on_faces_change_no_keel_line(body):
    """Leaving out the edges between two edge-on faces (a flat end cap's fan, a box's flat
    sides) leaves the keel line as it is at every pitch: the edges around each such face's
    region cover its side view, and a vertex only those edges reach (a fan's centre) stays
    a point, so that the refinement between the break points is the same too. Against
    the keel line of every edge between port and starboard faces, edge-on ones included,
    at pitches from -30 to 60 degrees: the same break points, the same heights and slopes
    to rounding (1e-13 of the body's size; the slope to 1e-9, absolute and relative: a
    steep cap's facets are short)."""
    from hullslice import geometry

    hull = _edge_on_bodies(body)
    a, b = geometry.silhouette_edges(hull)
    every = np.array(sorted(outline_edges_brute_force(hull, edge_on=True)))
    assert len(every) > len(a[(a != b).any(axis=1)])  # some left out
    kept = geometry._silhouette_edges
    for pitch in np.radians([-30.0, -10.0, -3.0, 0.0, 2.0, 5.0, 12.0, 60.0]):
        line = geometry._frame(hull, pitch).keel
        other = hs.Hull.from_arrays(hull.vertices, hull.faces, mass=1.0, cg=hull.cg)
        try:  # a body of its own, whose silhouette is every such edge
            geometry._silhouette_edges = lambda _hull: (every[:, 0], every[:, 1])
            full = geometry._frame(other, pitch).keel
        finally:
            geometry._silhouette_edges = kept
        np.testing.assert_allclose(line.x, full.x, rtol=0, atol=1e-13 * hull.size)
        np.testing.assert_allclose(line.z, full.z, rtol=0, atol=1e-13 * hull.size)
        x = np.linspace(line.x[0], line.x[-1], 2001)
        np.testing.assert_allclose(line.at(x)[1], full.at(x)[1], rtol=1e-9, atol=1e-9)


def lowest_every_pair(a: np.ndarray, b: np.ndarray, xs: np.ndarray) -> np.ndarray:
    """The lowest height of the segments over each of the sorted abscissae ``xs``, every
    pair of a segment and an abscissa within its span at once (the numpy path as it was
    before it took the pairs a few thousand at a time)."""
    xa, za, xb, zb = a[:, 0], a[:, 1], b[:, 0], b[:, 1]
    dx, dz = xb - xa, zb - za
    i0 = np.searchsorted(xs, np.minimum(xa, xb), side="left")
    i1 = np.searchsorted(xs, np.maximum(xa, xb), side="right")
    count = np.maximum(i1 - i0, 0)
    total = int(count.sum())
    z = np.full(len(xs), np.inf)
    if total == 0:
        return z
    seg = np.repeat(np.arange(len(count)), count)
    step = np.ones(total, dtype=np.int64)
    starts = np.cumsum(count) - count
    has = count > 0
    step[starts[has]] = i0[has] - np.concatenate([[0], (i0 + count - 1)[has][:-1]])
    idx = np.cumsum(step)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (xs[idx] - xa[seg]) / dx[seg]
    z_on = za[seg] + t * dz[seg]
    vertical = dx[seg] == 0.0
    z_on[vertical] = np.minimum(za, zb)[seg[vertical]]
    np.minimum.at(z, idx, z_on)
    return z


def every_pair_lowest(xs, xa, za, xb, zb):
    """:func:`lowest_every_pair` in the signature of ``planecut_loops.lowest_loops``."""
    return lowest_every_pair(np.column_stack([xa, za]), np.column_stack([xb, zb]), xs)


def as_envelope(lowest):
    """A lowest-segment search in the signature of ``lower_envelope``'s ``loops``
    (``planecut_loops.envelope_loops``): the end abscissae sorted, each once, their
    middles, and ``lowest`` over both."""

    def envelope(xa, za, xb, zb):
        xs = np.unique(np.concatenate([xa, xb]))
        mid = 0.5 * (xs[1:] + xs[:-1])
        return xs, mid, lowest(xs, xa, za, xb, zb), lowest(mid, xa, za, xb, zb)

    return envelope


every_pair = as_envelope(every_pair_lowest)


def _bits(z: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(z, dtype=np.float64).view(np.int64)


def _abscissae(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    xs = np.unique(np.concatenate([a[:, 0], b[:, 0]]))
    return xs, 0.5 * (xs[1:] + xs[:-1])


def _random_segments(
    rng: np.random.Generator, n: int, floor: bool
) -> tuple[np.ndarray, np.ndarray]:
    """Segments on a coarse grid (ties between ends, duplicates), with long ones across the
    whole range, near-vertical and vertical ones, fans from a common end, and heights of
    +0 and -0 (on a floor, when ``floor``, that nothing is under: the lowest height is
    then +0 or -0 over much of the range, and which depends on the order of the pairs)."""
    grid = np.arange(-300, 301) / 64.0
    a = rng.choice(grid, size=(n, 2))
    b = a + rng.integers(-4, 5, size=(n, 2)) / 64.0  # short ones
    k = n // 5
    b[:k, 0] = rng.choice(grid, size=k)  # long ones
    near = slice(k, 2 * k)  # near-vertical: a tiny run, a large rise
    b[near, 0] = a[near, 0] + rng.choice([-1.0, 1.0], size=k) * 2.0**-40
    b[near, 1] = a[near, 1] + rng.uniform(-3.0, 3.0, size=k)
    vert = slice(2 * k, 2 * k + k // 2)
    b[vert, 0] = a[vert, 0]
    fan = slice(3 * k, 4 * k)  # a fan from one point, all but collinear
    a[fan] = (0.5, -1.0)
    b[fan, 0] = rng.uniform(-4.0, 0.4, size=k)
    b[fan, 1] = -1.0 + (b[fan, 0] - 0.5) * -0.7 + rng.uniform(0.0, 1e-15, size=k)
    if floor:
        a[:, 1], b[:, 1] = np.abs(a[:, 1]), np.abs(b[:, 1])
    zero = rng.random((n, 2)) < 0.05
    a[:, 1][zero[:, 0]] = rng.choice([0.0, -0.0], size=int(zero[:, 0].sum()))
    b[:, 1][zero[:, 1]] = rng.choice([0.0, -0.0], size=int(zero[:, 1].sum()))
    if floor:
        level = rng.random(n) < 0.1
        a[level, 1] = rng.choice([0.0, -0.0], size=int(level.sum()))
        b[level, 1] = rng.choice([0.0, -0.0], size=int(level.sum()))
    dup = rng.integers(0, n, size=n // 10)  # duplicates, in both directions
    a, b = np.concatenate([a, a[dup], b[dup]]), np.concatenate([b, b[dup], a[dup]])
    order = rng.permutation(len(a))
    return a[order], b[order]


@pytest.mark.parametrize(
    "seed, n, floor",
    [(0, 40, False), (1, 300, False), (2, 3000, False), (3, 12000, False), (4, 40, True),
     (5, 3000, True), (6, 12000, True)],
)  # fmt: skip
def test_the_lowest_segment_taken_in_parts_equals_every_pair_at_once(seed, n, floor):
    # to the last bit, the sign of a zero included; the larger sets hold more pairs (and
    # segments spanning more abscissae) than are taken at once
    from hullslice import planecut_loops
    from hullslice.kernel.envelope import _PAIRS, _Segments, lower_envelope

    a, b = _random_segments(np.random.default_rng(seed), n, floor)
    segments = _Segments(a, b)
    for xs in _abscissae(a, b):
        want = lowest_every_pair(a, b, xs)
        got = segments.lowest(xs)
        np.testing.assert_array_equal(_bits(got), _bits(want))
        compiled = planecut_loops.compiled("lowest") if planecut_loops.available() else None
        for loops in [compiled] if compiled is not None else []:
            # the loops keep the first of equal values: +0 and -0 compare as values
            np.testing.assert_array_equal(loops(xs, a[:, 0], a[:, 1], b[:, 0], b[:, 1]), got)
        if n <= 300:  # the loops as Python
            got = planecut_loops.LOOPS["lowest"](xs, a[:, 0], a[:, 1], b[:, 0], b[:, 1])
            np.testing.assert_array_equal(got, want)
    if n >= 3000:
        xs, _ = _abscissae(a, b)
        i0 = np.searchsorted(xs, segments.lo, side="left")
        i1 = np.searchsorted(xs, segments.hi, side="right")
        assert (i1 - i0).sum() > 2 * _PAIRS
    line, every = lower_envelope(a, b), lower_envelope(a, b, every_pair)
    np.testing.assert_array_equal(_bits(line.x), _bits(every.x))
    np.testing.assert_array_equal(_bits(line.z), _bits(every.z))


def _ellipsoid() -> hs.Hull:
    e = trimesh.creation.icosphere(subdivisions=3)
    e.apply_scale([2.0, 0.3, 0.3])  # slender along x; rings of vertices share a station
    return hs.Hull.from_arrays(e.vertices, e.faces, mass=100.0)


def test_the_keel_line_does_not_jump_as_the_pitch_leaves_zero():
    # vertices sharing a station at zero pitch part by height * pitch at another: at a
    # pitch of rounding's size (1e-12 rad) they are one break point, and the force, the
    # horizontal force and the moment on an x-symmetric body stay as at zero (symmetry:
    # zero horizontal force and moment)
    hull = _ellipsoid()
    motion = hs.Motion(-1.5, 0.0, 0.0)
    zero = hs.compute_force(hull, hs.Pose(0.05, 0.0), motion, slices=32, solver="mlm",
                            acceleration=0.0)  # fmt: skip
    assert len(hs.geometry.frame(hull, 1e-12).keel.x) == len(hs.geometry.frame(hull, 0.0).keel.x)
    for pitch in (1e-12, -1e-12, 1e-13):
        r = hs.compute_force(hull, hs.Pose(0.05, pitch), motion, slices=32, solver="mlm",
                             acceleration=0.0)  # fmt: skip
        assert r.total == pytest.approx(zero.total, rel=1e-7)
        assert abs(r.total_x) <= 1e-6 * zero.total
        assert abs(r.moment) <= 1e-6 * zero.total * 2.0  # the body's half-length, m


def test_a_symmetric_body_dropped_level_with_free_pitch_stays_level():
    # rounding pitches the sphere by 1e-16 rad or so: no moment may come of it
    s = trimesh.creation.icosphere(subdivisions=4, radius=0.5)
    hull = hs.Hull.from_arrays(s.vertices, s.faces, mass=100.0)
    h = hs.simulate(hull, -3.0, 0.05, dt=5e-4, slices=32, solver="wagner", stop_on=(),
                    free_pitch=True)  # fmt: skip
    assert np.abs(h.pitch).max() < 1e-9
    assert np.abs(h.moment).max() < 1e-6 * np.abs(h.force).max()


def test_two_crossing_edges_peak_between_their_ends_and_the_line_follows():
    # the lowest of z = -2x and z = x - 1 over 0..1 peaks at their crossing (1/3, -2/3),
    # above the straight line between its ends' heights (-2 and -1): the line is refined
    # at the middles of the halves that peak, to the interval over 2**CROSSING_PASSES
    from hullslice.kernel.envelope import CROSSING_PASSES, lower_envelope

    a = np.array([[0.0, 0.0], [0.0, -1.0]])
    b = np.array([[1.0, -2.0], [1.0, 0.0]])
    line = lower_envelope(a, b)
    x = np.linspace(0.0, 1.0, 10001)
    true = np.minimum(-2.0 * x, x - 1.0)
    assert np.abs(line.height(x) - true).max() <= 3.0 / 2**CROSSING_PASSES
    # the middle lies on the first edge, exactly, and the crossing is found to the bound
    assert line.height(np.array([0.5]))[0] == pytest.approx(-1.0, abs=1e-15)
    assert line.z.max() == pytest.approx(-2.0 / 3.0, abs=3.0 / 2**CROSSING_PASSES)
    # a vertical edge's foot below the others is a jump, not a ramp: a bottom at 0 ending
    # at x = 1, a vertical face up to 1, a higher bottom at 0.5 on to x = 2
    a = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.5]])
    b = np.array([[1.0, 0.0], [1.0, 1.0], [2.0, 0.5]])
    line = lower_envelope(a, b)
    np.testing.assert_allclose(line.height(np.array([0.5, 1.01, 1.5])), [0.0, 0.5, 0.5])


def test_the_side_outline_of_a_square_with_a_diagonal_is_the_square():
    # the outer boundary of a plane graph, counter-clockwise from its leftmost point (the
    # lowest of ties); the diagonal lies inside, and the point of the middle of the
    # bottom, in line with its neighbours, stays a point of the boundary
    from hullslice.kernel.envelope import side_outline

    p = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0], [1.0, 0.0]])
    edges = np.array([[0, 4], [4, 1], [1, 2], [2, 3], [3, 0], [0, 2]])
    assert side_outline(p, edges).tolist() == [0, 4, 1, 2, 3]
    # a point given twice (port and starboard in the side view) is one: the first stands
    p2 = np.vstack([p, [[2.0, 1.0]]])
    edges2 = np.array([[0, 4], [4, 1], [1, 5], [2, 3], [3, 0]])
    assert side_outline(p2, edges2).tolist() == [0, 4, 1, 2, 3]


def test_points_apart_by_rounding_are_one_point_of_the_side_outline():
    # port and starboard seen from the side, apart by rounding where the mesh's
    # coordinates are doubles: points within 1e-12 of the graph's size are one, the first
    # standing for them all; a chain of such points spanning more than twice that finds
    # no outline (its points would stand apart)
    from hullslice.kernel.envelope import side_outline

    p = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0], [2.0, 1.0 + 1e-15]])
    edges = np.array([[0, 1], [1, 2], [4, 3], [3, 0]])
    assert side_outline(p, edges).tolist() == [0, 1, 2, 3]
    tol = 1e-12 * 2.0
    chain = [[2.0, 1.0 + k * 0.9 * tol] for k in (1, 2, 3)]
    p = np.vstack([p[:4], chain])
    edges = np.array([[0, 1], [1, 2], [2, 4], [4, 5], [5, 6], [6, 3], [3, 0]])
    assert side_outline(p, edges) is None
    edges = np.array([[0, 1], [1, 2], [2, 4], [4, 5], [5, 3], [3, 0]])
    assert side_outline(p[:6], edges).tolist() == [0, 1, 2, 3]  # two steps: within twice it


@pytest.mark.parametrize(
    "points, edges, why",
    [
        ([[0, 0], [2, 0], [2, 2], [0, 2]], [[0, 2], [1, 3], [0, 1], [2, 3]], "two edges cross"),
        ([[0, 0], [2, 0], [1, 0], [3, 0], [1, 1]], [[0, 1], [2, 3], [0, 4], [3, 4]], "overlap"),
        ([[0, 0], [1, 0], [1, 1], [0, 1], [2, 2]], [[0, 1], [1, 2], [2, 3], [3, 0], [2, 4]],
         "an edge leading nowhere"),
        ([[0, 0], [1, 0], [0, 1], [3, 0], [4, 0], [3, 1]],
         [[0, 1], [1, 2], [2, 0], [3, 4], [4, 5], [5, 3]], "two parts"),
        ([[0, 0], [2, 0], [3, 0.45], [0.6, 0.65], [0.13, 0.72], [0.04, 0.5]],
         [[0, 1], [1, 2], [2, 3], [3, 4], [4, 0], [0, 5]], "an edge leading nowhere, at the start"),
        ([[0, 0], [1, -1], [2, 0], [1, 0.2], [1, 1], [2, 2]],
         [[0, 1], [1, 2], [2, 3], [3, 0], [0, 4], [4, 5], [5, 0]], "two loops at the start"),
    ],
)  # fmt: skip
def test_no_side_outline_where_the_graph_is_not_one_polygon(points, edges, why):
    from hullslice.kernel.envelope import side_outline

    p = np.asarray(points, dtype=float)
    assert side_outline(p, np.asarray(edges)) is None, why


def _turned(a, b, outline, g, degrees):
    """At each pitch (deg): the pitch (rad), the silhouette edges' ends ``a``, ``b`` and the
    side outline's points turned about the centre of gravity ``g`` as the keel line turns
    them."""
    from hullslice import geometry

    x, z = outline
    for pitch in np.radians(degrees):
        c, s = np.cos(pitch), np.sin(pitch)
        rx, rz = x - g[0], z - g[2]
        yield (pitch, geometry._turn(a - g, c, s), geometry._turn(b - g, c, s),
               (rx * c - rz * s, rx * s + rz * c))  # fmt: skip


@pytest.mark.parametrize(
    "name", ["fuselage_model.obj", "paper_prism.stl", "wedge", "paper prism, flipped diagonals"]
)
def test_the_keel_line_read_off_the_side_outline_is_the_edges_lower_envelope(name):
    # where the silhouette edges make one polygon, its lower side is their lower envelope:
    # the keel line read off it has that side's points as its break points, and each
    # line's heights at the other's break points are the other's within 1e-15 of the
    # body's size (the same line: the other ends lie on its facets); the same lowest and
    # highest points, at every pitch from -60 to 60 deg where that side runs forward
    # (and the envelope's, to the bit, at the others)
    from hullslice import geometry
    from hullslice.kernel.envelope import lower_envelope, lower_side

    from .test_planecut import BODIES

    hull = BODIES[name]
    a, b = geometry.silhouette_edges(hull)
    outline, whole = geometry.side_outline_points(hull)
    assert outline.shape[1] > 3 and whole
    g = np.asarray(hull.cg)
    x, z = outline
    assert 0.5 * float(x @ np.roll(z, -1) - np.roll(x, -1) @ z) > 0.0  # counter-clockwise
    assert x[0] == x.min()
    served = 0
    for pitch, ta, tb, side in _turned(a, b, outline, g, np.linspace(-60.0, 60.0, 25)):
        chain = lower_side(*side)
        got = lower_envelope(ta, tb, side=side)
        want = lower_envelope(ta, tb)
        if chain is None:
            assert np.array_equal(got.x, want.x) and np.array_equal(got.z, want.z)
        else:
            served += 1
            assert np.array_equal(got.x, chain[0]) and np.array_equal(got.z, chain[1])
            assert len(got.x) < len(want.x), np.degrees(pitch)  # the upper side's ends
            assert got.x[0] == want.x[0] and got.x[-1] == want.x[-1]
            for one, other in ((got, want), (want, got)):
                np.testing.assert_allclose(one.height(other.x), other.z, rtol=0.0,
                                           atol=1e-15 * hull.size, err_msg=str(pitch))  # fmt: skip
        _, low, high = geometry._side_keel(hull, a, b, (outline, whole), pitch,
                                              geometry._side_order)  # fmt: skip
        assert low == min(ta[:, 1].min(), tb[:, 1].min())
        assert high == max(ta[:, 1].max(), tb[:, 1].max())
    assert served >= 5


def test_the_keel_curvature_at_a_pitch_is_the_turned_bottom_lines(tmp_path):
    # the generic fuselage's tail cone has a closed-form bottom line, z = u H s^1.6 with
    # s = (l_t - x) / l_t (hullslice.shapes.fuselage). Turned by a pitch, the keel line's
    # curvature averaged over the keel window and over a 0.3 m slice is that of the turned
    # curve (sampled at 200,001 points, differentiated numerically) within 0.1 % and
    # 0.5 %, at 0, 3 and 6 deg: the line's break points are the bottom line's vertices at
    # every pitch. (Break points at the upper side's ends too split its facets where the
    # upper side's mesh falls: up to 0.9 % and 5.7 % off on the 1M-face fuselage, and the
    # local curvature zero on half the facets: the walk over every edge's end fails this
    # test at 3 and 6 deg.) The fuselage made from the arrays (doubles: port and starboard apart by
    # rounding in the side view, one point of its outline all the same) and read from a
    # binary STL (floats).
    from hullslice import shapes

    v, f = shapes.fuselage(stations=400, points=160)
    path = tmp_path / "fuselage.stl"
    trimesh.Trimesh(v, f).export(path)
    for hull in (hs.Hull.from_arrays(v, f, mass=6e4), hs.load_hull(path, mass=6e4)):
        _keel_curvature_is_the_turned_bottom_lines(hull)


def _keel_curvature_is_the_turned_bottom_lines(hull):
    from hullslice import geometry, shapes
    from hullslice.kernel.envelope import lower_envelope
    from hullslice.slicing.assemble import keel_window

    a, b = geometry.silhouette_edges(hull)
    (x, z), _ = geometry.side_outline_points(hull)
    assert x.shape == (958,)  # the outline found
    g = np.asarray(hull.cg)
    p = shapes.NARROW_BODY
    lt, up, height = p["tail_length"], p["tail_upsweep"], p["height"]
    xd = np.linspace(0.02 * lt, 0.98 * lt, 200_001)
    zd = up * height * ((lt - xd) / lt) ** 1.6
    x0 = np.linspace(0.15 * lt, 0.85 * lt, 15)  # points of the bottom line to test at
    z0 = up * height * ((lt - x0) / lt) ** 1.6
    for pitch, ta, tb, side in _turned(a, b, (x, z), g, [0.0, 3.0, 6.0]):
        c, s = np.cos(pitch), np.sin(pitch)
        keel = lower_envelope(ta, tb, side=side)
        tx, tz = (xd - g[0]) * c - (zd - g[2]) * s, (xd - g[0]) * s + (zd - g[2]) * c
        slope = np.gradient(tz, tx)
        at = (x0 - g[0]) * c - (z0 - g[2]) * s
        for dx, tol in ((keel_window(hull), 1e-3), (0.3, 5e-3)):
            want = (np.interp(at + dx / 2, tx, slope) - np.interp(at - dx / 2, tx, slope)) / dx
            got = keel.mean_curvature(at, np.full_like(at, dx))
            np.testing.assert_allclose(got, want, rtol=tol, err_msg=f"{np.degrees(pitch)} {dx}")


@pytest.mark.parametrize("name", ["fuselage_model.obj", "fuselage_full.obj", "paper_prism.stl",
                                  "wedge", "paper prism, flipped diagonals"])  # fmt: skip
def test_the_keel_line_off_the_outline_alone_is_the_one_off_its_lower_side(name):
    # where the side outline's points are all the silhouette edges' ends, numpy's reading
    # of the outline alone (no edge turned) gives the keel line of the edges' envelope
    # with the outline (the lower side's points, merged) to the bit, and on the edges'
    # own envelope (each line's heights at the other's break points within 1e-15 of the
    # size; the same first and last break points), and the edges' ends' lowest and
    # highest heights, at 61 pitches in +-66 deg; it declines where the lower side does
    # not serve, and the keel line is the edges' envelope there
    from hullslice import geometry
    from hullslice.kernel.envelope import lower_envelope, lower_side, side_envelope

    from .test_planecut import BODIES

    hull = BODIES[name]
    a, b = geometry.silhouette_edges(hull)
    (x, z), whole = geometry.side_outline_points(hull)
    assert whole
    g = np.asarray(hull.cg)
    merge = geometry.TOL.keel_merge * hull.size
    served = 0
    for pitch, ta, tb, side in _turned(a, b, (x, z), g, np.linspace(-66.0, 66.0, 61)):
        got = side_envelope(*side, merge)
        assert (got is None) == (lower_side(*side) is None), np.degrees(pitch)
        if got is None:
            continue
        served += 1
        want = lower_envelope(ta, tb, merge=merge, side=side)
        assert np.array_equal(got[0].x, want.x) and np.array_equal(got[0].z, want.z)
        assert np.array_equal(np.signbit(got[0].z), np.signbit(want.z))
        walk = lower_envelope(ta, tb, merge=merge)
        assert got[0].x[0] == walk.x[0] and got[0].x[-1] == walk.x[-1]
        for one, other in ((got[0], walk), (walk, got[0])):
            np.testing.assert_allclose(one.height(other.x), other.z, rtol=0.0,
                                       atol=1e-15 * hull.size, err_msg=str(pitch))  # fmt: skip
        assert got[1] == min(ta[:, 1].min(), tb[:, 1].min())
        assert got[2] == max(ta[:, 1].max(), tb[:, 1].max())
    assert served >= 20, served


def test_random_polygons_keel_lines_off_their_outline_are_the_walks():
    # polygons of 4 to 11 points, some with a chord inside or an edge leading out: wherever
    # an outline is found, the keel line read off it lies on the walk's and the walk's on
    # it (each's heights at the other's break points within 1e-12), at 33 pitches in
    # +-80 deg. (The walk may hold two more break points on a facet steeper than 1000:
    # rounding in its heights there looks like a jump to its refinement.)
    from hullslice.kernel.envelope import lower_envelope, side_outline

    rng = np.random.default_rng(11)
    rings = 0
    for _ in range(300):
        k = int(rng.integers(4, 12))
        ang = np.sort(rng.uniform(0.0, 2.0 * np.pi, k))
        r = rng.uniform(0.5, 2.0, k)
        p = np.stack([r * np.cos(ang) * rng.uniform(1.0, 3.0), r * np.sin(ang)], axis=1)
        edges = [[i, (i + 1) % k] for i in range(k)]
        if rng.random() < 0.5:  # a chord inside
            p = np.vstack([p, [[0.0, 0.0]]])
            edges.append([int(rng.integers(k)), len(p) - 1])
        if rng.random() < 0.5:  # an edge leading out
            i = int(rng.integers(k))
            p = np.vstack([p, 1.3 * p[i]])
            edges.append([i, len(p) - 1])
        e = np.asarray(edges)
        ring = side_outline(p, e)
        if ring is None:
            continue
        rings += 1
        x, z = p[ring, 0], p[ring, 1]
        for pitch in np.radians(np.linspace(-80.0, 80.0, 33)):
            c, s = np.cos(pitch), np.sin(pitch)
            turn = lambda q: np.stack([q[:, 0] * c - q[:, 1] * s, q[:, 0] * s + q[:, 1] * c], 1)  # noqa: B023, E731
            ta, tb = turn(p[e[:, 0]]), turn(p[e[:, 1]])
            got = lower_envelope(ta, tb, side=(x * c - z * s, x * s + z * c))
            want = lower_envelope(ta, tb)
            np.testing.assert_allclose(np.interp(want.x, got.x, got.z), want.z, rtol=0, atol=1e-12)
            np.testing.assert_allclose(np.interp(got.x, want.x, want.z), got.z, rtol=0, atol=1e-12)
    assert rings > 100


def test_a_graph_of_too_many_edges_side_by_side_is_left_to_the_envelope(monkeypatch):
    # the crossing test's pairs are bounded (memory): past the bound, no outline
    from hullslice.kernel import envelope

    p = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0], [1.0, 0.0]])
    edges = np.array([[0, 4], [4, 1], [1, 2], [2, 3], [3, 0], [0, 2]])
    assert envelope.side_outline(p, edges) is not None
    monkeypatch.setattr(envelope, "MAX_PAIRS", 3)
    assert envelope.side_outline(p, edges) is None


def test_a_body_with_wings_has_no_side_outline_and_keeps_the_envelope():
    # the catalogued airliner's silhouette edges cross in the side view (wings, fins): no
    # polygon, and its keel line is the edges' lower envelope at every pitch, as before
    from hullslice import geometry

    from .conftest import MESHES

    hull = hs.load_hull(MESHES / "airliner" / "airliner.obj", mass=6e4)
    outline, whole = geometry.side_outline_points(hull)
    assert outline.shape == (2, 0) and not whole
