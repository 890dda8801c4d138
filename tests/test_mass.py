"""Mass properties: uniform density, line densities and point masses."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import trimesh

import hullslice as hs
from hullslice import shapes
from hullslice.cli import main
from hullslice.mass import MassDistribution, read_mass_distribution

from .conftest import MESHES

PRISM = str(MESHES / "paper_prism.stl")


@pytest.fixture(scope="module")
def fuselage():
    return hs.load_hull(MESHES / "fuselage_full.obj", mass=60000.0)


def test_pitch_inertia_from_the_mesh_matches_trimesh(fuselage):
    tm = trimesh.Trimesh(fuselage.vertices, fuselage.faces, process=False)
    tm.density = fuselage.density
    # trimesh: inertia tensor about the centre of mass; the pitch axis is y
    assert fuselage.pitch_inertia == pytest.approx(tm.moment_inertia[1, 1], rel=1e-9)
    assert fuselage.cg == pytest.approx(tm.center_mass, abs=1e-9)


@pytest.mark.parametrize("pitch_deg", [0.0, 6.0])
def test_mass_per_metre_adds_up_to_the_mass(fuselage, pitch_deg):
    # the whole body under water, cut into many slices: sum M dX = m (midpoint rule)
    pose = hs.Pose(draft=0.0, pitch_rad=np.radians(pitch_deg))
    height = hs.sections._height_at(fuselage, pose.pitch)
    s = hs.cut(fuselage, hs.Pose(height, pose.pitch), 400)
    total = (s.mass_per_metre * s.dx).sum()
    assert total == pytest.approx(fuselage.mass, rel=0.005)


def test_line_distribution_mass_per_metre_adds_up(fuselage):
    x = np.linspace(0.0, 37.6, 50)
    m_per_m = 1000.0 + 1500.0 * np.sin(np.pi * x / 37.6)  # heavier in the middle
    dist = MassDistribution(x=x, mass_per_metre=m_per_m)
    hull = fuselage.with_mass(mass_distribution=dist)
    assert hull.mass == pytest.approx(np.trapezoid(m_per_m, x), rel=1e-12)
    for pitch in (0.0, np.radians(8.0)):
        height = hs.sections._height_at(hull, pitch)
        s = hs.cut(hull, hs.Pose(height, pitch), 400)
        assert (s.mass_per_metre * s.dx).sum() == pytest.approx(hull.mass, rel=0.005)
    # the sections carry the given density where the body is level
    s = hs.cut(hull, 1.0, 16)
    np.testing.assert_allclose(s.mass_per_metre, dist.at(s.x), rtol=1e-12)


def test_line_moments_are_exact():
    # a linear density: closed-form integrals
    x = np.array([0.0, 2.0, 5.0])
    m = np.array([1.0, 3.0, 0.0])
    dist = MassDistribution(x=x, mass_per_metre=m, line_z=0.5)
    fine = np.linspace(0.0, 5.0, 200001)
    mf = np.interp(fine, x, m)
    mass = np.trapezoid(mf, fine)
    xg = np.trapezoid(fine * mf, fine) / mass
    assert dist.total == pytest.approx(mass, rel=1e-9)
    cg = dist.cg(line_z=99.0)  # its own line height wins
    assert cg == pytest.approx([xg, 0.5], rel=1e-9)
    i = dist.pitch_inertia(cg, line_z=99.0)
    assert i == pytest.approx(np.trapezoid((fine - xg) ** 2 * mf, fine), rel=1e-8)


def test_point_masses():
    pts = np.array([[1.0, 0.0, 10.0, 0.5], [5.0, 2.0, 30.0, 1.0]])
    dist = MassDistribution(points=pts)
    assert dist.total == 40.0
    cg = dist.cg(line_z=0.0)
    assert cg == pytest.approx([(10 + 150) / 40, 60 / 40])
    # point masses plus thin rods of their lengths about their own centres
    expected = 10 * ((1 - 4) ** 2 + 1.5**2 + 0.5**2 / 12) + 30 * (1**2 + 0.5**2 + 1 / 12)
    assert dist.pitch_inertia(cg, 0.0) == pytest.approx(expected, rel=1e-12)
    assert dist.at(np.array([1.2, 1.3, 5.0])) == pytest.approx([20.0, 0.0, 30.0])


def test_given_cg_and_inertia_override(fuselage):
    hull = fuselage.with_mass(60000.0, cg=(18.0, 1.5), inertia=3.0e6)
    assert hull.cg[[0, 2]] == pytest.approx([18.0, 1.5])
    assert hull.pitch_inertia == 3.0e6


def test_a_cg_far_off_the_body_is_refused(fuselage, capsys):
    # a centre of gravity more than the body's size off its box is another unit or frame;
    # one above the mesh, within its size (a hull meshed without its upper works), is not
    lo, hi = fuselage.bounds
    size = float(np.linalg.norm(hi - lo))
    above = (0.5 * (lo[0] + hi[0]), hi[2] + 0.9 * size)
    assert fuselage.with_mass(6e4, cg=above).cg[2] == pytest.approx(above[1])
    with pytest.raises(hs.InputError, match=f"lies {1.1 * size:.6g} m off the body .* more than"):
        fuselage.with_mass(6e4, cg=(0.5 * (lo[0] + hi[0]), hi[2] + 1.1 * size))
    rc = main(["simulate", str(MESHES / "paper_prism.stl"), "--mass", "1", "--velocity=-3",
               "--t-end", "0.01", "--cg", "100,0"])  # fmt: skip
    err = capsys.readouterr().err.strip().splitlines()
    assert rc != 0 and len(err) == 1 and "99.65 m off the body" in err[0], err


def test_distribution_and_mass_must_agree(fuselage):
    dist = MassDistribution(x=[0.0, 10.0], mass_per_metre=[100.0, 100.0])
    with pytest.raises(hs.InputError, match="adds up to 1000 kg but the mass is given as 2000"):
        fuselage.with_mass(2000.0, mass_distribution=dist)
    assert fuselage.with_mass(1003.0, mass_distribution=dist).mass == 1003.0


def test_read_csv_forms(tmp_path):
    line = tmp_path / "line.csv"
    line.write_text("# aircraft\nx,mass_per_metre\n0,100\n10,300\n")
    d = read_mass_distribution(line)
    assert d.total == pytest.approx(2000.0)
    pts = tmp_path / "pts.csv"
    pts.write_text("x,z,mass,length\n1,0.5,100,2\n3,0.5,300,2\n")
    d = read_mass_distribution(pts)
    assert d.total == 400.0 and d.cg(0.0) == pytest.approx([2.5, 0.5])


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("x,weight\n0,1\n1,2\n", "needs x,mass_per_metre"),
        ("x,mass_per_metre\n0,1\n0,2\n", "strictly increasing"),
        ("x,mass_per_metre\n0,1\n1,-2\n", "negative"),
        ("x,mass_per_metre\n0,1\n1,abc\n", "line 3"),
        ("x,z,mass\n0,0,-5\n", "must be > 0"),
        ("", "is empty"),
    ],
)
def test_bad_mass_distribution_files(tmp_path, text, message):
    path = tmp_path / "m.csv"
    path.write_text(text)
    with pytest.raises(hs.CaseError, match=message):
        read_mass_distribution(path)


def test_uniform_prism_centroid_and_inertia_closed_form():
    # a box: I_yy = m (L^2 + H^2) / 12
    v, f = shapes.prism_from_sections(
        np.array([0.0, 2.0]),
        np.broadcast_to([[-0.5, 0.0], [0.5, 0.0], [0.5, 1.0], [-0.5, 1.0]], (2, 4, 2)),
    )
    hull = hs.Hull.from_arrays(v, f, mass=6.0)
    assert hull.pitch_inertia == pytest.approx(6.0 * (4.0 + 1.0) / 12, rel=1e-12)
    assert hull.cg == pytest.approx([1.0, 0.0, 0.5])


def test_pitched_distribution_puts_each_mass_at_its_own_height():
    # masses at different heights: on earth planes of a pitched body, the sections' mass
    # must sit where the masses are, so its centroid along X is the centre of gravity's X
    # (a wedge with 0.5 m high sides, so that the masses lie in the body)
    v, f = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=30.0, sides=0.5)
    pts = np.array([[0.2, -0.05, 4.0, 0.1], [0.7, 0.4, 6.0, 0.2]])
    hull = hs.Hull.from_arrays(v, f, mass_distribution=MassDistribution(points=pts))
    theta = np.radians(10.0)
    height = hs.sections._height_at(hull, theta)
    s = hs.cut(hull, hs.Pose(height, theta), 2000)
    m = s.mass_per_metre * s.dx
    assert m.sum() == pytest.approx(10.0, rel=2e-3)
    assert (m * s.x).sum() / m.sum() == pytest.approx(hull.cg[0], abs=2e-3)
    # the upper mass (0.45 m above the cg) lands ahead of its body x by (z - z_g) tan(pitch)
    zg = hull.cg[2]
    x_upper = hull.cg[0] + (0.7 - hull.cg[0]) * np.cos(theta) - (0.4 - zg) * np.sin(theta)
    upper = np.abs(s.x - x_upper) < 0.1 * np.cos(theta) - 1e-3
    np.testing.assert_allclose(s.mass_per_metre[upper], 6.0 / 0.2 / np.cos(theta), rtol=1e-9)


def test_sections_without_mass_get_no_force_and_are_flagged(wedge_hull):
    # point masses leave stations between them without mass: no free fall there
    pts = np.array([[0.2, 0.0, 5.0, 0.2], [0.8, 0.0, 5.0, 0.2]])
    hull = wedge_hull.with_mass(mass_distribution=MassDistribution(points=pts))
    r = hs.compute_force(hull, 0.03, -4.0, slices=10)
    empty = r.sections.mass_per_metre == 0
    assert empty.any() and (~empty).any()
    assert np.all(r.force[empty] == 0) and not r.valid[empty].any()
    assert "no mass per metre" in r.loads.reason[np.flatnonzero(empty)[0]]
    assert np.all(np.isfinite(r.force)) and r.total > 0


# -- the mass properties in one ---------------------------------------------------------------


def test_mass_properties_are_checked_once_and_hold_the_cg_as_a_point():
    props = hs.MassProperties(mass=2.0, cg=(0.1, -0.02), inertia=0.5)
    assert props.cg.tolist() == [0.1, 0.0, -0.02]  # (x, z): in the plane of symmetry
    assert hs.MassProperties(cg=(0.1, 0.01, -0.02)).cg.tolist() == [0.1, 0.01, -0.02]
    with pytest.raises(hs.InputError, match="not two numbers x, z or three"):
        hs.MassProperties(cg=(1.0,))
    with pytest.raises(hs.InputError, match="is not positive"):
        hs.MassProperties(mass=-1.0)
    with pytest.raises(hs.InputError, match="pitch inertia"):
        hs.MassProperties(inertia=0.0)
    dist = MassDistribution(x=[0.0, 1.0], mass_per_metre=[2.0, 2.0])
    assert hs.MassProperties(distribution=dist).mass == pytest.approx(2.0)


def test_a_hull_takes_the_mass_properties_or_the_keywords_not_both(wedge_hull):
    props = hs.MassProperties(mass=10.0, cg=(0.0, 0.05), inertia=0.3)
    a = wedge_hull.with_mass(mass_properties=props)
    b = wedge_hull.with_mass(10.0, cg=(0.0, 0.05), inertia=0.3)
    assert a.mass_properties is props
    assert a.mass == b.mass == 10.0
    assert a.cg.tolist() == b.cg.tolist() == [0.0, 0.0, 0.05]
    assert a.pitch_inertia == b.pitch_inertia == 0.3
    assert b.mass_properties.inertia == 0.3
    with pytest.raises(hs.InputError, match="mass_properties and mass both"):
        wedge_hull.with_mass(10.0, mass_properties=props)
    with pytest.raises(hs.InputError, match="mass_properties and cg, inertia both"):
        hs.load_hull(MESHES / "paper_prism.stl", mass_properties=props, cg=(0, 0), inertia=1)
    loaded = hs.load_hull(MESHES / "paper_prism.stl", mass_properties=hs.MassProperties(1.0))
    assert loaded.mass == 1.0 and loaded.mass_properties.mass == 1.0


def test_the_mass_properties_survive_a_pickle(wedge_hull):
    import pickle

    hull = wedge_hull.with_mass(10.0, cg=(0.0, 0.01, 0.05))
    back = pickle.loads(pickle.dumps(hull))
    assert back.mass_properties.mass == 10.0
    assert back.mass_properties.cg.tolist() == [0.0, 0.01, 0.05]
    assert back.cg.tolist() == hull.cg.tolist()


# -- point masses follow the body, and the distribution is checked against it ----------------


def _carried(hull: hs.Hull, slices: int, pitch_deg: float = 0.0) -> float:
    """The mass the sections of the whole body under water carry, kg."""
    pitch = np.radians(pitch_deg)
    s = hs.cut(hull, hs.Pose(hs.sections._height_at(hull, pitch), pitch), slices)
    return float((s.mass_per_metre * s.dx).sum())


def test_a_point_mass_without_a_length_is_spread_over_a_tenth_of_the_body(tmp_path):
    # 1 kg in the middle of the 0.35 m prism: spread over 0.035 m, all of it on the body
    # (over 1 m whatever the body, the sections carried 0.35 kg)
    path = tmp_path / "pm.csv"
    path.write_text("x,z,mass\n0.175,-0.05,1.0\n")
    hull = hs.load_hull(PRISM, mass_distribution=read_mass_distribution(path))
    for slices in (7, 16, 32, 64):
        for pitch in (0.0, 6.0):
            assert _carried(hull, slices, pitch) == pytest.approx(1.0, rel=0.005)
    lo, hi = hull.mass_distribution.spreads()
    assert [lo[0], hi[0]] == pytest.approx([0.1575, 0.1925], abs=1e-6)
    assert hull.mass_per_metre_at(np.array([0.17, 0.19, 0.2])) == pytest.approx(
        [1 / 0.035, 1 / 0.035, 0.0], rel=1e-5
    )
    # the pitch inertia of a 1 kg rod 0.035 m long about its middle (1/12 kg m^2 before)
    assert hull.pitch_inertia == pytest.approx(0.035**2 / 12, rel=1e-5)


def test_a_point_mass_on_a_small_body_stays_on_it():
    # a 1 cm wedge with 1 g at its middle: spread over 1 mm (over 1 m, 1 % was on the body,
    # and the pitch inertia was 8.3e-5 kg m^2)
    v, f = shapes.wedge_prism(length=0.01, beam=0.002, deadrise_deg=30.0)
    z = -0.0003
    hull = hs.Hull.from_arrays(v, f, mass_distribution=MassDistribution(points=[[0.005, z, 1e-3]]))
    assert _carried(hull, 16) == pytest.approx(1e-3, rel=0.005)
    assert hull.pitch_inertia == pytest.approx(1e-3 * 0.001**2 / 12, rel=1e-6)


def test_point_masses_at_the_ends_and_thin_ones_are_carried_whole(wedge_hull):
    # at the body's very ends the spread is narrowed to stay on the body; a given length
    # thinner than the slices is still carried whole (before: by the stations inside it)
    pts = [[0.0, -0.02, 2.0, np.nan], [1.0, -0.02, 3.0, np.nan], [0.43, -0.02, 5.0, 0.004]]
    hull = wedge_hull.with_mass(mass_distribution=MassDistribution(points=pts))
    lo, hi = hull.mass_distribution.spreads()
    assert lo == pytest.approx([0.0, 0.99975, 0.428]) and hi == pytest.approx([2.5e-4, 1, 0.432])
    for slices in (5, 16, 33):
        assert _carried(hull, slices) == pytest.approx(10.0, rel=0.005)
        assert _carried(hull, slices, 8.0) == pytest.approx(10.0, rel=0.005)


def test_a_point_mass_without_a_length_needs_a_body():
    dist = MassDistribution(points=[[0.5, 0.0, 2.0]])
    assert dist.total == 2.0 and dist.cg(0.0) == pytest.approx([0.5, 0.0])
    with pytest.raises(hs.InputError, match="give the distribution to a hull"):
        dist.at(np.array([0.5]))
    assert dist.on_body(0.0, 2.0).at(np.array([0.5])) == pytest.approx([10.0])


@pytest.mark.parametrize(
    ("rows", "message"),
    [
        # 2 kg of 2.35 kg beyond the 0.35 m prism's ends
        ("x,mass_per_metre\n-1,1\n1.35,1\n", "2 kg of the mass distribution's 2.35 kg (85.1 %)"),
        ("x,mass_per_metre\n10,1\n11,1\n", "1 kg of the mass distribution's 1 kg (100 %)"),
        ("x,z,mass\n0.1,-0.05,1\n0.5,-0.05,1\n", "1 kg of the mass distribution's 2 kg (50 %)"),
        ("x,z,mass,length\n0.33,-0.05,1,0.1\n", "0.3 kg of the mass distribution's 1 kg (30 %)"),
    ],
)
def test_mass_beyond_the_body_is_refused(capsys, tmp_path, rows, message):
    path = tmp_path / "m.csv"
    path.write_text(rows)
    code = main(["force", PRISM, "--mass-distribution", str(path), "--draft", "0.0383",
                 "--velocity=-3.4943", "--slices", "16"])  # fmt: skip
    out, err = capsys.readouterr()
    assert code != 0 and out == "" and len(err.strip().splitlines()) == 1
    assert message in err and "lies beyond the body's ends, x = 0 to 0.35 m (the rows at" in err
    assert "give the distribution in the body frame" in err and "Traceback" not in err
    with pytest.raises(hs.InputError, match="lies beyond the body's ends"):
        hs.load_hull(PRISM, mass_distribution=read_mass_distribution(path))


def test_a_tiny_share_beyond_the_ends_is_warned_of(capsys, tmp_path):
    # a row 0.1 mm past the bow: 1e-4 kg of 0.3501 kg (0.0286 %), warned of
    path = tmp_path / "m.csv"
    path.write_text("x,mass_per_metre\n0,1\n0.3501,1\n")
    with pytest.warns(hs.HullsliceWarning, match=r"\(0.0286 %\) lies beyond .* x = 0.3501 m"):
        hull = hs.load_hull(PRISM, mass_distribution=read_mass_distribution(path))
    assert _carried(hull, 64) == pytest.approx(0.35, rel=1e-3)
    code = main(["info", PRISM, "--mass-distribution", str(path)])
    _out, err = capsys.readouterr()
    assert code == 0 and "warning:" in err and "the sections do not carry that share" in err
    # rounding past the ends (the prism ends at 0.34999999 m) is not mentioned
    path.write_text("x,mass_per_metre\n0,1\n0.35,1\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        hull = hs.load_hull(PRISM, mass_distribution=read_mass_distribution(path))
    assert _carried(hull, 64) == pytest.approx(0.35, rel=0.005)


def test_a_centre_of_gravity_outside_the_body_is_refused(capsys, tmp_path):
    # 1 kg 5 cm above the prism's deck (z = 0)
    path = tmp_path / "m.csv"
    path.write_text("x,z,mass\n0.175,0.05,1\n")
    code = main(["info", PRISM, "--mass-distribution", str(path)])
    _out, err = capsys.readouterr()
    assert code != 0 and len(err.strip().splitlines()) == 1
    assert "centre of gravity (x, z) = (0.175, 0.05) m lies outside the body" in err
    assert "z = -0.1 to 0 m" in err
