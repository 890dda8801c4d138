"""Gravity's correction of Wagner's contact at low Froude number (option ``gravity_contact``).

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

**Beyond the wedge** (an approximation): the contact of a penetration ``h`` is Wagner's at
``h (1 - delta)``, ``delta = kappa g h tan(beta_e) / V^2``, with the section's own
deadrise at the contact ``tan(beta_e) = pi / (2 c')`` from Wagner's ``c' = dc/dh`` (a
wedge's exactly). ``c'`` is taken quasi-steadily, at the current speed and ``beta_e``
held: ``dc/dh = c'(h (1 - delta)) (1 - 2 delta)``, as a wedge's at constant speed.
``delta`` is held at :data:`DELTA_MAX` (the first-order expansion is not valid beyond),
and such sections are flagged.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "DELTA_MAX",
    "KAPPA",
    "contact_shift",
    "wedge_alpha",
    "wedge_alpha_numerical",
    "wedge_plate_force",
]

#: The largest relative shift ``delta = kappa / Fr*^2`` of the penetration; beyond it the
#: first-order expansion is not valid (the section is flagged and ``delta`` held there).
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


def _q_by_quadrature(x: np.ndarray, nodes: int = 24) -> np.ndarray:
    """``q(X) = -phi1 / (g V t^2)`` on the free surface from ``eta0``'s history by
    Gauss-Legendre quadrature: ``q = X^2 integral_0^{asin(1/X)} (w - sin w) cos w dw``
    (``u = gamma tau / x = sin w``)."""
    u, wu = np.polynomial.legendre.leggauss(nodes)
    top = np.arcsin(1.0 / x)[:, None]
    w = 0.5 * top * (u + 1.0)
    integrand = (w - np.sin(w)) * np.cos(w)
    return x**2 * (0.5 * top[:, 0]) * (integrand @ wu)


def _composite_gauss(top: float, panels: int, nodes: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights of composite Gauss-Legendre on ``(0, top)``."""
    u, w = np.polynomial.legendre.leggauss(nodes)
    edges = np.linspace(0.0, top, panels + 1)
    half = 0.5 * np.diff(edges)[:, None]
    return ((edges[:-1, None] + half * (u + 1.0)).ravel(), (half * w).ravel())


def wedge_alpha_numerical(mu_top: float = 20.0, k_top: float = 30.0, panels: int = 40) -> float:
    """``alpha`` by an independent solution of the mixed problem for ``Phi``: in elliptic
    coordinates ``X + i Y = cosh(mu - i nu)`` (``mu > 0``, ``0 < nu < pi``) the disc is
    ``mu = 0`` (``Phi_mu = 0``) and the free surface ``nu = 0, pi`` (``Phi = q(cosh mu)``),
    so ``Phi = integral_0^inf A(k) cos(k mu) cosh(k (nu - pi/2)) / cosh(k pi/2) dk`` with
    ``A`` the cosine transform of ``q(cosh mu)`` (``q`` from ``eta0`` by quadrature), and
    ``Phi_Y = -Phi_nu / sinh(mu)`` on ``nu = 0``:
    ``alpha = integral A(k) k tanh(k pi/2) integral cos(k mu) / cosh(mu)^3 dmu dk``.
    Both transforms by composite Gauss-Legendre on ``(0, mu_top)`` and ``(0, k_top)``."""
    mu, w_mu, k, w_k, a = _transform(mu_top, k_top, panels)
    c = np.cos(np.outer(k, mu)) @ (w_mu / np.cosh(mu) ** 3)
    return float(np.sum(w_k * a * k * np.tanh(0.5 * math.pi * k) * c))


def _transform(mu_top: float, k_top: float, panels: int):
    """The nodes in ``mu`` and ``k`` and the cosine transform ``A(k)`` of ``q(cosh mu)``."""
    mu, w_mu = _composite_gauss(mu_top, panels)
    k, w_k = _composite_gauss(k_top, panels)
    a = (2.0 / math.pi) * np.cos(np.outer(k, mu)) @ (w_mu * _q_by_quadrature(np.cosh(mu)))
    return mu, w_mu, k, w_k, a


def wedge_plate_force(mu_top: float = 20.0, k_top: float = 60.0, panels: int = 80) -> float:
    """The force of the gravity potential's own pressure ``-rho phi1_t`` on the wetted disc
    of a wedge at constant speed, in units of the buoyancy ``rho g h^2 / tan(beta)``
    (not in the MLM's load; an estimate of what the contact correction leaves out).

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


def contact_shift(penetration, speed, g, cp):
    """The relative shift ``delta`` of the penetration that gives the contact with gravity
    (Wagner's contact at ``h (1 - delta)``), held at :data:`DELTA_MAX`, and where it was
    held. ``cp`` is Wagner's ``c' = dc/dh`` per side (its local deadrise
    ``tan(beta_e) = pi / (2 c')``); no shift where ``c'`` is not positive or ``g`` is 0."""
    cp = np.asarray(cp, dtype=np.float64)
    h = np.broadcast_to(np.asarray(penetration, dtype=np.float64), cp.shape)
    v2 = np.broadcast_to(np.asarray(speed, dtype=np.float64) ** 2, cp.shape)
    with np.errstate(divide="ignore", invalid="ignore"):
        k_e = np.where(cp > 0, 0.5 * np.pi / np.where(cp > 0, cp, 1.0), 0.0)
        raw = np.where(
            (k_e > 0) & (h > 0) & (g > 0), KAPPA * g * np.maximum(h, 0.0) * k_e / v2, 0.0
        )
    raw = np.where(np.isnan(raw), np.inf, raw)
    held = raw > DELTA_MAX
    return np.minimum(raw, DELTA_MAX), held
