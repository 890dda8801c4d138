"""Loading meshes: units, axes, checks and the repairs that are safe."""

from __future__ import annotations

import math

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
        (b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "badindex.obj", "vertex that does not exist"),
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


def test_repeated_faces_are_removed():
    v, f = box()
    f = np.vstack([f, f[[2, 7]]])  # two triangles written twice, same winding
    with pytest.warns(hs.MeshRepairWarning, match="removed 2 repeated faces"):
        hull = hs.Hull.from_arrays(v, f)
    assert hull.volume == pytest.approx(1.0, rel=1e-12)
    assert len(hull.faces) == 12


def test_a_flat_surface_is_not_a_body():
    v = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    with pytest.raises(hs.MeshError, match=r"encloses no volume .* flat or zero-thickness"):
        hs.Hull.from_arrays(v, [[0, 1, 2], [0, 2, 1]])


def test_a_single_tetrahedron_is_a_body():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    hull = hs.Hull.from_arrays(v, [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    assert hull.volume == pytest.approx(1 / 6, rel=1e-12)
    # its section at x is the triangle y, z >= 0, y + z <= 1 - x: area (1 - x)^2 / 2
    s = hs.cut(hull, 1.0, 8)
    assert s.area == pytest.approx(0.5 * (1 - s.x) ** 2, rel=1e-6)


@pytest.mark.parametrize("scale", [1e-9, 1e-3, 1e9])
def test_tiny_and_huge_bodies_are_cut_as_accurately_as_a_metre_sized_one(scale):
    # manifold3d rounds cross sections to a fixed grid: the hull is scaled to unit size first
    v, f = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0)
    hull = hs.Hull.from_arrays(v * scale, f)
    draft = 0.05 * scale
    s = hs.cut(hull, draft, 4)
    h = 0.1 * np.tan(np.radians(30.0))  # keel depth of the unit body
    assert s.area == pytest.approx(0.1 * h * scale**2, rel=1e-6)
    assert s.penetration == pytest.approx(draft, rel=1e-6)
    assert s.half_beam == pytest.approx(draft / np.tan(np.radians(30.0)), rel=1e-6)
    assert s.deadrise_deg == pytest.approx(30.0, abs=1e-4)


def test_near_duplicate_vertices_of_a_6_digit_ascii_stl_are_merged(tmp_path):
    # a CAD export: each triangle's corners computed apart (float32 noise, 3e-7), then
    # written with 6 significant digits, so copies of a vertex may round 1e-6 apart
    from .test_mesh_files import ascii_stl

    v, f = shapes.paper_prism()
    rng = np.random.default_rng(7)
    tri = v[f] * (1.0 + rng.uniform(-3e-7, 3e-7, (len(f), 3, 3)))
    soup = tri.reshape(-1, 3)
    path = tmp_path / "prism6.stl"
    path.write_text(ascii_stl({"hull": (soup, np.arange(len(soup)).reshape(-1, 3))}, ".6g"))
    with pytest.warns(hs.MeshRepairWarning, match=r"merged \d+ vertices closer than"):
        hull = hs.load_hull(path, mass=1.0)
    assert hull.volume == pytest.approx(0.0020586, rel=5e-5)  # METHOD section 4
    ref = hs.load_hull(MESHES / "paper_prism.stl", mass=1.0)
    r6 = hs.compute_force(hull, 0.0383, -3.4943, slices=32).total
    assert r6 == pytest.approx(hs.compute_force(ref, 0.0383, -3.4943, slices=32).total, rel=1e-4)


@pytest.mark.parametrize(
    ("scale", "units", "hint"),
    [
        (1000.0, "m", "if the mesh is in millimetres, give its units (units='mm', --units mm): "
         "the density is then 142.9 kg/m^3"),
        (1.0, "mm", "if the mesh is in metres, give its units (units='m', --units m): the "
         "density is then 142.9 kg/m^3"),
        (100.0, "m", "if the mesh is in centimetres, give its units (units='cm', --units cm)"),
    ],
)  # fmt: skip
def test_the_units_warning_names_the_unit_that_fits(scale, units, hint):
    # a 0.35 x 0.2 x 0.1 m box of 1 kg (142.9 kg/m^3) in a file of another unit
    v, f = box(extents=(0.35 * scale, 0.2 * scale, 0.1 * scale))
    with pytest.warns(hs.UnitsWarning) as record:
        hs.Hull.from_arrays(v, f, mass=1.0, units=units)
    assert hint in str(record[0].message)


def test_the_units_warning_without_a_fitting_unit_asks_to_check():
    v, f = box(extents=(0.35, 0.2, 0.1))
    with pytest.warns(hs.UnitsWarning, match="check the mass and the mesh's units"):
        hs.Hull.from_arrays(v, f, mass=1e-30)


def test_read_only_arrays_are_handed_to_manifold3d_as_writeable_copies():
    # manifold3d refuses a read-only array; a repair pass or a cache hands back read-only
    # views, which np.ascontiguousarray does not copy
    import numpy as np

    from hullslice import shapes
    from hullslice.topology import to_manifold

    v, f = shapes.wedge_prism()
    v = np.asarray(v, dtype=np.float64)
    f = np.asarray(f, dtype=np.uint64)
    v.flags.writeable = False
    f.flags.writeable = False
    man = to_manifold(v, f, "read-only")
    # a 1 m prism of a 30-degree wedge 0.2 m wide: half the beam times its height
    assert man.volume() == pytest.approx(0.1 * 0.1 * np.tan(np.radians(30.0)), rel=1e-12)


def test_every_array_for_manifold3d_is_an_owned_writeable_copy_of_its_dtype():
    # a read-only, strided, float32 / int32 pair: what a reader or a cache may hand on
    import numpy as np

    from hullslice import shapes
    from hullslice.topology import manifold_arrays, mesh_arrays, to_manifold

    v, f = shapes.wedge_prism()
    wide = np.zeros((len(v), 6), dtype=np.float32)
    wide[:, ::2] = v
    vs, fs = wide[:, ::2], np.asarray(f, dtype=np.int32)[:, [0, 1, 2]]
    vs.flags.writeable = False
    fs.flags.writeable = False
    for a, dtype in zip(manifold_arrays(vs, fs), (np.float64, np.uint64), strict=True):
        assert a.dtype == dtype and a.flags.owndata and a.flags.writeable
        assert a.flags.c_contiguous
    man = to_manifold(vs, fs, "strided")
    back_v, back_f = mesh_arrays(man)
    assert back_v.flags.owndata and back_v.flags.writeable and back_f.dtype == np.int64
    # the float32 wedge: half the 0.2 m beam times the keel depth, to float32 rounding
    assert man.volume() == pytest.approx(0.1 * 0.1 * np.tan(np.radians(30.0)), rel=1e-6)


@pytest.mark.parametrize("reverse_both", [False, True])
def test_overlapping_shells_one_inside_out_are_taken_as_their_union(reverse_both):
    # two 1 m wedge prisms overlapping by 0.45 m, the second wound inside out (or both):
    # the body is one 1.55 m prism, not the first with the second's volume taken away
    import numpy as np

    from hullslice import shapes

    v, f = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0)
    second = f[:, ::-1] + len(v)
    faces = np.vstack([f[:, ::-1] if reverse_both else f, second])
    with pytest.warns(hs.MeshRepairWarning) as record:
        hull = hs.Hull.from_arrays(np.vstack([v, v + np.array([0.55, 0.0, 0.0])]), faces)
    assert "inside out" in str(record[0].message) or "inside-out" in str(record[0].message)
    assert "2 shells overlap" in str(record[-1].message)
    h30 = 0.1 * np.tan(np.radians(30.0))
    assert hull.volume == pytest.approx(1.55 * 0.1 * h30, rel=1e-9)
    np.testing.assert_allclose(hull.extents, (1.55, 0.2, h30), rtol=1e-9)


def test_a_nearly_flat_wedge_prism_is_not_taken_for_a_self_intersection():
    # a convex prism of 0.01 deg deadrise: its sections are so thin (26 um) that
    # manifold3d's rounding of their points (about 1e-9 of the body's size) is more than
    # 1e-4 of their area; the integrity check's floor of 1e-8 of the size squared lets it
    # through, with its exact volume
    for deadrise in (0.01, 0.0001):
        v, f = shapes.wedge_prism(length=1.0, beam=0.3, deadrise_deg=deadrise)
        hull = hs.Hull.from_arrays(v, f)
        depth = 0.15 * math.tan(math.radians(deadrise))
        assert hull.volume == pytest.approx(1.0 * 0.15 * depth, rel=1e-9)
