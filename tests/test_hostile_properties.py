"""Property-based tests on hostile bodies (Hypothesis): none passes silently, none costs
memory out of proportion to its file.

- **Self-intersecting bodies**: a box with a corner pushed through the opposite face, a
  wedge prism with the keel of some stations pushed up through its deck; any size, any
  rotation, anywhere within a thousand sizes of the origin. Each is closed, manifold and
  consistently oriented, and each passes through itself: loading it must raise a
  ``MeshError`` that says so.
- **Bodies far from the origin**: spheres of 2,562 vertices, open (faces removed) or closed,
  moved 1e3 to 1e7 of their sizes away, written as OBJ (double precision) or binary STL
  (single). An open one must be refused (open, or too far out to be resolved), a closed
  one loaded with its volume or refused as too far out; and the allocations of the load
  (``tracemalloc``, which sees numpy's arrays) must stay under the bound the README states
  for a file: ``TRACED_BASE + TRACED_PER_BYTE`` times its size. A vertex merge whose
  distance grew with the coordinates listed every pair of the 2,562 vertices: 53 MB.
"""

from __future__ import annotations

import tracemalloc
import warnings
from pathlib import Path

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

import hullslice as hs
from hullslice import shapes

SIZE = st.floats(0.05, 5.0)

#: The bound on a load's traced allocations: this many bytes, plus this many per byte of
#: the file (the README's "Bad input": peak memory within 25 times the file's size).
TRACED_BASE = 16 * 1024**2
TRACED_PER_BYTE = 25


def rotated(draw, v: np.ndarray) -> np.ndarray:
    rot = Rotation.from_rotvec(draw(st.tuples(*[st.floats(-np.pi, np.pi)] * 3))).as_matrix()
    size = float(np.linalg.norm(np.ptp(v, axis=0)))
    shift = np.array(draw(st.tuples(*[st.floats(-1e3, 1e3)] * 3))) * size
    return v @ rot.T + shift


@st.composite
def self_intersecting(draw):
    """A closed, manifold body passing through itself, as (vertices, faces, what)."""
    if draw(st.booleans()):
        ext = np.array([draw(SIZE), draw(SIZE), draw(SIZE)])
        b = trimesh.creation.box(extents=ext)
        v, f = np.array(b.vertices), np.asarray(b.faces)
        corner = draw(st.sampled_from(np.flatnonzero(v[:, 2] > 0).tolist()))
        # the top corner pushed down through the bottom face, by 5 % to 100 % of the height
        v[corner, 2] = -ext[2] / 2 - draw(st.floats(0.05, 1.0)) * ext[2]
        what = "box"
    else:
        length, beam = draw(SIZE), draw(SIZE)
        v, f = shapes.wedge_prism(
            length=length,
            beam=beam,
            deadrise_deg=draw(st.floats(10.0, 60.0)),
            stations=draw(st.integers(4, 8)),
        )
        v = v.copy()
        keel = np.flatnonzero(v[:, 2] < -1e-9 * length)
        stations = np.unique(v[keel, 0])
        lo = draw(st.integers(1, len(stations) - 2))
        hi = draw(st.integers(lo, len(stations) - 2))
        pushed = keel[(v[keel, 0] >= stations[lo]) & (v[keel, 0] <= stations[hi])]
        # the keel of stations lo..hi pushed up through the deck (z = 0)
        v[pushed, 2] = draw(st.floats(0.05, 1.0)) * beam
        what = "wedge"
    return rotated(draw, v), f, what


@settings(max_examples=40)
@given(body=self_intersecting())
def test_no_self_intersecting_body_passes(body):
    v, f, _ = body
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an inside-out repair may come first
        with pytest.raises(hs.MeshError, match="intersects itself"):
            hs.Hull.from_arrays(v, f, mass=1.0)


SPHERE = trimesh.creation.icosphere(subdivisions=4)


def write(path: Path, v: np.ndarray, f: np.ndarray) -> Path:
    if path.suffix == ".obj":
        rows = [f"v {x!r} {y!r} {z!r}" for x, y, z in v.tolist()]
        rows += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in f.tolist()]
        path.write_text("\n".join(rows) + "\n")
    else:
        trimesh.Trimesh(v, f, process=False).export(path)
    return path


def traced_load(path: Path):
    """Load ``path``; the hull or the MeshError, and the peak of the allocations (bytes)."""
    tracemalloc.start()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                result = hs.load_hull(path)
            except hs.MeshError as exc:
                result = exc
        return result, tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


@settings(max_examples=15)
@given(
    radius=SIZE,
    far=st.floats(3.0, 7.0),
    direction=st.sampled_from([(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1)]),
    missing=st.integers(0, 3),
    suffix=st.sampled_from([".obj", ".stl"]),
)
def test_far_bodies_are_loaded_or_refused_in_bounded_memory(
    tmp_path_factory, radius, far, direction, missing, suffix
):
    v = np.asarray(SPHERE.vertices) * radius
    f = np.asarray(SPHERE.faces)
    offset = 10.0**far * 2 * radius * np.asarray(direction) / np.linalg.norm(direction)
    # a removed face whose corners coincide at the file's precision (an STL holds single
    # precision) is no hole: the surface the file describes is closed without it
    stored = (v + offset).astype(np.float32 if suffix == ".stl" else np.float64)
    corners = stored[f[:missing]]
    holes = sum(
        not (np.array_equal(a, b) or np.array_equal(b, c) or np.array_equal(a, c))
        for a, b, c in corners
    )
    f = f[missing:]  # the first faces removed: a hole, or none
    path = write(tmp_path_factory.mktemp("far") / f"sphere{suffix}", v + offset, f)
    result, peak = traced_load(path)
    assert peak <= TRACED_BASE + TRACED_PER_BYTE * path.stat().st_size, peak
    if isinstance(result, hs.MeshError):
        # never a wrong reason: a hole, coordinates too far out to resolve the sphere, or
        # (single precision) vertices that coincide or faces that collapse there
        reasons = ("is open", "from the origin", "not manifold", "encloses no volume")
        assert any(r in str(result) for r in reasons), result
        assert missing or suffix == ".stl" or "from the origin" in str(result), result
    else:
        # loaded: closed, and the sphere's volume (to its coordinates' precision)
        assert holes == 0
        eps = (1e-15 if suffix == ".obj" else 6e-8) * 10.0**far * 2
        assert result.volume == pytest.approx(trimesh.Trimesh(v, f).volume, rel=max(1e-9, 30 * eps))
