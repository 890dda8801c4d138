"""The ``zarnick`` strip-theory plugin and the contour method, against closed forms.

References:

- Wagner (1932) and von Karman (1929): a wedge at constant speed ``V`` carries
  ``rho pi gamma^2 V^3 t / tan^2(beta)`` per metre before its chine; a circular cylinder of
  radius ``R`` carries ``C rho R V^2`` at small penetration, with the slamming coefficient
  ``C = 2 pi`` (Wagner) or ``pi`` (von Karman). METHOD, sections 6-7.
- Zarnick (1978): after the chine the added mass is frozen and a cross-flow drag
  ``C_D,c rho b V^2`` carries the load, with a buoyancy ``a_B rho g A``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import hullslice as hs
from hullslice import shapes
from hullslice.cli import main
from hullslice.forces import momentum_terms, solve_accelerations
from hullslice.solvers.registry import get_solver

from .conftest import MESHES

RHO = 1000.0


def wedge(deadrise_deg: float = 30.0) -> hs.Hull:
    v, f = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=deadrise_deg)
    return hs.Hull.from_arrays(v, f)


def constant_speed(V: float, p: np.ndarray) -> dict[str, np.ndarray]:
    return {"t": p / V, "draft": p, "velocity": np.full(len(p), -V)}


def test_zarnick_is_installed_as_a_plugin_of_the_momentum_kind():
    info = {i.name: i for i in hs.list_solvers()}["zarnick"]
    assert (info.status, info.kind, info.distribution) == ("ok", "momentum", "hullslice-zarnick")
    assert hs.get_solver("zarnick").models_separation


@pytest.mark.parametrize("deadrise_deg", [20.0, 30.0])
def test_before_the_chine_zarnick_is_the_momentum_wagner_solver(deadrise_deg):
    # without gravity (no buoyancy) and before the chine (no drag) the strip theory is the
    # momentum theory with Wagner's pile-up
    hull = wedge(deadrise_deg)
    p = np.linspace(0.0, 0.5 * 0.1 * math.tan(math.radians(deadrise_deg)) / (math.pi / 2), 9)
    kin = constant_speed(6.0, p)
    fluid = hs.Fluid(RHO, 0.0)
    z = hs.prescribed(hull, kin, solver="zarnick", slices=8, fluid=fluid)
    w = hs.prescribed(hull, kin, solver="wagner", slices=8, fluid=fluid)
    np.testing.assert_allclose(z.force, w.force, rtol=1e-12, atol=1e-9)
    assert z.valid.all()


@pytest.mark.parametrize(
    ("solver", "options", "coefficient"),
    [
        ("zarnick", {}, 2 * math.pi),
        ("wagner", {}, 2 * math.pi),
        ("zarnick", {"pile_up": "von-karman"}, math.pi),
        ("von-karman", {}, math.pi),
    ],
)
@pytest.mark.parametrize("depth", [0.005, 0.01])
def test_a_circular_cylinder_has_the_slamming_coefficient_of_its_theory(
    solver, options, coefficient, depth
):
    # a 1 m cylinder of radius 0.5 m (720 points around), at constant speed, no gravity:
    # f = C rho R V^2, within 3 % at p / R = 0.005 and 0.01 (measured 1.3 % at most: the
    # exact coefficients fall as 1 - O(p / R), and the polygon is not a circle)
    v, f = shapes.circular_cylinder(length=1.0, radius=0.5)
    hull = hs.Hull.from_arrays(v, f)
    R, V = 0.5, 5.0
    r = hs.compute_force(
        hull, depth * R, -V, slices=4, solver=hs.get_solver(solver, **options),
        fluid=hs.Fluid(RHO, 0.0), acceleration=0.0,
    )  # fmt: skip
    assert r.loads.diagnostics["contour"].all()  # a round section: its own contour
    assert r.total / (RHO * R * V**2) == pytest.approx(coefficient, rel=0.03)


def test_the_equivalent_wedge_would_overestimate_the_cylinder():
    # the same cylinder through the equivalent wedge tan(beta) = p / c: Wagner's c and the
    # rate of a wedge, pi^2 / 4 times the contour's at small penetration
    v, f = shapes.circular_cylinder(length=1.0, radius=0.5)
    hull = hs.Hull.from_arrays(v, f)
    kw = {"slices": 4, "fluid": hs.Fluid(RHO, 0.0), "acceleration": 0.0}
    auto = hs.compute_force(hull, 0.0025, -5.0, solver="wagner", **kw).total
    as_wedge = hs.get_solver("wagner", section_method="wedge")
    wedge_total = hs.compute_force(hull, 0.0025, -5.0, solver=as_wedge, **kw).total
    assert wedge_total / auto == pytest.approx(math.pi**2 / 4, rel=0.05)


def test_after_the_chine_the_load_is_drag_and_buoyancy():
    # a 30 deg wedge prism (deck half-width 0.1 m, chine depth 0.0577 m) at 4 m/s: once
    # Wagner's spray root is past the chine (p > 0.1 tan(30) / (pi/2) = 0.0368 m) the added
    # mass is frozen, and f = C_D rho b V^2 + a_B rho g A with b the chine half-width and
    # A the submerged area: the deck is above the water, A = area of the triangle below it
    hull = wedge(30.0)
    tb, b, V = math.tan(math.radians(30.0)), 0.1, 4.0
    p = np.array([0.040, 0.045, 0.050, 0.055])
    h = hs.prescribed(hull, constant_speed(V, p), solver="zarnick", slices=8)
    area = p**2 / tb  # the submerged triangle of depth p and half-width p / tan(beta)
    expected = 1.0 * RHO * b * V**2 + 0.5 * RHO * 9.81 * area
    np.testing.assert_allclose(h.force, expected, rtol=1e-6)
    assert h.valid.all()


def test_buoyancy_alone_is_the_hydrostatic_force_with_a_factor_one():
    # a body at rest (v = 0, a = 0) half sunk: the only force is a_B rho g V_sub; with
    # a_B = 1 it is Archimedes'
    hull = wedge(30.0)
    solver = hs.get_solver("zarnick", buoyancy_factor=1.0)
    p = 0.03
    r = hs.compute_force(hull, p, 0.0, slices=8, solver=solver, acceleration=0.0)
    volume = p**2 / math.tan(math.radians(30.0)) * 1.0
    assert r.total == pytest.approx(RHO * 9.81 * volume, rel=1e-6)


def test_no_force_behind_the_transom():
    # a wedge prism planing at 4 deg and 10 m/s: every slice with a force lies on the body,
    # and the aft end of the wetted part is the transom (x = 0)
    hull = wedge(20.0).with_mass(5.0)
    r = hs.compute_force(
        hull, hs.Pose(0.01, math.radians(4.0)), hs.Motion(-0.2, 10.0), slices=16,
        solver="zarnick", acceleration=0.0,
    )  # fmt: skip
    s = r.sections
    loaded = np.abs(r.force) > 0
    x_body = hull.bounds[:, 0]
    assert np.all(s.x[loaded] - s.dx[loaded] / 2 >= x_body[0] - 1e-9)
    assert r.total > 0


def test_a_ditching_with_zarnick_and_free_pitch_runs_to_its_end():
    # the 1:10 fuselage at 8 deg, 6 m/s forward, 0.5 m/s down: buoyancy and separation are
    # modelled, so neither a slow section nor a wetted chine ends the run
    hull = hs.load_hull(MESHES / "fuselage_model.obj", mass=60.0)
    h = hs.simulate(
        hull, -0.5, 0.06, dt=1e-3, pitch_rad=math.radians(8.0), forward_speed=6.0,
        free_pitch=True, slices=32, solver="zarnick",
    )  # fmt: skip
    assert h.stop_reason == "t_end"
    assert h.max_flagged_share == 0.0
    assert np.all(np.isfinite(h.force)) and h.force.max() > 0


@pytest.mark.parametrize(
    ("option", "message"),
    [
        ("cross_flow_drag=-1", "option cross_flow_drag=-1 is not a finite number >= 0"),
        ("cross_flow_drag=NaN", "'cross_flow_drag=NaN': nan is not a finite number"),
        ("buoyancy_factor=1.5", "option buoyancy_factor=1.5 is not a finite number in [0, 1]"),
        ("buoyancy_factor=-0.1", "buoyancy_factor=-0.1 is not a finite number in [0, 1]"),
        ("section_method=round", "section_method='round' is unknown"),
        ("pile_up=1.2", "section_method=contour needs pile_up=wagner"),
    ],
)
def test_bad_coefficients_are_one_line_errors(capsys, option, message):
    extra = ["--solver-option", "section_method=contour"] if option.startswith("pile_up") else []
    code = main(
        ["force", str(MESHES / "wedge_prism.stl"), "--mass", "10", "--draft", "0.02",
         "--velocity=-4", "--solver", "zarnick", "--solver-option", option, *extra]
    )  # fmt: skip
    out, err = capsys.readouterr()
    # NaN is refused with the command line (status 2), the others as inputs (status 3)
    assert code == (2 if "NaN" in option else 3) and out == ""
    assert message in err and len(err.strip().splitlines()) == 1


def test_the_contour_method_on_a_section_without_a_keel_is_refused():
    # a box has a flat bottom: no keel for Wagner's condition
    v, f = shapes.prism_from_sections(
        np.linspace(0.0, 1.0, 3),
        np.broadcast_to(np.array([[-0.1, 0.0], [-0.1, -0.1], [0.1, -0.1], [0.1, 0.0]]), (3, 4, 2)),
    )
    hull = hs.Hull.from_arrays(v, f)
    solver = hs.get_solver("zarnick", section_method="contour")
    with pytest.raises(hs.InputError, match=r"has no keel .* use section_method=auto or wedge"):
        hs.compute_force(hull, 0.02, -4.0, slices=4, solver=solver, acceleration=0.0)


def test_a_catamarans_buoyancy_is_each_floats_own():
    # two 30 deg wedge prisms 1 m apart, one 0.04 m higher: at a draft of 0.06 m the low
    # float (0.0577 m deep) is wholly under the water, the high one 0.02 m deep. With
    # a_B = 1 each float carries rho g times its own submerged triangle, and the submerged
    # one is flagged
    import trimesh

    v, f = shapes.wedge_prism(1.0, 0.2, 30.0)
    low, high = trimesh.Trimesh(v, f), trimesh.Trimesh(v, f)
    low.apply_translation([0.0, 0.5, 0.0])
    high.apply_translation([0.0, -0.5, 0.04])
    both = trimesh.util.concatenate([low, high])
    hull = hs.Hull.from_arrays(both.vertices, both.faces)
    solver = hs.get_solver("zarnick", buoyancy_factor=1.0)
    r = hs.compute_force(hull, 0.06, -1.0, slices=2, solver=solver, acceleration=0.0)
    area = r.loads.diagnostics["submerged_area"]
    tb = math.tan(math.radians(30.0))
    is_low = r.sections.y_keel > 0
    np.testing.assert_allclose(area[is_low], 0.1**2 * tb, rtol=1e-6)  # the whole triangle
    np.testing.assert_allclose(area[~is_low], 0.02**2 / tb, rtol=1e-6)
    assert not r.loads.valid[is_low].any() and r.loads.valid[~is_low].all()


def test_a_flat_bottom_runs_with_every_momentum_solver():
    # a box: no keel for the contour, so the equivalent wedge (flagged flat bottom)
    import trimesh

    box = trimesh.creation.box(extents=(1.0, 0.4, 0.2))
    hull = hs.Hull.from_arrays(box.vertices, box.faces, mass=40.0)
    for name in ("von-karman", "wagner", "zarnick"):
        r = hs.compute_force(hull, 0.01, -3.0, solver=name, slices=8)
        assert np.isfinite(r.total) and r.total > 0, name


def test_von_karmans_added_mass_stays_at_the_widest_point():
    # a cylinder sunk past its widest point: the calm-water width shrinks, the added mass
    # must not (it keeps its value at the widest point, rho pi R^2 / 2, and no flux force)
    v, f = shapes.circular_cylinder(radius=0.5, points=720)
    hull = hs.Hull.from_arrays(v, f)
    kw = {"slices": 4, "fluid": hs.Fluid(RHO, 0.0), "acceleration": 0.0}
    at_widest = RHO * math.pi * 0.5**2 / 2
    for p in (0.6, 0.8):
        r = hs.compute_force(hull, p, -3.0, solver="von-karman", **kw)
        assert r.added_mass == pytest.approx(at_widest, rel=1e-3)
        assert r.total == pytest.approx(0.0, abs=1e-9)


def test_a_fine_time_step_does_not_stop_a_cylinders_drop():
    # at a penetration of 0.1 mm the round section's contour is read (not a flat wedge)
    v, f = shapes.circular_cylinder(radius=0.5, points=720)
    hull = hs.Hull.from_arrays(v, f, mass=100.0)
    h = hs.simulate(hull, -2.0, 0.005, dt=1e-4, slices=4, solver="zarnick")
    assert h.stop_reason == "t_end" and h.max_flagged_share == 0.0


def test_fixed_slicing_has_no_spike_where_a_slice_starts_to_wet():
    # the 1:10 fuselage at 8 deg: a 0.2 mm change of draft changes the force smoothly (a
    # barely wetted mid-station scaled up once made a flat bottom and a 60-fold jump)
    hull = hs.load_hull(MESHES / "fuselage_model.obj", mass=60.0)
    forces = [
        hs.compute_force(
            hull, hs.Pose(d, math.radians(8.0)), hs.Motion(-0.5, 19.0), slices=64,
            solver="zarnick", slicing="fixed", acceleration=0.0,
        ).total
        for d in (0.0108, 0.0110, 0.0112)
    ]  # fmt: skip
    assert max(abs(f) for f in forces) < 1000.0
    assert abs(forces[1] - forces[0]) < 0.5 * max(abs(forces[0]), abs(forces[1]))


def test_buoyancy_is_vertical_on_a_pitched_body():
    # a box at rest, pitched 3 deg and half sunk, a_B = 1: Archimedes' force is vertical,
    # whatever the slope of the keel line, so no horizontal force
    import trimesh

    box = trimesh.creation.box(extents=(2.0, 0.4, 0.3))
    hull = hs.Hull.from_arrays(box.vertices, box.faces, mass=40.0)
    solver = hs.get_solver("zarnick", buoyancy_factor=1.0)
    r = hs.compute_force(
        hull, hs.Pose(0.1, math.radians(3.0)), hs.Motion(0.0, 0.0), slices=64,
        solver=solver, acceleration=0.0,
    )  # fmt: skip
    assert r.total_x == 0.0
    # Archimedes' force: the side view (a 2 x 0.3 m rectangle turned 3 deg, its lowest
    # corner 0.1 m under the water) below the water, times the 0.4 m width; measured 0.3 %
    th = math.radians(3.0)
    corners = [(-1.0, -0.15), (1.0, -0.15), (1.0, 0.15), (-1.0, 0.15)]
    pts = [(x * math.cos(th) - z * math.sin(th), x * math.sin(th) + z * math.cos(th))
           for x, z in corners]  # fmt: skip
    low = min(z for _, z in pts)
    pts = [(x, z - low - 0.1) for x, z in pts]
    under = []
    for (x1, z1), (x2, z2) in zip(pts, pts[1:] + pts[:1], strict=True):
        if z1 <= 0:
            under.append((x1, z1))
        if (z1 <= 0) != (z2 <= 0):
            under.append((x1 + (x2 - x1) * z1 / (z1 - z2), 0.0))
    area = 0.5 * abs(sum(x1 * z2 - x2 * z1 for (x1, z1), (x2, z2)
                         in zip(under, under[1:] + under[:1], strict=True)))  # fmt: skip
    assert r.total == pytest.approx(RHO * 9.81 * 0.4 * area, rel=5e-3)


def test_a_free_body_obeys_newton_with_the_forces_it_reports():
    # zarnick's buoyancy acts vertically, not along the section's normal: the accelerations
    # solved over heave, pitch and surge must be the reported force, moment and horizontal
    # force divided by the body's mass and inertia (Newton, to rounding)
    v, f = shapes.wedge_prism(length=1.0, beam=0.2, deadrise_deg=20.0)
    hull = hs.Hull.from_arrays(v, f, mass=5.0)
    solver = get_solver("zarnick")
    motion = hs.Motion(-2.0, 5.0, 0.3)
    s = hs.cut(hull, hs.Pose(0.06, math.radians(6)), slices=16)
    fluid = hs.Fluid()
    terms = momentum_terms(s, motion, solver, fluid, hull.cg[0])
    assert np.abs(terms.added.vertical).sum() > 0.0  # the buoyancy is there
    acc = solve_accelerations(terms, hull.mass, hull.pitch_inertia, fluid.g, (True, True, True))
    r = terms.result(acc, solver, fluid, motion, hull.cg[0])
    heave, pitch, surge = acc.as_array()
    assert hull.mass * heave == pytest.approx(r.total - hull.mass * fluid.g, rel=1e-9)
    assert hull.pitch_inertia * pitch == pytest.approx(r.moment, rel=1e-9)
    assert hull.mass * surge == pytest.approx(r.total_x, rel=1e-9)
