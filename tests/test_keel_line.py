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
    from hullslice.kernel.keel import lower_envelope

    e = np.array(ends, dtype=np.float64)
    a, b = e[:, :2], e[:, 2:]
    line = lower_envelope(a, b)
    assert np.all(np.diff(line.x) >= 0)
    want = np.array([lowest_brute_force(a, b, x) for x in line.x])
    np.testing.assert_allclose(line.z, want, rtol=0.0, atol=1e-12)
    ends_x = np.unique(np.concatenate([a[:, 0], b[:, 0]]))
    assert set(ends_x.tolist()) <= set(line.x.tolist())


def outline_edges_brute_force(hull) -> set:
    """Every edge whose two faces do not both face port or both starboard (a normal's y
    component of one sign, or zero), as a set of sorted vertex pairs."""
    v, f = hull.vertices, hull.faces
    ny = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])[:, 1]
    faces_of: dict[tuple[int, int], list[int]] = {}
    for i, tri in enumerate(f.tolist()):
        for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            faces_of.setdefault((min(a, b), max(a, b)), []).append(i)
    out = set()
    for (a, b), (f1, f2) in faces_of.items():
        if np.sign(ny[f1]) * np.sign(ny[f2]) <= 0:
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
