"""Von Karman's momentum theory for hullslice: a wedge entering water without pile-up.

The wetted half-width of a section is its calm-water half-width, ``c = p / tan(beta)``
(pile-up coefficient ``gamma = 1``). The closed form, its inverse use (the free fall each
slice is in, ``F = M (a + g) d``) and its range of validity come from
:class:`hullslice.MomentumSolver`; this plugin gives the pile-up law.

For a free-falling wedge the peak deceleration is (paper, Eq. 2, ``gamma = 1``)

    a_max = v_z0^2 (5/6)^3 / tan(beta) sqrt(2 pi rho / (5 M)).
"""

from __future__ import annotations

import numpy as np

from hullslice import MomentumSolver
from hullslice.solvers import von_karman_pile_up

__all__ = ["VonKarman"]
__version__ = "0.1.0"


class VonKarman(MomentumSolver):
    """Von Karman's momentum theory, closed form, no pile-up (``gamma = 1``).

    Parameters
    ----------
    froude_min : float, optional
        Smallest peak Froude number ``Fr*`` inside the range (default 6.5).
    """

    name = "von-karman"
    description = "Von Karman's momentum theory in closed form, no pile-up (gamma = 1)"

    def pile_up(self, deadrise: np.ndarray) -> np.ndarray:
        """``gamma = 1`` for every deadrise (rad)."""
        return von_karman_pile_up(deadrise)
