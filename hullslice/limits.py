"""The limits that the library, case files and the command line all enforce, each one named
constant, and their checks.

The checks raise :class:`~hullslice.errors.InputError` with a message that names the value
and the fix; every layer calls them, so each of these limits and its message is written
once.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .constants import MAX_SLICES, MAX_STEPS
from .errors import InputError

__all__ = [
    "MAX_CASE_BYTES",
    "MAX_PITCH",
    "MAX_PITCH_DEG",
    "MAX_SLICES",
    "MAX_STEPS",
    "check_pitch",
    "check_slice_count",
    "no_mass",
]

#: Largest case file read, in bytes: a case is a few lines of TOML; anything larger is not one.
MAX_CASE_BYTES = 1024**2

#: Largest pitch magnitude, in degrees, a 2D+t model describes (the cross-sections of a
#: body pitched further are no longer thin slices across the flow).
MAX_PITCH_DEG = 80.0

#: :data:`MAX_PITCH_DEG` in rad.
MAX_PITCH = math.radians(MAX_PITCH_DEG)


def check_slice_count(slices: Any) -> int:
    """A slice count as an ``int`` in ``[1, MAX_SLICES]``, or an :class:`InputError`."""
    if isinstance(slices, bool) or not isinstance(slices, int | np.integer):
        raise InputError(f"slice count {slices!r} is not a whole number: give n >= 1")
    if slices < 1:
        raise InputError(f"slice count {slices!r} is not positive: give n >= 1 (e.g. 32)")
    if slices > MAX_SLICES:
        raise InputError(
            f"slice count {slices!r} is more than the {MAX_SLICES} hullslice allows: the "
            "force converges with far fewer (the paper uses 16 to 64)"
        )
    return int(slices)


def check_pitch(pitch: float) -> float:
    """A pitch in rad whose magnitude is below :data:`MAX_PITCH`, or an :class:`InputError`."""
    if abs(pitch) >= MAX_PITCH:
        raise InputError(
            f"pitch {math.degrees(pitch):.4g} deg is too steep for a 2D+t model: give a "
            f"pitch between -{MAX_PITCH_DEG:g} and {MAX_PITCH_DEG:g} deg (in rad to the "
            "library, deg on the command line)"
        )
    return pitch


def no_mass(name: str | None = None) -> InputError:
    """The error for a computation that needs the body's mass and has none."""
    what = "the hull" if name is None else f"hull {name!r}"
    return InputError(f"{what} has no mass: give its mass in kg (mass=...)")
