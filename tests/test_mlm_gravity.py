"""Gravity's first-order correction in the ``mlm`` plugin (``gravity = "hulin"``): the
contact and the gravity potential's pressure.

References:

- The first-order problem for the gravity potential (``hullslice_mlm.gravity``, after the
  approach of Hulin et al. 2022, J. Fluid Mech. 944): a wedge's ``c / c0 = 1 - kappa /
  Fr*^2``, ``kappa = alpha / pi``, ``alpha`` by the Keldysh-Sedov solution (one smooth
  quadrature) and, independently, by separation of variables in elliptic coordinates.
- Korobkin (2004): the MLM's closed-form force on a wedge at constant speed, here with the
  contact ``c`` and ``c' = dc/dh`` of the derivation.
- The gravity potential on the disc by the Keldysh-Sedov form, ``Phi(X) = q(1) + (2/pi)
  integral_1^inf q'(s) atan(sqrt(1 - X^2) / sqrt(s^2 - 1)) ds``, against the
  elliptic-coordinate solution; its pressure ``rho g h (2 Phi - m X Phi')``.
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
    ``g`` set for the section's ``Fr* = V / sqrt(g h tan(beta))``: the result, the force
    per metre, the wetted half-width, ``h`` and ``g``."""
    k = math.tan(math.radians(deadrise_deg))
    p = 0.02 * k
    g = 0.0 if math.isinf(froude_star) else SPEED**2 / (froude_star**2 * p * k)
    r = hs.compute_force(
        wedge(deadrise_deg), p, -SPEED, slices=4, solver=mlm.MLM(**options),
        acceleration=0.0, fluid=hs.Fluid(RHO, g),
    )  # fmt: skip
    force = np.asarray(r.force) / np.asarray(r.sections.dx)
    return r, force, np.asarray(r.loads.diagnostics["wetted_half_width"]), p, g


def parts(r) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The force per metre with the corrected contact alone, the gravity potential's
    pressure force (``extra``) and the buoyancy (``vertical``), N/m."""
    force = np.asarray(r.force) / np.asarray(r.sections.dx)
    extra = np.asarray(r.loads.diagnostics["extra_force"])
    vertical = np.asarray(r.loads.diagnostics["vertical_force"])
    return force - extra - vertical, extra, vertical


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
    _, f0, c0, p, g = wedge_case(deadrise_deg, froude_star)
    r1, _, c1, _, _ = wedge_case(deadrise_deg, froude_star, gravity="hulin")
    f_contact, f_pressure, f_buoyancy = parts(r1)
    delta = gravity.KAPPA / froude_star**2
    # reference: the derivation, c / c0 = 1 - kappa / Fr*^2
    assert c1[1] / c0[1] == pytest.approx(1.0 - delta, abs=1e-10)
    assert r1.loads.diagnostics["gravity_shift"][1] == pytest.approx(delta, rel=1e-9)
    # reference: Korobkin's closed form with c = c0 (1 - delta), c' = c0' (1 - 2 delta)
    cp0 = math.pi / (2 * k)
    ref = closed_form(k, cp0 * p * (1 - delta), cp0 * (1 - 2 * delta), SPEED)
    assert f_contact[1] == pytest.approx(ref, rel=1e-6)
    # the contact lowers the force: about three times its shift (f ~ c c')
    assert 2.0 * delta < 1.0 - f_contact[1] / f0[1] < 4.0 * delta
    # reference: the buoyancy rho g A of the option gravity, A = h^2 / tan(beta)
    assert f_buoyancy[1] == pytest.approx(RHO * g * p * p / k, rel=1e-6)
    # the gravity potential's pressure: 0.12 to 0.14 buoyancies (up to the sign change)
    assert 0.11 * f_buoyancy[1] < f_pressure[1] < 0.14 * f_buoyancy[1]


def test_without_gravity_or_fast_the_correction_vanishes():
    # reference: today's MLM (gravity off, or buoyancy only), to 1e-12
    _, f_off, c_off, _, _ = wedge_case(20.0, math.inf)
    _, f_on, c_on, _, _ = wedge_case(20.0, math.inf, gravity="hulin")  # g = 0
    np.testing.assert_allclose(f_on, f_off, rtol=1e-12, atol=0)
    np.testing.assert_allclose(c_on, c_off, rtol=1e-12, atol=0)
    _, f_off, c_off, _, _ = wedge_case(20.0, 1e7, gravity=True)  # kappa / Fr*^2 ~ 1e-16
    _, f_on, c_on, _, _ = wedge_case(20.0, 1e7, gravity="hulin")
    np.testing.assert_allclose(f_on, f_off, rtol=1e-12, atol=0)
    np.testing.assert_allclose(c_on, c_off, rtol=1e-12, atol=0)


def test_the_option_gravity_true_is_the_buoyancy_alone():
    # reference: gravity off plus rho g A, A = h^2 / tan(beta); the contact as without gravity
    r, f, c, p, g = wedge_case(20.0, 2.0, gravity=True)
    _, f_off, c_off, _, _ = wedge_case(20.0, 2.0)
    buoyancy = RHO * g * p * p / math.tan(math.radians(20.0))
    assert r.loads.diagnostics["buoyancy"][1] == pytest.approx(buoyancy, rel=1e-6)
    assert f[1] - f_off[1] == pytest.approx(buoyancy, rel=1e-6)
    assert c[1] == pytest.approx(c_off[1], rel=1e-15)
    assert r.loads.diagnostics["extra_force"][1] == 0.0
    assert "gravity_shift" not in r.loads.diagnostics
    for spelled in ("Hulin", " hulin "):  # the choice's spelling is free
        assert mlm.MLM(gravity=spelled).settings["gravity"] == "hulin"


def test_beyond_the_first_order_range_the_shift_is_held_and_flagged():
    # reference: kappa / Fr*^2 = 0.894 at Fr* = 0.1, above DELTA_MAX = 0.2
    r, _, c1, _, _ = wedge_case(20.0, 0.1, gravity="hulin")
    _, _, c0, _, _ = wedge_case(20.0, 0.1, gravity=True)
    assert r.loads.diagnostics["gravity_shift"][1] == pytest.approx(gravity.DELTA_MAX, abs=1e-15)
    assert c1[1] / c0[1] == pytest.approx(1.0 - gravity.DELTA_MAX, abs=1e-10)
    assert "gravity's contact correction held" in r.loads.reason[1]
    assert not r.loads.valid[1]


def parabola(radius: float, half_beam: float) -> hs.Hull:
    y = np.linspace(-half_beam, half_beam, 801)
    section = np.stack([y, y * y / (2 * radius)], axis=1)  # counter-clockwise, top closed
    v, f = shapes.prism_from_sections(np.array([0.0, 1.0]), np.stack([section, section]))
    return hs.Hull.from_arrays(v, f)


def _parabola_p_slope(x: float) -> float:
    """P_2'(X) = integral_0^1 s^(1/2) E_2'(X s^(-1/2)) ds (s = 1 - v^2), with
    E_2(xi) = 2 xi (xi - sqrt(xi^2 - 1)) - 1."""
    from scipy import integrate

    def rise_slope(xi):
        r = math.sqrt(max(xi * xi - 1.0, 0.0))
        return 4 * xi - 2 * r - 2 * xi * xi / r

    return integrate.quad(
        lambda v: math.sqrt(1 - v * v) * rise_slope(x / math.sqrt(1 - v * v)) * 2 * v,
        0.0, 1.0, limit=200,
    )[0]  # fmt: skip


def test_beta_2_by_the_keldysh_sedov_kernel():
    # reference: beta_2 = -(2/pi) integral_1^inf P_2'(s) sqrt(s^2 - 1) K_2(s) ds with the
    # elementary kernel K_2 = 3 pi / (16 s^2) + pi / (4 s^4) + pi / (2 s^6) and
    # E_2(xi) = 2 xi (xi - sqrt(xi^2 - 1)) - 1, against the elliptic-coordinate solution
    from scipy import integrate

    p_slope = _parabola_p_slope

    def kernel(s):
        return 3 * math.pi / (16 * s**2) + math.pi / (4 * s**4) + math.pi / (2 * s**6)

    beta = -(2 / math.pi) * integrate.quad(
        lambda th: p_slope(1 / math.sin(th)) * (math.cos(th) / math.sin(th))
        * kernel(1 / math.sin(th)) * math.cos(th) / math.sin(th) ** 2,
        1e-9, 0.5 * math.pi, limit=200,
    )[0]  # fmt: skip
    assert beta == pytest.approx(gravity.power_law_beta(2.0), rel=1e-7)
    assert beta == pytest.approx(1 / 15, rel=1e-7)


def test_the_lambda_table_is_the_power_laws():
    # reference: power_law_lambda (the elliptic-coordinate solution) at a coarser
    # resolution than the table's, and between its points the fit
    ms, lams = gravity.LAMBDA_TABLE
    for m, lam in zip(ms[::3], lams[::3], strict=True):
        assert gravity.power_law_lambda(1 / m) == pytest.approx(lam, rel=1e-8)
        assert gravity.growth_lambda(m) == pytest.approx(lam, rel=1e-7)
    assert gravity.growth_lambda(1.0) == pytest.approx(gravity.wedge_alpha() / 2, abs=1e-16)
    mid = gravity.power_law_lambda(1 / 0.675)  # halfway between two of the table's points
    assert gravity.growth_lambda(0.675) == pytest.approx(mid, rel=1e-7)
    assert gravity.LAMBDA_TABLE[1][5] == pytest.approx(16 / (225 * math.pi), rel=1e-9)


def test_a_parabolic_section_has_its_power_laws_correction():
    # reference: f = y^2 / (2 R), c0 = 2 sqrt(R h): c / c0 = 1 - lambda_2 g h^2 / (V^2 c0),
    # lambda_2 = 16 / (225 pi) (beta_2 = 1/15), to first order (the solver's h (1 - delta)
    # differs by delta^2 / 8 ~ 1e-5)
    radius, p, g, speed = 0.5, 0.005, 9.81, 0.105
    hull = parabola(radius, 0.2)
    c = []
    for on in (False, True):
        r = hs.compute_force(
            hull, p, -speed, slices=4, solver=mlm.MLM(gravity="hulin" if on else False),
            acceleration=0.0, fluid=hs.Fluid(RHO, g),
        )  # fmt: skip
        c.append(r.loads.diagnostics["wetted_half_width"][1])
    assert c[0] == pytest.approx(2 * math.sqrt(radius * p), rel=2e-3)  # Wagner's
    expected = 16 / (225 * math.pi) * g * p * p / (speed**2 * c[0])
    assert 1 - c[1] / c[0] == pytest.approx(expected, rel=1e-2)
    assert expected == pytest.approx(0.005, rel=0.05)
    # reference: the gravity potential's pressure of the power law n = 2 (plate_pressure,
    # the elliptic-coordinate solution) up to the pressure's sign change, 2 rho g h c
    # integral_0^{y*/c} S_2 dX by Gauss-Legendre (the contour's own growth exponent m is
    # 1/2 to 2e-3)
    top = r.loads.diagnostics["pressure_half_width"][1] / c[1]
    u, w = np.polynomial.legendre.leggauss(64)
    t = 0.5 * math.asin(top) * (u + 1)
    shape = 0.5 * math.asin(top) * np.sum(w * gravity.plate_pressure(np.sin(t), 2.0) * np.cos(t))
    extra = r.loads.diagnostics["extra_force"][1]
    assert extra == pytest.approx(2 * RHO * g * p * c[1] * shape, rel=2e-3)


@pytest.mark.parametrize("bad", ["yes", "hulin2022", 1, 0.5, None, math.nan])
def test_bad_values_of_the_option_are_refused(bad):
    with pytest.raises(
        InputError, match=r"option gravity=.* is not (true, false or 'hulin'|a finite)"
    ):
        mlm.MLM(gravity=bad)


def test_the_gravity_potentials_force_on_the_disc_converges():
    # reference: the elliptic-coordinate solution at two resolutions (the estimate quoted
    # in docs/validation.md, 0.105 buoyancies); Phi on the disc meets q(1) at its edges
    coarse = gravity.wedge_plate_force(20.0, 30.0, 40)
    fine = gravity.wedge_plate_force(25.0, 120.0, 160)
    assert fine == pytest.approx(0.1045992, abs=1e-6)
    assert coarse == pytest.approx(fine, abs=2e-6)


@pytest.mark.parametrize("m", [1.0, 0.5, 0.3])
def test_the_contact_rate_is_the_corrected_contacts_derivative(m):
    # reference: for a power-law contact c_W = C h^m, the corrected contact
    # c(h) = c_W(h (1 - delta(h))) differentiated by central differences at fixed V and g
    big_c, g, speed = 0.7, 9.81, 0.3

    def wagner(h):
        return big_c * h**m

    def corrected(h):
        shift, _, _ = gravity.contact_shift(h, speed, g, wagner(h), m * wagner(h) / h)
        return wagner(h * (1 - shift)), shift

    h, dh = 0.01, 1e-7
    _, shift = corrected(h)
    assert 0.005 < shift < 0.05  # inside the first-order range
    _, _, factor = gravity.contact_shift(h, speed, g, wagner(h), m * wagner(h) / h)
    rate = m * wagner(h * (1 - shift)) / (h * (1 - shift)) * factor
    numeric = (corrected(h + dh)[0] - corrected(h - dh)[0]) / (2 * dh)
    assert rate == pytest.approx(numeric, rel=1e-6)


def _wallis(p: float) -> float:  # integral_0^{pi/2} sin^p
    return 0.5 * math.sqrt(math.pi) * math.gamma(0.5 * (p + 1)) / math.gamma(0.5 * p + 1)


def _march(n: float, g: float, beta: float, steps: int = 400) -> tuple[np.ndarray, np.ndarray]:
    """Wagner's condition with gravity marched on the contacts ``c_j = j dc`` of
    ``f = y^n`` entering at ``V = 1``: the times ``t_j`` where
    ``integral_0^t c / sqrt(c^2 - c(tau)^2) dtau = c^n - eta1(t)`` (``eta0`` of the marched
    history at its own contact, exact for ``t(c)`` linear between the contacts), the
    surface lowered at the contact by ``eta1 = -n g t^3 beta_n / c``."""
    from scipy import optimize

    c = np.linspace(0.0, 1.0, steps + 1)
    dc = c[1]
    t = np.zeros(steps + 1)
    for i in range(1, steps + 1):
        w = (np.arcsin(c[1 : i + 1] / c[i]) - np.arcsin(c[:i] / c[i])) * c[i] / dc
        known = float(np.sum(np.diff(t[:i]) * w[: i - 1]))

        def residual(ti, i=i, w=w, known=known):
            return known + (ti - t[i - 1]) * w[-1] - c[i] ** n - n * g * ti**3 * beta / c[i]

        t[i] = optimize.brentq(residual, t[i - 1], t[i - 1] + 2.0, xtol=1e-15, rtol=1e-15)
    return c, t


@pytest.mark.parametrize("n", [1.0, 2.0])
def test_wagners_condition_marched_in_time_gives_the_contacts_shift(n):
    # reference: c / c0 = 1 - lambda_n g h^2 / (V^2 c0), lambda_n = 2 beta_n I_(3n-1) / pi,
    # against Wagner's condition marched in time (no use of Wagner's integral form): at
    # the same contact the time is longer by eps / m, m = 1/n (the same grid without
    # gravity takes out the marching's own error)
    beta = gravity.power_law_beta(n)
    c, t0 = _march(n, 0.0, beta)
    _, tg = _march(n, 1e-3, beta)
    assert t0[-1] == pytest.approx(2 * _wallis(n) / math.pi, rel=1e-4)  # Wagner: c^n I_n = pi h/2
    lam = 2 * beta * _wallis(3 * n - 1) / math.pi
    eps = lam * 1e-3 * t0[-1] ** 2 / c[-1]
    assert tg[-1] / t0[-1] - 1 == pytest.approx(n * eps, rel=1e-3)


def test_the_surface_lowered_at_the_contact_is_the_time_integral_of_phi1_y():
    # reference: eta1(c0(t), t) = integral_0^t phi1_y(c0(t), tau) dtau with
    # phi1_y(x, tau) = -(g V tau^2 / c0(tau)) Phi_Y(x / c0(tau)) (Phi_Y by the Hilbert
    # formula) equals -alpha g V t^2 / gamma on the wedge (g = V = gamma = t = 1)
    from scipy import integrate

    def qp(s):
        return math.asin(min(1 / s, 1.0)) + 2 * math.sqrt(max(s * s - 1, 0.0)) - 2 * s

    def phi_y_root(x):  # Phi_Y(X) sqrt(X - 1), smooth at the contact
        x = max(x, 1.0 + 1e-9)

        def f(s, x=x):
            return qp(s) * math.sqrt(max(s * s - 1, 0.0)) / (s + x)

        pv = integrate.quad(f, 1.0, 3 * x, weight="cauchy", wvar=x, limit=400)[0]
        pv += integrate.quad(lambda s, x=x, f=f: f(s) / (s - x), 3 * x, np.inf, limit=400)[0]
        return -2 * x / (math.pi * math.sqrt(x + 1)) * pv

    # tau = 1 / X: Phi_Y(1 / tau) ~ (1 - tau)^(-1/2) at the contact, taken out by the weight
    eta1 = -integrate.quad(
        lambda tau: tau * phi_y_root(1 / tau) * math.sqrt(tau), 1e-6, 1.0,
        weight="alg", wvar=(0.0, -0.5), limit=200,
    )[0]  # fmt: skip
    assert eta1 == pytest.approx(-gravity.wedge_alpha(), rel=1e-6)


Q1 = 0.5 * math.pi - 1.5  # q(1), the free surface's potential at the contact


def _q_slope(s: float) -> float:  # q'(s)
    return math.asin(min(1 / s, 1.0)) + 2 * math.sqrt(max(s * s - 1, 0.0)) - 2 * s


def _disc_phi(x: float, slope=_q_slope, edge: float = Q1) -> float:
    """Phi on the disc by the Keldysh-Sedov form: P(1) + (2/pi) integral_1^inf P'(s)
    atan(sqrt(1 - X^2) / sqrt(s^2 - 1)) ds."""
    from scipy import integrate

    r = math.sqrt(1 - x * x)
    tail = integrate.quad(
        lambda s: slope(s) * math.atan(r / math.sqrt(s * s - 1)), 1, np.inf, limit=400
    )[0]
    return edge + 2 / math.pi * tail


def _disc_phi_x(x: float) -> float:
    """Phi' on the disc, -Im H / sqrt(1 - X^2) (H by Hilbert's formula)."""
    from scipy import integrate

    tail = integrate.quad(
        lambda s: _q_slope(s) * math.sqrt(s * s - 1) / (s * s - x * x), 1, np.inf, limit=400
    )[0]
    return -2 * x / (math.pi * math.sqrt(1 - x * x)) * tail


def test_the_gravity_potential_on_the_disc_by_two_solutions():
    # reference: the Keldysh-Sedov form against the elliptic-coordinate solution, Phi and
    # Phi' on the wedge's disc; Phi meets q(1) at the contact
    x = np.array([0.0, 0.3, 0.7, 0.95])
    phi, phi_t = gravity.plate_potential(np.arcsin(x))
    for xi, f, ft in zip(x, phi, phi_t, strict=True):
        assert f == pytest.approx(_disc_phi(xi), rel=1e-9)
        assert ft / math.sqrt(1 - xi * xi) == pytest.approx(_disc_phi_x(xi), rel=1e-7, abs=1e-12)
    edge, _ = gravity.plate_potential(np.array([0.5 * math.pi]))
    assert edge[0] == pytest.approx(Q1, rel=1e-4)
    assert phi[0] == pytest.approx(0.0296238437559, rel=1e-9)


def test_the_pressure_of_the_gravity_potential_on_the_whole_disc():
    # reference: the force (2 + m) I - 2 m P(1) per rho g h c with I = integral Phi dX by
    # the Keldysh-Sedov form, I = 2 P(1) + 2 integral_1^inf P'(s) (s - sqrt(s^2 - 1)) ds,
    # against the elliptic-coordinate solution (plate_force, and wedge_plate_force by a
    # quadrature over the disc); the wedge's 0.1046 buoyancies
    from scipy import integrate

    tail = integrate.quad(lambda s: _q_slope(s) * (s - math.sqrt(s * s - 1)), 1, np.inf)
    big_i = 2 * Q1 + 2 * tail[0]
    wedge_force = 0.5 * math.pi * (3 * big_i - 2 * Q1)
    assert wedge_force == pytest.approx(0.5 * math.pi * gravity.plate_force(1.0), abs=1e-9)
    assert wedge_force == pytest.approx(gravity.wedge_plate_force(25.0, 120.0, 160), abs=1e-9)
    assert wedge_force == pytest.approx(0.1045992, abs=1e-7)
    # the parabola: P_2(1) = integral_0^1 s E_2(s^(-1/2)) ds, E_2(xi) = 2 xi (xi -
    # sqrt(xi^2 - 1)) - 1, and its force 2/9 per rho g h c
    p1 = integrate.quad(
        lambda s: s * (2 / s * (1 - math.sqrt(max(1 - s, 0.0))) - 1), 0, 1, limit=200
    )[0]
    assert p1 == pytest.approx(
        float(gravity._free_surface_potential(np.array([1.0]), 2.0)[0]), rel=1e-12
    )
    tail = integrate.quad(lambda s: _parabola_p_slope(s) * (s - math.sqrt(s * s - 1)), 1, np.inf)
    big_i = 2 * p1 + 2 * tail[0]
    assert 2.5 * big_i - p1 == pytest.approx(gravity.plate_force(2.0), rel=1e-7)
    assert gravity.plate_force(2.0) == pytest.approx(2 / 9, rel=1e-8)


@pytest.mark.parametrize("deadrise_deg", [10.0, 20.0, 30.0])
def test_the_solvers_gravity_pressure_on_a_wedge(deadrise_deg):
    # reference: 2 rho g h c integral_0^{y*/c} (2 Phi - X Phi') dX with Phi and Phi' by the
    # Keldysh-Sedov form (no use of the solver's table), y* the pressure's sign change
    from scipy import integrate

    r, _, c, p, g = wedge_case(deadrise_deg, 2.0, gravity="hulin")
    _, f_pressure, _ = parts(r)
    top = r.loads.diagnostics["pressure_half_width"][1] / c[1]
    shape = integrate.quad(lambda x: 2 * _disc_phi(x) - x * _disc_phi_x(x), 0, top, limit=200)
    assert f_pressure[1] == pytest.approx(2 * RHO * g * p * c[1] * shape[0], rel=3e-5)


def test_the_disc_table_is_the_power_laws():
    # reference: plate_pressure (the elliptic-coordinate solution of each power law) against
    # the solver's table, between its nodes in m and in t
    t = np.linspace(0.0, 1.5, 11)
    for m in (1.0, 0.675, 0.4, 0.25):
        ref = gravity.plate_pressure(np.sin(t), 1 / m)
        got = gravity.disc_pressure(np.broadcast_to(t, (2, 1, len(t))), np.full((2, 1), m))
        np.testing.assert_allclose(got[0, 0], ref, rtol=0, atol=5e-4)
        np.testing.assert_allclose(got[0, 0, :8], ref[:8], rtol=0, atol=2e-5)  # t < 1.05
