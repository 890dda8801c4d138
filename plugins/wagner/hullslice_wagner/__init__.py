"""Wagner's pile-up for hullslice: momentum theory with the water rising along the wedge.

Wagner's flat-plate solution for a wedge of small deadrise gives a wetted half-width
``c = (pi / 2) p / tan(beta)``: the pile-up coefficient is ``gamma = pi / 2``. The solver is
a momentum-form solver (:class:`hullslice.MomentumSolver`): each section's added mass
``m_a = rho pi c^2 / 2`` and its rate, with the body's accelerations on the left of its
equations of motion. At a constant downward speed ``V`` the force per metre from first
contact is Wagner's classical result,

    f = rho pi^3 V^3 t / (4 tan^2(beta)).

The option ``pile_up`` takes any other law (``von-karman``, ``dobrovolskaya`` or a number).
"""

from __future__ import annotations

from typing import Any, ClassVar

from hullslice import MomentumSolver

__all__ = ["Wagner"]
__version__ = "0.2.0"


class Wagner(MomentumSolver):
    """Momentum theory, closed form, with Wagner's pile-up (``gamma = pi / 2``) by default.

    Parameters
    ----------
    pile_up : str or float, optional
        The pile-up law (default ``"wagner"``, ``gamma = pi / 2``).
    froude_min : float, optional
        Smallest section Froude number ``|v| / sqrt(g p)`` inside the range (default 2).
    """

    name = "wagner"
    description = "Momentum form, closed form, Wagner's pile-up (gamma = pi/2)"
    options: ClassVar[dict[str, Any]] = {**MomentumSolver.options, "pile_up": "wagner"}
