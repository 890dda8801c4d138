"""From stations and their wetted properties to :class:`~hullslice.slicing.record.Sections`.

Both slicings (over the wetted length, or fixed over the body's length) end here: the
stations' positions and thicknesses, the keel line at them, and the mass per metre of each
station shared between its wetted pieces.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from ..geometry import Frame
from ..kernel.keel import KeelLine
from ..kernel.outline import Polygons
from ..mesh import Hull
from ..state import Pose
from .own_keel import own_keels, widest_beam
from .record import Sections, ShiftedPolygons

__all__ = ["assemble", "station_mass"]


#: The keel line's curvature is averaged over at least this share of the beam of the
#: body's widest connected piece: 2D+t describes the flow around sections no finer along
#: the body than their own width, and a mesh's keel line zigzags about the true one at its
#: facets' scale.
KEEL_WINDOW_BEAMS = 0.5


def keel_window(hull) -> float:
    """The shortest length (m) over which a section's keel curvature is averaged: half the
    beam (:data:`KEEL_WINDOW_BEAMS`) of the body's widest connected piece (the body's own
    beam for a body of one piece; a float's, not the span across a catamaran's two)."""
    return KEEL_WINDOW_BEAMS * widest_beam(hull)


def station_mass(
    hull: Hull, fr: Frame, area: np.ndarray, rel: np.ndarray, dx: np.ndarray | None = None
) -> np.ndarray:
    """Mass per metre (kg/m) of the stations at ``rel`` (m, relative ``X``) with section
    ``area`` (m^2) and slices ``dx`` thick (m; a point mass then counts whole on the slices
    it spans); NaN without a hull mass."""
    if hull.mass is None:
        return np.full(len(rel), np.nan)
    if hull.mass_distribution is None:
        return hull.mass / hull.volume * area
    # the distribution's parts, each at its own height, crossed by the tilted planes
    return hull.mass_distribution.on_planes(
        rel, fr.pitch, (fr.cg[0], fr.cg[2]), float(hull.centroid[2]), dx
    )


def assemble(
    hull: Hull,
    fr: Frame,
    *,
    pose: Pose,
    level: float,
    length: float,
    rel: np.ndarray,
    dx: np.ndarray,
    props: Mapping[str, np.ndarray],
    polys: Sequence[Polygons],
    deadrise: str,
    lift: np.ndarray | None = None,
    keel: np.ndarray | None = None,
    slope_width: np.ndarray | None = None,
    line: KeelLine | None = None,
) -> Sections:
    """:class:`Sections` from per-station positions and per-entry properties.

    Parameters
    ----------
    hull, fr : Hull, Frame
        The body and its frame at the pose's pitch.
    pose : Pose
        The pose.
    level : float
        Height of the water above the centre of gravity in the pitched frame, m.
    length : float
        Length of the wetted part along ``X``, m.
    rel, dx : (s,) float
        Stations relative to the centre of gravity and their slices' thicknesses, m.
    props : mapping of arrays
        Per-entry wetted properties (see :func:`~hullslice.kernel.wetted.wetted_properties`).
    polys : (s,) sequence of contours
        Each station's contours in the cutter's coordinates (see :meth:`Frame.cut`).
    deadrise : str
        The deadrise estimator used.
    lift : (s,) float, optional
        Height by which each station's contours are moved, m: a station whose properties
        were taken with the water at ``level - lift`` (another station's section moved to
        where this one's keel is).
    keel : (s,) float, optional
        The keel line's height at the stations when already known.
    slope_width : (s,) float, optional
        The length over which each station's keel slope is the keel line's chord, m:
        ``dx`` when not given. Fixed slices give their wetted part or half the slice,
        whichever is longer, so that a slice beginning to wet does not take the slope of
        the one facet under it; given stations their spacing.
    line : KeelLine, optional
        The keel line read (default the frame's; see
        :meth:`~hullslice.geometry.Frame.keel_for`).
    """
    st = props["station"]
    line = fr.keel if line is None else line
    keel_z = line.height(rel) if keel is None else keel
    # the keel's slope is its chord over the slice; its curvature is averaged over the
    # wetted slice or half a beam, whichever is longer
    slope = line.mean_slope(rel, dx if slope_width is None else slope_width)
    window = np.maximum(dx, keel_window(hull))
    # a station in a gap between parts one behind the other has no section: its (dry)
    # entry's keel is put at the water, not infinitely high (no NaN in its kinematics)
    keel_z = np.where(np.isfinite(keel_z), keel_z, level)
    z_cg = -level
    shift = (fr.origin[0], fr.origin[1] + z_cg)
    m_station = station_mass(hull, fr, props["area"], rel, dx)
    keel_slope = slope[st]
    keel_at = (keel_z + z_cg)[st]
    curvature = line.mean_curvature(rel, window)[st]
    # on a body of separate pieces each entry takes its own piece's keel line
    own = own_keels(
        hull, fr, props, x=rel, chord=dx if slope_width is None else slope_width,
        window=window, level=level,
    )  # fmt: skip
    if own is not None:
        entry, own_slope, own_curvature, height = own
        keel_slope[entry] = own_slope
        curvature[entry] = own_curvature
        keel_at[entry] = height + z_cg
    return Sections(
        station=st,
        x=(rel + fr.cg[0])[st],
        dx=dx[st],
        penetration=props["penetration"],
        half_beam=props["half_beam"],
        half_beam_port=props["half_beam_port"],
        half_beam_stbd=props["half_beam_stbd"],
        deadrise=props["deadrise"],
        deadrise_port=props["deadrise_port"],
        deadrise_stbd=props["deadrise_stbd"],
        area=props["area"][st],
        mass_per_metre=m_station[st] * props["mass_share"],
        chine_wetted=props["chine_wetted"],
        keel_slope=keel_slope,
        keel_z=keel_at,
        y_keel=props["y_keel"],
        part_half_beam=props["part_half_beam"],
        polygons=ShiftedPolygons(polys, shift, fr.scale, lift),
        deadrise_method=deadrise,
        draft=pose.draft,
        pitch=pose.pitch,
        wetted_length=length,
        z_cg=z_cg,
        keel_curvature=curvature,
    )
