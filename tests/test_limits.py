"""Inputs that would run for hours or return nonsense are refused with what to do instead."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import hullslice as hs
from hullslice.constants import MAX_SLICES, MAX_STEPS
from hullslice.motion import prescribed, read_kinematics, simulate


def test_a_slice_count_beyond_the_limit_is_refused(paper_hull):
    with pytest.raises(hs.InputError, match=f"slice count {MAX_SLICES + 1} is more than the"):
        hs.cut(paper_hull, 0.0383, MAX_SLICES + 1)
    with pytest.raises(hs.InputError, match="is more than the 100000 hullslice allows"):
        hs.convergence(paper_hull, 0.0383, -3.0, slices=(16, 32, 10**8))


def test_a_run_of_too_many_steps_is_refused_before_it_starts(paper_hull):
    with pytest.raises(hs.InputError, match=r"is 1e\+12 steps, more than the 1000000"):
        simulate(paper_hull, -4.0, 1.0, dt=1e-12)
    # a step so short that t_end / dt overflows to infinity
    with pytest.raises(hs.InputError, match="is inf steps"):
        simulate(paper_hull, -4.0, 1.0, dt=1e-320)
    assert MAX_STEPS == 1_000_000


def test_a_non_finite_solver_result_names_the_section_and_warns_nothing(paper_hull):
    # a mass of 1e-300 kg: the curves' scaling divides by sqrt(M) and overflows
    with pytest.warns(hs.UnitsWarning, match="check the mass"):
        tiny = paper_hull.with_mass(1e-300)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no numpy RuntimeWarning may escape
        with pytest.raises(hs.SolverError) as info:
            hs.compute_force(tiny, 0.0383, -3.4943, slices=4)
    msg = str(info.value)
    assert "non-finite force per metre for 4 of 4 sections" in msg
    assert "mass per metre 4.6" in msg and "e-300 kg/m" in msg
    assert "velocity -3.4943 m/s" in msg


def test_kinematics_that_are_no_text_file(tmp_path, paper_hull):
    with pytest.raises(hs.CaseError, match="is not a file: give a CSV file"):
        read_kinematics(tmp_path)
    binary = tmp_path / "k.csv"
    binary.write_bytes(b"t,penetration,velocity\n\xd2\x00\x01")
    with pytest.raises(hs.CaseError, match=r"is not UTF-8 text \(byte 23\)"):
        read_kinematics(binary)
    binary.write_bytes(b"t,penetration,velocity\n0,0,-1\0\n")
    with pytest.raises(hs.CaseError, match="holds binary data"):
        read_kinematics(binary)


def test_kinematics_from_a_spreadsheet_with_a_byte_order_mark(tmp_path, paper_hull):
    path = tmp_path / "k.csv"
    path.write_bytes("t,penetration,velocity\n0,0.01,-3\n0.001,0.013,-3\n".encode("utf-8-sig"))
    kin = read_kinematics(path)
    assert kin["t"].tolist() == [0.0, 0.001]
    h = prescribed(paper_hull, kin, slices=8)
    assert np.all(np.isfinite(h.force)) and h.force[1] > h.force[0] > 0.0


def test_a_time_step_that_steps_through_the_impact_is_refused(paper_hull):
    # at 1000 m/s a 1e-3 s step moves the 0.1 m body 1 m (at 1e6 m/s, now refused as past
    # the speed of sound, such a run recorded a draft of -2e17 m)
    with pytest.raises(hs.InputError) as info:
        simulate(paper_hull, -1000.0, 0.1, dt=1e-3)
    assert "moves the body 1 m a step, more than 0.1 of its height 0.1 m" in str(info.value)
    assert "give a time step below 1e-05 s" in str(info.value)
    # the paper's run moves 0.4 mm a step
    h = simulate(paper_hull, -4.0, 2e-4, dt=1e-4, slices=4)
    assert len(h) == 3 and np.all(np.isfinite(h.draft))
