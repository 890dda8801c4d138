"""Gravity's first-order correction of Wagner's flow at low Froude number (option
``gravity = "hulin"``): the contact and the gravity potential's own pressure.

After the approach of Hulin, Del Buono, Tassin, Bernardini & Iafrati (2022, J. Fluid Mech.
944, "Gravity effects in two-dimensional and axisymmetric water impact models": Wagner's
model with a free-surface condition modified for gravity, the pressure by the MLM, the
effect governed by ``Fr* = V / (sqrt(g h) sqrt(tan beta))``); the correction below is
derived here, to first order in ``1 / Fr*^2``.

**Wagner's problem with gravity.** A body enters at speed ``V`` (down); linearised flow in
``y < 0``, the wetted flat disc ``|x| < c(t)``, ``phi_y = -V`` on it. On the free surface
``|x| > c`` the kinematic condition ``eta_t = phi_y`` and the dynamic condition
``phi_t + g eta = 0``. Expanding in ``g``: ``phi = phi0 + phi1``, ``eta = eta0 + eta1``,

- ``phi0 = 0`` on the free surface (Wagner's problem), ``eta0_t = phi0_y``;
- ``phi1 = -g integral_0^t eta0 dt`` on the free surface, ``phi1_y = 0`` on the disc,
  ``phi1`` bounded at the contact points and decaying far away; ``eta1_t = phi1_y``;
- Wagner's condition ``eta0(c, t) + eta1(c, t) = f(c) - h``. ``eta0`` of the actual
  contact history at its own contact gives Wagner's integral exactly, so with
  ``G(c) = eta1(c(t), t)`` along the contact's path it reads
  ``integral_0^{pi/2} [f(c sin u) - G(c sin u)] du = (pi / 2) h``.

**The wedge at constant speed** (``f = k y``, ``k = tan beta``) is self-similar:
``c0 = gamma t``, ``gamma = pi V / (2 k)``; with ``X = x / c0`` the free surface rises as
``eta0 = V t (X asin(1/X) - 1)`` and ``phi1 = -g V t^2 q(X)`` on it,
``q(X) = X asin(1/X) + X sqrt(X^2 - 1) - X^2 - 1/2``. If ``Phi`` is the bounded harmonic
function in ``Y < 0`` equal to ``q`` on ``|X| > 1`` with ``Phi_Y = 0`` on ``|X| < 1``,
then ``eta1(c0, t) = -alpha g V t^2 / gamma`` with
``alpha = integral_1^inf Phi_Y(X) X^-3 dX``. Wagner's condition then gives, to first
order, ``k c + alpha k g c^2 / (2 gamma^2) = (pi / 2) h``:

    c / c0 = 1 - kappa / Fr*^2,   Fr*^2 = V^2 / (g h tan beta),   kappa = alpha / pi.

``alpha`` semi-analytically (:func:`wedge_alpha`): ``H = (Phi_X - i Phi_Y) sqrt(z^2 - 1)``
is analytic in ``Y < 0``, bounded, with ``Re H = q'(X) sqrt(X^2 - 1)`` on ``|X| > 1`` and
``Re H = 0`` on the disc (the Keldysh-Sedov form of the mixed problem), so Hilbert's
formula gives ``Phi_Y`` on the free surface,

    Phi_Y(X) = -(2 X / (pi sqrt(X^2 - 1))) PV integral_1^inf q'(s) sqrt(s^2 - 1) / (s^2 - X^2) ds,

and the ``X`` integral is elementary:

    alpha = -(2/pi) integral_1^inf q'(s) [sqrt(s^2 - 1) / s^2 + acosh(s) / s^3] ds
          = 0.02808793198,   kappa = alpha / pi = 0.008940666.

:func:`wedge_alpha_numerical` solves the mixed problem independently (separation of
variables in elliptic coordinates, both transforms by quadrature, ``q`` from ``eta0`` by
quadrature); the two agree to 1e-15.
Gravity lowers the raised free surface (``eta1 < 0``): the contact grows more slowly.

**Power-law sections** ``f = A y^n`` at constant speed are self-similar too (``c0`` as
``t^(1/n)``; ``n = 1`` the wedge, ``n = 2`` a parabola, a circle's bottom): with
``eta0 = V t E_n(x / c0)``, ``phi1 = -g V t^2 P_n(x / c0)`` and ``Phi`` the mixed problem's
solution for the data ``P_n``, ``eta1(c0, t) = -n g V t^3 beta_n / c0``,
``beta_n = integral_1^inf Phi_Y X^(-3n) dX``, and Wagner's condition gives

    c / c0 = 1 - lambda_n g h^2 / (V^2 c0),   lambda_n = 2 beta_n I_(3n-1) / pi,

``I_p = integral_0^{pi/2} sin^p``. ``beta_1 = alpha`` (``lambda_1 = alpha / 2``; on the wedge
``g h^2 / (V^2 c0) = 2 / (pi Fr*^2)``); ``beta_2 = 1/15``, to 1e-12 by the
elliptic-coordinate solution and to 1e-7 by the Keldysh-Sedov kernel (in the tests), so
``lambda_2 = 16 / (225 pi)``, 1.61 times the wedge's. :data:`LAMBDA_TABLE` holds
``lambda`` against the contact's growth exponent ``m = 1/n``, by the elliptic-coordinate
solution.

**Any section** (an approximation beyond the power laws): the power law with the same
local exponent ``m = d ln c / d ln h = c' h / c`` (Wagner's ``c'``; ``m`` held in
``[1/4, 1]``), that is the contact of the penetration ``h (1 - delta)``,
``delta = lambda(m) g h^2 / (m V^2 c)`` (a wedge's ``delta = kappa / Fr*^2``). ``c'`` is
taken quasi-steadily, at the current speed with ``m`` held, as a power law's:
``dc/dh = c'(h (1 - delta)) (1 - (3 - m) delta)`` (a wedge's ``1 - 2 delta``).
``delta`` is held at :data:`DELTA_MAX` (the first-order expansion is not valid beyond),
and such sections are flagged.

**The gravity potential's pressure.** ``phi1`` has its own pressure on the disc,
``p1 = -rho phi1_t``, first order in ``1 / Fr*^2`` like the contact's shift. On
``f = A y^n`` at constant speed ``phi1 = -g V t^2 Phi(x / c0)`` on the disc (``Phi`` the
mixed problem's solution above, now on ``|X| < 1``) and ``c0`` grows as ``t^m``,
``m = 1/n``, so

    p1 = rho g h S_m(x / c),   S_m(X) = 2 Phi(X) - m X Phi'(X),

a pressure of the buoyancy's scale ``rho g h``, independent of ``V`` at a given ``h``.
``Phi'`` grows as ``1 / sqrt(1 - X^2)`` at the contact (``S`` falls to minus infinity
there, as the MLM's velocity term does). Two solutions of the mixed problem give ``Phi``
on the disc: in elliptic coordinates (``mu = 0``, ``X = sin t``,
``Phi = integral A(k) cosh(k t) / cosh(k pi/2) dk``, :func:`plate_potential`), and by the
Keldysh-Sedov form (``Phi_X = -Im H / sqrt(1 - X^2)`` on the disc, integrated in from the
contact, where ``Phi = P(1)``), which leaves one integral:

    Phi(X) = P(1) + (2/pi) integral_1^inf P'(s) atan(sqrt(1 - X^2) / sqrt(s^2 - 1)) ds.

Over the whole disc the force is ``rho g h c integral_{-1}^{1} S dX = rho g h c ((2 + m) I
- 2 m P(1))``, ``I = integral_{-1}^{1} Phi dX`` (:func:`plate_force`); on the wedge
``(pi / 2)(3 I - 2 q(1)) = 0.1046`` buoyancies ``rho g h^2 / tan(beta)``, on the parabola
``I = 7/45``. In the MLM the pressure is taken, as Logvinovich's, on the real body's wetted
part up to the velocity term's change of sign (:func:`disc_pressure`, ``S`` of the
section's own ``m``; ``phi1_y = 0`` on the disc, so the body's offset ``f - h`` adds
nothing at first order). The cross term ``rho grad(phi0) . grad(phi1)`` of Bernoulli's
equation is left out: it is smaller by the deadrise's slope, ``O(tan(beta))``, and not
integrable at the contact in the flat-disc approximation.
"""

from __future__ import annotations

import functools
import math

import numpy as np

__all__ = [
    "DELTA_MAX",
    "KAPPA",
    "LAMBDA_TABLE",
    "contact_shift",
    "disc_pressure",
    "growth_exponent",
    "growth_lambda",
    "plate_force",
    "plate_potential",
    "plate_pressure",
    "power_law_beta",
    "power_law_lambda",
    "wedge_alpha",
    "wedge_alpha_numerical",
    "wedge_plate_force",
]

#: The largest relative shift ``delta`` of the penetration (a wedge's ``kappa / Fr*^2``);
#: beyond it the first-order expansion is not valid (the section is flagged, ``delta`` held).
DELTA_MAX = 0.2


def wedge_alpha(nodes: int = 64) -> float:
    """``alpha = -eta1(c, t) gamma / (g V t^2)`` from the Keldysh-Sedov solution, one smooth
    quadrature in ``s = 1 / sin(theta)`` (Gauss-Legendre):
    ``alpha = -(2/pi) integral_0^{pi/2} (theta - 2 tan(theta/2))
    [cos(theta)^2 / sin(theta) + sin(theta) cos(theta) ln(cot(theta/2))] dtheta``."""
    u, w = np.polynomial.legendre.leggauss(nodes)
    t = 0.25 * math.pi * (u + 1.0)
    st, ct = np.sin(t), np.cos(t)
    f = (t - 2.0 * np.tan(0.5 * t)) * (ct**2 / st + st * ct * np.log(1.0 / np.tan(0.5 * t)))
    return float(-(2.0 / math.pi) * 0.25 * math.pi * (f @ w))


#: The wedge's ``c / c0 = 1 - KAPPA / Fr*^2`` (``Fr*^2 = V^2 / (g h tan beta)``).
KAPPA = wedge_alpha() / math.pi


_GL_U, _GL_W = np.polynomial.legendre.leggauss(48)


def _rise(xi: np.ndarray, n: float) -> np.ndarray:
    """``E_n(xi) = eta0 / (V t)`` at ``x = xi c0`` (``xi >= 1``) for ``f = A y^n``:
    ``integral_0^1 (xi / sqrt(xi^2 - s^(2/n)) - 1) ds = n xi^n integral_0^{asin(1/xi)}
    sin(w)^(n-1) dw - 1``, by Gauss-Legendre."""
    top = np.arcsin(np.minimum(1.0 / xi, 1.0))[..., None]
    w = 0.5 * top * (_GL_U + 1.0)
    return n * xi**n * (0.5 * top[..., 0]) * ((np.sin(w) ** (n - 1.0)) @ _GL_W) - 1.0


def _free_surface_potential(x: np.ndarray, n: float = 1.0) -> np.ndarray:
    """``P_n(X) = -phi1 / (g V t^2)`` on the free surface from ``eta0``'s history by
    quadrature, ``P_n(X) = integral_0^1 s E_n(X s^(-1/n)) ds`` (``s = tau / t``; ``s = 1 - v^2``
    takes out ``E_n``'s square root at the contact). ``P_1 = q``."""
    v = 0.5 * (_GL_U + 1.0)
    s = 1.0 - v * v
    xi = np.asarray(x, dtype=np.float64)[:, None] * s[None, :] ** (-1.0 / n)
    return (s * _rise(xi, n) * 2.0 * v) @ (0.5 * _GL_W)


def _q_by_quadrature(x: np.ndarray) -> np.ndarray:
    """The wedge's ``q(X)`` (:func:`_free_surface_potential` at ``n = 1``)."""
    return _free_surface_potential(x, 1.0)


def _composite_gauss(top: float, panels: int, nodes: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights of composite Gauss-Legendre on ``(0, top)``."""
    u, w = np.polynomial.legendre.leggauss(nodes)
    edges = np.linspace(0.0, top, panels + 1)
    half = 0.5 * np.diff(edges)[:, None]
    return ((edges[:-1, None] + half * (u + 1.0)).ravel(), (half * w).ravel())


def power_law_beta(
    n: float = 1.0, mu_top: float = 20.0, k_top: float = 30.0, panels: int = 40
) -> float:
    """``beta_n`` by an independent solution of the mixed problem for ``Phi``: in elliptic
    coordinates ``X + i Y = cosh(mu - i nu)`` (``mu > 0``, ``0 < nu < pi``) the disc is
    ``mu = 0`` (``Phi_mu = 0``) and the free surface ``nu = 0, pi`` (``Phi = P_n(cosh mu)``),
    so ``Phi = integral_0^inf A(k) cos(k mu) cosh(k (nu - pi/2)) / cosh(k pi/2) dk`` with
    ``A`` the cosine transform of ``P_n(cosh mu)``, and ``Phi_Y = -Phi_nu / sinh(mu)`` on
    ``nu = 0``, so with ``dX = sinh(mu) dmu``
    ``beta_n = integral A(k) k tanh(k pi/2) [integral cos(k mu) cosh(mu)^(-3n) dmu] dk``,
    both transforms by composite Gauss-Legendre on ``(0, mu_top)`` and ``(0, k_top)``."""
    mu, w_mu, k, w_k, a = _transform(mu_top, k_top, panels, n)
    c = np.cos(np.outer(k, mu)) @ (w_mu / np.cosh(mu) ** (3.0 * n))
    return float(np.sum(w_k * a * k * np.tanh(0.5 * math.pi * k) * c))


def wedge_alpha_numerical(mu_top: float = 20.0, k_top: float = 30.0, panels: int = 40) -> float:
    """``alpha = beta_1`` by the elliptic-coordinate solution (:func:`power_law_beta`)."""
    return power_law_beta(1.0, mu_top, k_top, panels)


def power_law_lambda(n: float, **resolution: float) -> float:
    """``lambda_n = 2 beta_n I_(3n-1) / pi`` of ``f = A y^n`` (:func:`power_law_beta`)."""
    p = 3.0 * n - 1.0
    wallis = 0.5 * math.sqrt(math.pi) * math.gamma(0.5 * (p + 1.0)) / math.gamma(0.5 * p + 1.0)
    return 2.0 * power_law_beta(n, **resolution) * wallis / math.pi  # type: ignore[arg-type]


def _transform(mu_top: float, k_top: float, panels: int, n: float = 1.0):
    """The nodes in ``mu`` and ``k`` and the cosine transform ``A(k)`` of ``P_n(cosh mu)``."""
    mu, w_mu = _composite_gauss(mu_top, panels)
    k, w_k = _composite_gauss(k_top, panels)
    data = _free_surface_potential(np.cosh(mu), n)
    a = (2.0 / math.pi) * np.cos(np.outer(k, mu)) @ (w_mu * data)
    return mu, w_mu, k, w_k, a


def wedge_plate_force(mu_top: float = 20.0, k_top: float = 60.0, panels: int = 80) -> float:
    """The force of the gravity potential's own pressure ``-rho phi1_t`` on the wetted disc
    of a wedge at constant speed, in units of the buoyancy ``rho g h^2 / tan(beta)``
    (over the whole disc; the MLM takes it up to the pressure's change of sign,
    :func:`disc_pressure`).

    ``phi1 = -g V t^2 Phi(x / c0)`` on the disc gives the force
    ``rho g V gamma t^2 (3 I - 2 q(1))``, ``I = integral_{-1}^{1} Phi dX``, that is
    ``(pi / 2) (3 I - 2 q(1))`` buoyancies; ``Phi`` on the disc (``mu = 0``) from the
    elliptic-coordinate solution of :func:`wedge_alpha_numerical`."""
    _, _, k, w_k, a = _transform(mu_top, k_top, panels)
    nu, w_nu = _composite_gauss(math.pi, 20)
    shape = np.cosh(np.outer(k, nu - 0.5 * math.pi)) / np.cosh(0.5 * math.pi * k)[:, None]
    disc = (w_k * a) @ shape  # Phi(X = cos nu) on the disc
    integral = float(np.sum(disc * np.sin(nu) * w_nu))
    q1 = 0.5 * math.pi - 1.5
    return 0.5 * math.pi * (3.0 * integral - 2.0 * q1)


#: ``lambda`` against the contact's growth exponent ``m = 1/n`` of ``f = A y^n``
#: (:func:`power_law_lambda` at ``mu_top, k_top, panels = 25, 120, 160``), m = 0.25 to 1.
LAMBDA_TABLE = (
    np.round(np.arange(0.25, 1.0001, 0.05), 2),
    np.array([
        0.0303535636683, 0.0285002331866, 0.02682583857, 0.0253032640286, 0.0239118890611,
        0.0226353696841, 0.0214603596865, 0.020375720296, 0.0193720015739, 0.0184410841044,
        0.0175759206947, 0.0167703439464, 0.0160189193279, 0.0153168308303, 0.0146597905335,
        0.0140439659895,
    ]),
)  # fmt: skip
#: ``(lambda(m) - lambda_1) / (1 - m)`` as a polynomial (``lambda(1) = alpha / 2`` exactly).
_LAMBDA_FIT = np.polynomial.Polynomial.fit(
    LAMBDA_TABLE[0][:-1],
    (LAMBDA_TABLE[1][:-1] - 0.5 * wedge_alpha()) / (1.0 - LAMBDA_TABLE[0][:-1]),
    9,
)


def growth_lambda(m):
    """``lambda`` of the power law whose contact grows as ``h^m`` (``m`` held in [1/4, 1])."""
    m = np.clip(m, LAMBDA_TABLE[0][0], 1.0)
    return 0.5 * wedge_alpha() + (1.0 - m) * _LAMBDA_FIT(m)


def growth_exponent(penetration, c, cp):
    """The contact's growth exponent ``m = c' h / c`` (held in ``[1/4, 1]``) and where the
    correction applies (``c``, ``c'`` and ``h`` positive)."""
    c = np.asarray(c, dtype=np.float64)
    cp = np.asarray(cp, dtype=np.float64)
    h = np.broadcast_to(np.asarray(penetration, dtype=np.float64), cp.shape)
    ok = (c > 0) & (cp > 0) & (h > 0)
    m = np.where(ok, cp * h / np.where(ok, c, 1.0), 1.0)
    return np.clip(m, LAMBDA_TABLE[0][0], 1.0), ok


def contact_shift(penetration, speed, g, c, cp):
    """The relative shift ``delta`` of the penetration that gives the contact with gravity
    (Wagner's contact at ``h (1 - delta)``), held at :data:`DELTA_MAX`, where it was held,
    and the factor of ``c'``. ``c, cp`` are Wagner's contact and ``c' = dc/dh`` per side
    (the growth exponent ``m = c' h / c``); no shift where ``c`` or ``c'`` is not
    positive or ``g`` is 0."""
    m, ok = growth_exponent(penetration, c, cp)
    ok = ok & (g > 0)
    cp = np.asarray(cp, dtype=np.float64)
    h = np.broadcast_to(np.asarray(penetration, dtype=np.float64), cp.shape)
    v2 = np.broadcast_to(np.asarray(speed, dtype=np.float64) ** 2, cp.shape)
    c_ok = np.where(ok, c, 1.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        raw = np.where(ok, growth_lambda(m) * g * h * h / (m * v2 * c_ok), 0.0)
    raw = np.where(np.isnan(raw), np.inf, raw)
    held = raw > DELTA_MAX
    shift = np.minimum(raw, DELTA_MAX)
    return shift, held, 1.0 - (3.0 - m) * shift


def _on_disc(t, k: np.ndarray, wa: np.ndarray):
    """``Phi`` and ``dPhi/dt`` on the disc at ``X = sin(t)`` from the transform ``wa``
    (weights times ``A(k)``, ``(K,)`` or ``(K, j)``): ``cosh(k t) / cosh(k pi/2)`` and its
    ``t`` derivative, written without overflow."""
    t = np.asarray(t, dtype=np.float64)[..., None]
    down = 1.0 + np.exp(-math.pi * k)
    up = np.exp(k * (t - 0.5 * math.pi)) / down
    low = np.exp(-k * (t + 0.5 * math.pi)) / down
    return (up + low) @ wa, (up - low) @ (k[:, None] * wa if wa.ndim == 2 else k * wa)


def plate_potential(t, n: float = 1.0, mu_top: float = 25.0, k_top: float = 120.0,
                    panels: int = 160):  # fmt: skip
    """``Phi`` and ``dPhi/dt`` on the disc at ``X = sin(t)`` for ``f = A y^n`` by the
    elliptic-coordinate solution (``mu = 0``, ``nu = pi/2 - t``):
    ``Phi = integral_0^inf A(k) cosh(k t) / cosh(k pi/2) dk``."""
    _, _, k, w_k, a = _transform(mu_top, k_top, panels, n)
    return _on_disc(t, k, w_k * a)


def plate_pressure(x, n: float = 1.0, **resolution: float):
    """``S_n(X) = p1 / (rho g h) = 2 Phi - X Phi' / n`` on the disc, ``X`` in ``[0, 1)``."""
    t = np.arcsin(np.asarray(x, dtype=np.float64))
    phi, phi_t = plate_potential(t, n, **resolution)  # type: ignore[arg-type]
    return 2.0 * phi - np.tan(t) * phi_t / n


def plate_force(n: float = 1.0, mu_top: float = 25.0, k_top: float = 120.0,
                panels: int = 160) -> float:  # fmt: skip
    """``integral_{-1}^{1} S_n dX = (2 + m) I - 2 m P_n(1)``: the force of ``p1`` on the
    whole disc in units of ``rho g h c``, ``I = integral Phi dX = 2 integral A(k) /
    (1 + k^2) dk`` (the elliptic-coordinate solution)."""
    _, _, k, w_k, a = _transform(mu_top, k_top, panels, n)
    integral = 2.0 * float(np.sum(w_k * a / (1.0 + k * k)))
    m = 1.0 / n
    edge = float(_free_surface_potential(np.array([1.0]), n)[0])
    return (2.0 + m) * integral - 2.0 * m * edge


#: Points of the disc's table over ``t`` in ``[0, pi/2]`` (``X = sin t``) and its
#: Chebyshev nodes in the growth exponent ``m`` over ``[1/4, 1]``.
PLATE_POINTS, PLATE_EXPONENTS = 513, 9


@functools.lru_cache(maxsize=1)
def _plate_table() -> tuple[np.ndarray, np.ndarray]:
    """Chebyshev coefficients in ``m`` of ``Phi`` and ``dPhi/dt`` on the disc, each
    ``(PLATE_EXPONENTS, PLATE_POINTS)``, one transform for every node (``P_n`` is below
    1e-10 past ``mu = 12``)."""
    lo = LAMBDA_TABLE[0][0]
    x = np.cos(math.pi * (np.arange(PLATE_EXPONENTS) + 0.5) / PLATE_EXPONENTS)
    ms = lo + 0.5 * (1.0 - lo) * (x + 1.0)
    mu, w_mu = _composite_gauss(12.0, 80)
    k, w_k = _composite_gauss(120.0, 160)
    data = np.stack([_free_surface_potential(np.cosh(mu), 1.0 / m) for m in ms], axis=1)
    wa = w_k[:, None] * ((2.0 / math.pi) * np.cos(np.outer(k, mu)) @ (w_mu[:, None] * data))
    phi, phi_t = _on_disc(np.linspace(0.0, 0.5 * math.pi, PLATE_POINTS), k, wa)
    fit = np.polynomial.chebyshev.chebfit
    return fit(x, phi.T, PLATE_EXPONENTS - 1), fit(x, phi_t.T, PLATE_EXPONENTS - 1)


def disc_pressure(t, m):
    """``S_m(sin t) = p1 / (rho g h)`` at the points ``t`` ((2, n, k), in ``[0, pi/2)``) of
    sections whose contacts grow with the exponents ``m`` ((2, n), in ``[1/4, 1]``), from
    the table of :func:`_plate_table` (linear in ``t``)."""
    lo = LAMBDA_TABLE[0][0]
    m = np.clip(np.asarray(m, dtype=np.float64), lo, 1.0)
    x = 2.0 * (m - lo) / (1.0 - lo) - 1.0
    c_phi, c_phi_t = _plate_table()
    t = np.asarray(t, dtype=np.float64)
    pos = np.clip(t / (0.5 * math.pi) * (PLATE_POINTS - 1), 0.0, PLATE_POINTS - 1)
    i0 = np.minimum(np.floor(pos).astype(np.int64), PLATE_POINTS - 2)
    frac = pos - i0

    def at(coef):
        rows = np.moveaxis(np.polynomial.chebyshev.chebval(x, coef), 0, -1)  # (2, n, T)
        a = np.take_along_axis(rows, i0, axis=-1)
        return a + frac * (np.take_along_axis(rows, i0 + 1, axis=-1) - a)

    return 2.0 * at(c_phi) - m[..., None] * np.tan(t) * at(c_phi_t)
