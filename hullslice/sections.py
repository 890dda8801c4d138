"""Cutting a hull into cross-sections at a pose: the 2D+t slices and their properties.

At a pose the wetted part of the hull (below ``Z = 0``), of length ``DeltaL`` along the
earth's ``X``, is cut into ``n`` slices of thickness ``d = DeltaL / n`` (paper, Eq. 7); each
slice is represented by the hull's cross-section at its mid-station, cut by manifold3d along
the earth-fixed plane ``X = const`` (for a pitched body a tilted plane in its own frame).

A section may have several wetted pieces (two floats, a catamaran): each piece is an
**entry** of :class:`Sections` with its own keel, penetration and deadrise, and its share of
the section's mass per metre. A section with one piece (the usual case) is one entry. The
mass is shared first between the section's separate parts (disjoint outer contours, such as
a catamaran's floats) by their areas, each carrying its own; then between the wetted pieces
of one part (twin keels joined above the water) by their widths at the waterline.

Local deadrise estimators (each per side, port and starboard, of each piece):

``wedge`` (default)
    The equivalent wedge of the wetted piece: ``tan(beta) = p / c``, ``p`` the depth of its
    keel below the water, ``c`` the horizontal distance from the keel to the waterline on
    that side. Exact for a wedge.
``waterline-slope``
    The slope of the contour where it meets the water: ``tan(beta) = |dz/dy|`` there.
``keel-fit``
    A least-squares line through the keel fitted to the wetted contour of that side,
    ``z - z_k = tan(beta) |y - y_k|``, integrated exactly over the contour's segments.

The two sides combine into the section's deadrise by the harmonic mean of ``tan(beta)``
(for ``wedge``: ``tan(beta) = p / c`` with ``c`` the half-width of the piece).

This module is the slicing's front: :func:`cut` checks its inputs and places the stations.
The contours' properties are computed by the numpy kernel (:mod:`hullslice.kernel`), the
pitch's placement and cutter kept by :mod:`hullslice.geometry`, and the fixed slicing and
the :class:`Sections` record live in :mod:`hullslice.slicing`.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .constants import TOL
from .errors import InputError
from .geometry import frame, loops_in_use
from .kernel.outline import Outline, Polygons
from .kernel.wetted import DEADRISE_ESTIMATORS, section_properties, wetted_properties
from .limits import check_slice_count
from .mesh import Hull
from .slicing.assemble import assemble, keel_window
from .slicing.fixed import TABLE_AFTER, fixed_sections
from .slicing.record import Sections, ShiftedPolygons
from .state import Pose

__all__ = [
    "DEADRISE_ESTIMATORS",
    "SLICINGS",
    "TABLE_AFTER",
    "Outline",
    "Polygons",
    "Sections",
    "ShiftedPolygons",
    "area_curve",
    "cut",
    "section_properties",
    "sections_at",
    "wetted_properties",
]


# -- inputs ------------------------------------------------------------------------------------


def _as_pose(pose: Pose | float) -> Pose:
    return pose if isinstance(pose, Pose) else Pose(draft=pose)


_slice_count = check_slice_count


def _check_deadrise(deadrise: str) -> str:
    if deadrise not in DEADRISE_ESTIMATORS:
        raise InputError(
            f"deadrise estimator {deadrise!r} is unknown; choose one of "
            f"{', '.join(DEADRISE_ESTIMATORS)}"
        )
    return deadrise


def _height_at(hull: Hull, pitch: float) -> float:
    """Vertical extent of the body at a pitch, m."""
    fr = frame(hull, pitch)
    return fr.highest - fr.lowest


# -- cutting -----------------------------------------------------------------------------------


def cut(
    hull: Hull,
    pose: Pose | float,
    slices: int = 32,
    *,
    deadrise: str = "wedge",
    stations: Sequence[float] | None = None,
    slicing: str = "wetted",
) -> Sections:
    """Cut a hull at a pose into the slices of the 2D+t method.

    Parameters
    ----------
    hull : Hull
        The body.
    pose : Pose or float
        The pose (draft in m, pitch in rad), or the draft alone (level body).
    slices : int
        Number of slices ``n`` over the wetted length (default 32); ignored when
        ``stations`` is given.
    deadrise : str
        Deadrise estimator, a key of :data:`DEADRISE_ESTIMATORS` (default ``"wedge"``).
    stations : sequence of float, optional
        Explicit station positions along ``X`` in m, instead of the mid-stations of ``n``
        equal slices; each then stands for a slice reaching halfway to its neighbours
        (clipped to the wetted length).
    slicing : str
        ``"wetted"`` (default, the paper's: ``n`` slices over the wetted length) or
        ``"fixed"`` (``n`` slices over the body's length, cut once per pitch), see
        :data:`SLICINGS`.

    Returns
    -------
    Sections
    """
    pose = _as_pose(pose)
    _check_deadrise(deadrise)
    _check_slicing(slicing)
    height = _height_at(hull, pose.pitch)
    if pose.draft > height + TOL.coordinate * hull.size:
        raise InputError(
            f"draft {pose.draft:g} m is deeper than the body's height {height:.6g} m: the body "
            "would be under water; give a draft between 0 and the height"
        )
    if stations is None:
        return sections_at(hull, pose, _slice_count(slices), deadrise, slicing=slicing)
    x = np.asarray(stations, dtype=np.float64).ravel()
    if not np.all(np.isfinite(x)) or np.any(np.diff(x) <= 0):
        raise InputError("stations must be finite and strictly increasing (in m)")
    return sections_at(hull, pose, len(x), deadrise, stations=x)


#: How the slices are placed, by name.
SLICINGS: dict[str, str] = {
    "wetted": "n equal slices over the wetted length at each instant (the paper's)",
    "fixed": "n equal slices over the body's length, cut once per pitch; the slices at the "
    "ends of the wetted part count their wetted length only",
}


def _check_slicing(slicing: str) -> str:
    if slicing not in SLICINGS:
        raise InputError(f"slicing {slicing!r} is unknown; choose one of {', '.join(SLICINGS)}")
    return slicing


def sections_at(
    hull: Hull,
    pose: Pose,
    n: int,
    deadrise: str,
    stations: np.ndarray | None = None,
    slicing: str = "wetted",
    cache: bool = True,
    cutter: str = "manifold3d",
    first: bool = False,
) -> Sections:
    """The sections at a pose, inputs already checked (see :func:`cut`).

    ``slicing="fixed"`` places the slices over the body's length (see :data:`SLICINGS`);
    ``cache=False`` cuts its stations afresh instead of reusing the pitch's cut (the same
    numbers, for checking); ``cutter`` names how a new pitch is cut
    (:data:`~hullslice.geometry.CUTTERS`); ``first``: the pitch's first evaluation in a
    run's stage (its frame made just now), whose fixed slices read the keel line where
    they are (:meth:`~hullslice.geometry.Frame.keel_for`).
    """
    fr = frame(hull, pose.pitch)
    level = fr.lowest + pose.draft  # the water surface, relative to the cg
    fixed = slicing == "fixed" and stations is None
    line = fr.keel_for(level, n, keel_window(hull)) if first and fixed else fr.keel
    extent = line.bottom(level)
    tol = TOL.coordinate * hull.size
    if fixed:
        return fixed_sections(
            hull,
            fr,
            pose=pose,
            n=n,
            deadrise=deadrise,
            level=level,
            extent=extent,
            tol=tol,
            cache=cache,
            cutter=cutter,
            line=line,
        )
    if extent is None:
        x0 = x1 = float(fr.keel.x[np.argmin(fr.keel.z)])
    else:
        x0, x1 = extent
    length = x1 - x0
    width = None  # the slices' own thickness
    if stations is None:
        if length > 0.0:
            d = length / n
            rel = x0 + (np.arange(n) + 0.5) * d
            dx = np.full(n, d)
        else:
            rel, dx = np.empty(0), np.empty(0)
    else:
        rel = np.asarray(stations, dtype=np.float64) - fr.cg[0]
        bounds = np.concatenate([[x0], 0.5 * (rel[1:] + rel[:-1]), [x1]])
        dx = np.diff(np.clip(bounds, x0, x1))
        if len(rel) > 1:  # the keel's slope over the stations' spacing, not the wet part
            bounds[0], bounds[-1] = 2.0 * rel[0] - bounds[1], 2.0 * rel[-1] - bounds[-2]
            width = np.diff(bounds)
    polys = fr.cut(rel, cutter)
    outline = Outline.of(polys, tol, fr.origin, fr.scale, loops=loops_in_use("outline"))
    props = wetted_properties(outline, level, tol, deadrise, loops_in_use("wetted"))
    return assemble(
        hull,
        fr,
        pose=pose,
        level=level,
        length=fr.keel.wet_length(level, x0, x1) if length > 0.0 else 0.0,
        rel=rel,
        dx=dx,
        props=props,
        polys=polys,
        deadrise=deadrise,
        slope_width=width,
    )


def area_curve(hull: Hull, stations: int = 40) -> tuple[np.ndarray, np.ndarray]:
    """The sectional area curve of a level hull.

    Parameters
    ----------
    hull : Hull
    stations : int
        Number of stations, the mid-points of equal parts of the body's length (default 40).

    Returns
    -------
    x : (stations,) float
        Stations along the body, m.
    area : (stations,) float
        Area of the cross-section at each, m^2. ``sum(area) * length / stations`` is the
        volume by the midpoint rule.
    """
    n = _slice_count(stations)
    fr = frame(hull, 0.0)
    _, rel = fr.fixed_stations(n)
    outline = Outline.of(fr.cut(rel), TOL.coordinate * hull.size, fr.origin, fr.scale)
    return rel + fr.cg[0], outline.area.copy()
