"""Wagner's pile-up for hullslice: momentum theory with the water rising along the wedge.

Wagner's flat-plate solution for a wedge of small deadrise gives a wetted half-width
``c = (pi / 2) p / tan(beta)``: the pile-up coefficient is ``gamma = pi / 2``. The closed
form, its inverse use (the free fall each slice is in, ``F = M (a + g) d``) and its range
of validity come from :class:`hullslice.MomentumSolver`; this plugin gives the pile-up law.

For a free-falling wedge the peak deceleration is (paper, Eq. 2, ``gamma = pi / 2``)

    a_max = v_z0^2 (5/6)^3 (pi / 2) / tan(beta) sqrt(2 pi rho / (5 M)).
"""

from __future__ import annotations

import numpy as np

from hullslice import MomentumSolver
from hullslice.solvers import wagner_pile_up

__all__ = ["Wagner"]
__version__ = "0.1.0"


class Wagner(MomentumSolver):
    """Momentum theory, closed form, with Wagner's pile-up (``gamma = pi / 2``).

    Parameters
    ----------
    froude_min : float, optional
        Smallest peak Froude number ``Fr*`` inside the range (default 6.5).
    """

    name = "wagner"
    description = "Momentum theory in closed form with Wagner's pile-up (gamma = pi/2)"

    def pile_up(self, deadrise: np.ndarray) -> np.ndarray:
        """``gamma = pi / 2`` for every deadrise (rad)."""
        return wagner_pile_up(deadrise)
