"""From the arrays of a mesh file to the arrays of the hull: repair, parts and scale.

:func:`load_hull` reads a file and hands its arrays here before it builds the
:class:`~hullslice.mesh.Hull`. In order:

1. ``repair="close"``: holes filled and shells that cannot be closed dropped
   (:mod:`hullslice.repair`); never done unasked.
2. ``keep``: the bodies (shells) kept, ``"largest"`` or numbers from 1 (largest first,
   :mod:`hullslice.parts`); a body number does not depend on the scale or the axes.
3. The scale: ``units`` (a named unit), ``scale`` (metres per file unit, times the unit's
   when both are given) or ``length`` (the kept bodies' extent along ``forward``, m).

The box cut (``keep_box``) comes after, on the closed hull in the body frame. Each step
that changes the geometry says so in one :class:`~hullslice.errors.MeshRepairWarning`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from .axes import axis_matrix
from .constants import LENGTH_UNITS
from .errors import InputError, MeshRepairWarning
from .parts import Body, find_bodies, keep_faces, parse_keep
from .topology import drop_unused_vertices, unique_rows

__all__ = ["REPAIRS", "Prepared", "check_scale", "prepare_arrays"]

#: The values of ``repair``: ``none`` (refuse what is open, the default) and ``close``.
REPAIRS = ("none", "close")


@dataclass
class Prepared:
    """The arrays of the hull to build and what was done to them.

    ``vertices`` are in the file's ``units`` (times ``scale``, or set by ``length``), mesh
    axes; ``scale`` is metres per file unit in all.
    """

    vertices: np.ndarray
    faces: np.ndarray
    scale: float  # m per file unit
    notes: list[str] = field(default_factory=list)
    bodies: list[dict] = field(default_factory=list)
    kept: tuple[int, ...] = ()


#: Largest ``scale`` factor and ``length`` (m) taken: beyond, the coordinates would lose
#: their precision or overflow.
MAX_SIZE = 1e12


def _positive(value, what: str, fix: str) -> float:
    if isinstance(value, bool):
        raise InputError(f"{what} {value!r} is not a number: {fix}")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what} {value!r} is not a number: {fix}") from None
    if not math.isfinite(x) or x <= 0.0:
        raise InputError(f"{what} {value!r} is not a positive number: {fix}")
    if not 1.0 / MAX_SIZE <= x <= MAX_SIZE:
        raise InputError(f"{what} {value!r} is outside {1 / MAX_SIZE:g} to {MAX_SIZE:g}: {fix}")
    return x


def check_scale(units: str, scale, length) -> tuple[float, float | None, float | None]:
    """Check the three ways of giving the size; returns (m per unit, scale, length).

    ``scale`` and ``length`` exclude each other, and ``length`` gives the size alone, so it
    is refused with a unit other than metres.
    """
    key = str(units).strip().lower()
    if key not in LENGTH_UNITS:
        raise InputError(f"length unit {units!r} is not one of {', '.join(LENGTH_UNITS)}")
    if scale is not None and length is not None:
        raise InputError(
            f"scale {scale!r} and length {length!r} m both give the mesh's size: give one of "
            "them (--scale FACTOR or --length M)"
        )
    if scale is not None:
        scale = _positive(
            scale, "scale", "give the factor from the file's units to metres, e.g. --scale 2.56"
        )
    if length is not None:
        length = _positive(
            length, "length", "give the body's length along --forward in m, e.g. --length 37.6"
        )
        if key != "m":
            raise InputError(
                f"length {length:g} m sets the mesh's size by itself; units {units!r} would be "
                "ignored: leave out --units, or give --scale instead of --length"
            )
    return LENGTH_UNITS[key], scale, length


def prepare_arrays(
    vertices: np.ndarray,
    faces: np.ndarray,
    name: str,
    *,
    units: str = "m",
    scale: float | None = None,
    length: float | None = None,
    forward: str = "+x",
    up: str = "+z",
    repair: str | None = None,
    keep=None,
) -> Prepared:
    """Repair, keep and scale the arrays of a mesh file (see the module's documentation).

    Parameters
    ----------
    vertices : (n, 3) float
        As in the file (its units and axes).
    faces : (m, 3) int
    name : str
        For messages.
    units, scale, length, forward, up, repair, keep
        As :func:`hullslice.load_hull` takes them.

    Returns
    -------
    Prepared
        Vertices in the file's unit and axes, scaled; the notes for the hull's ``repairs``;
        the bodies (as dicts, body frame, m) and the numbers kept.
    """
    unit, scale, length = check_scale(units, scale, length)
    mode = "none" if repair is None else str(repair).strip().lower()
    if mode not in REPAIRS:
        raise InputError(
            f"repair {repair!r} is not one of {', '.join(REPAIRS)}: give --repair close to "
            "fill holes and drop what cannot be closed"
        )
    rot = axis_matrix(forward, up)
    v = np.asarray(vertices, dtype=np.float64)
    f = np.asarray(faces, dtype=np.int64)
    if mode == "none" and keep is None and length is None:
        # nothing to find out about the bodies: the hull's own checks do the rest
        return Prepared(v * (scale or 1.0), f, unit * (scale or 1.0))
    if not (v.ndim == 2 and v.shape[1] == 3 and np.isfinite(v).all() and f.ndim == 2
            and len(f) and f.min() >= 0 and f.max() < len(v)):  # fmt: skip
        # the hull's checks report what is wrong
        return Prepared(v * (scale or 1.0), f, unit * (scale or 1.0))
    v, inverse = unique_rows(v)
    f = inverse[f]
    report = None
    if mode == "close":
        from .repair.close import close_mesh

        v, f, report = close_mesh(v, f, name)
    bodies, numbers = find_bodies(v, f)
    mask, kept = keep_faces(bodies, numbers, keep, name)
    if length is not None:
        fwd = rot[0]
        used = np.unique(f[mask])
        extent = float(np.ptp(v[used] @ fwd))
        if extent <= 0.0:
            raise InputError(f"mesh {name!r} has no extent along {forward!r}: check --forward")
        factor = length / extent
    else:
        factor = unit * (scale if scale is not None else 1.0)
    notes = []
    if report is not None:
        notes.append(report.message(factor))
    described = [_in_body_frame(b, rot, factor) for b in bodies]
    if parse_keep(keep) is not None:
        dropped = [b for b in described if b["number"] not in kept]
        kept_vol = sum(b["volume"] or 0.0 for b in described if b["number"] in kept)
        text = (
            f"kept bod{'y' if len(kept) == 1 else 'ies'} {', '.join(map(str, kept))} of "
            f"{len(bodies)} ({int(mask.sum())} faces, {kept_vol:.6g} m^3)"
        )
        if dropped:
            shown = ", ".join(f"{b['number']} ({_size_text(b)})" for b in dropped[:5]) + (
                f" and {len(dropped) - 5} more" if len(dropped) > 5 else ""
            )
            text += f"; dropped {shown}"
        notes.append(text)
        v, f = drop_unused_vertices(v, f[mask])
    for b in described:
        b["kept"] = b["number"] in kept
    for note in notes:
        warnings.warn(f"mesh {name!r}: {note}", MeshRepairWarning, stacklevel=3)
    # in the file's unit, for the hull to convert (its density check names the unit)
    return Prepared(v * (factor / unit), f, factor, notes, described, kept)


def _in_body_frame(body: Body, rot: np.ndarray, factor: float) -> dict:
    """A body's description with its box in metres, body frame (axes are a signed
    permutation, so the box maps to a box)."""
    d = body.as_dict()
    a = rot @ (np.array(body.bounds_min) * factor)
    b = rot @ (np.array(body.bounds_max) * factor)
    d["bounds_min"] = np.minimum(a, b).tolist()
    d["bounds_max"] = np.maximum(a, b).tolist()
    d["extents"] = (np.maximum(a, b) - np.minimum(a, b)).tolist()
    d["volume"] = None if body.volume is None else body.volume * factor**3
    return d


def _size_text(b: dict) -> str:
    e = b["extents"]
    vol = f"{b['volume']:.3g} m^3" if b["volume"] is not None else "open"
    return f"{e[0]:.3g} x {e[1]:.3g} x {e[2]:.3g} m, {vol}"
