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
from .errors import HullsliceWarning, InputError, MeshError, UnitsWarning
from .reduce import bounds

__all__ = [
    "MASS_OFF_BODY_NOISE",
    "MASS_OFF_BODY_SHARE",
    "MASS_OFF_BODY_TOLERANCE",
    "MAX_CASE_BYTES",
    "MAX_PITCH",
    "MAX_PITCH_DEG",
    "MAX_ROUNDING",
    "MAX_SLICES",
    "MAX_STEPS",
    "WARN_ROUNDING",
    "check_cg_in_body",
    "check_cg_near_body",
    "check_density",
    "check_mass_on_body",
    "check_pitch",
    "check_precision",
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


def check_cg_near_body(cg: np.ndarray, bounds: np.ndarray, name: str) -> None:
    """Refuse a centre of gravity ``cg = (x, y, z)`` (m) given apart from a mass
    distribution that lies farther from the body's bounding box ``bounds`` ((2, 3), m)
    than the box's diagonal: no body's centre of gravity is that far off (a hull meshed
    without its upper works has its centre above the mesh, but within its size); the
    numbers are in other units or another frame."""
    lo, hi = np.asarray(bounds, dtype=np.float64)
    size = float(np.linalg.norm(hi - lo))
    off = float(np.linalg.norm(np.maximum(np.maximum(lo - cg, cg - hi), 0.0)))
    if off <= size:
        return
    raise InputError(
        f"hull {name!r}: the centre of gravity ({cg[0]:.6g}, {cg[1]:.6g}, {cg[2]:.6g}) m "
        f"lies {off:.6g} m off the body (x = {_span(lo[0], hi[0])}, y = "
        f"{_span(lo[1], hi[1])}, z = {_span(lo[2], hi[2])}), more than its size "
        f"({size:.6g} m): give it in the body frame (m, x forward, z up, after the mesh's "
        "units and axes; --cg X,Z)"
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
    one (``units`` is the unit the mesh was read in). A mass whose density overflows a
    float (``1e308`` kg) is refused (:class:`InputError`): no section could carry it."""
    with np.errstate(over="ignore", divide="ignore"):
        rho = float(np.float64(mass) / np.float64(volume))
    if not math.isfinite(rho):
        raise InputError(
            f"hull {name!r}: mass {mass:g} kg in a volume of {volume:.6g} m^3 is a density "
            "that overflows a float (infinite mass per metre): give the body's mass in kg "
            "(a real body's is below 1e12)"
        )
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


#: Largest rounding of a mesh file's coordinates, as a fraction of the body's size (the
#: diagonal of its bounding box), that a hull is loaded with. The rounding is the step
#: between neighbouring stored values where the body lies: for a float32 file (binary STL,
#: GLB) ``np.spacing(max |coordinate|)``, for text the decimal step its values are written
#: to. Measured on a 1 m wedge prism at a 0.02 m draft (Wagner, 16 slices): a step of
#: 3e-5 of the size changes the force by up to 0.09 %, 1.2e-4 by 0.06 %, 2.4e-4 by 0.5 %,
#: 1e-3 by 2.7 % and 8e-3 by 15 % (0.4 % of the volume at 2.4e-4).
MAX_ROUNDING = 1e-4

#: Rounding, as a fraction of the body's size, above which loading warns (below it the
#: force moves by less than about 0.04 %).
WARN_ROUNDING = 1e-5

#: Fewest distinct values along an axis for it to tell whether a text file's values are
#: rounded, and the share of the decimal grid's steps they must fill along each such axis
#: (at least two axes), unless the rounding made faces degenerate: a body drawn on a coarse
#: grid on purpose, such as a box, does neither. This is an estimate, so a text file is
#: warned about, not refused.
_GRID_VALUES = 5
_GRID_FILL = 0.5

#: Values sampled along each axis to find a text file's decimal step.
_GRID_SAMPLE = 200_000


def check_precision(
    vertices: np.ndarray,
    faces: np.ndarray,
    name: str,
    *,
    float32: bool = False,
    unit: str = "file units",
) -> str | None:
    """Refuse a mesh whose stored coordinates are rounded too coarsely for its size.

    Parameters
    ----------
    vertices : (n, 3) float
        As stored in the file (its units and axes).
    faces : (m, 3) int
        Triangles; only the vertices they use count.
    name : str
        For messages.
    float32 : bool
        The file stores single precision (binary STL, GLB); also when ``vertices`` are
        float32.
    unit : str
        The coordinates' unit, for messages.

    Returns
    -------
    str or None
        The warning given (a :class:`~hullslice.errors.HullsliceWarning`), else None: for a
        float32 file a rounding between :data:`WARN_ROUNDING` and :data:`MAX_ROUNDING` of
        the size; for a text file values that fill a decimal grid coarser than
        :data:`MAX_ROUNDING` of the size (an estimate, so not refused).

    Raises
    ------
    MeshError
        A float32 file whose rounding exceeds :data:`MAX_ROUNDING` of the body's size: the
        message names the offset, the size, the precision and the fix.
    """
    import warnings

    v = all_v = np.asarray(vertices)
    f = np.asarray(faces)
    if v.ndim != 2 or v.shape[1] != 3 or len(v) == 0 or f.ndim != 2 or f.size == 0:
        return None  # the hull's checks say what is wrong
    if f.min() < 0 or f.max() >= len(v):
        return None
    used = np.zeros(len(v), dtype=bool)
    used[f.ravel()] = True
    v = v[used]
    if not np.isfinite(v).all():
        return None
    lo, hi = (b.astype(np.float64) for b in bounds(v))
    size = float(np.linalg.norm(hi - lo))
    if size == 0.0:
        return None
    reach = float(np.abs(v).max())
    fix = (
        "move the body near the origin in the CAD tool, or export it in double precision "
        "(e.g. OBJ with 9 or more significant digits)"
    )
    more_digits = "export it with more digits (9 or more significant digits)"
    if float32 or v.dtype == np.float32:
        step = float(np.spacing(np.float32(reach)))
        ratio = step / size
        if ratio <= WARN_ROUNDING:
            return None
        where = (
            f"mesh {name!r} lies {reach:.3g} {unit} from the origin, {reach / size:.3g} times "
            f"its size ({size:.3g} {unit}): stored in single precision (float32, about 7 "
            f"digits), its coordinates there step by {step:.3g} {unit}, {ratio:.2g} of its size"
        )
        if ratio > MAX_ROUNDING:
            raise MeshError(
                f"{where}, more than the {MAX_ROUNDING:g} that keeps the volume and force "
                f"within about 0.1 %: {fix}"
            )
        text = f"{where}: the volume and force may be off by up to about 0.1 %; {fix}"
    else:
        grid = _decimal_step(v, lo, hi, all_v, f)
        if grid is None or grid / size <= MAX_ROUNDING:
            return None
        text = (
            f"mesh {name!r} is {size:.3g} {unit} across and its coordinates look rounded to "
            f"{grid:.3g} {unit}, {grid / size:.2g} of its size: the volume and force may "
            f"be off by more than 0.1 %; {more_digits}"
        )
    warnings.warn(text, HullsliceWarning, stacklevel=3)
    return text


def _decimal_step(
    v: np.ndarray, lo: np.ndarray, hi: np.ndarray, all_v: np.ndarray, f: np.ndarray
) -> float | None:
    """The decimal step ``10**k`` that every coordinate is a multiple of, when the values
    fill that grid along two axes or faces are degenerate (a text file written with few
    digits); else None. ``v`` are the used vertices, ``all_v`` and ``f`` the mesh."""
    stride = max(1, len(v) // _GRID_SAMPLE)
    sample = np.asarray(v[::stride], dtype=np.float64)
    columns = [np.unique(sample[:, k]) for k in range(3)]
    values = np.concatenate(columns)
    finest = 10 * float(np.spacing(np.abs(values).max()))
    extent = float((hi - lo).max())
    for k in range(math.floor(math.log10(extent)), -17, -1):
        step = 10.0**k
        if step < finest:
            return None
        r = values / step
        if np.all(np.abs(r - np.round(r)) <= 1e-6 + 1e-12 * np.abs(r)):
            break
    else:
        return None
    varied = [c for c in columns if len(c) >= _GRID_VALUES]
    if len(varied) >= 2 and all(
        len(c) >= _GRID_FILL * (float(c[-1] - c[0]) / step + 1.0) for c in varied
    ):
        return step
    corners = all_v[f]
    degenerate = (
        (corners[:, 0] == corners[:, 1]).all(axis=1)
        | (corners[:, 1] == corners[:, 2]).all(axis=1)
        | (corners[:, 2] == corners[:, 0]).all(axis=1)
    )
    return step if degenerate.any() else None
