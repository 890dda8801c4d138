"""The limits that the library, case files and the command line all enforce, each one named
constant, and their checks.

The checks raise :class:`~hullslice.errors.InputError` with a message that names the value
and the fix; every layer calls them, so each of these limits and its message is written
once.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from typing import Any

import numpy as np

from .constants import LENGTH_UNITS, MAX_SLICES, MAX_STEPS
from .errors import HullsliceWarning, InputError, UnitsWarning

__all__ = [
    "MASS_OFF_BODY_NOISE",
    "MASS_OFF_BODY_SHARE",
    "MASS_OFF_BODY_TOLERANCE",
    "MAX_CASE_BYTES",
    "MAX_PITCH",
    "MAX_PITCH_DEG",
    "MAX_SLICES",
    "MAX_STEPS",
    "check_cg_in_body",
    "check_density",
    "check_mass_on_body",
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


#: Largest share of a mass distribution that may lie beyond the body's ends: the sections
#: give the mass back within this share (a larger one is refused, a smaller one warned of).
MASS_OFF_BODY_SHARE = 0.005

#: Share of a mass distribution beyond the body's ends too small to mention (rounding).
MASS_OFF_BODY_NOISE = 1e-6

#: How far beyond the body's ends or bounding box, as a fraction of its length (``x``) or
#: of the box's diagonal (the centre of gravity), a mass distribution's rows still count
#: as on the body (rounded coordinates).
MASS_OFF_BODY_TOLERANCE = 1e-4


def _span(lo: float, hi: float) -> str:
    return f"{lo:.6g} to {hi:.6g} m"


def check_mass_on_body(
    outside: float, total: float, rows: Sequence[float], body: tuple[float, float], name: str
) -> None:
    """Refuse a mass distribution of which more than :data:`MASS_OFF_BODY_SHARE` of the
    ``total`` (kg) lies beyond the body's ends ``body = (x0, x1)`` (m), and warn
    (:class:`~hullslice.errors.HullsliceWarning`) of a smaller share above
    :data:`MASS_OFF_BODY_NOISE`.

    Parameters
    ----------
    outside, total : float
        The mass beyond the body's ends and the distribution's total, kg.
    rows : sequence of float
        ``x`` (m) of the rows (stations and point masses) that lie beyond the ends.
    body : (float, float)
        The body's range of ``x``, m.
    name : str
        The hull's name, for the message.
    """
    share = outside / total
    if share <= MASS_OFF_BODY_NOISE:
        return
    where = ", ".join(f"{x:.6g}" for x in rows[:6]) + (", ..." if len(rows) > 6 else "")
    what = (
        f"hull {name!r}: {outside:.6g} kg of the mass distribution's {total:.6g} kg "
        f"({100 * share:.3g} %) lies beyond the body's ends, x = {_span(*body)}"
        + (f" (the rows at x = {where} m)" if rows else "")
    )
    if share > MASS_OFF_BODY_SHARE:
        raise InputError(
            f"{what}: the sections carry only the mass along the body; give the distribution "
            f"in the body frame (x forward, m, after the mesh's units and axes) within "
            f"x = {_span(*body)}"
        )
    warnings.warn(f"{what}: the sections do not carry that share", HullsliceWarning, stacklevel=4)


def check_cg_in_body(cg: np.ndarray, bounds: np.ndarray, name: str) -> None:
    """Refuse a mass distribution whose centre of gravity ``cg = (x, z)`` (m) lies outside
    the body's bounding box ``bounds`` ((2, 3), m) by more than
    :data:`MASS_OFF_BODY_TOLERANCE` of the box's diagonal."""
    lo, hi = np.asarray(bounds, dtype=np.float64)[:, [0, 2]]
    tol = MASS_OFF_BODY_TOLERANCE * float(np.linalg.norm(hi - lo))
    if np.all(cg >= lo - tol) and np.all(cg <= hi + tol):
        return
    raise InputError(
        f"hull {name!r}: the mass distribution's centre of gravity (x, z) = "
        f"({cg[0]:.6g}, {cg[1]:.6g}) m lies outside the body, x = {_span(lo[0], hi[0])}, "
        f"z = {_span(lo[1], hi[1])}: give its masses' x and z in the body frame (m, x "
        "forward, z up, after the mesh's units and axes)"
    )


def no_mass(name: str | None = None) -> InputError:
    """The error for a computation that needs the body's mass and has none."""
    what = "the hull" if name is None else f"hull {name!r}"
    return InputError(f"{what} has no mass: give its mass in kg (mass=...)")


# Densities outside this range (kg/m^3) are not a plausible body for a water-impact study:
# lighter than air means a mesh in mm read as metres, denser than osmium the reverse.
_PLAUSIBLE_DENSITY = (1.0, 25000.0)

# the length units by name, the most common in hull and CAD files first
_UNIT_NAMES = {
    "m": "metres",
    "mm": "millimetres",
    "cm": "centimetres",
    "in": "inches",
    "ft": "feet",
}


def check_density(mass: float, volume: float, units: str, name: str) -> None:
    """Warn (:class:`~hullslice.errors.UnitsWarning`) when ``mass`` (kg) in ``volume``
    (m^3) is not a plausible density for a body, naming the file units that would make it
    one (``units`` is the unit the mesh was read in)."""
    rho = mass / volume
    lo, hi = _PLAUSIBLE_DENSITY
    if lo <= rho <= hi:
        return
    units = str(units).strip().lower()
    scale = LENGTH_UNITS.get(units, 1.0)
    # the density the same mass would have if the file were in each of the other units;
    # the plausible ones are named, the most common unit first
    plausible = {
        u: rho * (scale / LENGTH_UNITS[u]) ** 3
        for u in _UNIT_NAMES
        if u != units and lo <= rho * (scale / LENGTH_UNITS[u]) ** 3 <= hi
    }
    if plausible:
        u, *others = plausible
        hint = (
            f"if the mesh is in {_UNIT_NAMES[u]}, give its units (units={u!r}, --units {u}): "
            f"the density is then {plausible[u]:.4g} kg/m^3"
        )
        if others:
            hint += (
                " (in "
                + ", ".join(f"{_UNIT_NAMES[o]} {plausible[o]:.4g} kg/m^3" for o in others)
                + ")"
            )
    else:
        hint = "check the mass and the mesh's units"
    warnings.warn(
        f"hull {name!r}: mass {mass:g} kg in a volume of {volume:.6g} m^3 "
        f"(units {units!r}) is a density of {rho:.4g} kg/m^3, implausible for a body; "
        f"{hint}",
        UnitsWarning,
        stacklevel=3,
    )
