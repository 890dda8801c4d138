"""Gravity's correction of Wagner's contact in the ``mlm`` plugin (``gravity_contact``).

References:

- The first-order problem for the gravity potential (``hullslice_mlm.gravity``, after the
  approach of Hulin et al. 2022, J. Fluid Mech. 944): a wedge's ``c / c0 = 1 - kappa /
  Fr*^2``, ``kappa = alpha / pi``, ``alpha`` by the Keldysh-Sedov solution (one smooth
  quadrature) and, independently, by separation of variables in elliptic coordinates.
- Korobkin (2004): the MLM's closed-form force on a wedge at constant speed, here with the
  contact ``c`` and ``c' = dc/dh`` of the derivation.
- The free surface's potential ``q(X) = X asin(1/X) + X sqrt(X^2 - 1) - X^2 - 1/2`` from
  the time integral of Wagner's free-surface rise.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import hullslice as hs
from hullslice import InputError, shapes

mlm = pytest.importorskip("hullslice_mlm")
gravity = pytest.importorskip("hullslice_mlm.gravity")

RHO, SPEED = 1000.0, 5.0


def wedge(deadrise_deg: float) -> hs.Hull:
    v, f = shapes.wedge_prism(length=1.0, beam=0.4, deadrise_deg=deadrise_deg, sides=0.0)
    return hs.Hull.from_arrays(v, f)


def wedge_case(deadrise_deg: float, froude_star: float, **options):
    """The middle slice of a wedge at constant speed, its keel ``0.02 tan(beta)`` deep,
    ``g`` set for the section's ``Fr* = V / sqrt(g h tan(beta))``."""
    k = math.tan(math.radians(deadrise_deg))
    p = 0.02 * k
    g = 0.0 if math.isinf(froude_star) else SPEED**2 / (froude_star**2 * p * k)
    r = hs.compute_force(
        wedge(deadrise_deg), p, -SPEED, slices=4, solver=mlm.MLM(**options),
        acceleration=0.0, fluid=hs.Fluid(RHO, g),
    )  # fmt: skip
    force = np.asarray(r.force) / np.asarray(r.sections.dx)
    return r, force, np.asarray(r.loads.diagnostics["wetted_half_width"]), p, g


def closed_form(k: float, c: float, cp: float, speed: float) -> float:
    """Korobkin's (2004) wedge force per metre for a contact ``c`` and ``c' = dc/dh``."""

    def bracket(t: float) -> float:
        return cp - 0.5 * math.cos(t) - math.sin(t) ** 2 / (2.0 * math.cos(t) * (1.0 + k * k))

    lo, hi = 0.0, 0.5 * math.pi * (1.0 - 1e-15)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if bracket(mid) > 0.0 else (lo, mid)
    s = math.sin(0.5 * (lo + hi))
    t = 0.5 * (lo + hi)
    return (
        2.0 * RHO * speed**2 * c * (cp * t - 0.5 * s - (math.atanh(s) - s) / (2.0 * (1.0 + k * k)))
    )


def test_kappa_semi_analytic_and_numerical_agree():
    # reference: the Keldysh-Sedov quadrature against the elliptic-coordinate solution
    alpha = gravity.wedge_alpha()
    assert alpha == pytest.approx(gravity.wedge_alpha_numerical(), abs=1e-12)
    assert alpha == pytest.approx(0.0280879319789, abs=1e-12)
    assert gravity.wedge_alpha(32) == pytest.approx(alpha, abs=1e-14)  # quadrature converged
    # a coarser numerical solution still within 1e-9 (its truncation of both transforms)
    assert gravity.wedge_alpha_numerical(15.0, 20.0, 20) == pytest.approx(alpha, abs=1e-9)
    assert pytest.approx(alpha / math.pi, abs=1e-15) == gravity.KAPPA


def test_the_free_surface_potential_by_quadrature_has_its_closed_form():
    # reference: q(X) = X asin(1/X) + X sqrt(X^2 - 1) - X^2 - 1/2, and far away its series
    # 1 / (24 X^2) + 1 / (80 X^4) (the closed form loses digits there)
    x = np.array([1.0, 1.001, 1.3, 3.0])
    exact = x * np.arcsin(1 / x) + x * np.sqrt(x * x - 1) - x * x - 0.5
    np.testing.assert_allclose(gravity._q_by_quadrature(x), exact, rtol=1e-12, atol=0)
    far = gravity._q_by_quadrature(np.array([1e3]))[0]
    assert far == pytest.approx(1 / 24e6 + 1 / 80e12, rel=1e-10)


def test_the_hilbert_formula_gives_the_numerical_solutions_vertical_velocity():
    # reference: Phi_Y on the free surface by the Keldysh-Sedov (Hilbert) formula against
    # the elliptic-coordinate solution, Phi_Y = -Phi_nu / sinh(mu) on nu = 0
    from scipy import integrate

    def qp(s):
        return math.asin(min(1 / s, 1.0)) + 2 * math.sqrt(max(s * s - 1, 0.0)) - 2 * s

    _, _, k, w_k, a = gravity._transform(20.0, 400.0, 400)  # pointwise: slower in k
    for x in (1.1, 2.0, 5.0):

        def f(s, x=x):
            return qp(s) * math.sqrt(max(s * s - 1, 0.0)) / (s + x)

        pv = integrate.quad(f, 1.0, 3 * x, weight="cauchy", wvar=x, limit=400)[0]
        pv += integrate.quad(lambda s, x=x, f=f: f(s) / (s - x), 3 * x, np.inf, limit=400)[0]
        hilbert = -2 * x / (math.pi * math.sqrt(x * x - 1)) * pv
        mu = math.acosh(x)
        numeric = np.sum(w_k * a * k * np.tanh(0.5 * math.pi * k) * np.cos(k * mu)) / math.sinh(mu)
        assert hilbert == pytest.approx(numeric, rel=1e-5)


@pytest.mark.parametrize("deadrise_deg", [10.0, 20.0, 30.0])
@pytest.mark.parametrize("froude_star", [2.0, 4.0, 8.0])
def test_a_wedges_contact_and_force_with_gravity(deadrise_deg, froude_star):
    k = math.tan(math.radians(deadrise_deg))
    _, f0, c0, p, _ = wedge_case(deadrise_deg, froude_star)
    r1, f1, c1, _, _ = wedge_case(deadrise_deg, froude_star, gravity_contact=True)
    delta = gravity.KAPPA / froude_star**2
    # reference: the derivation, c / c0 = 1 - kappa / Fr*^2
    assert c1[1] / c0[1] == pytest.approx(1.0 - delta, abs=1e-10)
    assert r1.loads.diagnostics["gravity_shift"][1] == pytest.approx(delta, rel=1e-9)
    # reference: Korobkin's closed form with c = c0 (1 - delta), c' = c0' (1 - 2 delta)
    cp0 = math.pi / (2 * k)
    ref = closed_form(k, cp0 * p * (1 - delta), cp0 * (1 - 2 * delta), SPEED)
    assert f1[1] == pytest.approx(ref, rel=1e-6)
    # gravity lowers the force: about three times the contact's shift (f ~ c c')
    assert 2.0 * delta < 1.0 - f1[1] / f0[1] < 4.0 * delta


def test_without_gravity_or_fast_the_correction_vanishes():
    # reference: today's MLM (the option off), to 1e-12
    _, f_off, c_off, _, _ = wedge_case(20.0, math.inf)
    _, f_on, c_on, _, _ = wedge_case(20.0, math.inf, gravity_contact=True)  # g = 0
    np.testing.assert_allclose(f_on, f_off, rtol=1e-12, atol=0)
    np.testing.assert_allclose(c_on, c_off, rtol=1e-12, atol=0)
    _, f_off, c_off, _, _ = wedge_case(20.0, 1e7)  # Fr* = 1e7: kappa / Fr*^2 ~ 1e-16
    _, f_on, c_on, _, _ = wedge_case(20.0, 1e7, gravity_contact=True)
    np.testing.assert_allclose(f_on, f_off, rtol=1e-12, atol=0)
    np.testing.assert_allclose(c_on, c_off, rtol=1e-12, atol=0)


def test_with_the_hydrostatic_pressure_both_are_in():
    # reference: the buoyancy rho g A of the option gravity, A = h^2 / tan(beta)
    r, f, _, p, g = wedge_case(20.0, 2.0, gravity=True, gravity_contact=True)
    _, f_contact, _, _, _ = wedge_case(20.0, 2.0, gravity_contact=True)
    buoyancy = RHO * g * p * p / math.tan(math.radians(20.0))
    assert r.loads.diagnostics["buoyancy"][1] == pytest.approx(buoyancy, rel=1e-6)
    assert f[1] - f_contact[1] == pytest.approx(buoyancy, rel=1e-6)


def test_beyond_the_first_order_range_the_shift_is_held_and_flagged():
    # reference: kappa / Fr*^2 = 0.894 at Fr* = 0.1, above DELTA_MAX = 0.2
    r, _, c1, _, _ = wedge_case(20.0, 0.1, gravity=True, gravity_contact=True)
    _, _, c0, _, _ = wedge_case(20.0, 0.1, gravity=True)
    assert r.loads.diagnostics["gravity_shift"][1] == pytest.approx(gravity.DELTA_MAX, abs=1e-15)
    assert c1[1] / c0[1] == pytest.approx(1.0 - gravity.DELTA_MAX, abs=1e-10)
    assert "gravity's contact correction held" in r.loads.reason[1]
    assert not r.loads.valid[1]


def test_a_round_section_takes_its_local_deadrise():
    # reference: a circle of radius R, f(y) = R - sqrt(R^2 - y^2): Wagner's
    # integral_0^{pi/2} f(c sin t) dt = pi h / 2 and c' = (pi / 2) / integral f'(c sin t)
    # sin t dt by quadrature, so tan(beta_e) = pi / (2 c'), delta = kappa g h tan(beta_e) / V^2
    from scipy import integrate, optimize

    radius, p, g = 0.5, 0.01, 9.81
    v, f = shapes.circular_cylinder(length=1.0, radius=radius, points=720)
    hull = hs.Hull.from_arrays(v, f)
    r = hs.compute_force(
        hull, p, -1.0, slices=4, solver=mlm.MLM(gravity_contact=True),
        acceleration=0.0, fluid=hs.Fluid(RHO, g),
    )  # fmt: skip

    def f(y):
        return radius - math.sqrt(radius**2 - y * y)

    def wagner(c):
        return integrate.quad(lambda t: f(c * math.sin(t)), 0, 0.5 * math.pi)[0] - 0.5 * math.pi * p

    c = optimize.brentq(wagner, 1e-6, radius)
    fp = integrate.quad(
        lambda t: c * math.sin(t) / math.sqrt(radius**2 - (c * math.sin(t)) ** 2)
        * math.sin(t), 0, 0.5 * math.pi,
    )[0]  # fmt: skip
    tan_e = fp  # pi / (2 c') = integral_0^{pi/2} f'(c sin t) sin t dt
    delta = gravity.KAPPA * g * p * tan_e / 1.0**2
    assert r.loads.diagnostics["gravity_shift"][1] == pytest.approx(delta, rel=2e-3)


@pytest.mark.parametrize("bad", ["yes", 1, 0.5, None, math.nan])
def test_bad_values_of_the_option_are_refused(bad):
    with pytest.raises(
        InputError, match=r"option gravity_contact=.* is not (true or false|a finite)"
    ):
        mlm.MLM(gravity_contact=bad)


def test_the_gravity_potentials_force_on_the_disc_converges():
    # reference: the elliptic-coordinate solution at two resolutions (the estimate quoted
    # in docs/validation.md, 0.105 buoyancies); Phi on the disc meets q(1) at its edges
    coarse = gravity.wedge_plate_force(20.0, 30.0, 40)
    fine = gravity.wedge_plate_force(25.0, 120.0, 160)
    assert fine == pytest.approx(0.1045992, abs=1e-6)
    assert coarse == pytest.approx(fine, abs=2e-6)
