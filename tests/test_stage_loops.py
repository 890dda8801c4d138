"""A new pitch's sums in one compiled call (:func:`hullslice.planecut_loops.stage_loops`,
served by :meth:`hullslice.forces.fused.FusedEvaluation.stage_totals`) against the same
steps one by one (a frame made, its stations cut and outlined, the fused evaluation's
loops): the same sums to the last bit on every catalogued body, at pitches, drafts and
motions drawn at random; what it leaves to the steps one by one; and the digest that keeps
numba's cache of it fresh. The call is compiled only: it needs numba."""

from __future__ import annotations

import hashlib
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import hullslice as hs
from hullslice import planecut_loops
from hullslice.contour_loops import empty_memo
from hullslice.forces import fused
from hullslice.geometry import FRAMES, frame
from hullslice.motion import ForceModel
from hullslice.state import Motion, Pose

from .test_planecut import BODIES, MESHES

needs_numba = pytest.mark.skipif(not planecut_loops.available(), reason="needs numba")


def _massive(hull):
    return hull if hull.mass is not None else hull.with_mass(1000.0 * hull.volume)


def _model(hull, slices: int = 32) -> ForceModel:
    model = ForceModel(hull, slices=slices, slicing="fixed", cutter="exact")
    assert model.fused is not None and model.fused.stage is not None
    return model


def assert_same_sums(got, want, size: float) -> None:
    """The vertical force, the moment about the centre of gravity and the horizontal force
    of the one call (``got``) and of the steps one by one (``want``) within 1e-12 of their
    scale (the largest force, or moment over the body's ``size``): the call's keel line
    holds the break points the evaluation reads, its running sums (the slope's offsets,
    the bend, the bottom's rise) from the line's first point there rather than the
    whole line's, so that the slopes and curvatures it gives differ by rounding."""
    scale = max(abs(want[0]), abs(want[2]), abs(want[1]) / size, 1e-300)
    for i, (a, b) in enumerate(zip(got, want, strict=True)):
        assert abs(a - b) <= 1e-12 * scale * (size if i == 1 else 1.0), (got, want)


@needs_numba
@pytest.mark.parametrize("name", sorted(BODIES))
def test_a_new_pitchs_sums_in_one_call_equal_the_steps_one_by_one(name):
    """At 30 new pitches from -0.1 to 0.35 rad, each at a draft from a touch to most of
    the body's height and a motion down (sometimes up: a section leaving), the one call's
    sums equal those of a frame of the same pitch evaluated by the fused loops, within
    1e-12 (:func:`assert_same_sums`); most poses are served by the call (the rest are
    handed back by both)."""
    hull = _massive(BODIES[name])
    twin = hull.with_mass(hull.mass)  # the same body, its own frames
    one, steps = _model(hull), _model(twin)
    rng = np.random.default_rng(5)
    served = 0
    for pitch in rng.uniform(-0.1, 0.35, 30):
        fr = frame(twin, pitch)
        depth = fr.highest - fr.lowest
        draft = float(rng.uniform(0.002, 0.9)) * depth
        z_cg = -(fr.lowest + draft)
        w = -float(rng.uniform(0.3, 3.0)) if rng.random() < 0.85 else 0.5
        u, q = float(rng.uniform(0.0, 20.0)), float(rng.normal(0.0, 0.3))
        got = one.fused.stage_totals(pitch, z_cg, w, u, q)
        want = steps.fused.totals_at(fr, max(0.0, -(fr.lowest + z_cg)), w, u, q)
        if got is None:
            continue
        served += 1
        assert want is not None
        assert_same_sums(got, want, hull.size)
    assert served >= 15, served


@needs_numba
def test_a_framed_pitch_goes_the_steps_one_by_one_and_a_dry_body_sums_nothing():
    """A pitch that has a frame keeps its kept cut and waterline tables: the call leaves it
    to them. A body clear of the water (a ditching's skip) has no slice: the call's sums
    are zero, numpy's path's (no section summed), and no frame is made for its pitch, met
    again or not (the two middle stages of a step in the air share a pitch)."""
    hull = _massive(BODIES["fuselage_model.obj"])
    model = _model(hull)
    fr = frame(hull, 0.07)
    z_cg = -(fr.lowest + 0.2 * (fr.highest - fr.lowest))
    assert model.fused.stage_totals(0.07, z_cg, -1.0, 10.0, 0.0) is None
    high = 10.0 * hull.size
    for _ in range(2):
        got = model.fused.stage_totals(0.071, high, -1.0, 10.0, 0.0)
        assert got == (0.0, 0.0, 0.0) and [np.copysign(1.0, v) for v in got] == [1.0, 1.0, 1.0]
    assert hull.cache[FRAMES].get(0.071) is None
    twin = _model(hull.with_mass(hull.mass))
    r = twin._numpy(Pose(twin.draft(high, 0.071), 0.071), Motion(-1.0, 10.0, 0.0))
    want = (r.total, r.moment, r.total_x)
    assert want == (0.0, 0.0, 0.0)
    assert [np.copysign(1.0, v) for v in want] == [1.0, 1.0, 1.0]  # +0.0 too


@needs_numba
@pytest.mark.parametrize("above", [0.0, 0.3])
def test_a_dry_bodys_result_in_one_call_is_numpys_with_no_section(above):
    """The first stage's result (the record's) of a body clear of the water, or just
    touching it, is made from the call as numpy's path makes it: no section, every array
    empty of numpy's type, the water's level, the draft and the contours' origin the
    same to the bit; and no frame is made for its pitch."""
    hull = _massive(BODIES["fuselage_model.obj"])
    model, twin = _model(hull), _model(hull.with_mass(hull.mass))
    motion = Motion(-1.0, 10.0, 0.2)
    for pitch in (-0.05, 0.073, 0.2):
        fr = frame(twin.hull, pitch)
        z_cg = -fr.lowest + above * (fr.highest - fr.lowest)
        got = model.fused.stage_result(z_cg, pitch, motion)
        assert got is not None and hull.cache[FRAMES].get(pitch) is None
        r, pose = got
        want = twin._numpy(Pose(twin.draft(z_cg, pitch), pitch), motion)
        assert pose == want.pose == r.pose == Pose(0.0, pitch)
        s, t = r.sections, want.sections
        assert len(s) == len(t) == 0 and len(s.polygons) == len(t.polygons) == 0
        for name in s._ARRAYS:
            a, b = getattr(s, name), getattr(t, name)
            assert a.dtype == b.dtype and a.shape == b.shape == (0,), name
        for name in ("draft", "pitch", "wetted_length", "z_cg", "deadrise_method"):
            assert getattr(s, name) == getattr(t, name), name
        assert np.array_equal(s.polygons._shift, t.polygons._shift)
        assert s.polygons._scale == t.polygons._scale
        for a, b in ((r.loads.force_per_metre, want.loads.force_per_metre),
                     (r.loads.valid, want.loads.valid), (r.loads.reason, want.loads.reason),
                     (r.velocity, want.velocity)):  # fmt: skip
            assert a.dtype == b.dtype and a.shape == b.shape == (0,)
        assert r.loads.diagnostics == want.loads.diagnostics == {}
        assert (r.solver, r.fluid, r.motion, r.x_cg) == (want.solver, want.fluid, want.motion,
                                                          want.x_cg)  # fmt: skip
        assert (r.total, r.moment, r.total_x) == (want.total, want.moment, want.total_x)


@needs_numba
@pytest.mark.parametrize("name", ["fuselage_model.obj", "fuselage_full.obj", "fuselage"])
def test_the_first_contact_is_cut_in_one_call_as_numpys_path_cuts_it(name, monkeypatch):
    """At a touch of the water a partial slice with no wetted station near it (the first
    contact) is cut where it is, as numpy's path cuts it. The one call cuts it too: its
    result (the slice's own section, its area, its contours) and its sums are those of a
    frame of the same pitch evaluated by the fused loops, to the bit, and numpy's, to 1e-12
    of the forces (numpy sums pairwise)."""
    from hullslice.slicing import fixed

    from .test_fused import assert_same_result

    hull = _massive(BODIES[name])
    twin = hull.with_mass(hull.mass)
    one, steps = _model(hull), _model(twin)
    with_fresh, fresh = fixed._with_fresh, []

    def counted(*args, **kw):
        fresh.append(1)
        return with_fresh(*args, **kw)

    monkeypatch.setattr(fixed, "_with_fresh", counted)
    for pitch in np.linspace(0.02, 0.25, 12):
        for j, share in enumerate((2e-4, 1e-3, 4e-3)):
            p = float(pitch) + 1e-7 * j  # a new pitch for each call
            fr = frame(twin, p)
            z_cg = -(fr.lowest + share * (fr.highest - fr.lowest))
            pose, motion = Pose(steps.draft(z_cg, p), p), Motion(-1.5, 19.0, 0.1)
            got = one.fused.stage_result(z_cg, p, motion)
            assert got is not None
            before = len(fresh)
            assert_same_result(got[0], steps._numpy(pose, motion))
            if len(fresh) == before:
                continue  # not the first contact
            want = steps.fused.force(pose, motion)
            assert want is not None
            assert_same_result(got[0], want)
            assert_same_sums((got[0].total, got[0].moment, got[0].total_x),
                             (want.total, want.moment, want.total_x), hull.size)  # fmt: skip
            q = p + 1e-9  # the sums alone, at a pitch of its own
            sums = one.fused.stage_totals(q, z_cg, -1.5, 19.0, 0.1)
            assert_same_sums(sums, steps.fused.totals_at(frame(twin, q), steps.draft(z_cg, q),
                                                         -1.5, 19.0, 0.1), hull.size)  # fmt: skip
    assert len(fresh) >= 3, len(fresh)


@needs_numba
def test_a_free_pitch_run_takes_its_stages_from_the_one_call(monkeypatch):
    """In a free-pitch run the three later stages of a step are new pitches whose sums
    alone are needed: the call serves them, and the history is the same within 1e-12 of
    its peaks as with the call switched off (see :func:`assert_same_sums`)."""
    hull = _massive(BODIES["fuselage_model.obj"])
    run = dict(pitch_deg=6.0, forward_speed=19.0, slices=32, slicing="fixed", stop_on=(),
               dt=1e-3, free_pitch=True)  # fmt: skip
    calls = []
    stage_totals = fused.FusedEvaluation.stage_totals

    def counted(self, *args):
        out = stage_totals(self, *args)
        calls.append(out is not None)
        return out

    monkeypatch.setattr(fused.FusedEvaluation, "stage_totals", counted)
    got = hs.simulate(hull.with_mass(hull.mass), -1.5, 0.03, **run)
    assert sum(calls) >= 0.9 * 3 * (len(got) - 1)
    monkeypatch.setattr(fused.FusedEvaluation, "stage_totals", lambda self, *a: None)
    want = hs.simulate(hull.with_mass(hull.mass), -1.5, 0.03, **run)
    for key in ("force", "force_x", "moment", "draft", "pitch", "pitch_rate"):
        a, b = np.asarray(getattr(got, key)), np.asarray(getattr(want, key))
        np.testing.assert_allclose(a, b, rtol=0.0, atol=1e-12 * np.abs(b).max(), err_msg=key)


def test_the_one_calls_cache_sees_its_helpers():
    """numba's cache of :func:`stage_loops` is stale when its own file changes; it calls
    loops in other files, whose digest its file holds."""
    root = Path(planecut_loops.__file__).parent
    names = ("keel_loops.py", "side_loops.py", "frame_loops.py", "outline_loops.py",
             "held_loops.py", "index_loops.py", "contour_loops.py")  # fmt: skip
    digest = hashlib.sha256(b"".join((root / n).read_bytes() for n in names)).hexdigest()[:16]
    assert planecut_loops.STAGE_HELPERS_DIGEST == digest, (
        f"set STAGE_HELPERS_DIGEST = {digest!r} in hullslice/planecut_loops.py (its helpers "
        "changed)"
    )


@needs_numba
@pytest.mark.parametrize("name", ["fuselage_model.obj", "wedge_prism.stl"])
def test_the_stage_kits_call_is_the_stages_own(name):
    """:func:`~hullslice.stage_kit.kit_stage_loops` is the stage's loops called with the
    arguments the kit holds: over a run of new pitches, each at a new draft, the same
    status, sums, columns, contours and memo, to the bit, as the stage given copies of
    those arguments and the memo it returned last."""
    import numba

    from hullslice import stage_kit

    kit_memo = numba.njit(lambda kit: kit.memo)
    hull = _massive(BODIES[name])
    fused_eval = _model(hull).fused
    kit, _, _, hull_args, buffers = fused_eval._kit()
    own = lambda v: v.copy() if isinstance(v, np.ndarray) else v  # noqa: E731
    args, bufs = tuple(own(v) for v in hull_args), tuple(own(v) for v in buffers)
    memo = empty_memo(len(hull_args[13]))
    rng = np.random.default_rng(5)
    statuses = []
    for pitch in rng.uniform(0.02, 0.14, 12):
        fr = frame(hull.with_mass(hull.mass), pitch)
        z_cg = -(fr.lowest + float(rng.uniform(0.05, 0.4)) * (fr.highest - fr.lowest))
        numbers = (float(np.cos(pitch)), float(np.sin(pitch)), z_cg, -1.5, 19.0, 0.1)
        status = stage_kit.kit_stage_loops(kit, *numbers)
        want = fused_eval.stage(*args, *numbers, *bufs, memo)
        memo = want[4]
        statuses.append(status)
        assert status == want[0]
        for a, b in zip(buffers, bufs, strict=True):  # the sums, columns, extra
            np.testing.assert_array_equal(a, b)
        if status == 0:
            for a, b in zip(stage_kit.kit_rings_loops(kit), want[1:4], strict=True):
                np.testing.assert_array_equal(a, b)
            for a, b in zip(kit_memo(kit), memo, strict=True):
                np.testing.assert_array_equal(a, b)
    assert statuses.count(0) >= 10, statuses
    # the kit's sums and columns are those the results read (this thread's buffers)
    opts, sums, fout, iout = fused_eval._buffers()
    held = (buffers[0], buffers[1], buffers[2], buffers[4])
    assert all(a is b for a, b in zip(held, (fout, iout, sums, opts), strict=True))


def test_the_stage_kits_cache_sees_the_stage():
    """numba's cache of :mod:`hullslice.stage_kit`'s call is stale when its own file
    changes; it calls the stage's loops, whose file (holding its helpers' digest) its
    file holds the digest of."""
    root = Path(planecut_loops.__file__).parent
    digest = hashlib.sha256((root / "planecut_loops.py").read_bytes()).hexdigest()[:16]
    text = (root / "stage_kit.py").read_text()
    assert f'STAGE_DIGEST = "{digest}"' in text, (
        f"set STAGE_DIGEST = {digest!r} in hullslice/stage_kit.py (the stage's loops changed)"
    )


@needs_numba
def test_one_model_serves_two_threads_in_one_call():
    """The call releases the GIL; each thread has its own buffers, scratch array, ends'
    order and pitches met, so two threads evaluating one model at once, each at its own
    new pitches, get the sums the same model gives one call at a time."""
    import threading

    body = _massive(BODIES["fuselage_model.obj"])
    hull, twin = body.with_mass(body.mass), body.with_mass(body.mass)  # frames of their own
    fr = frame(body.with_mass(body.mass), 0.08)
    z_cg = -(fr.lowest + 0.3 * (fr.highest - fr.lowest))
    pitches = [np.linspace(0.06, 0.07, 60), np.linspace(0.09, 0.1, 60)]
    alone = _model(twin)
    want = [[alone.fused.stage_totals(p, z_cg, -2.0, 10.0, 0.1) for p in ps] for ps in pitches]
    assert all(w is not None for ws in want for w in ws)
    model = _model(hull)
    wrong = [0, 0]

    def work(i: int) -> None:
        for p, w in zip(pitches[i], want[i], strict=True):
            wrong[i] += model.fused.stage_totals(p, z_cg, -2.0, 10.0, 0.1) != w

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert wrong == [0, 0]


@needs_numba
def test_a_pitch_met_again_goes_the_steps_one_by_one():
    """A pitch a thread has cut in one call and meets again (a pitch held still in a
    free-pitch run) goes the steps one by one, which make and keep its frame: its kept
    cut and waterline tables serve it from there on, as at a held pitch."""
    body = _massive(BODIES["fuselage_model.obj"])
    hull = body.with_mass(body.mass)
    model = _model(hull)
    fr = frame(body.with_mass(body.mass), 0.05)
    z_cg = -(fr.lowest + 0.3 * (fr.highest - fr.lowest))
    assert model.fused.stage_totals(0.05, z_cg, -2.0, 10.0, 0.0) is not None
    assert model.fused.stage_totals(0.05, z_cg, -2.0, 10.0, 0.0) is None
    total = model.totals_at(z_cg, 0.05, -2.0, 10.0, 0.0)
    assert hull.cache[FRAMES].get(0.05) is not None  # made by the steps one by one
    other = _model(hull.with_mass(hull.mass))  # a hull of no frame: the one call serves it
    assert_same_sums(total, other.totals_at(z_cg, 0.05, -2.0, 10.0, 0.0), hull.size)


@needs_numba
@pytest.mark.parametrize("name", ["fuselage_model.obj", "paper_prism.stl", "cylinder", "wedge"])
def test_a_new_pitchs_result_in_one_call_equals_the_steps_one_by_one(name):
    """The first stage of a free-pitch step wants the whole result: made in the one call,
    it is the result of a frame of the same pitch evaluated by the fused loops (every
    section array, the loads and the sums within 1e-12, see :func:`assert_same_sums`; the
    contours to the bit), and its pose is the model's (the draft
    :meth:`ForceModel.draft` gives that state)."""
    from .test_fused import assert_same_result

    hull = _massive(BODIES[name])
    twin = hull.with_mass(hull.mass)
    one, steps = _model(hull), _model(twin)
    rng = np.random.default_rng(9)
    served = 0
    for pitch in rng.uniform(-0.05, 0.3, 12):
        fr = frame(twin, pitch)
        z_cg = -(fr.lowest + float(rng.uniform(0.01, 0.7)) * (fr.highest - fr.lowest))
        motion = Motion(-float(rng.uniform(0.5, 3.0)), 15.0, float(rng.normal(0.0, 0.3)))
        got = one.fused.stage_result(z_cg, pitch, motion)
        if got is None:
            continue
        served += 1
        r, pose = got
        assert pose == Pose(steps.draft(z_cg, pitch), pitch)
        want = steps.fused.force(pose, motion)
        assert want is not None
        assert_same_result(r, want)
        assert_same_sums((r.total, r.moment, r.total_x), (want.total, want.moment, want.total_x),
                         hull.size)  # fmt: skip
        for a, b in zip(r.sections.polygons, want.sections.polygons, strict=True):
            assert all(np.array_equal(p, q) for p, q in zip(a, b, strict=True))
    assert served >= 6, served


#: Run in a process of its own: for each of the loops compiled by name (those with their
#: helpers in ``CALLS``, and those calling no other loops), from a fresh start (every
#: module's loops its Python functions, none compiled), ``compiled(name)``, then every
#: loops function it reaches through the compiled callees is checked: each loops function
#: it calls by name must be numba's in its module's namespace (numba types a callee from
#: its caller's globals when it first compiles the caller; a Python function there fails
#: that compile, on a machine whose numba cache is empty). Prints the failures.
_REACH = """
import sys
from numba.core.registry import CPUDispatcher
from hullslice import planecut_loops as pl

python = {id(f): f for f in pl.LOOPS.values()}
spaces = {id(f.__globals__): f.__globals__ for f in pl.LOOPS.values()}.values()
fresh = [(space, k, v) for space in spaces for k, v in space.items() if id(v) in python]

def calls_loops(f):
    return any(id(f.__globals__.get(g)) in python for g in f.__code__.co_names)


bad = []
# the loops compiled by name: those with helpers listed in CALLS, and those without any
for name in sorted(k for k, f in pl.LOOPS.items() if k in pl.CALLS or not calls_loops(f)):
    for space, k, v in fresh:
        space[k] = v
    pl._HELPERS.clear()
    pl._COMPILED.clear()
    pl.compiled(name)
    todo, seen = [pl.LOOPS[name]], set()
    while todo:
        f = todo.pop()
        if id(f) in seen:
            continue
        seen.add(id(f))
        for g in f.__code__.co_names:
            v = f.__globals__.get(g)
            if id(v) in python:
                bad.append(f"{name}: {f.__name__} calls {g} uncompiled")
            elif isinstance(v, CPUDispatcher):
                todo.append(v.py_func)
print("\\n".join(bad))
"""


@needs_numba
def test_each_of_the_loops_compiles_first_in_a_fresh_process():
    """Whichever of the loops a process compiles first (a free-pitch run's first compiled
    call is the one-call stage, whose keel line's loops call the side view's from another
    module), every loops function it reaches finds its callees compiled: a first free-pitch
    run on a machine with an empty numba cache once failed to compile for this."""
    out = subprocess.run(
        [sys.executable, "-c", _REACH], capture_output=True, text=True, check=True, timeout=300
    )
    assert out.stdout.strip() == "", out.stdout


@needs_numba
@pytest.mark.slow
def test_a_free_pitch_run_is_the_first_thing_a_fresh_process_compiles(tmp_path):
    """A free-pitch run of the 1:10 model in a new process whose numba cache is empty
    (numba compiles every loop it meets, in the order a run meets them: the one-call
    stage before the keel line's loops by name) runs, through the one call, to the same
    history as this process's. About a minute of compiling."""
    code = (
        "import sys, numpy as np, hullslice as hs\n"
        "hull = hs.load_hull(sys.argv[1], mass=60.0)\n"
        "h = hs.simulate(hull, -1.5, 0.01, dt=1e-3, pitch_deg=6.0, forward_speed=19.0,\n"
        "                slices=32, slicing='fixed', stop_on=(), free_pitch=True)\n"
        "np.save(sys.argv[2], np.stack([h.force, h.moment, h.pitch]))\n"
    )
    out = tmp_path / "history.npy"
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    path = MESHES / "fuselage_model.obj"
    subprocess.run([sys.executable, "-c", code, str(path), str(out)], env=env, check=True,
                   timeout=600, capture_output=True)  # fmt: skip
    hull = hs.load_hull(path, mass=60.0)
    want = hs.simulate(hull, -1.5, 0.01, dt=1e-3, pitch_deg=6.0, forward_speed=19.0,
                       slices=32, slicing="fixed", stop_on=(), free_pitch=True)  # fmt: skip
    np.testing.assert_array_equal(np.load(out), np.stack([want.force, want.moment, want.pitch]))


@needs_numba
@pytest.mark.slow
def test_random_free_pitch_runs_compiled_are_numpys_to_1e_12(monkeypatch):
    """Whole free-pitch runs drawn at random (seed fixed): a catalogued body at half the
    water's density, its sink rate, pitch and pitch rate, forward speed, slice count, both
    slicings and four solvers (most often the default, which the one call serves),
    compiled and by numpy's path: every history within 1e-12 of its own peak, the bound
    the compiled path keeps to numpy's (numpy sums pairwise, the loops in turn: the last
    bits may differ)."""
    rng = np.random.default_rng(11)
    names = sorted(BODIES)
    keys = ("force", "force_x", "moment", "draft", "pitch", "pitch_rate")
    for _ in range(12):
        base = BODIES[names[rng.integers(len(names))]]
        hull = base.with_mass(500.0 * base.volume)
        height = float(hull.bounds[1, 2] - hull.bounds[0, 2])
        w = -float(rng.uniform(0.3, 3.0))
        u = hull.size * float(rng.uniform(0.5, 3.0))
        dt = min(hull.size / u * float(rng.uniform(0.002, 0.01)), 0.05 * height / -w)
        kw = dict(
            velocity=w, pitch_rad=float(rng.uniform(-0.1, 0.4)),
            pitch_rate_rad_s=float(rng.uniform(-3.0, 3.0)), forward_speed=u, dt=dt,
            t_end=dt * int(rng.integers(10, 40)), slices=int(rng.integers(6, 70)),
            slicing=str(rng.choice(["fixed", "wetted"])), free_pitch=True, stop_on=(),
            solver=str(rng.choice(["extended-von-karman"] * 2 + ["mlm", "zarnick", "wagner"])),
        )  # fmt: skip
        runs = {}
        for switch in ("1", "0"):
            monkeypatch.setenv("HULLSLICE_NUMBA", switch)
            runs[switch] = hs.simulate(hull.with_mass(hull.mass), **kw)
        for key in keys:
            got, want = np.asarray(getattr(runs["1"], key)), np.asarray(getattr(runs["0"], key))
            assert got.shape == want.shape, (key, kw)
            peak = float(np.abs(want).max()) if want.size else 0.0
            diff = float(np.abs(got - want).max()) if want.size else 0.0
            assert diff <= 1e-12 * peak + 1e-300, (key, diff, peak, kw)


@needs_numba
@pytest.mark.parametrize("name", ["fuselage_model.obj", "paper_prism.stl", "wedge"])
def test_a_moved_slice_reads_its_source_below_the_edges_the_call_keeps(name):
    """The call keeps an end slice's source's edges up to the water's level plus the steep
    slope times two station spacings (what a slice moved to its depth can read: layout_loops
    cuts one afresh where its depth is more than the steep slope times its distance from
    its source's middle, 1.5 spacings at most). The call's Python text run by Python (its
    helpers compiled) at 30 poses: every slice it moves reads its source at a height
    within the steep slope times 1.5 spacings above the water, and some read above it."""
    from hullslice import slices_loops
    from hullslice.slices_loops import I_MOVED

    hull = _massive(BODIES[name])
    model = _model(hull)
    stage = planecut_loops.LOOPS["stage"]
    space = stage.__globals__
    pitch_loops = space["pitch_loops"]  # compiled (the call's helpers are, once it is)
    seen = []

    def watched(fout, iout, scal, opts, keel, *rest):
        status = pitch_loops(fout, iout, scal, opts, keel, *rest)
        if status == 0:
            steep = opts[22]
            d = (keel[0][-1] - keel[0][0]) / opts[6]
            for r in range(int(scal[0])):
                if iout[I_MOVED, r] == 1:
                    seen.append(-fout[slices_loops._LIFT, r] / (steep * d))  # at - level
        return status

    captured = []
    real = model.fused.kit_stage

    def capture(kit, *numbers):  # the call's arguments, the kit's and the stage's six
        hull_args, buffers = model.fused._local.stage[4:]
        memo = empty_memo(len(hull_args[13]))  # each replayed call cuts its stations afresh
        captured.append((*hull_args, *numbers, *buffers, memo))
        return real(kit, *numbers)

    model.fused.kit_stage = capture
    rng = np.random.default_rng(8)
    for pitch in rng.uniform(-0.1, 0.35, 30):
        fr = frame(hull.with_mass(hull.mass), pitch)
        draft = float(rng.uniform(0.002, 0.5)) * (fr.highest - fr.lowest)
        model.fused.stage_totals(pitch, -(fr.lowest + draft), -1.0, 5.0, 0.1)
    model.fused.kit_stage = real
    space["pitch_loops"] = watched
    try:
        for args in captured:
            stage(*args)
    finally:
        space["pitch_loops"] = pitch_loops
    assert seen, "no slice moved"
    assert max(seen) <= 1.5 * (1.0 + 1e-9), max(seen)
    assert max(seen) > 0.0
