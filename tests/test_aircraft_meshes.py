"""Aircraft meshes as users have them: any scale, open CAD exports, extra parts.

Every mesh here is generated: the generic fuselage of ``hullslice.shapes`` (the reference,
closed), with wings, tail planes, nacelles and stray shells from trimesh's primitives, holes
punched in it, in millimetres or in arbitrary units. Each is either loaded with the option
that fits (``scale``/``length``, ``keep``, ``keep_box``, ``repair="close"``), with a
warning naming what was done, or refused with a message naming that option.
"""

from __future__ import annotations

import json
import sys

import numpy as np
import pytest
import trimesh

import hullslice as hs
from hullslice import shapes
from hullslice.cli import main
from hullslice.orientation import orientation
from hullslice.parts import find_bodies

# a coarse fuselage (9,596 faces): 37.6 m long, 3.95 m wide, 4.14 m high
FUSELAGE = shapes.fuselage(stations=100, points=48)


@pytest.fixture(scope="module")
def fuselage_hull():
    return hs.Hull.from_arrays(*FUSELAGE)


def mesh(v, f) -> trimesh.Trimesh:
    return trimesh.Trimesh(np.asarray(v, float), np.asarray(f), process=False)


def box(extents, centre) -> trimesh.Trimesh:
    b = trimesh.creation.box(extents=extents)
    b.apply_translation(centre)
    return b


def airliner(scale: float = 1.0) -> trimesh.Trimesh:
    """Fuselage, a wing and tail planes through it, two nacelles apart, one stray shell."""
    parts = [
        mesh(*FUSELAGE),
        box((6.0, 34.0, 0.5), (17.0, 0.0, 1.0)),  # wing, through the fuselage
        box((4.0, 12.0, 0.25), (2.5, 0.0, 3.6)),  # tail plane
        box((5.0, 0.3, 6.0), (3.0, 0.0, 6.0)),  # fin
    ]
    for y in (-6.0, 6.0):  # nacelles under the wing, not touching it
        n = trimesh.creation.cylinder(radius=0.9, height=4.0, sections=24)
        n.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, (0, 1, 0)))
        n.apply_translation((16.0, y, -0.4))
        parts.append(n)
    parts.append(trimesh.creation.icosphere(subdivisions=1, radius=0.2).apply_translation(
        (120.0, 0.0, 0.0)))  # fmt: skip
    m = trimesh.util.concatenate(parts)
    m.apply_scale(scale)
    return m


def write(tmp_path, name: str, m: trimesh.Trimesh) -> str:
    path = tmp_path / name
    m.export(path)
    return str(path)


def punch(v, f, holes):
    """Faces of ``f`` without those whose centre is within r of a point (holes), and the
    area taken away."""
    tri = np.asarray(v)[f]
    centre = tri.mean(axis=1)
    keep = np.ones(len(f), dtype=bool)
    for point, radius in holes:
        keep &= np.linalg.norm(centre - np.array(point), axis=1) > radius
    area = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1) / 2
    return f[keep], float(area[~keep].sum())


# holes of several sizes on the fuselage: on the keel, the side, the crown, the tail cone
HOLES = {
    "small": [((20.0, 0.0, 0.0), 0.3), ((2.0, 0.0, 2.5), 0.5)],
    "medium": [((10.0, 1.9, 2.0), 0.8), ((34.0, 0.0, 3.0), 0.8)],
    "large": [((30.0, -1.5, 3.5), 1.5), ((20.0, 0.0, 0.0), 1.0), ((6.0, 1.5, 1.5), 1.2)],
}

# the volume a repaired fuselage keeps, relative to the undamaged one (measured at this
# resolution: 0.002 % for the small holes, 0.003 % for the medium, 0.1 % for the large;
# the fill is a smooth cap, flatter than the curved skin it replaces)
REPAIR_VOLUME_RTOL = 5e-3
# and per size of hole, ten times what was measured or more
HOLE_VOLUME_RTOL = {"small": 2e-4, "medium": 2e-4, "large": REPAIR_VOLUME_RTOL}


# -- scale ----------------------------------------------------------------------------------


def test_scale_multiplies_every_length(tmp_path, fuselage_hull):
    # a model in arbitrary units: 14.7 long for 37.6 m
    k = 37.6 / 14.7
    v, f = FUSELAGE
    path = write(tmp_path, "model.obj", mesh(v / k, f))
    hull = hs.load_hull(path, scale=k)
    # an OBJ holds 8 significant digits
    np.testing.assert_allclose(hull.extents, fuselage_hull.extents, rtol=1e-7)
    assert hull.volume == pytest.approx(fuselage_hull.volume, rel=1e-7)
    assert hull.source["scale"] == pytest.approx(k, rel=1e-15)


def test_length_sets_the_extent_along_forward(tmp_path, fuselage_hull):
    # 14.7 units long along the file's -y axis, z up
    v, f = FUSELAGE
    turned = np.column_stack([v[:, 1], -v[:, 0], v[:, 2]]) * (14.7 / 37.6)
    path = write(tmp_path, "turned.obj", mesh(turned, f))
    hull = hs.load_hull(path, length=37.6, forward="-y", up="+z")
    assert hull.extents[0] == pytest.approx(37.6, rel=1e-12)  # exact, whatever the file
    assert hull.volume == pytest.approx(fuselage_hull.volume, rel=1e-7)
    assert hull.source["scale"] == pytest.approx(37.6 / 14.7, rel=1e-7)


def test_scale_multiplies_the_unit(tmp_path, fuselage_hull):
    # a 1:10 model in millimetres: --units mm --scale 10 is full scale in metres
    v, f = FUSELAGE
    path = write(tmp_path, "model_mm.obj", mesh(v * 100.0, f))
    hull = hs.load_hull(path, units="mm", scale=10.0)
    assert hull.volume == pytest.approx(fuselage_hull.volume, rel=1e-7)
    assert hull.source["scale"] == pytest.approx(0.01, rel=1e-15)


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"scale": 2.0, "length": 37.6}, "both give the mesh's size: give one of them"),
        ({"length": 0.0}, "length 0.0 is not a positive number"),
        ({"length": -3.0}, "length -3.0 is not a positive number"),
        ({"scale": float("nan")}, "scale nan is not a positive number"),
        ({"length": 37.6, "units": "mm"}, "units 'mm' would be ignored"),
    ],
)
def test_conflicting_or_bad_sizes_are_refused(tmp_path, options, message):
    path = write(tmp_path, "f.obj", mesh(*FUSELAGE))
    with pytest.raises(hs.InputError, match=message):
        hs.load_hull(path, **options)


def test_a_mesh_in_mm_read_as_metres_is_named_and_length_fixes_it(tmp_path, fuselage_hull):
    v, f = FUSELAGE
    path = write(tmp_path, "mm.obj", mesh(v * 1000.0, f))
    with pytest.warns(hs.UnitsWarning, match=r"units='mm'"):
        hs.load_hull(path, mass=60000.0)
    by_length = hs.load_hull(path, mass=60000.0, length=37.6)
    by_units = hs.load_hull(path, mass=60000.0, units="mm")
    assert by_length.volume == pytest.approx(fuselage_hull.volume, rel=1e-7)
    assert by_units.volume == pytest.approx(fuselage_hull.volume, rel=1e-7)
    assert by_length.density == pytest.approx(60000.0 / fuselage_hull.volume, rel=1e-7)


# -- parts ----------------------------------------------------------------------------------


def test_bodies_are_numbered_largest_first_with_their_volumes(fuselage_hull):
    m = airliner()
    bodies, numbers = find_bodies(m.vertices, m.faces)
    assert len(bodies) == 7  # fuselage, wing, tail plane, fin, 2 nacelles, stray sphere
    assert [b.number for b in bodies] == list(range(1, 8))
    vols = [b.volume for b in bodies]
    assert vols == sorted(vols, reverse=True)
    assert vols[0] == pytest.approx(fuselage_hull.volume, rel=1e-9)
    assert vols[1] == pytest.approx(6.0 * 34.0 * 0.5, rel=1e-12)  # the wing box
    assert bodies[0].extents == pytest.approx(tuple(fuselage_hull.extents), rel=1e-12)
    assert np.bincount(numbers)[1:].tolist() == [b.faces for b in bodies]


def test_keep_largest_gives_the_fuselage_alone(tmp_path, fuselage_hull):
    path = write(tmp_path, "airliner.obj", airliner(scale=14.7 / 37.6))
    with pytest.warns(hs.MeshRepairWarning, match=r"kept body 1 of 7 .* dropped 2 \(6 x 34 x 0.5"):
        hull = hs.load_hull(path, keep="largest", length=37.6)
    assert hull.volume == pytest.approx(fuselage_hull.volume, rel=1e-7)
    np.testing.assert_allclose(hull.extents, fuselage_hull.extents, rtol=1e-7)
    assert hull.source["kept"] == (1,)
    assert [b["kept"] for b in hull.source["bodies"]] == [True] + [False] * 6


def test_keep_some_bodies_unites_those_that_overlap(tmp_path, fuselage_hull):
    # fuselage and wing overlap: their union is less than the sum
    path = write(tmp_path, "airliner.obj", airliner())
    with pytest.warns(hs.MeshRepairWarning) as record:
        hull = hs.load_hull(path, keep="1,2")
    messages = [str(w.message) for w in record]
    assert any("kept bodies 1, 2 of 7" in m for m in messages)
    assert any("2 shells overlap" in m for m in messages)
    wing = 6.0 * 34.0 * 0.5
    assert fuselage_hull.volume < hull.volume < fuselage_hull.volume + wing
    assert hull.extents[1] == pytest.approx(34.0, rel=1e-12)


def test_keep_a_body_the_mesh_does_not_have_is_refused(tmp_path):
    path = write(tmp_path, "three.obj", trimesh.util.concatenate(
        [box((1, 1, 1), (0, 0, 0)), box((1, 1, 1), (3, 0, 0)), box((1, 1, 1), (6, 0, 0))]
    ))  # fmt: skip
    with pytest.raises(hs.InputError, match=r"keep 7: mesh 'three' has 3 bodies"):
        hs.load_hull(path, keep=7)
    with pytest.raises(hs.InputError, match=r"keep 'wings' is not 'largest' or body numbers"):
        hs.load_hull(path, keep="wings")


def test_keep_box_cuts_the_body_exactly(tmp_path):
    # a wedge prism 1 m long: the box x 0.25 to 0.75 keeps half of it (the section is
    # uniform)
    v, f = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0)
    whole = hs.Hull.from_arrays(v, f)
    x0 = whole.bounds[0][0]
    path = write(tmp_path, "wedge.stl", mesh(v, f))
    with pytest.warns(hs.MeshRepairWarning, match="kept the part inside the box"):
        half = hs.load_hull(path, keep_box=[x0 + 0.25, x0 + 0.75, -1, 1, -1, 1], mass=5.0)
    with pytest.raises(hs.InputError, match="keeps nothing of mesh 'wedge'"):
        hs.load_hull(path, keep_box=[5, 6, -1, 1, -1, 1])
    with pytest.raises(hs.InputError, match="its y range is empty"):
        hs.load_hull(path, keep_box=[0, 1, 1, -1, -1, 1])
    # an STL holds single precision
    assert half.volume == pytest.approx(whole.volume / 2, rel=1e-6)
    assert half.extents[0] == pytest.approx(0.5, rel=1e-6)
    assert half.mass == 5.0  # the mass given is the cut body's


def test_stray_far_shells_are_dropped_by_keep(tmp_path, fuselage_hull):
    v, f = FUSELAGE
    strays = [trimesh.creation.icosphere(subdivisions=0, radius=0.05).apply_translation(
        (200.0 + 10 * i, 50.0, -30.0)) for i in range(5)]  # fmt: skip
    path = write(tmp_path, "strays.obj", trimesh.util.concatenate([mesh(v, f), *strays]))
    # loaded as it is, the body spans 250 m: the bounding box says something is wrong
    plain = hs.load_hull(path)
    assert plain.extents[0] > 200.0
    with pytest.warns(hs.MeshRepairWarning, match=r"kept body 1 of 6 .* and 0 more|dropped"):
        hull = hs.load_hull(path, keep="largest")
    np.testing.assert_allclose(hull.extents, fuselage_hull.extents, rtol=1e-7)


# -- repair ---------------------------------------------------------------------------------


@pytest.mark.parametrize("size", list(HOLES))
def test_repair_close_restores_the_volume(tmp_path, fuselage_hull, size):
    pytest.importorskip("pymeshfix")
    v, f = FUSELAGE
    holed, area = punch(v, f, HOLES[size])
    path = write(tmp_path, "holed.obj", mesh(v, holed))
    with pytest.raises(hs.MeshError, match=r"is open: .* --repair close \(repair='close'\)"):
        hs.load_hull(path)
    n = len(HOLES[size])
    with pytest.warns(hs.MeshRepairWarning, match=rf"repair close: closed {n} holes") as rec:
        hull = hs.load_hull(path, repair="close")
    assert hull.volume == pytest.approx(fuselage_hull.volume, rel=HOLE_VOLUME_RTOL[size])
    # the surface added is the surface taken away, to the fill's curvature
    added = float(str(rec[0].message).split("adding ")[1].split(" m^2")[0])
    assert added == pytest.approx(area, rel=0.05)
    assert "volume undefined before" in str(rec[0].message)


def test_repair_close_of_a_light_aircraft_export(tmp_path, fuselage_hull):
    """A modelling tool's STL: the fuselage in patches whose seams do not share vertices
    (copies differ by rounding), with holes, loose open sheets and triangles (about 100
    shells), and closed wheels."""
    pytest.importorskip("pymeshfix")
    rng = np.random.default_rng(5)
    v, f = FUSELAGE
    holed, _ = punch(v, f, HOLES["medium"])
    # cut the skin into 8 patches along x, each with its own copies of its vertices
    # (rounded differently, as an export that writes each patch on its own)
    x_face = v[holed].mean(axis=1)[:, 0]
    patches = []
    for a, b in zip(np.linspace(-1, 38, 9)[:-1], np.linspace(-1, 38, 9)[1:], strict=True):
        pf = holed[(x_face >= a) & (x_face < b)]
        pv = v * (1.0 + rng.uniform(-2e-7, 2e-7, v.shape))
        patches.append(mesh(pv, pf))
    sheets = []
    for i in range(60):  # loose single triangles and flat quads around the aircraft
        centre = rng.uniform((-5, -15, -3), (45, 15, 8))
        if i % 2:
            sheets.append(mesh(centre + rng.normal(0, 0.1, (3, 3)), [[0, 1, 2]]))
        else:
            q = centre + np.array([[0, 0, 0], [0.3, 0, 0], [0.3, 0.3, 0], [0, 0.3, 0]])
            sheets.append(mesh(q, [[0, 1, 2], [0, 2, 3]]))
    wheels = [trimesh.creation.icosphere(subdivisions=1, radius=0.4).apply_translation(
        (x, y, -1.0)) for x, y in ((12, -2, ), (12, 2), (30, 0))]  # fmt: skip
    m = trimesh.util.concatenate([*patches, *sheets, *wheels])
    path = write(tmp_path, "light.stl", m)
    # as it is: refused, naming the repair
    with pytest.raises(hs.MeshError, match="--repair close"):
        hs.load_hull(path)
    bodies, _ = find_bodies(*hs.mesh.read_mesh(__import__("pathlib").Path(path)))
    assert len(bodies) > 100  # every triangle of an STL is its own until merged
    with pytest.warns(hs.MeshRepairWarning) as record:
        hull = hs.load_hull(path, repair="close", keep="largest")
    messages = " | ".join(str(w.message) for w in record)
    assert "merged" in messages and "differed by rounding" in messages
    assert "dropped 60 of 64 shells that could not be closed" in messages
    assert "kept body 1 of 4" in messages  # the fuselage and 3 wheels
    assert hull.volume == pytest.approx(fuselage_hull.volume, rel=REPAIR_VOLUME_RTOL)
    np.testing.assert_allclose(hull.extents, fuselage_hull.extents, rtol=1e-5)


def test_repair_close_leaves_a_closed_mesh_alone(tmp_path, fuselage_hull):
    path = write(tmp_path, "closed.obj", mesh(*FUSELAGE))
    hull = hs.load_hull(path, repair="close")  # no warning: nothing was repaired
    assert hull.volume == pytest.approx(fuselage_hull.volume, rel=1e-7)
    assert len(hull.faces) == len(fuselage_hull.faces)


def test_repair_close_of_what_is_not_a_body_is_refused(tmp_path):
    pytest.importorskip("pymeshfix")
    sheet = mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2], [0, 2, 3]])
    path = write(tmp_path, "sheet.obj", sheet)
    with pytest.raises(hs.MeshError, match="repair close left nothing that encloses a volume"):
        hs.load_hull(path, repair="close")


def test_repair_close_without_pymeshfix_says_what_to_install(tmp_path, monkeypatch):
    v, f = FUSELAGE
    holed, _ = punch(v, f, HOLES["small"])
    path = write(tmp_path, "holed.obj", mesh(v, holed))
    monkeypatch.setitem(sys.modules, "pymeshfix", None)  # import pymeshfix fails
    with pytest.raises(hs.HullsliceError, match=r"pip install 'hullslice\[repair\]'"):
        hs.load_hull(path, repair="close")


def test_an_unknown_repair_is_refused(tmp_path):
    path = write(tmp_path, "f.obj", mesh(*FUSELAGE))
    with pytest.raises(hs.InputError, match="repair 'fill' is not one of none, close"):
        hs.load_hull(path, repair="fill")


# -- orientation ------------------------------------------------------------------------------


@pytest.mark.parametrize(("forward", "nose"), [("+x", "fore"), ("-x", "aft")])
def test_the_nose_is_found_despite_tail_planes(forward, nose):
    m = airliner()
    _, numbers = find_bodies(m.vertices, m.faces)
    with pytest.warns(hs.MeshRepairWarning, match="4 shells overlap"):
        hull = hs.Hull.from_arrays(m.vertices, m.faces[numbers <= 4], forward=forward)
    o = orientation(hull, forward, "+z")
    assert o.nose == nose
    assert "fuller" in o.reason
    # the fuselage's sections near the nose are ellipses: pi/4 of their rectangle
    assert o.fullness[["aft", "fore"].index(nose)] == pytest.approx(np.pi / 4, rel=0.03)


def test_alike_ends_name_no_nose():
    hull = hs.Hull.from_arrays(*shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0))
    o = orientation(hull)
    assert o.nose is None and o.fullness == pytest.approx((0.5, 0.5), rel=1e-6)


# -- the command line -------------------------------------------------------------------------


def test_info_lists_the_bodies_and_warns_of_the_axis(tmp_path, capsys, fuselage_hull):
    # the airliner in arbitrary units, its length along the file's y
    m = airliner(scale=14.7 / 37.6)
    m.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, (0, 0, 1)))
    path = write(tmp_path, "airliner.obj", m)
    out = tmp_path / "info.json"
    code = main(["info", path, "--scale", str(37.6 / 14.7), "--format", "json",
                 "-o", str(out)])  # fmt: skip
    err = capsys.readouterr().err
    assert code == 0, err
    assert "is longest along its y axis (120" in err and "but --forward is +x (34 m)" in err
    code = main(["info", path, "--keep", "largest", "--scale", str(37.6 / 14.7),
                 "--format", "json", "-o", str(out)])  # fmt: skip
    err = capsys.readouterr().err
    assert code == 0, err
    assert "is longest along its y axis (37.6 m) but --forward is +x (3.95 m)" in err
    assert "kept body 1 of 7" in err
    code = main(["info", path, "--forward", "y", "--keep", "largest", "--length", "37.6",
                 "--format", "json", "-o", str(out)])  # fmt: skip
    err = capsys.readouterr().err
    assert code == 0 and "longest along" not in err, err
    data = json.loads(out.read_text())
    assert data["length"] == pytest.approx(37.6, rel=1e-12)
    assert data["volume"] == pytest.approx(fuselage_hull.volume, rel=1e-7)
    assert [b["number"] for b in data["bodies"]] == list(range(1, 8))
    assert data["kept"] == [1]
    assert data["orientation"]["nose"] == "fore"
    assert data["orientation"]["mesh_extents"]["y"] == pytest.approx(37.6, rel=1e-12)


def test_the_options_round_trip_through_a_case_file(tmp_path, capsys, fuselage_hull):
    pytest.importorskip("pymeshfix")
    v, f = FUSELAGE
    holed, _ = punch(v, f, HOLES["small"])
    m = trimesh.util.concatenate([mesh(v * 1000.0 / 2.0, holed), box((1, 1, 1), (0, 0, 9e4))])
    path = write(tmp_path, "dirty.obj", m)
    argv = ["sections", path, "--draft", "0.5", "--slices", "8", "--units", "mm", "--scale",
            "2", "--repair", "close", "--keep", "largest", "--keep-box=-1,30,-3,3,-1,5",
            "--format", "json"]  # fmt: skip
    code = main([*argv, "-o", str(tmp_path / "a.json"), "--save-case", str(tmp_path / "c.toml")])
    err = capsys.readouterr().err
    assert code == 0, err
    case = (tmp_path / "c.toml").read_text()
    for line in ("scale = 2.0", 'repair = "close"', 'keep = "largest"',
                 "keep_box = [-1.0, 30.0, -3.0, 3.0, -1.0, 5.0]"):  # fmt: skip
        assert line in case
    code = main(["run", str(tmp_path / "c.toml"), "-o", str(tmp_path / "b.json")])
    err2 = capsys.readouterr().err
    assert code == 0, err2
    a = json.loads((tmp_path / "a.json").read_text())
    b = json.loads((tmp_path / "b.json").read_text())
    assert a["sections"] == b["sections"]
    assert a["wetted_length"] == pytest.approx(b["wetted_length"], rel=1e-12)
    # the kept part is the fuselage up to x = 30 m (the box), full scale in metres: at a
    # draft of 0.5 m its flat-bottomed middle is wetted from where the tail cone's keel
    # comes down to 0.5 m up to the cut
    assert max(r["x"] for r in a["sections"]) < 30.0
    assert 17.0 < a["wetted_length"] < 30.0


def test_the_readme_example_on_the_dirty_sample(fuselage_hull):
    """meshes/dirty/dirty_aircraft.stl as the README loads it: the fuselage, 37.6 m long,
    its volume that of the undamaged coarse fuselage it was made from, within the repair's
    tolerance."""
    pytest.importorskip("pymeshfix")
    from .conftest import MESHES

    path = MESHES / "dirty" / "dirty_aircraft.stl"
    with pytest.raises(hs.MeshError, match="--repair close"):
        hs.load_hull(path)
    with pytest.warns(hs.MeshRepairWarning) as record:
        hull = hs.load_hull(
            path, forward="-x", repair="close", keep="largest", length=37.6, mass=60000.0
        )
    messages = " | ".join(str(w.message) for w in record)
    assert "closed 3 holes" in messages and "dropped 20 of 26 shells" in messages
    assert "kept body 1 of 6" in messages
    undamaged = hs.Hull.from_arrays(*shapes.fuselage(stations=80, points=40))
    assert hull.extents[0] == pytest.approx(37.6, rel=1e-12)
    assert hull.volume == pytest.approx(undamaged.volume, rel=REPAIR_VOLUME_RTOL)
    assert orientation(hull, "-x", "+z").nose == "fore"


def test_the_views_are_the_body_outlines(fuselage_hull):
    pytest.importorskip("matplotlib")
    from hullslice import plots

    fig = plots.plot_views(fuselage_hull, "+x", "+z", nose="fore")
    lo, hi = fuselage_hull.bounds
    # side (x, z), front (y, z) and top (x, y), in the figure's order: each outline spans
    # the body's box
    for ax, (i, j) in zip(fig.axes[:3], [(0, 2), (1, 2), (0, 1)], strict=True):
        (patch,) = ax.patches
        pts = patch.get_path().vertices
        np.testing.assert_allclose(pts.min(axis=0), [lo[i], lo[j]], atol=1e-6 * 37.6)
        np.testing.assert_allclose(pts.max(axis=0), [hi[i], hi[j]], atol=1e-6 * 37.6)
    texts = [t.get_text() for ax in fig.axes for t in ax.texts]
    assert any("forward (+x, the file's +x)" in t for t in texts) and "nose?" in texts
    plots._pyplot().close(fig)
