"""Loads for the structure: the sections' pressures on the mesh's faces, frame loads, files.

References:

- conservation: the faces' loads add up to the slices' forces (the mapping integrates the
  sections' pressure exactly over each face's footprint, linear between stations);
- Korobkin (2004), Eur. J. Appl. Math. 15, 821-838: the MLM pressure on a wedge at
  constant speed, ``p = rho V^2 (c'/cos t - 1/2 - tan^2 t / (2 (1 + tan^2 beta)))`` at
  ``y = c sin t``, ``c = c' h``, ``c' = pi / (2 tan beta)``, its positive part;
- the frame bays hold the whole body, so their loads add up to the body's force.
"""

from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import hullslice as hs
from hullslice import shapes
from hullslice.cli import main
from hullslice.loads import face_geometry, face_pressures

from .conftest import MESHES

pytest.importorskip("hullslice_mlm")

RHO, V = 1000.0, 5.0
GAUSS = np.polynomial.legendre.leggauss(200)


def fine_wedge(deadrise_deg: float = 20.0, points: int = 81) -> hs.Hull:
    """A wedge prism with ``points`` corners across its bottom (faces 5 mm wide)."""
    beta = math.radians(deadrise_deg)
    half = 0.2
    y = np.linspace(-half, half, points)
    sec = np.c_[y, np.abs(y) * math.tan(beta) - half * math.tan(beta)]
    x = np.linspace(0.0, 1.0, 11)
    v, f = shapes.prism_from_sections(x, np.broadcast_to(sec, (len(x), len(sec), 2)))
    return hs.Hull.from_arrays(v, f, mass=50.0)


def korobkin(y: np.ndarray, deadrise_deg: float, penetration: float) -> np.ndarray:
    """The MLM pressure on a wedge at constant speed (Korobkin 2004), Pa."""
    tb = math.tan(math.radians(deadrise_deg))
    cp = math.pi / (2 * tb)
    c = cp * penetration
    st = np.clip(np.abs(y) / c, 0.0, 1.0 - 1e-15)
    cos = np.sqrt(1 - st**2)
    bracket = cp / cos - 0.5 - st**2 / cos**2 / (2 * (1 + tb**2))
    return np.where(np.abs(y) < c, np.maximum(bracket, 0.0), 0.0) * RHO * V * V


def footprint_mean(corners: np.ndarray, p) -> float:
    """The mean of ``p(y)`` over a triangle's projection on the water plane."""
    x, y = corners[:, 0], corners[:, 1]
    o = np.argsort(y)
    x, y = x[o], y[o]
    long = x[0] + (x[2] - x[0]) * (y[1] - y[0]) / (y[2] - y[0])
    mid = abs(long - x[1])
    g, w = GAUSS
    num = den = 0.0
    for a, b, wa, wb in ((y[0], y[1], 0.0, mid), (y[1], y[2], mid, 0.0)):
        if b - a < 1e-14:
            continue
        yq, wq = 0.5 * (b - a) * g + 0.5 * (a + b), 0.5 * (b - a) * w
        width = wa + (wb - wa) * (yq - a) / (b - a)
        num += float((p(yq) * width * wq).sum())
        den += float((width * wq).sum())
    return num / den


def test_a_wedge_at_constant_speed_has_the_closed_form_pressure_on_its_faces():
    hull = fine_wedge(20.0)
    h = 0.04
    r = hs.compute_force(
        hull, hs.Pose(h), hs.Motion(-V), solver="mlm", slices=8, acceleration=hs.Acceleration(0.0)
    )
    fp = face_pressures(hull, r)
    # conservation on a prism: to rounding
    assert fp.total == pytest.approx(r.total, rel=1e-12)
    corners = face_geometry(hull).corners
    wet = np.nonzero(fp.pressure > 0)[0]
    assert len(wet) > 1000
    want = np.array([footprint_mean(corners[k], lambda y: korobkin(y, 20.0, h)) for k in wet])
    err = np.abs(fp.pressure[wet] - want) / want
    # the solver's 32 points a side stand for its pressure: 1.7 % at worst near the edge
    assert np.median(err) < 0.005
    assert err.max() < 0.02


def test_dry_faces_have_no_pressure():
    hull = fine_wedge(20.0)
    r = hs.compute_force(hull, hs.Pose(0.04), hs.Motion(-V), solver="mlm", slices=8)
    fp = face_pressures(hull, r)
    geom = face_geometry(hull)
    c = r.loads.diagnostics["wetted_half_width"][0]
    outside = np.abs(geom.centroid[:, 1]) > c + 0.005  # beyond the contact, plus a face
    up = geom.normal[:, 2] >= 0.0  # the deck and the ends
    assert np.all(fp.pressure[outside | up] == 0.0)
    assert np.all(fp.pressure >= 0.0)  # the MLM's load is its pressure's positive part


@pytest.fixture(scope="module")
def ditching():
    """The bundled fuselage (model scale) ditching at 8 deg, free in pitch, with gravity."""
    hull = hs.load_hull(MESHES / "fuselage_model.obj", mass=40.0)
    solver = hs.get_solver("mlm", gravity=True)
    history = hs.simulate(
        hull, -1.0, 0.12, dt=0.002, pitch_rad=math.radians(8.0), forward_speed=15.0,
        free_pitch=True, slices=32, solver=solver, fluid=hs.Fluid.sea(), sections_every=10,
    )  # fmt: skip
    return hull, history


def test_a_fuselage_s_face_loads_add_up_to_the_slices_forces(ditching):
    hull, history = ditching
    assert len(history.sections) == 7  # every 10th of 61 instants, with the last
    checked = 0
    for fp, rec in zip(history.face_pressures(hull), history.sections, strict=True):
        if rec.total == 0.0:
            assert not fp.wetted.any()
            continue
        checked += 1
        assert fp.total == pytest.approx(rec.total, rel=1e-5)
        # the moment of the vertical loads about the cg (the faces' horizontal loads act
        # on the skin, the slices' at their keel: their lever arms differ by design)
        mz = float(((fp.centroid[:, 0] - fp.x_cg) * fp.force[:, 2]).sum())
        mz_slices = float(((rec.x - rec.x_cg) * rec.force).sum())
        assert mz == pytest.approx(mz_slices, rel=1e-3)
        assert fp.total_x == pytest.approx(rec.total_x, rel=0.02)
    assert checked >= 5


def test_the_frame_loads_add_up_to_the_body_s_force_at_every_instant(ditching):
    hull, history = ditching
    fl = history.frame_loads(hull, spacing=0.25)
    assert fl.vertical.shape == (len(history.sections), fl.bays)
    np.testing.assert_allclose(fl.vertical.sum(axis=1), fl.body, rtol=1e-12, atol=1e-9)
    totals_x = np.array([r.total_x for r in history.sections])
    np.testing.assert_allclose(fl.horizontal.sum(axis=1), totals_x, rtol=1e-12, atol=1e-9)
    assert np.all(np.diff(fl.edges) > 0) and fl.edges[0] == hull.bounds[0, 0]
    # and the history's own force at those times
    kept = np.searchsorted(history.t, fl.t)
    np.testing.assert_allclose(fl.body, history.force[kept], rtol=1e-12)


def test_frame_stations_are_checked():
    with pytest.raises(hs.InputError, match="not inside the body"):
        hs.loads.frame_stations((0.0, 3.76), [1.0, 5.0])
    with pytest.raises(hs.InputError, match="given twice"):
        hs.loads.frame_stations((0.0, 3.76), [1.0, 1.0])
    with pytest.raises(hs.InputError, match="not positive"):
        hs.loads.frame_stations((0.0, 3.76), spacing=-1.0)
    np.testing.assert_allclose(hs.loads.frame_stations((0.0, 3.76), spacing=1.0), [1, 2, 3])


def test_a_run_without_its_sections_or_pressures_says_how_to_get_them():
    hull = fine_wedge(20.0)
    plain = hs.simulate(hull, -V, 0.01, dt=0.001, solver="mlm")
    with pytest.raises(hs.InputError, match="sections_every"):
        plain.face_pressures(hull)
    forces = hs.simulate(hull, -V, 0.01, dt=0.001, solver="zarnick", sections_every=2)
    with pytest.raises(hs.InputError, match="solver='mlm'"):
        forces.face_pressures(hull)
    assert forces.frame_loads(hull, [0.5]).bays == 2  # frame loads need no pressures
    with pytest.raises(hs.InputError, match="sections_every"):
        hs.simulate(hull, -V, 0.01, dt=0.001, solver="mlm", sections_every=-1)


def test_the_command_writes_a_pvd_series_and_tables_that_read_back(tmp_path, capsys):
    meshio = pytest.importorskip("meshio")
    out = tmp_path / "loads"
    args = ["simulate", str(MESHES / "fuselage_model.obj"), "--mass", "40", "--velocity=-1",
            "--t-end", "0.06", "--dt", "0.002", "--pitch", "8", "--forward-speed", "15",
            "--solver", "mlm", "--water", "sea", "--slices", "24",
            "--pressures-out", str(out), "--pressures-every", "5", "--frames", "1,2,3"]  # fmt: skip
    assert main(args) == 0
    text = capsys.readouterr()
    assert "face pressures: 7 instants" in text.out and "frame loads: 4 bays" in text.out
    doc = ET.parse(out / "pressure.pvd").getroot()
    sets = doc.findall("./Collection/DataSet")
    assert len(sets) == 7
    table = np.loadtxt(out / "face_pressures.csv", delimiter=",", skiprows=1, ndmin=2)
    faces = np.loadtxt(out / "faces.csv", delimiter=",", skiprows=1)
    for ds in sets:
        mesh = meshio.read(out / ds.get("file"))
        p = mesh.cell_data["pressure"][0]
        assert len(p) == len(faces)
        t = float(ds.get("timestep"))
        rows = table[np.isclose(table[:, 0], t, rtol=0, atol=1e-12)]
        back = np.zeros(len(p))
        back[rows[:, 1].astype(int)] = rows[:, 2]
        np.testing.assert_allclose(back, p, rtol=1e-8, atol=1e-6)  # the CSV's 9 digits
    peak = meshio.read(out / "peak.vtu")
    assert peak.cell_data["peak_pressure"][0].max() > 0
    manifest = json.loads((out / "loads.json").read_text())
    assert manifest["units"]["pressure"] == "Pa" and len(manifest["instants"]) == 7
    frames = np.genfromtxt(out / "frames.csv", delimiter=",", names=True)
    assert len(frames) == 7 * 4


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        (["--solver", "zarnick", "--pressures-out", "{d}"], "use --solver mlm"),
        (["--solver", "mlm", "--frames", "1"], "needs --pressures-out"),
        (["--solver", "mlm", "--pressures-out", "{busy}"], "holds other files"),
    ],
)
def test_bad_loads_outputs_are_refused_before_any_work(tmp_path, capsys, extra, words):
    busy = tmp_path / "busy"
    busy.mkdir()
    (busy / "notes.txt").write_text("mine")
    extra = [e.format(d=tmp_path / "new", busy=busy) for e in extra]
    args = ["simulate", str(MESHES / "fuselage_model.obj"), "--mass", "40", "--velocity=-1",
            "--t-end", "0.02", *extra]  # fmt: skip
    rc = main(args)
    err = capsys.readouterr().err
    assert rc != 0 and words in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "new").exists()
    assert (busy / "notes.txt").read_text() == "mine"


def test_the_frame_loads_are_a_labelled_dataset_with_units(ditching):
    pytest.importorskip("xarray")
    hull, history = ditching
    fl = history.frame_loads(hull, [1.0, 2.0])
    ds = fl.to_xarray()
    assert ds["vertical"].attrs["units"] == "N" and ds["t"].attrs["units"] == "s"
    assert ds.sizes == {"t": len(history.sections), "bay": 3}
    np.testing.assert_allclose(ds["vertical"].sum("bay").values, fl.body, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(ds["x_fore"].values, [1.0, 2.0, hull.bounds[1, 0]])


def test_a_catamaran_s_floats_each_take_their_own_pressure():
    v, f = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=20.0)
    shift = np.array([0.0, 0.3, 0.0])
    both = np.concatenate([v - shift, v + shift]), np.concatenate([f, f + len(v)])
    cat = hs.Hull.from_arrays(*both, mass=20.0)
    one = hs.Hull.from_arrays(v, f, mass=10.0)
    state = (hs.Pose(0.02), hs.Motion(-V))
    acc = hs.Acceleration(0.0)
    rc = hs.compute_force(cat, *state, solver="mlm", slices=8, acceleration=acc)
    r1 = hs.compute_force(one, *state, solver="mlm", slices=8, acceleration=acc)
    fc, f1 = face_pressures(cat, rc), face_pressures(one, r1)
    assert fc.total == pytest.approx(rc.total, rel=1e-12)
    # each float carries the lone float's pressures, face for face
    np.testing.assert_allclose(fc.pressure[: len(f)], f1.pressure, rtol=1e-9, atol=1e-6)
    np.testing.assert_allclose(fc.pressure[len(f) :], f1.pressure, rtol=1e-9, atol=1e-6)
