"""Objects that travel between processes: a pickled Hull computes exactly what the original
does, and histories, force results and sections become labelled xarray/pandas tables."""

from __future__ import annotations

import copy
import math
import pickle
from pathlib import Path

import numpy as np

import hullslice as hs

ROOT = Path(__file__).resolve().parents[1]
WEDGE = ROOT / "meshes" / "wedge_prism.stl"
PAPER = ROOT / "meshes" / "paper_prism.stl"


def test_a_pickled_hull_gives_the_same_history_exactly():
    hull = hs.load_hull(PAPER, mass=1.0)
    hull.volume  # noqa: B018 (fill a cache: caches are not pickled, they refill)
    back = pickle.loads(pickle.dumps(hull))
    assert back.name == hull.name and back.mass == hull.mass
    assert np.array_equal(back.vertices, hull.vertices)
    assert not back.vertices.flags.writeable and not back.faces.flags.writeable
    assert back.manifold.volume() == hull.manifold.volume()
    # the reference: the same free fall on the hull that was never pickled, bit for bit
    kw = {"dt": 2e-4, "slices": 16}
    a = hs.simulate(hull, -4.0, 0.01, **kw)
    b = hs.simulate(back, -4.0, 0.01, **kw)
    assert len(a) == len(b) == 51
    assert np.array_equal(a.force, b.force)
    assert a.peak["force"] == b.peak["force"]


def test_a_pickled_hull_keeps_its_mass_properties():
    hull = hs.load_hull(WEDGE, mass=10.0).with_mass(10.0, cg=(0.4, 0.02), inertia=2.5)
    back = pickle.loads(pickle.dumps(hull))
    assert np.array_equal(back.cg, hull.cg)
    assert back.cg[0] == 0.4 and back.pitch_inertia == 2.5
    pose, motion = hs.Pose(0.02, math.radians(3.0)), hs.Motion(-3.0, 5.0)
    ra = hs.compute_force(hull, pose, motion, slices=8)
    rb = hs.compute_force(back, pose, motion, slices=8)
    assert ra.total == rb.total and ra.moment == rb.moment
    assert copy.copy(hull).volume == hull.volume  # copy goes through the same state


def test_history_to_xarray_and_dataframe_carry_every_column_with_units():
    hull = hs.load_hull(PAPER, mass=1.0)
    h = hs.simulate(hull, -4.0, 0.01, dt=2e-4, slices=16)
    ds = h.to_xarray()
    cols = h.columns()
    # every column travels, generically: the dataset's variables are the history's columns
    assert set(ds.data_vars) | {"t"} == set(h.COLUMNS)
    assert np.array_equal(ds["t"].values, h.t)
    assert np.array_equal(ds["force"].values, h.force)
    assert ds["force"].attrs["units"] == "N" and ds["velocity"].attrs["units"] == "m s-1"
    assert ds["pitch_deg"].attrs["units"] == "degree"
    assert ds.attrs["stop_reason"] == h.stop_reason
    df = h.to_dataframe()
    assert len(df) == len(h) == 51
    assert df["acceleration"].max() == float(np.max(cols["acceleration"]))
    assert df.attrs["units"]["moment"] == "N m"


def test_force_result_and_sections_to_xarray():
    hull = hs.load_hull(PAPER, mass=1.0)
    r = hs.compute_force(hull, 0.0383, -3.4943, slices=16)
    ds = r.to_xarray()
    # the slices' forces add up to the total (Eq. 12) to rounding
    assert abs(float(ds["force"].sum()) - r.total) <= 1e-12 * abs(r.total)
    assert ds["force_per_metre"].attrs["units"] == "N m-1"
    assert ds.attrs["total_force_N"] == r.total
    sec = r.sections.to_xarray()
    assert np.array_equal(sec["area"].values, r.sections.area)
    assert sec["area"].attrs["units"] == "m2"
    df = r.sections.to_dataframe()
    assert len(df) == len(r.sections) == 16
    assert df.attrs["units"]["mass_per_metre"] == "kg m-1"
    assert len(r.to_dataframe()) == 16
