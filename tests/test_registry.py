"""Solvers are found through entry points of group 'hullslice.solvers', never hard-wired."""

from __future__ import annotations

import warnings
from importlib.metadata import EntryPoint, entry_points

import numpy as np
import pytest

import hullslice as hs
from hullslice.solvers import registry

GROUP = "hullslice.solvers"


class FakeDist:
    def __init__(self, name: str, version: str = "1.0") -> None:
        self.metadata = {"Name": name}
        self.version = version


def ep(name: str, value: str, dist: str = "fake-plugin") -> EntryPoint:
    e = EntryPoint(name=name, value=value, group=GROUP)
    vars(e).update(dist=FakeDist(dist))  # as importlib.metadata does for installed ones
    return e


DEFAULT = ep("extended-von-karman", "hullslice.solvers.karman:ExtendedVonKarman", "hullslice")
CONSTANT = ep("constant", "tests.fake_solvers:ConstantSolver")


def test_default_solver_is_an_installed_entry_point():
    eps = {e.name: e for e in entry_points(group=GROUP)}
    assert "extended-von-karman" in eps
    e = eps["extended-von-karman"]
    assert e.value == "hullslice.solvers.karman:ExtendedVonKarman"
    assert e.dist.metadata["Name"] == "hullslice"
    assert e.load() is hs.solvers.ExtendedVonKarman


def test_without_entry_points_even_the_default_is_unknown(fake_entry_points):
    fake_entry_points([])
    with pytest.raises(hs.UnknownSolverError, match="installed solvers: none"):
        hs.get_solver()
    assert hs.list_solvers() == []


def test_a_registered_solver_is_found_and_used(fake_entry_points, paper_hull):
    fake_entry_points([DEFAULT, CONSTANT])
    solver = hs.get_solver("constant", accel=50.0)
    assert type(solver).__name__ == "ConstantSolver"
    r = hs.compute_force(paper_hull, 0.0383, -3.0, slices=8, solver="constant")
    # f = M * 100 N/m over the wetted length: the wetted part's mass times 100 m/s^2
    wet_mass = (r.sections.mass_per_metre * r.sections.dx).sum()
    assert r.total == pytest.approx(100.0 * wet_mass, rel=1e-12)


def test_unknown_name_lists_the_installed_solvers(fake_entry_points):
    fake_entry_points([DEFAULT, CONSTANT])
    with pytest.raises(hs.UnknownSolverError) as err:
        hs.get_solver("wagnr")
    assert "'wagnr'" in str(err.value)
    assert "constant, extended-von-karman" in str(err.value)
    assert isinstance(err.value, LookupError)


def test_broken_plugins_are_reported_and_the_others_work(fake_entry_points):
    fake_entry_points(
        [
            DEFAULT,
            ep("missing", "tests.no_such_module:Solver", "broken-dist"),
            ep("not-a-solver", "tests.fake_solvers:NotASolver", "odd-dist"),
        ]
    )
    # the error names the plugin and its distribution (no warning repeating it)
    with pytest.raises(hs.PluginError, match=r"'missing'.*broken-dist.*failed to load"):
        hs.get_solver("missing")
    with pytest.raises(hs.PluginError, match=r"odd-dist.*not a subclass of hullslice.Solver"):
        hs.get_solver("not-a-solver")
    infos = {i.name: i for i in hs.list_solvers()}
    assert infos["missing"].status == "broken"
    assert "ModuleNotFoundError" in infos["missing"].error
    assert infos["not-a-solver"].status == "broken"
    assert infos["extended-von-karman"].status == "ok"
    assert isinstance(hs.get_solver(), hs.solvers.ExtendedVonKarman)


def test_duplicate_names_resolve_deterministically_with_a_warning(fake_entry_points):
    imposter = ep("extended-von-karman", "tests.fake_solvers:ConstantSolver", "aaa-first")
    for order in ([imposter, DEFAULT], [DEFAULT, imposter]):
        with pytest.warns(hs.PluginWarning, match="two solvers are registered"):
            fake_entry_points(order)
            registry._registry()
        # hullslice's own registration wins whatever the order
        assert isinstance(hs.get_solver("extended-von-karman"), hs.solvers.ExtendedVonKarman)
    statuses = sorted(i.status for i in hs.list_solvers())
    assert statuses == ["ok", "shadowed"]


def test_between_two_plugins_the_first_distribution_by_name_wins(fake_entry_points):
    a = ep("dup", "tests.fake_solvers:ConstantSolver", "alpha")
    b = ep("dup", "tests.fake_solvers:NaNSolver", "beta")
    for order in ([a, b], [b, a]):
        with pytest.warns(hs.PluginWarning, match="alpha"):
            fake_entry_points(order)
            registry._registry()
        assert type(hs.get_solver("dup")).__name__ == "ConstantSolver"


def test_plugins_can_be_switched_off(fake_entry_points, monkeypatch):
    monkeypatch.setenv("HULLSLICE_NO_PLUGINS", "1")
    fake_entry_points([DEFAULT, CONSTANT])
    assert [i.name for i in hs.list_solvers()] == ["extended-von-karman"]
    with pytest.raises(hs.UnknownSolverError, match="plugins are off"):
        hs.get_solver("constant")


def test_solver_given_as_class_or_instance(paper_hull):
    from .fake_solvers import ConstantSolver

    a = hs.compute_force(paper_hull, 0.02, -3.0, slices=4, solver=ConstantSolver)
    b = hs.compute_force(paper_hull, 0.02, -3.0, slices=4, solver=ConstantSolver(accel=100.0))
    assert a.total == b.total
    with pytest.raises(hs.InputError, match="no option 'acel'"):
        ConstantSolver(acel=1.0)


@pytest.mark.parametrize(
    ("cls", "message"),
    [
        ("NaNSolver", "non-finite force"),
        ("WrongShapeSolver", "shape"),
        ("RaisingSolver", "ZeroDivisionError: boom"),
    ],
)
def test_faulty_solver_output_is_a_clear_error(paper_hull, cls, message):
    from . import fake_solvers

    with pytest.raises(hs.SolverError, match=message):
        hs.compute_force(paper_hull, 0.02, -3.0, slices=4, solver=getattr(fake_solvers, cls))


def test_dry_sections_get_no_force_and_are_not_passed_to_the_solver(paper_hull):
    seen = []

    from .fake_solvers import ConstantSolver

    class Spy(ConstantSolver):
        def section_loads(self, sections, velocity, fluid):
            seen.append(sections.penetration.copy())
            return super().section_loads(sections, velocity, fluid)

    stations = np.linspace(0.01, 0.34, 12)  # the draft wets only the first part
    secs = hs.cut(paper_hull, 0.02, stations=stations)
    loads = hs.forces.evaluate(Spy(), secs, -3.0, hs.Fluid())
    assert np.all(seen[0] > 0)
    assert len(seen[0]) == secs.wetted.sum() < len(secs)
    assert np.all(loads.force_per_metre[~secs.wetted] == 0.0)


def test_a_solver_cannot_write_into_the_callers_velocities(paper_hull):
    from .fake_solvers import ConstantSolver

    class Scribbler(ConstantSolver):
        def section_loads(self, sections, velocity, fluid):
            velocity *= 2.0  # not allowed: the caller's array
            return super().section_loads(sections, velocity, fluid)

    secs = hs.cut(paper_hull, 0.02, 4)
    velocity = np.full(len(secs), -3.0)
    with pytest.raises(hs.SolverError, match="read-only"):
        hs.forces.evaluate(Scribbler(), secs, velocity, hs.Fluid())
    assert np.all(velocity == -3.0)


def test_no_warning_on_a_clean_registry():
    registry.refresh()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        hs.list_solvers()
