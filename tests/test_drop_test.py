"""The drop test of a wedge with knuckles (``examples/drop_test.py``): the model of the rig,
the measured motion it is driven along, and the strip theory's force on it, each against a
closed form. The comparison with the measurement itself is the script's output, quoted in
``docs/validation.md`` (and checked there by ``tests/test_docs.py``).

Sources: Zhao, Faltinsen & Aarsnes (1996), Section 5 and Figure 15 (the test); Wagner
(1932) for the wetted half-width ``c = (pi / 2) p / tan(beta)`` of a wedge; Zarnick (1978)
for the strip theory's force ``f = dm_a/dp v^2 - m_a a + a_B rho g A``.
"""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

import hullslice as hs

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def drop() -> ModuleType:
    spec = importlib.util.spec_from_file_location("drop_test", ROOT / "examples" / "drop_test.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("draft", [0.05, 0.1443 - 1e-4, 0.2])
def test_the_rig_has_the_tests_section_with_knuckles(drop, draft):
    # 30 deg wedge, knuckles 0.25 tan(30 deg) = 0.1443 m above the keel, vertical sides
    rig = drop.rig()
    assert rig.mass == pytest.approx(241.0, rel=1e-12)
    s = hs.cut(rig, draft, slices=4)
    h_k = 0.25 * math.tan(math.radians(30.0))
    assert drop.knuckle_height() == pytest.approx(h_k, rel=1e-12)
    half = min(draft, h_k) / math.tan(math.radians(30.0))
    area = min(draft, h_k) * half + max(draft - h_k, 0.0) * 0.5  # below the water
    np.testing.assert_allclose(s.half_beam, half, rtol=1e-9)
    np.testing.assert_allclose(s.penetration, draft, rtol=1e-9)
    assert np.all(s.chine_wetted == (draft > h_k))
    # the level rig's mass per metre: 241 kg over 1.0 m, shared by the sections' areas
    np.testing.assert_allclose(s.mass_per_metre, 241.0 * s.area / rig.volume, rtol=1e-9)
    assert rig.volume == pytest.approx(1.0 * (h_k * 0.25 + 0.35 * 0.5), rel=1e-9)
    assert area <= s.area[0] + 1e-12


def test_the_measured_motion_follows_the_measured_velocity(drop):
    kin = drop.measured_motion(steps=1000)
    # through every measured point (a spline), its draft the velocity's integral
    at = np.interp(drop.T_VELOCITY[1:], kin["t"], -kin["velocity"])
    np.testing.assert_allclose(at, drop.V_MEASURED[1:], atol=2e-5)
    v = drop.V_MEASURED
    trapezoid = np.sum(np.diff(drop.T_VELOCITY) * 0.5 * (v[1:] + v[:-1]))
    assert kin["draft"][-1] == pytest.approx(trapezoid, rel=2e-3)
    # its acceleration is the velocity's slope (up positive: the rig slows down)
    slope = np.gradient(kin["velocity"], kin["t"])
    np.testing.assert_allclose(kin["acceleration"][5:-5], slope[5:-5], atol=0.05)


def test_the_data_agree_with_the_rigs_momentum(drop):
    # Newton on the whole rig, independent of the force curve: the measuring section's
    # impulse is 0.2 / 1.0 of mass (g t - (V(t) - V(0))). It carries 5 to 12 % more than
    # that share (it is the middle of the rig, the ends lose some force to the flow around
    # them), within the reading's +-250 N and +-0.05 m/s
    for t in (0.015, 0.020, 0.025):
        implied = drop.rig_impulse_from_velocity(t)
        measured = drop.measured_impulse(t)
        assert implied < measured < 1.15 * implied


def test_zarnick_along_the_measured_motion_is_the_closed_form_before_the_knuckles(drop):
    # Wagner's c = (pi/2) p / tan(beta) < 0.25 m until p = 0.0919 m (about 15 ms): the
    # added mass rho pi c^2 / 2, its rate rho pi c dc/dp, buoyancy a_B rho g p^2 / tan(beta)
    kin = drop.measured_motion(steps=50)
    h = hs.prescribed(drop.rig(), kin, slices=4, solver="zarnick", fluid=drop.fluid())
    rho, g, tb = 1000.0, 9.81, math.tan(math.radians(30.0))
    p, v, a = kin["draft"], kin["velocity"], kin["acceleration"]
    c = 0.5 * math.pi * p / tb
    before = c < 0.25 * (1 - 1e-3)
    assert before.sum() >= 25
    f = rho * math.pi * c * (0.5 * math.pi / tb) * v**2 - rho * math.pi * c**2 / 2 * a
    f += 0.5 * rho * g * p**2 / tb
    np.testing.assert_allclose(np.asarray(h.force)[before], f[before] * 1.0, rtol=1e-6)
    # past the knuckles: frozen added mass, cross-flow drag on the half-breadth, buoyancy
    after = c > 0.25 * (1 + 1e-3)
    h_k = 0.25 * tb
    area = np.minimum(p, h_k) ** 2 / tb + np.maximum(p - h_k, 0.0) * 0.5
    f_after = -rho * math.pi * 0.25**2 / 2 * a + rho * 0.25 * v**2 + 0.5 * rho * g * area
    np.testing.assert_allclose(np.asarray(h.force)[after], f_after[after], rtol=1e-5)
