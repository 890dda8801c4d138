"""One unit convention for angles: every angle parameter of the Python API says its unit.

The API's angles are in rad under names that say so (``pitch_rad``, ``pitch_rate_rad_s``,
``pitch_acceleration_rad_s2``, ``pitch_rad_s2``), or in degrees under ``_deg`` names where
they are taken too; the command line, case files and :class:`~hullslice.Study` are in
degrees. The former bare names still work for one release, with a
:class:`DeprecationWarning` that names the new one, and give the same results.
"""

from __future__ import annotations

import dataclasses
import inspect
import math

import numpy as np
import pytest

import hullslice as hs
from hullslice.motion import ForceModel

#: Parameter names that would leave an angle's unit unsaid.
BARE = frozenset({"pitch", "pitch_rate", "pitch_acceleration", "angle", "deadrise", "theta"})

#: The justified exceptions: ``(callable, parameter) -> why``.
EXCEPTIONS: dict[tuple[str, str], str] = {
    # a string option: the name of the deadrise estimator ("wedge", ...), not an angle
    **{
        (name, "deadrise"): "the deadrise estimator's name (str)"
        for name in (
            "compute_force",
            "convergence",
            "cut",
            "simulate",
            "prescribed",
            "ForceModel",
            "Study",
            "Sections",
        )
    },
    # results the library builds (never the user): their arrays keep their names, in rad
    ("History", "pitch"): "a result's (k,) array, rad (documented)",
    ("History", "pitch_rate"): "a result's (k,) array, rad/s (documented)",
    ("Sections", "pitch"): "a result's field, rad (documented)",
    # the solver protocol: called positionally by the library, overridden by plugins
    ("CurveSolver.pile_up", "deadrise"): "solver protocol, (n,) array in rad",
    ("MomentumSolver.pile_up", "deadrise"): "solver protocol, (n,) array in rad",
    ("FreeFallMomentumSolver.pile_up", "deadrise"): "solver protocol, (n,) array in rad",
    # the aerodynamics protocol: called positionally by the integrator, overridden by users
    ("Aerodynamics.start", "theta"): "aerodynamics protocol, rad",
    ("Aerodynamics.forces", "theta"): "aerodynamics protocol, rad",
    ("Coefficients.start", "theta"): "aerodynamics protocol, rad",
    ("Coefficients.forces", "theta"): "aerodynamics protocol, rad",
    ("WeightLift.start", "theta"): "aerodynamics protocol, rad",
    ("WeightLift.forces", "theta"): "aerodynamics protocol, rad",
}


def _public_callables():
    """``(name, callable)`` of ``hullslice.__all__``, with the public methods of its classes."""
    for name in hs.__all__:
        obj = getattr(hs, name)
        if inspect.isclass(obj):
            yield name, obj
            for member, f in inspect.getmembers(obj, callable):
                if not member.startswith("_") and not inspect.isclass(f):
                    yield f"{name}.{member}", f
        elif callable(obj):
            yield name, obj
    yield "ForceModel.draft", ForceModel.draft


def test_no_public_parameter_names_an_angle_without_its_unit():
    bare = []
    for name, obj in _public_callables():
        try:
            params = inspect.signature(obj).parameters
        except (TypeError, ValueError):
            continue
        bare += [(name, p) for p in params if p in BARE and (name, p) not in EXCEPTIONS]
    assert not bare, f"angle parameters without their unit: {bare}"
    # and the exceptions are still there (a stale one is removed from the list)
    names = dict(_public_callables())
    for name, param in EXCEPTIONS:
        assert param in inspect.signature(names[name]).parameters, (name, param)


def test_the_state_dataclasses_say_their_angles_units():
    assert [f.name for f in dataclasses.fields(hs.Pose)] == ["draft", "pitch_rad"]
    assert [f.name for f in dataclasses.fields(hs.Motion)] == [
        "velocity",
        "forward_speed",
        "pitch_rate_rad_s",
    ]
    assert [f.name for f in dataclasses.fields(hs.Acceleration)] == [
        "vertical",
        "pitch_rad_s2",
        "forward",
    ]
    pose, motion = hs.Pose(0.5, 0.1), hs.Motion(-1.0, 2.0, 0.3)  # positional: unchanged
    assert (pose.pitch, pose.pitch_rad, pose.pitch_deg) == (0.1, 0.1, math.degrees(0.1))
    assert (motion.pitch_rate, motion.pitch_rate_deg_s) == (0.3, math.degrees(0.3))
    assert hs.Acceleration(0.0, 0.2).pitch == hs.Acceleration(pitch_rad_s2=0.2).pitch_rad_s2
    assert dataclasses.replace(pose, draft=0.2) == hs.Pose(draft=0.2, pitch_rad=0.1)


@pytest.mark.parametrize(
    ("make", "old", "new"),
    [
        (lambda **kw: hs.Pose(0.5, **kw), "pitch", "pitch_rad"),
        (lambda **kw: hs.Motion(-1.0, 2.0, **kw), "pitch_rate", "pitch_rate_rad_s"),
        (lambda **kw: hs.Acceleration(1.0, **kw), "pitch", "pitch_rad_s2"),
    ],
)
def test_the_former_keywords_of_the_states_warn_and_mean_the_same(make, old, new):
    with pytest.warns(DeprecationWarning, match=f"the keyword {old}= is deprecated: give {new}="):
        before = make(**{old: 0.1})
    assert before == make(**{new: 0.1})
    with pytest.raises(hs.InputError, match=f"give {new}= only"):
        make(**{old: 0.1, new: 0.1})


def test_simulate_takes_the_pitch_in_rad_or_degrees_and_its_former_names(paper_hull):
    run = {"dt": 2e-4, "slices": 8, "forward_speed": 3.0}
    pitch, rate = math.radians(3.0), math.radians(20.0)
    now = hs.simulate(paper_hull, -4.0, 0.004, pitch_rad=pitch, pitch_rate_rad_s=rate, **run)
    with pytest.warns(DeprecationWarning) as record:
        before = hs.simulate(paper_hull, -4.0, 0.004, pitch=pitch, pitch_rate=rate, **run)
    said = sorted(str(w.message) for w in record)
    assert len(said) == 2
    assert said[0].startswith("simulate: the keyword pitch= is deprecated: give pitch_rad=")
    assert said[0].endswith("(the same value, in rad)")
    assert "give pitch_rate_rad_s= (the same value, in rad/s)" in said[1]
    deg = hs.simulate(paper_hull, -4.0, 0.004, pitch_deg=3.0, pitch_rate_deg_s=20.0, **run)
    for other in (before, deg):
        for name in ("force", "moment", "pitch", "draft", "velocity"):
            np.testing.assert_allclose(
                getattr(other, name), getattr(now, name), rtol=1e-12, atol=1e-12
            )
    with pytest.raises(hs.InputError, match="give pitch_rad= or pitch_deg=, not both"):
        hs.simulate(paper_hull, -4.0, 0.004, pitch_rad=0.05, pitch_deg=3.0, **run)
    with pytest.raises(hs.InputError, match="pitch_deg 'x' is not a number"):
        hs.simulate(paper_hull, -4.0, 0.004, pitch_deg="x", **run)


def test_the_former_names_of_the_methods_and_of_study_warn(paper_hull):
    model = ForceModel(paper_hull, slices=8)
    with pytest.warns(DeprecationWarning, match="give pitch_rad="):
        assert model.draft(0.0, pitch=0.05) == model.draft(0.0, pitch_rad=0.05)
    study = hs.Study(command="force", mesh="meshes/paper_prism.stl", mass=1.0, draft=0.03,
                     velocity=-3.0, pitch_deg=3.0, pitch_rate_deg_s=10.0)  # fmt: skip
    assert study.pitch_rad == math.radians(3.0)
    assert study.pitch_rate_rad_s == math.radians(10.0)
    with pytest.warns(DeprecationWarning, match="Study.pitch is deprecated: read pitch_rad"):
        assert study.pitch == study.pitch_rad
    with pytest.warns(DeprecationWarning, match="read pitch_rate_rad_s"):
        assert study.pitch_rate == study.pitch_rate_rad_s


def test_the_mass_on_planes_takes_the_former_pitch_keyword():
    dist = hs.MassDistribution(
        x=np.array([0.0, 1.0, 2.0]), mass_per_metre=np.array([1.0, 2.0, 3.0])
    )
    x_rel = np.array([-0.5, 0.0, 0.5])
    now = dist.on_planes(x_rel, pitch_rad=0.1, cg=(1.0, 0.2), line_z=0.0)
    with pytest.warns(DeprecationWarning, match="MassDistribution.on_planes: the keyword pitch="):
        before = dist.on_planes(x_rel, pitch=0.1, cg=(1.0, 0.2), line_z=0.0)
    np.testing.assert_allclose(before, now, rtol=1e-12)
    np.testing.assert_array_equal(dist.on_planes(x_rel, 0.1, (1.0, 0.2), 0.0), now)


def test_results_give_their_angles_in_degrees_too(paper_hull):
    h = hs.simulate(
        paper_hull, -4.0, 0.004, dt=2e-4, slices=8, pitch_deg=3.0, pitch_rate_deg_s=20.0
    )
    np.testing.assert_allclose(h.pitch_deg, np.degrees(h.pitch), rtol=1e-15)
    np.testing.assert_allclose(h.pitch_rate_deg_s, np.degrees(h.pitch_rate), rtol=1e-15)
    assert h.pitch_deg[0] == pytest.approx(3.0, rel=1e-14)
    s = hs.cut(paper_hull, hs.Pose(0.03, math.radians(2.0)), slices=8)
    assert s.pitch_deg == pytest.approx(2.0, rel=1e-14)
