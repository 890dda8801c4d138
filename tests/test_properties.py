"""Property-based tests on generated closed bodies (Hypothesis).

Bodies: boxes, wedge prisms, ellipsoids and convex hulls of random points, each randomly
rotated and moved; for the part properties also pairs of such bodies side by side. All are
convex (or unions of disjoint convex bodies), which gives the exact references used here:

- **areas**: the section of a convex body at ``x`` is the convex hull of the points where
  its edges cross the plane, computed here in double precision with scipy, independently
  of manifold3d; hullslice's areas must match it to manifold3d's precision: it cuts in
  single precision (with a grid of 1e-8) after scaling the body to unit size, so each
  contour point may be off by about 1e-7 of the body's ``size``, and an area by that times
  the perimeter, at most ``2 (W + H)``: the tests allow ``EPS = 1e-6 size (W + H)``;
- **volume**: over a cut of the whole body the midpoint sum ``sum(area * dx)`` equals the
  volume within the midpoint rule's error. For a convex body ``sqrt(A(x))`` is concave
  (Brunn-Minkowski), so ``A`` rises and falls once and its total variation is at most
  ``2 max A <= 2 W H`` (the bounding box's cross-section); each slice's error is at most
  ``d`` times the variation of ``A`` over it, so ``|sum - V| <= 2 d W H``, plus ``EPS L``
  for the single-precision cut. Bodies of constant section (boxes, prisms) have no
  midpoint error: ``EPS L`` alone;
- **forces** are finite for any draft and downward velocity;
- **invariance**: a level body's force does not depend on where it is (translation in
  ``x``, ``y``, ``z``; the draft is measured from its lowest point), nor on a 180-degree
  turn about the vertical axis (the same slices in the reverse order, mirrored), nor on a
  quarter turn when ``forward`` names the turned axis (the very same body frame). A
  general rotation about the vertical is *not* an invariance: the body is cut along its
  own ``x``, so a turned body is cut differently.

The Hypothesis profile (tests/conftest.py) is derandomised with a fixed example count, so
CI runs the same examples every time.
"""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from hypothesis import assume, given
from hypothesis import strategies as st
from scipy.spatial import ConvexHull, QhullError
from scipy.spatial.transform import Rotation

import hullslice as hs
from hullslice import shapes

DENSITY = 500.0  # kg/m^3: a plausible body, so no units warning
SIZE = st.floats(0.05, 5.0)


@st.composite
def convex_bodies(draw, constant_section: bool = False):
    """A convex body as (vertices, faces, kind), in metres, faces outward."""
    kinds = ["box", "wedge"] if constant_section else ["box", "wedge", "ellipsoid", "hull"]
    kind = draw(st.sampled_from(kinds))
    if kind == "box":
        b = trimesh.creation.box(extents=[draw(SIZE), draw(SIZE), draw(SIZE)])
        v, f = np.asarray(b.vertices), np.asarray(b.faces)
    elif kind == "wedge":
        v, f = shapes.wedge_prism(
            length=draw(SIZE),
            beam=draw(SIZE),
            deadrise_deg=draw(st.floats(5.0, 75.0)),
            stations=draw(st.integers(2, 6)),
        )
    elif kind == "ellipsoid":
        s = trimesh.creation.icosphere(subdivisions=2)
        v = np.asarray(s.vertices) * [draw(SIZE), draw(SIZE), draw(SIZE)]
        f = np.asarray(s.faces)
    else:
        n = draw(st.integers(6, 24))
        seed = draw(st.integers(0, 2**32 - 1))
        pts = np.random.default_rng(seed).uniform(-1.0, 1.0, (n, 3))
        pts *= [draw(SIZE), draw(SIZE), draw(SIZE)]
        h = trimesh.convex.convex_hull(pts)
        v, f = np.asarray(h.vertices), np.asarray(h.faces)
        ext = np.ptp(v, axis=0)
        # not a sliver: a body, not a near-flat sheet the loader would call flat
        assume(h.volume > 0.02 * np.prod(ext))
        edges = np.linalg.norm(v[f] - v[np.roll(f, 1, axis=1)], axis=2)
        assume(edges.min() > 1e-3 * np.linalg.norm(ext))
    if not constant_section:
        # any rigid rotation makes another convex body
        q = draw(st.tuples(*[st.floats(-1.0, 1.0)] * 4))
        assume(np.linalg.norm(q) > 0.1)
        v = Rotation.from_quat(q).apply(v)
    shift = np.array([draw(st.floats(-100.0, 100.0)) for _ in range(3)])
    return v + shift, f, kind


def eps(hull: hs.Hull) -> float:
    """Precision of a cut section's area, m^2 (see the module's documentation)."""
    _, width, height = hull.extents
    return 1e-6 * hull.size * (width + height)


def hull_of(v, f, **kw) -> hs.Hull:
    volume = trimesh.Trimesh(v, f, process=False).volume
    return hs.Hull.from_arrays(v, f, mass=DENSITY * volume, **kw)


def exact_section_area(v: np.ndarray, f: np.ndarray, x: float) -> float:
    """Area of a convex body's section at ``x``: the hull of the edges' crossings."""
    e = np.unique(np.sort(f[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1), axis=0)
    a, b = v[e[:, 0]], v[e[:, 1]]
    crossing = (a[:, 0] - x) * (b[:, 0] - x) < 0.0
    t = (x - a[crossing, 0]) / (b[crossing, 0] - a[crossing, 0])
    pts = a[crossing, 1:] + t[:, None] * (b[crossing, 1:] - a[crossing, 1:])
    pts = np.vstack([pts, v[v[:, 0] == x, 1:]])
    if len(np.unique(pts, axis=0)) < 3:
        return 0.0
    try:
        return float(ConvexHull(pts).volume)  # a 2D hull's "volume" is its area
    except QhullError:  # the points on one line: a section of no area
        return 0.0


# -- sections -------------------------------------------------------------------------------


@given(convex_bodies(), st.floats(0.0, 1.0), st.integers(1, 40))
def test_sections_are_real_areas(body, fraction, slices):
    v, f, _ = body
    hull = hull_of(v, f)
    s = hs.cut(hull, fraction * hull.extents[2], slices)
    assert np.all(s.area >= 0.0)
    assert np.all(s.penetration >= 0.0) and np.all(s.half_beam >= 0.0)
    assert np.all((s.mass_per_metre >= 0.0) & np.isfinite(s.mass_per_metre))
    assert list(s.station) == list(range(len(s)))  # a convex body: one entry per station
    if len(s):
        assert s.n_stations == slices
        assert s.dx.sum() == pytest.approx(s.wetted_length, rel=1e-12)
    # the areas are those of the body, computed another way
    exact = [exact_section_area(hull.vertices, hull.faces, x) for x in s.x]
    assert s.area == pytest.approx(exact, rel=0.0, abs=eps(hull))


@given(convex_bodies())
def test_midpoint_sum_of_areas_is_the_volume(body):
    v, f, _ = body
    hull = hull_of(v, f)
    n = 256
    s = hs.cut(hull, hull.extents[2], n)  # the whole body under water
    total = float((s.area * s.dx).sum())
    W, H = hull.extents[1], hull.extents[2]
    bound = 2.0 * s.dx[0] * W * H + eps(hull) * hull.extents[0]
    assert abs(total - hull.volume) <= bound
    assert s.wetted_length == pytest.approx(hull.extents[0], rel=1e-9)


@given(convex_bodies(constant_section=True), st.integers(1, 64))
def test_a_body_of_constant_section_integrates_exactly(body, slices):
    v, f, _ = body
    hull = hull_of(v, f)
    s = hs.cut(hull, hull.extents[2], slices)
    total = float((s.area * s.dx).sum())
    assert total == pytest.approx(hull.volume, rel=0.0, abs=eps(hull) * hull.extents[0])


@given(
    convex_bodies(),
    convex_bodies(),
    st.floats(0.01, 1.0),
    st.integers(1, 24),
)
def test_disjoint_bodies_give_an_entry_each_with_its_own_mass(first, second, gap, slices):
    (v1, f1, _), (v2, f2, _) = first, second
    # the second body to port of the first, with a gap; both at the same height
    v2 = v2 + np.array(
        [0.0, v1[:, 1].max() - v2[:, 1].min() + gap, v1[:, 2].min() - v2[:, 2].min()]
    )
    both = hull_of(np.vstack([v1, v2]), np.vstack([f1, f2 + len(v1)]))
    s = hs.cut(both, both.extents[2], slices)
    assert np.all(np.bincount(s.station) <= 2)  # at most one entry per body at a station
    # each station's section is both bodies' sections there
    first = np.flatnonzero(np.r_[True, s.station[1:] != s.station[:-1]])
    x = s.x[first]
    exact = [exact_section_area(v1, f1, xi) + exact_section_area(v2, f2, xi) for xi in x]
    assert s.area[first] == pytest.approx(exact, rel=0.0, abs=eps(both))
    # each body carries its own mass, under water all of it: the entries' masses add up to
    # the pair's within the midpoint bound of each body (times the density)
    mass = float((s.mass_per_metre * s.dx)[s.penetration > 0.0].sum())
    (_, w1, h1), (_, w2, h2) = np.ptp(v1, axis=0), np.ptp(v2, axis=0)
    bound = 2.0 * s.dx[0] * (w1 * h1 + w2 * h2) + eps(both) * both.extents[0]
    assert abs(mass - both.mass) <= DENSITY * bound


# -- forces ---------------------------------------------------------------------------------

STATE = st.tuples(st.floats(0.02, 0.98), st.floats(-10.0, -0.5), st.integers(1, 32))


def force(v, f, fraction, velocity, slices, **kw) -> hs.ForceResult:
    hull = hull_of(v, f, **kw)
    return hs.compute_force(hull, fraction * hull.extents[2], velocity, slices=slices)


@given(convex_bodies(), STATE)
def test_forces_are_finite(body, state):
    v, f, _ = body
    r = force(v, f, *state)
    assert np.isfinite(r.total)
    assert np.all(np.isfinite(r.force))
    assert r.valid.dtype == bool and len(r.loads.reason) == len(r)


def close(a: hs.ForceResult, b: hs.ForceResult, rel: float) -> bool:
    """Totals equal to ``rel`` of the slices' summed magnitude (a total may cancel out)."""
    scale = float(np.abs(a.force).sum()) + 1e-12
    return abs(a.total - b.total) <= rel * scale


@given(convex_bodies(), STATE, st.tuples(*[st.floats(-50.0, 50.0)] * 3))
def test_force_does_not_change_with_translation(body, state, shift):
    v, f, _ = body
    a = force(v, f, *state)
    b = force(v + np.array(shift), f, *state)
    # the cut is made relative to the body's own box: 1e-6 for single precision
    assert close(a, b, 1e-6), (a.total, b.total)


@given(convex_bodies(), STATE)
def test_force_does_not_change_with_a_half_turn_about_the_vertical(body, state):
    v, f, _ = body
    a = force(v, f, *state)
    turned = v * [-1.0, -1.0, 1.0]  # 180 degrees about z: a rotation, faces stay outward
    b = force(turned, f, *state)
    assert close(a, b, 1e-6), (a.total, b.total)
    # the same as keeping the mesh and reversing its forward axis
    c = force(v, f, *state, forward="-x")
    assert close(a, c, 1e-6), (a.total, c.total)


@given(convex_bodies(), STATE, st.integers(1, 3))
def test_a_quarter_turn_with_the_forward_axis_is_the_same_body(body, state, quarters):
    v, f, _ = body
    a = force(v, f, *state)
    turned = Rotation.from_euler("z", 90.0 * quarters, degrees=True).apply(v)
    turned = np.round(turned, 12) + 0.0  # exact quarter turns: cos and sin are 0 or 1
    forward = {1: "+y", 2: "-x", 3: "-y"}[quarters]
    b = force(turned, f, *state, forward=forward)
    assert close(a, b, 1e-6), (a.total, b.total)
