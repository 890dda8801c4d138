"""Peak values of a free-falling wedge by momentum theory (paper, Eq. 2).

The closed forms are derived in :mod:`hullslice.solvers.momentum`; the curve solvers and
the momentum solvers both check a section's peak Froude number with them.
"""

from __future__ import annotations

import numpy as np

__all__ = ["peak_froude", "peak_values"]


def peak_values(
    v_z0: np.ndarray,
    mass_per_metre: np.ndarray,
    deadrise: np.ndarray,
    gamma: np.ndarray,
    rho: float,
) -> dict[str, np.ndarray]:
    """Peak values of a free-falling wedge by momentum theory (paper, Eq. 2).

    Parameters
    ----------
    v_z0 : float or array
        Initial velocity in m/s (negative down).
    mass_per_metre : float or array
        Wedge mass per metre in kg/m.
    deadrise : float or array
        Deadrise in rad.
    gamma : float or array
        Pile-up coefficient.
    rho : float
        Water density in kg/m^3.

    Returns
    -------
    dict
        ``a_max`` (m/s^2, upward), ``z_star`` (m, penetration at the peak, positive),
        ``v_star`` (m/s), ``t_star`` (s).
    """
    tb = np.tan(deadrise)
    root = np.sqrt(2.0 * mass_per_metre / (5.0 * np.pi * rho * gamma**2))
    return {
        "a_max": v_z0**2
        * (5.0 / 6.0) ** 3
        * gamma
        / tb
        * np.sqrt(2.0 * np.pi * rho / (5.0 * mass_per_metre)),
        "z_star": root * tb,
        "v_star": 5.0 / 6.0 * v_z0,
        "t_star": np.abs(16.0 / 15.0 * root * tb / v_z0),
    }


def peak_froude(
    v_z0: np.ndarray,
    mass_per_metre: np.ndarray,
    deadrise: np.ndarray,
    gamma: np.ndarray,
    rho: float,
    g: float,
) -> np.ndarray:
    """Froude number at the peak of a free-falling wedge, ``Fr* = |v_z*| / sqrt(g z*)``.

    ``v_z*`` and ``z*`` are the velocity and penetration at the peak of the free fall
    (Eq. 2, :func:`peak_values`); the paper asks for ``Fr* > 6.5`` (gravity negligible during
    the impact). Parameters as for :func:`peak_values`, with ``g`` the gravitational
    acceleration in m/s^2; infinite for ``g = 0``.
    """
    # v_z* and z* as peak_values gives them, without its other peak values
    z_star = np.sqrt(2.0 * mass_per_metre / (5.0 * np.pi * rho * gamma**2)) * np.tan(deadrise)
    with np.errstate(divide="ignore"):
        return np.abs(5.0 / 6.0 * v_z0) / np.sqrt(g * z_star)
