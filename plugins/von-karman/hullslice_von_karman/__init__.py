"""Von Karman's momentum theory for hullslice: a wedge entering water without pile-up.

The wetted half-width of a section is its calm-water half-width, ``c = p / tan(beta)``
(pile-up coefficient ``gamma = 1``). The solver is a momentum-form solver
(:class:`hullslice.MomentumSolver`): each section's added mass ``m_a = rho pi c^2 / 2`` and
its rate, with the body's accelerations on the left of its equations of motion. At a
constant downward speed ``V`` the force per metre from first contact is

    f = rho pi V^3 t / tan^2(beta).

The option ``pile_up`` takes any other law (``wagner``, ``dobrovolskaya`` or a number).
"""

from __future__ import annotations

from typing import Any, ClassVar

from hullslice import MomentumSolver

__all__ = ["VonKarman"]
__version__ = "0.2.0"


class VonKarman(MomentumSolver):
    """Von Karman's momentum theory, closed form, no pile-up (``gamma = 1``) by default.

    Parameters
    ----------
    pile_up : str or float, optional
        The pile-up law (default ``"von-karman"``, ``gamma = 1``).
    froude_min : float, optional
        Smallest section Froude number ``|v| / sqrt(g p)`` inside the range (default 2).
    """

    name = "von-karman"
    description = "Momentum form, closed form, no pile-up (gamma = 1)"
    options: ClassVar[dict[str, Any]] = {**MomentumSolver.options, "pile_up": "von-karman"}
