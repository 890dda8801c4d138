"""The 2D kernel: cross-sections' contours and their wetted properties, in numpy alone.

:mod:`~hullslice.kernel.outline`
    :class:`Outline`: the edges of station sections sorted for cutting at any waterline.
:mod:`~hullslice.kernel.wetted`
    :func:`wetted_properties` and :func:`section_properties`: wetted pieces, keels,
    half-beams, deadrise and mass shares of all stations at once.
:mod:`~hullslice.kernel.waterline_table`
    :class:`WaterlineTable`: those properties tabulated once against the water's height.
:mod:`~hullslice.kernel.keel` and :mod:`~hullslice.kernel.envelope`
    :class:`KeelLine`, the lower edge of the side view, and :func:`lower_envelope`, which
    draws it from the side views of the outline's edges.

Nothing here knows of meshes, poses or hulls: the layers above cut a body into contours and
hand them over.
"""

from __future__ import annotations

from .outline import Outline, Polygons
from .waterline_table import WaterlineTable
from .wetted import DEADRISE_ESTIMATORS, section_properties, wetted_properties

__all__ = [
    "DEADRISE_ESTIMATORS",
    "Outline",
    "Polygons",
    "WaterlineTable",
    "section_properties",
    "wetted_properties",
]
