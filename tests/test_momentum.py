"""hullslice's momentum-theory base, pile-up laws and user curves, against closed forms."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import hullslice as hs
from hullslice.solvers import (
    PAPER_CURVES,
    CharacteristicCurves,
    CurveSolver,
    FreeFallMomentumSolver,
    MomentumFormSolver,
    momentum_curves,
    peak_values,
    pile_up_law,
)
from hullslice.testing import wedge_sections


class ConstantGamma(FreeFallMomentumSolver):
    """Momentum theory with a constant pile-up, for tests."""

    name = "constant-gamma"
    description = "test: momentum theory (free-fall form), gamma = 1.3"

    def pile_up(self, deadrise):
        return np.full_like(deadrise, 1.3)


def test_one_section_by_hand():
    # the formulas of the module docstring, evaluated by hand for one wedge
    p, beta, M, v, rho, g, gam = 0.02, math.radians(20.0), 8.0, -4.0, 1025.0, 9.81, 1.3
    tb = math.tan(beta)
    m_a = rho * math.pi * gam**2 * p**2 / (2 * tb**2)
    v0 = v * (M + m_a) / M
    a = rho * math.pi * gam**2 * p * v**2 / (tb**2 * (M + m_a))
    z_star = tb * math.sqrt(2 * M / (5 * math.pi * rho * gam**2))
    froude = abs(5 / 6 * v0) / math.sqrt(g * z_star)

    secs = wedge_sections(p, beta, M)
    loads = ConstantGamma().section_loads(secs, np.array([v]), hs.Fluid(rho, g))
    d = loads.diagnostics
    assert d["added_mass"][0] == pytest.approx(m_a, rel=1e-12)
    assert d["v_z0"][0] == pytest.approx(v0, rel=1e-12)
    assert d["acceleration"][0] == pytest.approx(a, rel=1e-12)
    assert d["froude"][0] == pytest.approx(froude, rel=1e-12)
    assert loads.force_per_metre[0] == pytest.approx(M * (a + g), rel=1e-12)
    assert loads.valid[0] and loads.reason[0] == ""


def test_acceleration_is_the_rate_of_change_of_the_free_fall_velocity():
    # along the free fall v(p) = M v0 / (M + m_a(p)), so a = dv/dt = -v dv/dp: a central
    # difference of the momentum balance checks the derivation (truncation ~ h^2 ~ 1e-10)
    M, beta, rho, gam, v0 = 5.0, math.radians(25.0), 1000.0, 1.3, -6.0
    k = rho * math.pi * gam**2 / (2 * math.tan(beta) ** 2)

    def vel(p):
        return M * v0 / (M + k * p**2)

    p, h = np.array([0.005, 0.012, 0.03]), 1e-6
    dv_dp = (vel(p + h) - vel(p - h)) / (2 * h)
    expected = -vel(p) * dv_dp
    loads = ConstantGamma().section_loads(wedge_sections(p, beta, M), vel(p), hs.Fluid(rho, 0.0))
    np.testing.assert_allclose(loads.diagnostics["acceleration"], expected, rtol=1e-8)
    np.testing.assert_allclose(loads.diagnostics["v_z0"], v0, rtol=1e-12)  # momentum kept


def test_peak_of_the_free_fall_is_eq_2():
    # a(p) along one free fall, maximised on a fine grid, against the paper's Eq. 2
    M, beta, rho, gam, v0 = 5.0, math.radians(25.0), 1000.0, 1.3, -6.0
    k = rho * math.pi * gam**2 / (2 * math.tan(beta) ** 2)
    p = np.linspace(0.005, 0.015, 20001)  # around z* = 9.05 mm, step 5e-7 m
    v = M * v0 / (M + k * p**2)
    loads = ConstantGamma().section_loads(wedge_sections(p, beta, M), v, hs.Fluid(rho, 9.81))
    a = loads.diagnostics["acceleration"]
    i = int(np.argmax(a))
    ref = peak_values(v0, M, beta, gam, rho)
    assert a[i] == pytest.approx(ref["a_max"], rel=1e-8)  # grid max: O(step^2) below
    assert p[i] == pytest.approx(ref["z_star"], abs=2e-6)  # a few grid steps
    # v changes by 184 m/s per m of p there: 2e-6 m off the peak is 7e-5 of v*
    assert v[i] == pytest.approx(ref["v_star"], rel=1e-4)


def test_validity_reasons():
    beta, M = math.radians(20.0), 8.0
    secs = wedge_sections([0.01, 0.01, 0.01, 0.02], beta, M, chine_half_width=[1, 1, 1, 0.06])
    v = np.array([-5.0, 1.0, -0.3, -5.0])
    loads = ConstantGamma().section_loads(secs, v, hs.Fluid())
    assert list(loads.valid) == [True, False, False, False]
    assert "not moving down" in loads.reason[1]
    assert "Fr* <= 6.5" in loads.reason[2]
    # gamma p / tan(beta) = 1.3 * 0.02 / 0.364 = 0.0714 m > 0.06 m (> c = 0.055 m)
    assert "spray root past the chine" in loads.reason[3]
    assert loads.diagnostics["wetted_half_width"][3] == pytest.approx(
        1.3 * 0.02 / math.tan(beta), rel=1e-12
    )


def test_only_mass_over_density_matters():
    # von Karman's balance depends on M and rho only through M / rho: doubling both keeps a
    secs1 = wedge_sections([0.01, 0.02], math.radians(30.0), 4.0)
    secs2 = wedge_sections([0.01, 0.02], math.radians(30.0), 8.0)
    s = ConstantGamma()
    a1 = s.section_loads(secs1, -5.0, hs.Fluid(1000.0)).diagnostics["acceleration"]
    a2 = s.section_loads(secs2, -5.0, hs.Fluid(2000.0)).diagnostics["acceleration"]
    np.testing.assert_allclose(a1, a2, rtol=1e-12)


def test_momentum_form_solver_needs_an_added_mass():
    class NoAddedMass(MomentumFormSolver):
        name = "no-added-mass"

    with pytest.raises(TypeError, match="added_mass"):
        NoAddedMass()


def test_momentum_curves_are_the_closed_form():
    # the scaled closed form peaks at z~* = -sqrt(2 / (5 pi rho)) with a~ = (5/6)^3
    # sqrt(2 pi rho / 5) (Eq. 2 in the scaled variables of Eq. 3), v~ = 5/6 there
    rho = 1025.0
    curves = momentum_curves(rho, points=20001)
    z_peak, a_peak = curves.peak
    assert z_peak == pytest.approx(-math.sqrt(2 / (5 * math.pi * rho)), rel=1e-3)
    assert a_peak == pytest.approx((5 / 6) ** 3 * math.sqrt(2 * math.pi * rho / 5), rel=1e-6)
    assert float(curves.v(z_peak)) == pytest.approx(5 / 6, rel=1e-4)


@pytest.mark.parametrize(
    ("spec", "beta_deg", "gamma"),
    [
        ("dobrovolskaya", 45.0, -0.0114 * 45 + 1.5669),
        ("wagner", 10.0, math.pi / 2),
        ("Von-Karman", 30.0, 1.0),
        (1.2, 30.0, 1.2),
    ],
)
def test_pile_up_laws(spec, beta_deg, gamma):
    law = pile_up_law(spec)
    assert float(law(np.radians(beta_deg))) == pytest.approx(gamma, rel=1e-12)


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("wagnr", "pile-up law 'wagnr' is unknown"),
        (0.0, "not a positive number"),
        (float("nan"), "not a positive number"),
        (True, "neither a law's name"),
        ([1.0], "neither a law's name"),
    ],
)
def test_bad_pile_up_is_an_input_error(spec, message):
    with pytest.raises(hs.InputError, match=message):
        pile_up_law(spec)


def test_curve_table_from_csv(tmp_path):
    z = np.linspace(PAPER_CURVES.z_range[0], 0.0, 41)
    rows = ["# comment", "v_tilde,note,z_tilde,a_tilde"]  # any column order, extra ignored
    a, v = PAPER_CURVES.a(z).tolist(), PAPER_CURVES.v(z).tolist()
    rows += [f"{vi!r},x,{zi!r},{ai!r}" for zi, ai, vi in zip(z.tolist(), a, v, strict=True)]
    path = tmp_path / "curves.csv"
    path.write_text("\n".join(rows) + "\n")
    curves = CharacteristicCurves.from_csv(path, rho=1025.0)
    assert curves.rho == 1025.0
    assert curves.z_range == pytest.approx((z[0], 0.0), rel=1e-15)
    # at the table's own rows linear interpolation returns the rows
    np.testing.assert_allclose(curves.a(z), PAPER_CURVES.a(z), rtol=1e-15)
    np.testing.assert_allclose(curves.v(z), PAPER_CURVES.v(z), rtol=1e-15)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("z_tilde,a_tilde\n-0.01,1\n0,0\n", "lacks the column(s) v_tilde"),
        ("# c\nz_tilde,a_tilde,v_tilde\n-0.01,1,x\n0,0,1\n", "line 3"),
        ("z_tilde,a_tilde,v_tilde\n-0.01,1,0.9\n", "at least two rows"),
        ("z_tilde,a_tilde,v_tilde\n-0.01,1,0.9\n0.01,0,1\n", "z~ = 0.01 > 0"),
        ("z_tilde,a_tilde,v_tilde\n-0.01,1,0.9\n-0.01,0,1\n", "repeated z~"),
        ("", "is empty"),
    ],
)
def test_bad_curve_table_is_a_case_error(tmp_path, text, message):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(hs.CaseError, match=re_escape(message)):
        CharacteristicCurves.from_csv(path)


def test_missing_curve_table_names_the_path(tmp_path):
    with pytest.raises(hs.CaseError, match=r"nope\.csv' does not exist"):
        CharacteristicCurves.from_csv(tmp_path / "nope.csv")


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"a_coeffs": (1.0, 2.0)}, "both a~ and v~"),
        ({"a_coeffs": "abc", "v_coeffs": (1.0,)}, "not made of numbers"),
        ({"a_coeffs": [[1.0]], "v_coeffs": (1.0,)}, "not a list of finite numbers"),
        ({"table": [[-0.01, 1, 0.9], [0, 0, 1]], "a_coeffs": (1.0,)}, "not both"),
        ({"table": [[-0.01, 1], [0, 0]]}, "rows of three"),
        ({"table": [[-0.01, 1, 0.9], [0, 0, 1]], "rho": "sea"}, "not a number"),
        ({"table": [[-0.01, 1, 0.9], [0, 0, 1]], "rho": -1}, "not positive"),
        ({"table": [[-0.01, 1, 0.9], [0, 0, 1]], "z_range": (0, -0.01)}, "low < high"),
    ],
)
def test_bad_curves_are_input_errors(kwargs, message):
    with pytest.raises(hs.InputError, match=re_escape(message)):
        CharacteristicCurves(**kwargs)


def test_polynomial_curves_with_an_explicit_range_need_no_fitted_floor():
    # a~ = 100 z~^2 has no peak below 0, so the range cannot be found: give it explicitly
    with pytest.raises(hs.InputError, match="give z_range"):
        CharacteristicCurves(a_coeffs=(0, 0, 100.0), v_coeffs=(1.0,))
    c = CharacteristicCurves(a_coeffs=(0, 0, 100.0), v_coeffs=(1.0,), z_range=(-0.02, 0))
    assert c.z_range == (-0.02, 0.0)
    assert float(c.a(-0.01)) == pytest.approx(0.01, rel=1e-12)


def test_curve_solver_with_the_closed_form_curves_is_the_momentum_solver():
    # the closed form's scaled curves (momentum_curves) in the curve solver reproduce the
    # analytic solver with the same pile-up, to the table's interpolation error
    class TableCurves(CurveSolver):
        name = "table"
        curves = momentum_curves(1000.0, points=4001)

        def pile_up(self, deadrise):
            return np.full_like(deadrise, 1.3)

    secs = wedge_sections(np.linspace(0.002, 0.035, 9), math.radians(25.0), 6.0)
    fluid = hs.Fluid()
    f_table = TableCurves().section_loads(secs, -5.0, fluid).force_per_metre
    f_exact = ConstantGamma().section_loads(secs, -5.0, fluid).force_per_metre
    np.testing.assert_allclose(f_table, f_exact, rtol=2e-5)


def re_escape(text: str) -> str:
    return re.escape(text)
