"""The fused evaluation (hullslice.forces.fused, its loops in hullslice.held_loops) where a
section meets the water in two pieces: a real airliner's nacelles under its wings, wetted
with its fuselage in a ditching (``meshes/airliner``). Numpy's path gives such a slice one
entry per wetted piece; the loops give the same entries, in the same order, from the
waterline table (a held pitch) or computed afresh (a new pitch), and the same results to
1e-12 (see tests/test_fused.py for the one-piece bodies). The loops run as Python (on
every machine) and, where numba is installed, compiled."""

from __future__ import annotations

import numpy as np
import pytest

import hullslice as hs
from hullslice.forces import fused
from hullslice.slices_loops import COLUMNS, I_ROWS
from hullslice.slicing.fixed import TABLE_AFTER
from hullslice.state import Motion, Pose

from .conftest import MESHES
from .test_fused import _models, _paths, assert_same_result


@pytest.fixture(autouse=True)
def _ieee_division():
    """As in tests/test_fused.py: the loops as Python divide numpy's scalars by zero."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        yield


@pytest.fixture(scope="module")
def airliner():
    """The public airliner mesh at a narrow-body's length and mass (its README)."""
    return hs.load_hull(MESHES / "airliner" / "airliner.obj", length=37.6, mass=60000.0)


#: Ditching poses of the airliner with its nacelles in the water (those of the history
#: below, from 0.3 m at 6 deg): pitches (rad) and drafts (m).
PITCHES = (0.096, 0.1047, 0.11)
DRAFTS = np.linspace(0.26, 0.40, 8)


def _pieces(result) -> int:
    """The most entries a slice of ``result`` has."""
    return int(np.bincount(result.sections.station).max())


@pytest.mark.parametrize("path", [p for p, _ in _paths()])
@pytest.mark.parametrize("cutter", ["manifold3d", "exact"])
def test_slices_in_two_wetted_pieces_equal_numpy(airliner, cutter, path):
    """The nacelles' slices, two or three entries each: by the kept cut's waterline table (held
    pitch, the manifold3d cutter, the table made first at the deepest pose so that it holds
    every shallower one) and computed afresh at each pose (the exact cutter, no table), the
    loops' results equal numpy's, entry by entry."""
    loops = dict(_paths())[path]
    served = 0
    for pitch in PITCHES:
        fast, slow = _models(airliner, loops, slices=32, cutter=cutter)
        deepest = Pose(float(DRAFTS[-1]), pitch)
        if cutter == "manifold3d":  # the kept cut and its table, at the deepest pose
            for _ in range(TABLE_AFTER):
                slow(deepest, Motion(-1.5, 60.0))
        for draft in DRAFTS[::-1]:
            pose, motion = Pose(float(draft), pitch), Motion(-1.5, 60.0, 0.1)
            want = slow(pose, motion)
            got = fast.fused.force(pose, motion)
            if got is not None:
                assert _pieces(want) >= 2  # the nacelles (and the fuselage) in one slice
                assert_same_result(got, want)
                served += 1
    assert served >= 10, served


@pytest.mark.parametrize("path", [p for p, _ in _paths()])
@pytest.mark.parametrize("free", [False, True])
def test_an_airliner_ditching_with_its_nacelles_wet_equals_numpy(airliner, free, path,
                                                                 monkeypatch):  # fmt: skip
    """A ditching of the airliner from a draft where its nacelles touch the water, its pitch
    held or free: the loops serve nearly every evaluation, and the history is numpy's."""
    loops = dict(_paths())[path]
    run = dict(draft=0.3, pitch_deg=6.0, forward_speed=60.0, slices=32, slicing="fixed",
               stop_on=(), dt=1e-3, free_pitch=free)  # fmt: skip
    monkeypatch.setattr(fused, "_loops", lambda: None)
    want = hs.simulate(airliner.with_mass(airliner.mass), -1.5, 0.04, **run)
    served = []
    original = fused.FusedEvaluation._run

    def counted(self, *args):
        out = original(self, *args)
        served.append(out is not None)
        return out

    monkeypatch.setattr(fused, "_loops", lambda: loops)
    monkeypatch.setattr(fused.FusedEvaluation, "_run", counted)
    got = hs.simulate(airliner.with_mass(airliner.mass), -1.5, 0.04, **run)
    assert len(got) == len(want) == 41
    assert sum(served) >= 0.9 * len(served) > 0, (sum(served), len(served))
    peak = float(np.abs(want.force).max())
    assert peak > 1e6  # N: the nacelles and the fuselage in the water
    for key in ("force", "force_x", "moment", "draft", "pitch", "acceleration"):
        a, b = getattr(got, key), getattr(want, key)
        assert np.allclose(a, b, rtol=0.0, atol=1e-11 * (float(np.abs(b).max()) or 1.0)), key
    assert np.array_equal(got.slices, want.slices)
    assert list(got.reason) == list(want.reason)


def test_more_entries_than_the_columns_hold_go_to_numpy(airliner, monkeypatch):
    """With columns for one more row than there are slices, slices of two entries each hand
    the evaluation back (status 8), and numpy's path gives the result; with the usual
    room the loops serve it."""
    loops = dict(_paths())[_paths()[-1][0]]
    pose, motion = Pose(0.3, 0.1047), Motion(-1.5, 60.0)
    fast, slow = _models(airliner, loops, slices=32, cutter="exact")
    want = slow(pose, motion)
    slices = int(want.sections.station.max()) + 1
    assert len(want.sections.station) >= slices + 2  # two slices of two entries

    def narrow(n):
        return np.empty((len(COLUMNS), slices + 1)), np.empty((I_ROWS, slices + 1), dtype=np.int64)

    monkeypatch.setattr(fused, "_columns", narrow)
    fast, _ = _models(airliner, loops, slices=32, cutter="exact")
    assert fast.fused.force(pose, motion) is None
    assert fast.fused.totals(pose, motion) is None
    assert_same_result(fast(pose, motion), want)
    monkeypatch.undo()
    fast, _ = _models(airliner, loops, slices=32, cutter="exact")
    assert_same_result(fast.fused.force(pose, motion), want)
