"""Helpers for testing 2D solvers, hullslice's own and plugins alike.

:func:`wedge_sections` builds the input of :meth:`hullslice.Solver.section_loads` for exact
wedges without a mesh, so a solver can be checked against a closed form or an invariant
on any grid of penetrations, deadrise angles and masses.
"""

from __future__ import annotations

import numpy as np

from .errors import InputError
from .sections import Sections

__all__ = ["wedge_sections"]


def wedge_sections(
    penetration: np.ndarray | float,
    deadrise: np.ndarray | float,
    mass_per_metre: np.ndarray | float,
    chine_half_width: np.ndarray | float | None = None,
) -> Sections:
    """Wetted sections of exact wedges, one per entry of the broadcast inputs.

    Each section is a triangle: keel at ``z = -p`` on the centre line, sides at the
    deadrise ``beta``, flat deck at the chine half-width ``b``. Its half-beam at the
    waterline is ``p / tan(beta)``, its area ``b^2 tan(beta)``; every slice is 1 m thick.

    Parameters
    ----------
    penetration : float or (n,) float
        Keel depth below the calm water in m, positive.
    deadrise : float or (n,) float
        Deadrise in rad, in (0, pi/2).
    mass_per_metre : float or (n,) float
        Mass per metre in kg/m, positive.
    chine_half_width : float or (n,) float, optional
        Half-width of the deck in m (default ``2 p / tan(beta)``: the deck twice as high
        above the keel as the water, out of reach of a pile-up up to 2).

    Returns
    -------
    Sections
    """
    p, beta, m = (np.asarray(a, dtype=np.float64) for a in (penetration, deadrise, mass_per_metre))
    p, beta, m = np.broadcast_arrays(np.atleast_1d(p), beta, m)
    tb = np.tan(beta)
    if not (np.all(p > 0) and np.all((beta > 0) & (beta < np.pi / 2)) and np.all(m > 0)):
        raise InputError(
            "wedge sections need penetration > 0 m, deadrise in (0, pi/2) rad and mass per "
            "metre > 0 kg/m"
        )
    b = 2.0 * p / tb if chine_half_width is None else np.broadcast_to(chine_half_width, p.shape)
    b = np.asarray(b, dtype=np.float64)
    c = p / tb
    if np.any(b < c):
        raise InputError("the chine half-width is below the waterline half-width p / tan(beta)")
    n = p.size
    polys = tuple(
        (np.array([[0.0, -pi], [bi, -pi + bi * ti], [-bi, -pi + bi * ti]]),)
        for pi, bi, ti in zip(p.ravel(), b.ravel(), tb.ravel(), strict=True)
    )
    beta_flat = beta.ravel().copy()
    c_flat = c.ravel().copy()
    return Sections(
        station=np.arange(n),
        x=np.arange(n) + 0.5,
        dx=np.ones(n),
        penetration=p.ravel().copy(),
        half_beam=c_flat,
        half_beam_port=c_flat,
        half_beam_stbd=c_flat,
        deadrise=beta_flat,
        deadrise_port=beta_flat,
        deadrise_stbd=beta_flat,
        area=(b**2 * tb).ravel().copy(),
        mass_per_metre=m.ravel().copy(),
        chine_wetted=np.isclose(b, c).ravel(),
        keel_slope=np.zeros(n),
        keel_z=-p.ravel(),
        y_keel=np.zeros(n),
        part_half_beam=b.ravel().copy(),
        polygons=polys,
        deadrise_method="wedge",
        draft=float(p.max()),
        wetted_length=float(n),
    )
