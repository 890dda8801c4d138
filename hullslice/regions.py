"""Regions of a large hull for manifold3d's cut at a pitch.

Turning a mesh for a new pitch costs manifold3d time in proportion to its vertices (about
0.1 s for a million faces), so a large hull is cut through a **region**: the body trimmed
to a band of its own ``x`` that holds every face the planes to cut can cross (the planes'
reach along ``x`` at the pitch, widened by the longest face). Only that band is turned
(:meth:`hullslice.geometry.Frame.cut`). Trimming leaves the faces inside the band as they
are, so a section cut through a region has the same points as one cut through the whole
body. A region is kept on the hull and serves every pitch whose planes it holds; a larger
one is made when the wetted part outgrows it. A hull cut at one pitch only is cut whole:
making a region costs more than turning the whole once.
"""

from __future__ import annotations

from typing import Any

from .caching import LRU, Entry, Once
from .reduce import row_max, row_min

__all__ = ["REGIONS", "region"]

#: Hulls with fewer faces are always cut whole (turning them is cheap).
REGION_MIN_FACES = 50_000
#: A region longer than this share of the body is not worth trimming: the whole is cut.
REGION_MAX_SHARE = 0.6
#: Room to grow given to a new region on either side, as a share of the range asked for.
REGION_ROOM = 0.25
#: How many regions a hull keeps (and turned copies of them a frame keeps).
REGION_CACHE = 2

#: A hull's regions by their ``x`` range (m): trimmed manifold3d bodies, see :func:`region`.
#: Kept per hull (not shared by :meth:`~hullslice.mesh.Hull.with_mass`): a hull makes its
#: first region at its second pitch.
REGIONS: Entry[LRU[tuple[float, float], Any]] = Entry("regions", lambda: LRU(REGION_CACHE))
#: The longest extent of a face along ``x``, m (see :func:`region`).
FACE_REACH: Entry[Once[float]] = Entry("face reach", Once, geometry=True)


def region(hull, lo: float, hi: float) -> tuple[tuple[float, float] | None, object]:
    """A manifold3d body holding every face of the hull that reaches between body
    ``x = lo`` and ``hi`` (m) unchanged: ``(key, manifold)``, key None for the whole hull.

    The hull trimmed by two planes ``x = const`` beyond that range by the longest face's
    length along ``x`` and some room to grow (:data:`REGION_ROOM` of the range's length,
    at least 2 % of the body's); kept on the hull. Small hulls, and ranges over most of
    the body, get the whole hull.
    """
    xa, xb = (float(v) for v in hull.bounds[:, 0])
    length = xb - xa
    if len(hull.faces) < REGION_MIN_FACES:
        return None, hull.manifold
    reach = _face_reach(hull)
    need_lo, need_hi = lo - reach, hi + reach
    regions = hull.cache[REGIONS]
    found = regions.find(lambda key: key[0] < need_lo and need_hi < key[1])
    if found is not None:
        return found
    room = max(REGION_ROOM * (hi - lo), 0.02 * length)
    a, b = need_lo - room, need_hi + room
    if b - a > REGION_MAX_SHARE * length:
        return None, hull.manifold
    body = hull.manifold
    if a > xa:
        body = body.trim_by_plane((1.0, 0.0, 0.0), a)
    if b < xb:
        body = body.trim_by_plane((-1.0, 0.0, 0.0), -b)
    regions.put((a, b), body)
    return (a, b), body


def _face_reach(hull) -> float:
    """The longest extent of a face along ``x``, m (kept on the hull)."""

    def reach() -> float:
        x = hull.vertices[:, 0][hull.faces]
        return float((row_max(x) - row_min(x)).max())

    return hull.cache[FACE_REACH].get(reach)
