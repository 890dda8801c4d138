"""Loading meshes: units, axes, checks and the repairs that are safe."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

import hullslice as hs
from hullslice import shapes

from .conftest import MESHES


def box(extents=(2.0, 1.0, 0.5), center=(0.0, 0.0, 0.0)):
    b = trimesh.creation.box(extents=extents)
    b.apply_translation(center)
    return np.asarray(b.vertices), np.asarray(b.faces)


def write(tmp_path, name, vertices, faces):
    path = tmp_path / name
    trimesh.Trimesh(vertices, faces, process=False).export(path)
    return path


# -- reading ---------------------------------------------------------------------------------


def test_bundled_prism_is_the_papers_body(paper_hull, paper):
    assert paper_hull.volume == pytest.approx(0.0020586, rel=1e-4)  # METHOD section 4
    # STL stores single precision: 6e-8 relative
    assert paper_hull.extents == pytest.approx([0.35, 0.2, 0.1], rel=1e-7)
    assert paper_hull.density == pytest.approx(paper["prism"]["density_kg_m3"], rel=1e-3)
    assert paper_hull.source["repairs"] == ()


def test_obj_and_stl_give_the_same_hull(tmp_path, paper_hull):
    v, f = shapes.paper_prism()
    obj = hs.load_hull(write(tmp_path, "prism.obj", v, f), mass=1.0)
    assert obj.volume == pytest.approx(paper_hull.volume, rel=1e-6)
    r1 = hs.compute_force(obj, 0.0383, -3.4943, slices=16).total
    r2 = hs.compute_force(paper_hull, 0.0383, -3.4943, slices=16).total
    assert r1 == pytest.approx(r2, rel=1e-6)


def test_hull_is_immutable(paper_hull):
    with pytest.raises(ValueError, match="read-only"):
        paper_hull.vertices[0, 0] = 1.0
    with pytest.raises(ValueError, match="read-only"):
        paper_hull.faces[0, 0] = 1
    heavier = paper_hull.with_mass(2.0)
    assert heavier.mass == 2.0 and paper_hull.mass == 1.0
    assert heavier.volume == paper_hull.volume


def test_centroid_of_a_box():
    v, f = box(center=(1.0, -2.0, 3.0))
    hull = hs.Hull.from_arrays(v, f)
    assert hull.centroid == pytest.approx([1.0, -2.0, 3.0], abs=1e-12)
    assert hull.volume == pytest.approx(1.0, rel=1e-12)


@pytest.mark.parametrize(
    ("content", "name", "message"),
    [
        (None, "missing.stl", "does not exist"),
        (b"", "empty.stl", "is empty"),
        (b"solid x\nendsolid x\n", "hull.step", "hullslice reads stl, obj"),
        (b"this is not a mesh\n", "text.obj", "holds no triangles"),
        (b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "badindex.obj", "could not be read"),
    ],
)
def test_unreadable_files(tmp_path, content, name, message):
    path = tmp_path / name
    if content is not None:
        path.write_bytes(content)
    with pytest.raises(hs.MeshError, match=message):
        hs.load_hull(path)


# -- options ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("kw", "message"),
    [
        ({"units": "furlong"}, "length unit 'furlong' is not one of m, cm, mm, in, ft"),
        ({"forward": "+x", "up": "-x"}, "not perpendicular"),
        ({"forward": "w"}, "forward axis 'w' is not one of"),
        ({"mass": 0.0}, "not positive"),
        ({"mass": -1.0}, "not positive"),
        ({"mass": float("nan")}, "not positive"),
    ],
)
def test_bad_options(kw, message):
    v, f = box()
    with pytest.raises(hs.InputError, match=message):
        hs.Hull.from_arrays(v, f, **kw)


def test_mesh_in_mm_read_as_metres_warns():
    v, f = box(extents=(350.0, 200.0, 100.0))  # a 0.35 m body exported in mm
    with pytest.warns(hs.UnitsWarning, match="units='mm'"):
        hs.Hull.from_arrays(v, f, mass=1.0)
    hull = hs.Hull.from_arrays(v, f, mass=1.0, units="mm")  # no warning
    assert hull.volume == pytest.approx(0.35 * 0.2 * 0.1)


# -- what manifold3d refuses -------------------------------------------------------------------


def test_open_mesh():
    v, f = box()
    with pytest.raises(hs.MeshError, match="is open: 3 edges"):
        hs.Hull.from_arrays(v, f[1:])


def test_non_manifold_edge():
    v1, f1 = box(extents=(1, 1, 1), center=(0, 0, 0))
    v2, f2 = box(extents=(1, 1, 1), center=(1, 1, 0))  # touches the first along an edge
    v = np.vstack([v1, v2])
    f = np.vstack([f1, f2 + len(v1)])
    with pytest.raises(hs.MeshError, match="not manifold"):
        hs.Hull.from_arrays(v, f)


def test_nan_coordinates():
    v, f = box()
    v = v.copy()
    v[3, 1] = np.nan
    with pytest.raises(hs.MeshError, match="NaN or infinite"):
        hs.Hull.from_arrays(v, f)


def test_face_index_out_of_range():
    v, f = box()
    f = f.copy()
    f[5, 2] = 99
    with pytest.raises(hs.MeshError, match=r"refers to vertex .* only 8 vertices"):
        hs.Hull.from_arrays(v, f)


# -- what manifold3d accepts silently but wrongly, repaired with a warning --------------------


def test_inside_out_mesh_is_flipped():
    v, f = box()
    with pytest.warns(hs.MeshRepairWarning, match="inside out"):
        hull = hs.Hull.from_arrays(v, f[:, ::-1])
    assert hull.volume == pytest.approx(1.0)
    assert len(hs.cut(hull, 0.1, 4)) == 4


def test_one_flipped_face_is_reoriented():
    v, f = box()
    f = f.copy()
    f[4] = f[4, ::-1]
    with pytest.warns(hs.MeshRepairWarning, match="re-oriented 1 faces"):
        hull = hs.Hull.from_arrays(v, f)
    assert hull.volume == pytest.approx(1.0)


def test_many_flipped_faces_are_reoriented():
    sphere = trimesh.creation.icosphere(subdivisions=4)
    f = np.asarray(sphere.faces).copy()
    rng = np.random.default_rng(3)
    bad = rng.random(len(f)) < 0.3
    f[bad] = f[bad][:, ::-1]
    with pytest.warns(hs.MeshRepairWarning, match=f"re-oriented {bad.sum()} faces"):
        hull = hs.Hull.from_arrays(sphere.vertices, f)
    assert hull.volume == pytest.approx(sphere.volume, rel=1e-12)

    # the same triangles, each facing outward as in the sphere: compare centroids and normals
    def oriented(v, f):
        tri = np.asarray(v)[np.asarray(f)]
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        rows = np.hstack([tri.mean(axis=1), n]).round(9)
        return rows[np.lexsort(rows.T[::-1])]

    np.testing.assert_allclose(
        oriented(hull.vertices, hull.faces), oriented(sphere.vertices, sphere.faces), atol=1e-9
    )


def test_overlapping_shells_become_their_union():
    v1, f1 = box(extents=(2, 1, 1), center=(0, 0, 0))
    v2, f2 = box(extents=(2, 1, 1), center=(1, 0, 0))  # overlaps the first by half
    v = np.vstack([v1, v2])
    f = np.vstack([f1, f2 + len(v1)])
    with pytest.warns(hs.MeshRepairWarning, match="2 shells overlap"):
        hull = hs.Hull.from_arrays(v, f)
    assert hull.volume == pytest.approx(3.0, rel=1e-9)


def test_disjoint_bodies_are_kept():
    v1, f1 = box(extents=(1, 1, 1), center=(0, -2, 0))
    v2, f2 = box(extents=(1, 1, 1), center=(0, 2, 0))
    hull = hs.Hull.from_arrays(np.vstack([v1, v2]), np.vstack([f1, f2 + len(v1)]))
    assert hull.volume == pytest.approx(2.0)


def test_a_cavity_is_kept():
    outer = trimesh.creation.icosphere(subdivisions=3, radius=1.0)
    inner = trimesh.creation.icosphere(subdivisions=3, radius=0.5)
    v = np.vstack([outer.vertices, inner.vertices])
    f = np.vstack([outer.faces, inner.faces[:, ::-1] + len(outer.vertices)])
    hull = hs.Hull.from_arrays(v, f)
    assert hull.volume == pytest.approx(outer.volume - inner.volume, rel=1e-9)


def test_stl_triangle_soup_is_merged_silently(tmp_path):
    # every STL stores three corners per triangle; exact duplicates merge without comment
    v, f = shapes.wedge_prism()
    hull = hs.load_hull(write(tmp_path, "wedge.stl", v, f))
    assert hull.source["repairs"] == ()
    assert len(hull.vertices) == len(v)


def test_nearly_coincident_vertices_are_merged_with_a_warning():
    v, f = box()
    soup = v[f].reshape(-1, 3)
    rng = np.random.default_rng(1)
    soup = soup + rng.uniform(-1e-12, 1e-12, soup.shape)  # rounding noise of an export
    with pytest.warns(hs.MeshRepairWarning, match="merged 28 vertices"):
        hull = hs.Hull.from_arrays(soup, np.arange(len(soup)).reshape(-1, 3))
    assert hull.volume == pytest.approx(1.0, rel=1e-9)


def test_degenerate_faces_are_removed():
    v, f = box()
    f = np.vstack([f, [[0, 0, 1]]])
    with pytest.warns(hs.MeshRepairWarning, match="removed 1 degenerate"):
        hull = hs.Hull.from_arrays(v, f)
    assert hull.volume == pytest.approx(1.0)


def test_bundled_meshes_load_without_repairs():
    for path in MESHES.glob("*.stl"):
        hull = hs.load_hull(path)
        assert hull.source["repairs"] == ()
        assert hull.volume > 0
