"""The water's friction on the wetted hull: the ITTC-57 line.

The friction drag of the wetted surface ``S`` moving at the forward speed ``u`` is

    F = -1/2 rho u |u| S C_F,        C_F = 0.075 / (log10(Re) - 2)^2,    Re = |u| L / nu

(the ITTC 1957 model-ship correlation line, the standard friction line of ship resistance),
``L`` the wetted length and ``nu`` the water's kinematic viscosity. ``S`` is the sum of the
sections' wetted girths times their thickness, each girth the chords from the keel to the
calm water on both sides (the same for every solver; the spray's wetting above the calm
water is left out). The force acts along the keel line at each
section's keel, so it also has a moment about the centre of gravity (nose down when it acts
below the centre of gravity and the body moves forward).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..sections import Sections
from ..state import Fluid

__all__ = ["Friction", "friction", "ittc57"]

#: Below this Reynolds number the ITTC-57 line is not used (no friction is given).
MIN_REYNOLDS = 1.0e5


def ittc57(reynolds: float) -> float:
    """The ITTC-57 friction coefficient at a Reynolds number (0 below :data:`MIN_REYNOLDS`)."""
    if not reynolds >= MIN_REYNOLDS:
        return 0.0
    return 0.075 / (math.log10(reynolds) - 2.0) ** 2


@dataclass(frozen=True)
class Friction:
    """The friction on the wetted hull at one instant."""

    force_x: float = 0.0  # N, positive forward
    moment: float = 0.0  # N m, nose up, about the centre of gravity
    wetted_surface: float = 0.0  # m^2
    reynolds: float = 0.0
    coefficient: float = 0.0


def friction(sections: Sections, girth: np.ndarray, speed: float, fluid: Fluid) -> Friction:
    """The ITTC-57 friction on wetted sections of the given girths (m) at a forward speed
    (m/s)."""
    girth = np.where(sections.wetted, np.asarray(girth, dtype=np.float64), 0.0)
    area = girth * np.asarray(sections.dx, dtype=np.float64)
    surface = float(area.sum())
    length = float(sections.wetted_length)
    if surface <= 0.0 or length <= 0.0 or speed == 0.0:
        return Friction(wetted_surface=surface)
    re = abs(speed) * length / fluid.nu
    cf = ittc57(re)
    fx = -0.5 * fluid.rho * speed * abs(speed) * surface * cf
    share = area / surface
    r_z = np.asarray(sections.keel_z, dtype=np.float64) - sections.z_cg
    moment = float(-(r_z * share).sum() * fx)
    return Friction(fx, moment, surface, re, cf)
