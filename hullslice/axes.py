"""The body frame: which mesh axes point forward and up, and the length units.

The body frame is a mesh's own coordinates after the axis mapping and unit scale: ``x``
forward along the body, ``y`` to port, ``z`` up (right-handed), metres.
"""

from __future__ import annotations

import numpy as np

from .constants import AXES, LENGTH_UNITS
from .errors import InputError

__all__ = ["axis_matrix", "unit_scale"]


def axis_matrix(forward: str = "+x", up: str = "+z") -> np.ndarray:
    """Rotation taking mesh coordinates to the body frame.

    Parameters
    ----------
    forward, up : str
        Which mesh axis points forward along the body and which points up, each one of
        ``+x, -x, +y, -y, +z, -z`` (a bare ``x`` means ``+x``).

    Returns
    -------
    (3, 3) float
        Matrix ``R`` with ``body = R @ mesh``; its rows are the body's x (forward),
        y (port = up x forward) and z (up) axes in mesh coordinates. ``det(R) = +1``.
    """
    f = _axis(forward, "forward")
    u = _axis(up, "up")
    if abs(float(np.dot(f, u))) > 0.5:
        raise InputError(
            f"forward axis {forward!r} and up axis {up!r} are not perpendicular: "
            "choose two different mesh axes (for instance forward='+x', up='+z')"
        )
    return np.array([f, np.cross(u, f), u])


def _axis(name: str, role: str) -> np.ndarray:
    key = str(name).strip().lower()
    if key in ("x", "y", "z"):
        key = "+" + key
    if key not in AXES:
        raise InputError(f"{role} axis {name!r} is not one of {', '.join(AXES)}")
    return np.array(AXES[key])


def unit_scale(units: str) -> float:
    """Metres per ``units`` (one of ``m, cm, mm, in, ft``)."""
    try:
        return LENGTH_UNITS[str(units).strip().lower()]
    except KeyError:
        raise InputError(f"length unit {units!r} is not one of {', '.join(LENGTH_UNITS)}") from None
