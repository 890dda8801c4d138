"""The fused evaluation of a held pitch (hullslice.forces.fused, its loops in
hullslice.held_loops) against numpy's path: the same force result, slice by slice (every
section array, the velocities, the solver's forces, diagnostics, validity and reasons, the
contours) to 1e-12, at poses over the whole depth of every catalogued body, and the same
histories. The loops run as Python (on every machine) and, where numba is installed,
compiled."""

from __future__ import annotations

import numpy as np
import pytest

import hullslice as hs
from hullslice import planecut_loops
from hullslice.errors import UnitsWarning
from hullslice.forces import fused, fused_arrays
from hullslice.motion import ForceModel
from hullslice.slicing.fixed import TABLE_AFTER
from hullslice.solvers.karman import ExtendedVonKarman
from hullslice.state import Motion, Pose

from .fake_solvers import ConstantSolver
from .test_bad_input import catamaran
from .test_planecut import BODIES


@pytest.fixture(autouse=True)
def _ieee_division():
    """The loops run as Python on numpy's scalars, whose division by zero or overflow warns
    where the compiled loops give the same infinity or NaN silently (numba's
    ``error_model="numpy"``)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        yield


#: Relative agreement of the two paths (numpy's sums are pairwise, the loops' in order).
RTOL = 1e-12


#: The loops as Python.
PYTHON = tuple(planecut_loops.LOOPS[name] for name in ("held", "pitch", "window"))


def _paths() -> list[tuple[str, object]]:
    paths: list[tuple[str, object]] = [("python", PYTHON)]
    if planecut_loops.available():
        paths.append(("numba", fused._loops()))
    return paths


def _models(hull, loops, slices: int = 48, **kw) -> tuple[ForceModel, ForceModel]:
    """A model evaluated by the loops and one by numpy's path, on the same hull."""
    fast = ForceModel(hull, slices=slices, slicing="fixed", **kw)
    fast._fused = fused.FusedEvaluation(fast, loops)
    slow = ForceModel(hull, slices=slices, slicing="fixed", **kw)
    slow._fused = None
    return fast, slow


def _close(a, b, scale: float) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype.kind in "biuO":
        return a.shape == b.shape and bool(np.all(a == b))
    return a.shape == b.shape and np.allclose(a, b, rtol=RTOL, atol=RTOL * scale, equal_nan=True)


def assert_same_result(a, b) -> None:
    """Two force results equal: every per-slice array, the sums, the contours."""
    sa, sb = a.sections, b.sections
    size = max(float(np.nanmax(np.abs(sb.x))), 1.0)
    for name in sa._ARRAYS:
        x, y = getattr(sa, name), getattr(sb, name)
        scale = size if x.dtype.kind == "f" else 0.0
        if name == "mass_per_metre":
            scale = max(float(np.nanmax(np.abs(y), initial=0.0)), 1e-300)
        assert _close(x, y, scale), (name, x, y)
    for name in ("draft", "pitch", "wetted_length", "z_cg", "deadrise_method"):
        x, y = getattr(sa, name), getattr(sb, name)
        assert x == y if isinstance(x, str) else abs(x - y) <= RTOL * size, name
    force = max(float(np.abs(b.loads.force_per_metre).max(initial=0.0)), 1e-300)
    assert _close(a.loads.force_per_metre, b.loads.force_per_metre, force)
    assert _close(a.velocity, b.velocity, 1.0)
    assert np.array_equal(a.loads.valid, b.loads.valid)
    assert list(a.loads.reason) == list(b.loads.reason)
    assert list(a.loads.diagnostics) == list(b.loads.diagnostics)
    for k, x in a.loads.diagnostics.items():
        y = b.loads.diagnostics[k]
        assert _close(x, y, max(float(np.nanmax(np.abs(y), initial=0.0)), 1.0)), k
    total = max(abs(b.total), float(np.abs(b.force).sum()), 1e-300)
    assert abs(a.total - b.total) <= RTOL * total
    assert abs(a.total_x - b.total_x) <= RTOL * total
    assert abs(a.moment - b.moment) <= RTOL * total * size
    assert (a.pose, a.motion, a.solver, a.x_cg) == (b.pose, b.motion, b.solver, b.x_cg)
    assert len(sa.polygons) == len(sb.polygons)
    for pa, pb in zip(sa.polygons, sb.polygons, strict=True):
        assert len(pa) == len(pb)
        assert all(np.array_equal(u, v) for u, v in zip(pa, pb, strict=True))


def _massive(hull):
    """The body with a mass (its own, or 1000 kg per cubic metre)."""
    return hull if hull.mass is not None else hull.with_mass(1000.0 * hull.volume)


#: One-piece bodies whose mass the fused evaluation spreads (every catalogued one).
NAMES = sorted(BODIES)


@pytest.mark.parametrize("path", [p for p, _ in _paths()])
@pytest.mark.parametrize("name", NAMES)
def test_the_fused_evaluation_equals_numpy_on_every_body(name, path):
    """At three pitches, drafts from a touch to most of the body's height, and motions
    down, up (a section leaving: no force, flagged) and turning: the same results; the
    loops serve many of them (the rest, handed back, are numpy's own)."""
    loops = dict(_paths())[path]
    hull = _massive(BODIES[name])
    served = tried = 0
    rng = np.random.default_rng(7)
    for pitch in (0.08, 0.3, -0.05):
        fast, slow = _models(hull, loops)
        fr = hs.geometry.frame(hull, pitch)
        depth = fr.highest - fr.lowest
        for _ in range(TABLE_AFTER):  # the kept cut's table is made from here on
            slow(Pose(0.3 * depth, pitch), Motion(-2.0, 10.0))
        for share in np.linspace(0.004, 0.9, 25):
            w = -float(rng.uniform(0.5, 3.0)) if rng.random() < 0.85 else 0.4
            motion = Motion(w, float(rng.uniform(0.0, 20.0)), float(rng.normal(0.0, 0.3)))
            pose = Pose(share * depth, pitch)
            tried += 1
            served += fast.fused.force(pose, motion) is not None
            assert_same_result(fast(pose, motion), slow(pose, motion))
            total, moment, total_x = fast.totals(pose, motion)
            want = slow(pose, motion)
            scale = max(abs(want.total), float(np.abs(want.force).sum()), 1e-300)
            assert abs(total - want.total) <= RTOL * scale
            assert abs(total_x - want.total_x) <= RTOL * scale
            assert abs(moment - want.moment) <= RTOL * scale * max(hull.size, 1.0)
    # a round body's table stops well under its widest point (its cost): numpy's path then
    assert served >= 10, (served, tried)


@pytest.mark.parametrize("path", [p for p, _ in _paths()])
@pytest.mark.parametrize("name", NAMES)
def test_the_fused_evaluation_at_new_pitches_equals_numpy(name, path):
    """At new pitches (each cut afresh by the exact kernel, as free pitch cuts them, without
    a waterline table): the same results, the wetted properties computed afresh by the
    loops."""
    loops = dict(_paths())[path]
    hull = _massive(BODIES[name])
    fast, slow = _models(hull, loops, cutter="exact")
    rng = np.random.default_rng(11)
    served = 0
    for pitch in rng.uniform(-0.05, 0.3, 14):
        fr = hs.geometry.frame(hull, pitch)
        depth = fr.highest - fr.lowest
        for share in (0.01, 0.08, 0.3, 0.6):
            motion = Motion(-float(rng.uniform(0.5, 3.0)), 15.0, float(rng.normal(0.0, 0.3)))
            pose = Pose(share * depth, pitch)
            want = slow(pose, motion)
            got = fast.fused.force(pose, motion)
            served += got is not None
            assert_same_result(fast(pose, motion) if got is None else got, want)
    assert served >= 20, served


@pytest.mark.parametrize("path", [p for p, _ in _paths()])
@pytest.mark.parametrize("name", ["fuselage_model.obj", "fuselage_full.obj", "fuselage"])
def test_the_first_contacts_slices_are_cut_by_the_fused_evaluation(name, path, monkeypatch):
    """At a touch of the water a partial slice with no wetted station near it (the first
    contact) is cut where it is, as numpy's path cuts it: the fused evaluation does it too,
    at a held pitch with its waterline table and at a new one without, and gives numpy's
    result (the slice's own section, its area and contours)."""
    loops = dict(_paths())[path]
    hull = _massive(BODIES[name])
    outline_of = fused.fixed_slicing.outline_of
    cuts = []

    def counted(*args, **kw):
        cuts.append(args[1])
        return outline_of(*args, **kw)

    for cutter in ("manifold3d", "exact"):
        fast, slow = _models(hull, loops, slices=32, cutter=cutter)
        for pitch in np.linspace(0.02, 0.25, 12):
            fr = hs.geometry.frame(hull, pitch)
            depth = fr.highest - fr.lowest
            if cutter == "manifold3d":  # its table, then the loops read it
                for _ in range(TABLE_AFTER):
                    slow(Pose(0.3 * depth, pitch), Motion(-2.0, 10.0))
            for share in (2e-4, 1e-3):
                pose, motion = Pose(share * depth, pitch), Motion(-1.5, 19.0, 0.1)
                monkeypatch.setattr(fused.fixed_slicing, "outline_of", counted)
                got = fast.fused.force(pose, motion)
                monkeypatch.setattr(fused.fixed_slicing, "outline_of", outline_of)
                assert got is not None, (cutter, pitch, share)
                assert_same_result(got, slow(pose, motion))
    assert len(cuts) >= 6, len(cuts)


@pytest.mark.parametrize("path", [p for p, _ in _paths()])
@pytest.mark.parametrize("name", ["fuselage_model.obj", "wedge_prism.stl"])
def test_a_free_pitch_history_equals_numpy(name, path, monkeypatch):
    """A run with free pitch (every stage a new pitch, cut afresh) by the loops against
    numpy's path: the same history."""
    loops = dict(_paths())[path]
    hull = _massive(BODIES[name])
    t_end = 0.03 * hull.size / 1.5
    run = dict(pitch_deg=6.0, forward_speed=10.0, slices=32, slicing="fixed", stop_on=(),
               dt=t_end / 40, free_pitch=True)  # fmt: skip
    monkeypatch.setattr(fused, "_loops", lambda: None)
    want = hs.simulate(hull.with_mass(hull.mass), -1.5, t_end, **run)
    monkeypatch.setattr(fused, "_loops", lambda: loops)
    got = hs.simulate(hull.with_mass(hull.mass), -1.5, t_end, **run)
    assert len(got) == len(want)
    assert float(np.abs(want.force).max()) > 0.0
    for key in ("force", "force_x", "moment", "draft", "pitch", "pitch_rate", "acceleration"):
        a, b = getattr(got, key), getattr(want, key)
        assert np.allclose(a, b, rtol=0.0, atol=1e-11 * (float(np.abs(b).max()) or 1.0)), key
    assert list(got.reason) == list(want.reason)


@pytest.mark.parametrize("path", [p for p, _ in _paths()])
@pytest.mark.parametrize(
    ("name", "kw"),
    [
        ("fuselage_model.obj", dict(velocity=-1.5, pitch_deg=6.0, forward_speed=19.0)),
        ("wedge_prism.stl", dict(velocity=-3.0, pitch_deg=2.0, forward_speed=4.0)),
        ("fuselage", dict(velocity=-2.0, pitch_deg=4.0, forward_speed=30.0)),
    ],
)
def test_a_held_pitch_history_equals_numpy(name, kw, path, monkeypatch):
    """A whole run at a held pitch with its stages evaluated by the loops (the three later
    stages of each step by their sums alone) against numpy's path: the same history."""
    loops = dict(_paths())[path]
    hull = _massive(BODIES[name])
    t_end = 0.04 * hull.size / abs(kw["velocity"])
    run = dict(kw, slices=40, slicing="fixed", stop_on=(), dt=t_end / 60)
    velocity = run.pop("velocity")
    monkeypatch.setattr(fused, "_loops", lambda: None)
    want = hs.simulate(hull.with_mass(hull.mass), velocity, t_end, **run)
    monkeypatch.setattr(fused, "_loops", lambda: loops)
    got = hs.simulate(hull.with_mass(hull.mass), velocity, t_end, **run)
    peak = float(np.abs(want.force).max())
    assert peak > 0.0
    assert len(got) == len(want)
    for key in ("force", "force_x", "draft", "velocity", "acceleration", "wetted_length"):
        a, b = getattr(got, key), getattr(want, key)
        scale = peak if key.startswith("force") else float(np.abs(b).max()) or 1.0
        assert np.allclose(a, b, rtol=0.0, atol=1e-11 * scale), key
    moment = float(np.abs(want.moment).max()) or 1.0
    assert np.allclose(got.moment, want.moment, rtol=0.0, atol=1e-11 * moment)
    assert np.array_equal(got.valid, want.valid)
    assert list(got.reason) == list(want.reason)
    assert np.array_equal(got.slices, want.slices)


class _OwnPileUp(ExtendedVonKarman):
    name = "own-pile-up"

    def pile_up(self, deadrise):
        return np.full_like(deadrise, 1.2)


def test_the_fused_evaluation_serves_only_what_its_loops_describe(monkeypatch):
    """Numpy's path serves every model the loops do not describe: other slicing, cache,
    deadrise estimator, solver, a mass distribution, a body of several pieces, and a
    machine without the compiled loops."""
    monkeypatch.setattr(fused, "_loops", lambda: PYTHON)
    hull = _massive(BODIES["wedge"])
    assert fused.fused_for(ForceModel(hull, slicing="fixed")) is not None
    for kw in (
        dict(slicing="wetted"),
        dict(slicing="fixed", cache=False),
        dict(slicing="fixed", deadrise="waterline-slope"),
        dict(slicing="fixed", solver=ConstantSolver),
        dict(slicing="fixed", solver=_OwnPileUp),
    ):
        assert fused.fused_for(ForceModel(hull, **kw)) is None, kw
    v, f = catamaran()
    cat = hs.Hull.from_arrays(v, f).with_mass(50.0)
    assert fused.fused_for(ForceModel(cat, slicing="fixed")) is None
    x = np.linspace(0.0, 1.0, 11)
    spread = hull.with_mass(mass_distribution=hs.MassDistribution(x=x, mass_per_metre=10.0 + x))
    assert fused.fused_for(ForceModel(spread, slicing="fixed")) is None
    monkeypatch.setattr(fused, "_loops", lambda: None)
    assert fused.fused_for(ForceModel(hull, slicing="fixed")) is None


@pytest.mark.parametrize("name", NAMES)
def test_the_keel_arrays_by_the_loops_equal_numpy(name):
    """The fused evaluation's arrays of a keel line, built by
    :func:`~hullslice.keel_loops.keel_arrays_loops` (as Python, and compiled where numba
    serves) at pitches from nose down to well up: numpy's arrays, to the bit."""
    hull = BODIES[name]
    packs = [planecut_loops.LOOPS["keel_arrays"]]
    if planecut_loops.available():
        packs.append(planecut_loops.compiled("keel_arrays"))
    for pitch in (-0.2, 0.0, 0.08, 0.3, 0.6):
        fr = hs.geometry.frame(hull, pitch)
        want = fused_arrays.keel_arrays(fr)
        for pack in packs:
            got = fused_arrays.keel_arrays(fr, pack)
            assert got["has_chords"] == want["has_chords"]
            for key in ("keel", "runs", "chords"):
                assert got[key].shape == want[key].shape, (key, pitch)
                assert np.array_equal(got[key], want[key], equal_nan=True), (key, pitch)
                assert not np.any(np.signbit(got[key]) != np.signbit(want[key])), (key, pitch)


def test_numba_switched_off_is_read_when_a_model_first_evaluates(monkeypatch):
    """``HULLSLICE_NUMBA=0`` keeps numpy's path for the models made while it is set."""
    monkeypatch.setenv("HULLSLICE_NUMBA", "0")
    hull = _massive(BODIES["wedge"])
    assert fused.fused_for(ForceModel(hull, slicing="fixed")) is None


def test_the_loops_cache_sees_their_helpers():
    """numba's cache of a compiled function is stale when its own file changes; the fused
    loops call helpers in other files, whose digest their file holds."""
    import hashlib
    from pathlib import Path

    from hullslice import held_loops

    root = Path(held_loops.__file__).parent
    names = ("slices_loops.py", "wetted_loops.py", "loops_layout.py")
    digest = hashlib.sha256(b"".join((root / n).read_bytes() for n in names)).hexdigest()[:16]
    assert held_loops.HELPERS_DIGEST == digest, (
        f"set HELPERS_DIGEST = {digest!r} in hullslice/held_loops.py (its helpers changed)"
    )


@pytest.mark.parametrize("path", [p for p, _ in _paths()])
def test_one_model_serves_two_threads(path):
    """A model shared by the threads of a Dask worker (the compiled loops release the GIL):
    each thread's sums are its own pose's."""
    import threading

    loops = dict(_paths())[path]
    hull = _massive(BODIES["fuselage_model.obj"])
    fast, slow = _models(hull, loops, slices=40)
    fr = hs.geometry.frame(hull, 0.1)
    depth = fr.highest - fr.lowest
    motion = Motion(-2.0, 10.0)
    poses = [Pose(share * depth, 0.1) for share in (0.25, 0.35)]
    for _ in range(TABLE_AFTER + 2):
        slow(Pose(0.4 * depth, 0.1), motion)
    want = [fast.totals(pose, motion) for pose in poses]
    assert all(fast.fused.totals(pose, motion) is not None for pose in poses)
    wrong = [0, 0]

    def work(i: int) -> None:
        for _ in range(2000 if path == "numba" else 20):
            wrong[i] += fast.totals(poses[i], motion) != want[i]

    threads = [threading.Thread(target=work, args=(i,)) for i in (0, 1)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert wrong == [0, 0]


@pytest.mark.parametrize("path", [p for p, _ in _paths()])
def test_what_numpy_refuses_or_leaves_out_the_loops_do_too(path):
    """A mass so large that the slices' forces overflow: numpy's path refuses the solver's
    output, and the loops hand it back (the same SolverError, in the sums too); a water a
    rounding above the keel, where no section is given to the solver: no diagnostics."""
    loops = dict(_paths())[path]
    base = BODIES["cylinder"]
    _, area = hs.sections.area_curve(base, 40)
    with pytest.warns(UnitsWarning):  # the density is refused by no check: warned of
        hull = base.with_mass(5e307 / area.max() * base.volume)
    fast, slow = _models(hull, loops, slices=40)
    fr = hs.geometry.frame(hull, 0.05)
    pose, motion = Pose(0.4 * (fr.highest - fr.lowest), 0.05), Motion(-2.0, 5.0)
    for model in (slow, fast):
        for _ in range(TABLE_AFTER + 1):
            with pytest.raises(hs.SolverError, match="extended-von-karman"):
                model(pose, motion)
    assert fast.fused.totals(pose, motion) is None
    with pytest.raises(hs.SolverError):
        fast.totals(pose, motion)
    hull = _massive(base)
    fast, slow = _models(hull, loops, slices=40)
    pose = Pose(float(np.spacing(abs(hs.geometry.frame(hull, 0.0).lowest))), 0.0)
    want, got = slow(pose, motion), fast.fused.force(pose, motion)
    assert got is not None and got.loads.diagnostics == want.loads.diagnostics == {}
    assert_same_result(got, want)


def test_a_keel_under_an_overhang_is_a_wall_by_the_loops_too(monkeypatch):
    # tests/test_pitch.py's overhang: the wetted loops (as Python, and compiled) give its
    # port side's 90 deg as numpy does, and a held pitch's fused run, its properties from
    # the waterline table's loops, equals numpy's
    from hullslice.kernel.outline import Outline
    from hullslice.kernel.wetted import wetted_properties
    from hullslice.wetted_loops import wetted_loops

    from .test_pitch import OVERHANG, overhang_prism

    outline = Outline.of([(OVERHANG,)], 1e-9)
    ref = wetted_properties(outline, 0.0, 1e-9, "wedge")
    assert ref["deadrise_port"][0] == np.pi / 2
    paths = [wetted_loops]
    if planecut_loops.available():
        paths.append(planecut_loops.compiled("wetted"))
    for loops in paths:
        got = wetted_properties(outline, 0.0, 1e-9, "wedge", loops)
        for key in ("deadrise", "deadrise_port", "deadrise_stbd"):
            assert got[key][0] == ref[key][0], key
    if not planecut_loops.available():
        pytest.skip("the fused run's compiled path needs numba")
    hull = overhang_prism()
    runs = []
    for flag in ("0", "1"):
        monkeypatch.setenv("HULLSLICE_NUMBA", flag)
        runs.append(hs.simulate(hull, -2.0, 0.02, dt=0.002, slices=4, slicing="fixed",
                                stop_on=()))  # fmt: skip
    assert np.max(np.abs(runs[0].force)) > 0.0
    np.testing.assert_allclose(runs[1].force, runs[0].force, rtol=1e-12, atol=0.0)
