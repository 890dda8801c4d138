"""How each section moves at its fixed earth plane, from the body's motion.

The penetration velocity of a section and how its acceleration follows from the body's
accelerations; the formulas are in the notes of :mod:`hullslice.forces`.
"""

from __future__ import annotations

import math
from typing import cast

import numpy as np

from ..constants import SOUND_WATER
from ..errors import InputError
from ..sections import Sections
from ..state import Motion

__all__ = ["section_kinematics", "section_velocity"]


def section_velocity(sections: Sections, motion: Motion, x_cg: float) -> np.ndarray:
    """Penetration velocity of each section in m/s, negative down (see the module notes).

    Parameters
    ----------
    sections : Sections
    motion : Motion
        Vertical velocity and forward speed of the centre of gravity (m/s), pitch rate
        (rad/s).
    x_cg : float
        Earth ``X`` of the centre of gravity, m.
    """
    q, u = motion.pitch_rate, motion.forward_speed
    arm_x = sections.x - x_cg
    arm_z = sections.keel_z - sections.z_cg
    with np.errstate(over="ignore", invalid="ignore"):  # named below
        up, forward = motion.velocity + q * arm_x, u - q * arm_z
        v = up - forward * sections.keel_slope
        # the keel point's own speed (not the slope's share of it, a step's steep chord)
        fast = np.hypot(up, forward) >= SOUND_WATER  # an overflow too (inf)
    if fast.any():
        i = int(np.flatnonzero(fast)[0])
        raise InputError(
            f"the keel of the section at x = {sections.x[i]:.6g} m moves at "
            f"{math.hypot(up[i], forward[i]):.6g} m/s, from the body's vertical velocity "
            f"{motion.velocity:g} m/s, forward speed {u:g} m/s and pitch rate "
            f"{math.degrees(q):g} deg/s: past the speed of sound in water ({SOUND_WATER:g} "
            "m/s); give a pitch rate in deg/s (rad/s in Python's *_rad_s)"
        )
    return v


def section_kinematics(
    sections: Sections, motion: Motion, x_cg: float, velocity: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """How each section's penetration acceleration follows from the body's.

    Parameters
    ----------
    sections : Sections
    motion : Motion
        Vertical velocity and forward speed (m/s) and pitch rate (rad/s).
    x_cg : float
        Earth ``X`` of the centre of gravity, m.
    velocity : (n,) float
        The sections' penetration velocities (:func:`section_velocity`), m/s.

    Returns
    -------
    jac : (n, 3) float
        ``da/d(dw/dt)`` (1), ``da/d(dq/dt)`` (m) and ``da/d(du/dt)`` (1): the section's
        acceleration is ``jac @ (dw/dt, dq/dt, du/dt) + bias``.
    bias : (n,) float
        The part that multiplies no acceleration, m/s^2 (see the module notes).
    """
    q, u, w = motion.pitch_rate, motion.forward_speed, motion.velocity
    slope = sections.keel_slope
    arm_z = sections.keel_z - sections.z_cg
    jac = np.empty((len(sections), 3))
    jac[:, 0] = 1.0
    jac[:, 1] = sections.x - x_cg + arm_z * slope
    jac[:, 2] = -slope
    if q == 0.0 and u == 0.0:
        return jac, np.zeros(len(sections))
    slide = u - q * arm_z
    bias = (
        -q * u
        + q * (velocity - w) * slope
        - slide * q * (1.0 + slope * slope)
        + slide * slide * cast(np.ndarray, sections.keel_curvature)
    )
    return jac, bias
