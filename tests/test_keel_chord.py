"""A slice's keel slope is the keel line's chord over the slice (KeelLine.mean_slope).

References: the chord of a polyline, ``(Z(b) - Z(a)) / (b - a)``, written out from its
facets; a straight keel's slope; continuity of a chord in its end points.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import hullslice as hs
from hullslice import shapes
from hullslice.kernel.keel import KeelLine

from .conftest import ROOT


def junction() -> KeelLine:
    # a bottom at slope 0.13, a junction of parts 13 mm long at 0.67, a bottom at 0.18
    # (the public airliner's nacelle-to-fuselage junction at 3 degrees of pitch)
    x = np.array([-2.0, -0.3, 0.0, 0.013, 0.4, 2.0])
    s = np.array([0.13, 0.13, 0.67, 0.18, 0.18])
    return KeelLine(x, np.concatenate([[0.0], np.cumsum(s * np.diff(x))]))


def test_a_straight_keel_has_its_slope_over_any_slice():
    x = np.linspace(-1.0, 2.0, 7)
    k = KeelLine(x, 0.1 + 0.07 * x)
    at = np.linspace(-0.9, 1.9, 11)
    for width in (1e-3, 0.3, 5.0):  # the last longer than the line: shortened to fit
        np.testing.assert_allclose(k.mean_slope(at, np.full(11, width)), 0.07, rtol=1e-12)


def test_a_short_junction_weighs_its_length_not_its_slope():
    k = junction()
    # a 1.2 m slice centred on the junction: the chord from its facets' rises
    chord = (0.13 * (0.6 - 0.0065) + 0.67 * 0.013 + 0.18 * (0.6 - 0.0065)) / 1.2
    assert k.mean_slope(np.array([0.0065]), np.array([1.2]))[0] == pytest.approx(chord, 1e-12)
    assert chord == pytest.approx(0.1605, abs=1e-4)
    # the blend of the facets' slopes at their middles puts the junction's 0.67 at the
    # slice's middle: 0.5 too steep, 30 m/s of penetration velocity at 60 m/s
    assert k.at(np.array([0.0065]))[1][0] == pytest.approx(0.67, 1e-12)


def test_the_chord_is_continuous_along_the_line():
    rng = np.random.default_rng(3)
    x = np.cumsum(rng.uniform(0.001, 0.05, 200))  # facets 1 to 50 mm, zigzag slopes
    z = np.concatenate([[0.0], np.cumsum(rng.normal(0.1, 0.2, 199) * np.diff(x))])
    k = KeelLine(x, z)
    at = np.linspace(x[0] + 0.2, x[-1] - 0.2, 20001)
    s = k.mean_slope(at, np.full(len(at), 0.2))
    # the chord of a continuous line over a fixed width moves by at most twice the
    # steepest facet's slope times the step over the width
    step = at[1] - at[0]
    bound = 2.0 * np.abs(np.diff(z) / np.diff(x)).max() * step / 0.2
    assert np.abs(np.diff(s)).max() <= bound
    # and equals the chord from the line's heights
    h = np.interp(at + 0.1, x, z) - np.interp(at - 0.1, x, z)
    np.testing.assert_allclose(s, h / 0.2, rtol=1e-9, atol=1e-12)


def test_the_chord_stays_within_its_run_and_centred():
    # a bottom at 0.05, a step's face (slope 20, steeper than 75 deg), a bottom at -0.02
    x = np.array([0.0, 1.0, 1.001, 2.0])
    z = np.array([0.0, 0.05, 0.07, 0.05])
    k = KeelLine(x, z)
    # 0.1 m before the face with a 1 m slice: shortened to 0.2 m, on the first bottom only
    assert k.mean_slope(np.array([0.9]), np.array([1.0]))[0] == pytest.approx(0.05, 1e-12)
    assert k.mean_slope(np.array([1.1]), np.array([1.0]))[0] == pytest.approx(-0.02 / 0.999, 1e-12)
    # on the face, the face's own slope (as KeelLine.at gives it)
    on_face = np.array([1.0005])
    assert k.mean_slope(on_face, np.array([1.0]))[0] == pytest.approx(k.at(on_face)[1][0])
    # beyond the line's ends, the slope it is held at
    out = np.array([-0.5, 2.5])
    np.testing.assert_allclose(k.mean_slope(out, np.ones(2)), k.at(out)[1], rtol=1e-12)


@pytest.mark.slow
def test_the_whole_airliners_junctions_give_no_spike():
    # the whole public airliner ditching free in pitch, 10 deg, 60 m/s, -3 m/s (mlm, 32
    # fixed slices, 4 ms steps). With the slope at a slice's middle the forward slice took
    # the 13 mm junction's 0.67 at 0.584 s: 22 MN/m. With the chord, the slice past a
    # nacelle's end took the fuselage's section moved down 0.7 m: 12 MN/m. Cut where it
    # is, the largest force per metre measured 6.8 MN/m, on the nacelle's own lip at
    # 0.564 s (docs/meshes.md)
    pytest.importorskip("hullslice_mlm")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        whole = hs.load_hull(ROOT / "meshes/airliner/airliner.obj", length=37.6, mass=60000.0)
        h = hs.simulate(
            whole, -3.0, 0.62, dt=0.004, pitch_rad=math.radians(10.0), forward_speed=60.0,
            free_pitch=True, slices=32, slicing="fixed", solver="mlm", stop_on=(),
            fluid=hs.Fluid.sea(), aero="weight", sections_every=1,
        )  # fmt: skip
    per_metre = max(float(np.max(r.force / r.dx)) for r in h.sections if len(r.force))
    assert per_metre < 10.0e6


def two_parts():
    # a V "fuselage" 4 m long (keel 0.5 m up, 10 deg deadrise) beside a lower V "nacelle"
    # (keel at 0, 30 deg) at y = 1.5 m, whose bottom rises at its end at a slope of 3, from
    # x = 2.0 m to 0.6 m at 2.2 m (an inlet's lip, less steep than an end face)
    def vsec(y, keel, deadrise, top=0.8, half=0.4):
        chine = min(keel + half * math.tan(math.radians(deadrise)), top - 0.01)
        return np.array([[y - half, top], [y - half, chine], [y, keel], [y + half, chine],
                         [y + half, top]])  # fmt: skip

    fuselage = shapes.prism_from_sections(
        np.array([0.0, 4.0]), np.stack([vsec(0.0, 0.5, 10.0, top=1.3)] * 2)
    )
    nacelle = shapes.prism_from_sections(
        np.array([0.0, 2.0, 2.2]),
        np.stack([vsec(1.5, 0.0, 30.0), vsec(1.5, 0.0, 30.0), vsec(1.5, 0.6, 30.0)]),
    )
    v = np.concatenate([fuselage[0], nacelle[0]])
    f = np.concatenate([fuselage[1], nacelle[1] + len(fuselage[0])])
    return hs.Hull.from_arrays(v, f, mass=100.0)


def test_a_slice_past_a_parts_end_is_cut_where_it_is_not_moved_from_another_part():
    # 8 fixed slices of 0.5 m at a draft of 5 cm: only the nacelle is wet, to where its
    # lip rises out of the water, 2.0 m and a little, so the slice from 2.0 m is wet over
    # a centimetre, all on the lip. Its own station, at 2.25 m, has the fuselage only:
    # moved down 0.5 m to the keel line, the fuselage's section would stand in for the
    # nacelle's there
    hull = two_parts()
    r = hs.compute_force(
        hull, hs.Pose(draft=0.05), hs.Motion(-1.0), slices=8, slicing="fixed",
        solver="von-karman", acceleration=0.0,
    )  # fmt: skip
    s = r.sections
    part = s.wetted & (s.dx < 0.5 - 1e-9)
    assert part.sum() == 1
    x = float(s.x[part][0])
    assert 2.0 < x < 2.02
    assert s.y_keel[part][0] == pytest.approx(1.5, abs=1e-9)
    # the lip's keel rises linearly from 0 at 2.0 m to 0.6 m at 2.2 m
    assert s.penetration[part][0] == pytest.approx(0.05 - 3.0 * (x - 2.0), abs=1e-9)
