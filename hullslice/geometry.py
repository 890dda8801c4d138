"""Placing the hull in the earth frame at a pitch, and what depends only on the pitch.

The body turns about its centre of gravity ``g``. A body point ``r = v - g`` (``x``, ``z``
components; ``y`` is unchanged) is at

    X = x_g + r_x cos(theta) - r_z sin(theta)
    Z = Z_g + r_x sin(theta) + r_z cos(theta)

with ``theta`` the pitch, positive nose up. ``Z_g`` follows from the draft: the lowest point
of the body is ``draft`` below the water ``Z = 0``. Earth ``X`` is measured so that a level
body has ``X = x``: stations are reported in a frame moving horizontally with the body.

For one pitch, three things do not depend on the draft and are computed once
(:class:`Frame`): the lowest point, the keel line (the lower edge of the body's side view,
``Z_k(X)``, exact as a polyline) and the manifold3d object that cuts the body along earth
planes ``X = const``.

Turning a mesh for a new pitch costs manifold3d time in proportion to its vertices (about
0.1 s for a million faces), so a large hull is cut through a **region**: the body trimmed
to a band of its own ``x`` that holds every face the planes to cut can cross (the planes'
reach along ``x`` at the pitch, widened by the longest face). Only that band is turned.
Trimming leaves the faces inside the band as they are, so a section cut through a region
has the same points as one cut through the whole body. A region is kept on the hull and
serves every pitch whose planes it holds; a larger one is made when the wetted part
outgrows it. A hull cut at one pitch only is cut whole: making a region costs more than
turning the whole once.
"""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["Frame", "KeelLine", "frame"]


#: Slope of the side view beyond which a facet at an end of the keel line is an end face
#: (a transom, a blunt bow or tail; tan 75 deg), not the bottom.
END_FACE_SLOPE = float(np.tan(np.radians(75.0)))


@dataclass(frozen=True, eq=False)
class KeelLine:
    """The lower edge of the body's side view at one pitch: ``Z_k(X)`` as a polyline.

    Coordinates are relative to the centre of gravity in the pitched frame (``X - x_g``,
    ``Z - Z_g``), in m.

    Attributes
    ----------
    x : (k,) float
        Break points, increasing.
    z : (k,) float
        Height of the lowest point of the body's section at each break point; ``inf`` in a
        gap between parts one behind the other.
    """

    x: np.ndarray
    z: np.ndarray

    def at(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Keel height and slope ``dZ_k/dX`` at relative stations ``x``.

        A mesh's keel line is a polyline whose slope jumps from facet to facet, and a body
        moving forward turns every jump into a jump of penetration velocity (60 m/s times a
        slope change of 0.01 is 0.6 m/s). The slope is therefore taken continuous: each
        facet's slope stands at the facet's middle, linearly in between. It is exact on a
        straight keel, and a kink blends over the two facets beside it only, however thin
        the slices. An end face (a transom, a blunt bow or tail: facets at an end of the
        keel line steeper than :data:`END_FACE_SLOPE`) keeps its own slope over its own
        extent and does not blend into the bottom's.
        """
        x = np.asarray(x, dtype=np.float64)
        z = np.interp(x, self.x, self.z)
        mid, slopes = self._facets
        slope = np.interp(x, mid, slopes)
        (x0, x1), faces = self._end_faces
        for (lo, hi), (fmid, fslopes) in zip(
            ((self.x[0], x0), (x1, self.x[-1])), faces, strict=True
        ):
            inside = (x >= lo) & (x < hi) if hi > lo else None
            if inside is not None and inside.any():
                slope = np.where(inside, np.interp(x, fmid, fslopes), slope)
        return z, slope

    def curvature(self, x: np.ndarray) -> np.ndarray:
        """The keel line's ``d^2 Z_k / dX^2`` at relative stations ``x``, 1/m.

        The derivative of the continuous slope of :meth:`at`: constant between two facet
        middles, zero beyond the first and last (where the slope is held constant).
        """
        x = np.asarray(x, dtype=np.float64)
        mid, slopes = self._facets
        if len(mid) < 2:
            return np.zeros(x.shape)
        k = np.diff(slopes) / np.diff(mid)
        i = np.searchsorted(mid, x, side="right") - 1
        inside = (i >= 0) & (i < len(k))
        return np.where(inside, k[np.clip(i, 0, len(k) - 1)], 0.0)

    def mean_curvature(self, x: np.ndarray, dx: np.ndarray) -> np.ndarray:
        """The keel line's curvature averaged over slices of thickness ``dx`` centred on
        ``x``: ``(s(x + dx/2) - s(x - dx/2)) / dx`` with the slope ``s`` of :meth:`at`, 1/m.

        A mesh's keel line zigzags about the true one by the mesh's resolution, and its
        local curvature is noisy with it; over a slice the noise averages out, as it does
        for the force. Where ``dx`` is zero, the local :meth:`curvature`.
        """
        x = np.asarray(x, dtype=np.float64)
        dx = np.broadcast_to(np.asarray(dx, dtype=np.float64), x.shape)
        mid, slopes = self._facets
        if len(mid) < 2:
            return np.zeros(x.shape)
        ds = np.interp(x + dx / 2, mid, slopes) - np.interp(x - dx / 2, mid, slopes)
        thin = dx <= 0.0
        with np.errstate(divide="ignore", invalid="ignore"):
            out = ds / np.where(thin, 1.0, dx)
        return np.where(thin, self.curvature(x), out) if thin.any() else out

    @property
    def _facets(self) -> tuple[np.ndarray, np.ndarray]:
        """Middles and slopes of the bottom's facets: the keel line without its end faces
        (its first or last facets steeper than :data:`END_FACE_SLOPE`: a transom, a blunt
        bow or tail), whose slopes do not blend into the bottom's."""
        facets = self.__dict__.get("_facet_cache")
        if facets is None:
            mid, slopes = 0.5 * (self.x[1:] + self.x[:-1]), np.diff(self.z) / np.diff(self.x)
            idx = np.flatnonzero(np.isfinite(slopes))  # not the facets into a gap between parts
            if not len(idx):
                facets = (mid[:1], np.zeros(1))
                empty = (np.empty(0), np.empty(0))
                ends = ((float(self.x[0]), float(self.x[-1])), (empty, empty))
            else:
                mid, slopes = mid[idx], slopes[idx]
                steep = np.abs(slopes) > END_FACE_SLOPE
                lo, hi = 0, len(slopes)
                while lo < hi - 1 and steep[lo]:
                    lo += 1
                while hi - 1 > lo and steep[hi - 1]:
                    hi -= 1
                facets = (mid[lo:hi], slopes[lo:hi])
                ends = (
                    (float(self.x[idx[lo]]), float(self.x[idx[hi - 1] + 1])),
                    ((mid[:lo], slopes[:lo]), (mid[hi:], slopes[hi:])),
                )
            object.__setattr__(self, "_facet_cache", facets)
            object.__setattr__(self, "_end_cache", ends)
        return facets

    @property
    def _end_faces(self):
        """The bottom's extent ``(x0, x1)`` and the end faces' facet middles and slopes,
        before and after it."""
        self._facets  # noqa: B018 (fills the cache)
        return self.__dict__["_end_cache"]

    def below(self, level: float) -> tuple[float, float] | None:
        """The ``x`` range where the keel is below ``level`` (relative), or None."""
        x, z = self.x, self.z
        under = z < level
        first = int(under.argmax())
        if not under[first]:
            return None
        last = len(z) - 1 - int(under[::-1].argmax())

        def crossing(i: int) -> float:  # where the segment i, i + 1 meets the level
            t = (level - z[i]) / (z[i + 1] - z[i])
            return float(x[i] + t * (x[i + 1] - x[i]))

        # the first and last points under the level, or where the line goes under it
        lo = crossing(first - 1) if first > 0 else float(x[0])
        hi = crossing(last) if last < len(z) - 1 else float(x[-1])
        return min(lo, float(x[first])), max(hi, float(x[last]))


@dataclass(frozen=True, eq=False)
class Frame:
    """What depends on the pitch only: placement, keel line and the cutter.

    Attributes
    ----------
    pitch : float
        Pitch in rad, positive nose up.
    cg : (3,) float
        Centre of gravity in the body frame, m (the centre of rotation).
    lowest, highest : float
        Heights of the body's lowest and highest points above the centre of gravity in the
        pitched frame, m.
    keel : KeelLine
        The keel line, relative to the centre of gravity.
    """

    pitch: float
    cg: np.ndarray
    lowest: float
    highest: float
    keel: KeelLine
    _hull: Any = field(repr=False)
    _matrix: np.ndarray = field(repr=False)  # body point -> cutter (Y, Z, X), 3 x 4
    _offset: np.ndarray = field(repr=False)  # (Y, Z, X) of the cutter's origin, rel. cg
    _scale: float = 1.0  # the cutter's coordinates are metres times this
    _slicers: OrderedDict = field(default_factory=OrderedDict, repr=False)
    _fixed: dict = field(default_factory=dict, repr=False)

    def fixed_stations(self, n: int) -> tuple[float, np.ndarray]:
        """Thickness and mid-stations (relative to the cg) of ``n`` equal slices over the
        body's length at this pitch."""
        xa, xb = float(self.keel.x[0]), float(self.keel.x[-1])
        d = (xb - xa) / n
        return d, xa + (np.arange(n) + 0.5) * d

    def fixed_outline(self, n: int, tol: float, k0: int = 0, k1: int | None = None):
        """The outline of fixed stations ``k0`` to ``k1 - 1`` of ``n`` (mid-stations of
        equal slices over the body's length), cut once and kept.

        Returns ``(outline, polygons, c0)``: the outline and contours (relative to the cg)
        of stations ``c0`` to ``c0 + len(polygons) - 1``, a range holding the ones asked
        for. Stations are cut when first asked for, a couple beyond the range on either
        side once the range has had to grow, so that a wetted part growing along the body
        is cut a few stations at a time.
        """
        from .sections import Outline

        k1 = n if k1 is None else k1
        store = self._fixed.setdefault((int(n), float(tol)), {"polys": {}, "range": None})
        held = store["range"]
        if held is None or k0 < held[0] or k1 > held[1]:
            if held is None:  # a new pitch: only what is asked for
                lo, hi = k0, k1
            else:  # the wetted part grows at this pitch: some stations ahead
                lo = max(min(k0, held[0]) - FIXED_PAD, 0)
                hi = min(max(k1, held[1]) + FIXED_PAD, n)
            polys = store["polys"]
            missing = np.array([k for k in range(lo, hi) if k not in polys], dtype=np.int64)
            if len(missing):
                cuts = self.cut(self.fixed_stations(n)[1][missing])
                polys.update(zip(missing.tolist(), cuts, strict=True))
            rows = [polys[k] for k in range(lo, hi)]
            store["range"] = (lo, hi)
            store["outline"] = Outline.of(rows, tol, self.origin, self.scale)
            store["rows"] = rows
        return store["outline"], store["rows"], store["range"][0]

    def z_cg(self, draft: float) -> float:
        """Earth height of the centre of gravity for a draft (m)."""
        return -self.lowest - draft

    def cut(self, x_rel: np.ndarray) -> list[tuple[np.ndarray, ...]]:
        """Cross-sections at relative stations ``x_rel = X - x_g`` (m), as manifold3d gives
        them: one tuple of ``(k, 2)`` contours per station (outer ones counter-clockwise),
        in the cutter's coordinates: divide by :attr:`scale` and add :attr:`origin` (and
        ``Z_g``) for earth coordinates in m."""
        x_rel = np.asarray(x_rel, dtype=np.float64)
        if len(x_rel) == 0:
            return []
        slicer = self._slicer(*self._reach(x_rel))
        ox, k = self._offset[2], self._scale
        return [tuple(slicer.slice(float((xi - ox) * k)).to_polygons()) for xi in x_rel]

    def _reach(self, x_rel: np.ndarray) -> tuple[float, float]:
        """The body's ``x`` range (m) that the planes at ``x_rel`` cross."""
        c, s = np.cos(self.pitch), np.sin(self.pitch)
        bounds = self._hull.bounds
        rz = bounds[:, 2] - self.cg[2]
        # a plane X = x_rel holds the body points with r_x c - r_z s = x_rel
        rx = (np.array([x_rel.min(), x_rel.max()])[:, None] + rz[None, :] * s) / c
        return float(self.cg[0] + rx.min()), float(self.cg[0] + rx.max())

    def _slicer(self, lo: float, hi: float):
        """The cutter turned to this pitch, through a region of the hull holding the faces
        between body ``x = lo`` and ``hi``.

        The whole hull while it has been cut at one pitch only: a region costs more to make
        than turning the whole once, and pays off only over several pitches.
        """
        body: Any
        if len(self._hull.__dict__.get("_frames", ())) > 1:
            key, body = region(self._hull, lo, hi)
        else:
            key, body = None, self._hull.manifold
        slicer = self._slicers.get(key)
        if slicer is None:
            slicer = body.transform(self._matrix)
            self._slicers[key] = slicer
            while len(self._slicers) > REGION_CACHE:
                self._slicers.popitem(last=False)
        else:
            self._slicers.move_to_end(key)
        return slicer

    @property
    def scale(self) -> float:
        """The cutter's coordinates are metres times this (the body brought to unit size)."""
        return self._scale

    @property
    def origin(self) -> tuple[float, float]:
        """``(Y, Z - Z_g)`` of the origin of :meth:`cut`'s contours, m."""
        return float(self._offset[0]), float(self._offset[1])

    def body_to_earth(self, v: np.ndarray, z_cg: float) -> np.ndarray:
        """Earth coordinates ``(X, Y, Z)`` (m) of body points ``v`` (n, 3)."""
        c, s = np.cos(self.pitch), np.sin(self.pitch)
        r = np.asarray(v, dtype=np.float64) - self.cg
        X = self.cg[0] + r[:, 0] * c - r[:, 2] * s
        Z = z_cg + r[:, 0] * s + r[:, 2] * c
        return np.stack([X, r[:, 1] + self.cg[1], Z], axis=1)


#: How many pitches' frames a hull keeps.
FRAME_CACHE = 4
#: Fixed stations cut beyond the ones asked for, on either side (see Frame.fixed_outline).
FIXED_PAD = 2
#: Hulls with fewer faces are always cut whole (turning them is cheap).
REGION_MIN_FACES = 50_000
#: A region longer than this share of the body is not worth trimming: the whole is cut.
REGION_MAX_SHARE = 0.6
#: Room to grow given to a new region on either side, as a share of the range asked for.
REGION_ROOM = 0.25
#: How many regions a hull keeps (and turned copies of them a frame keeps).
REGION_CACHE = 2


def frame(hull, pitch: float) -> Frame:
    """The :class:`Frame` of a hull at a pitch (rad), kept on the hull for reuse."""
    pitch = float(pitch)
    cache: OrderedDict = hull.__dict__.setdefault("_frames", OrderedDict())
    if pitch in cache:
        cache.move_to_end(pitch)
        return cache[pitch]
    fr = _frame(hull, pitch)
    cache[pitch] = fr
    while len(cache) > FRAME_CACHE:
        cache.popitem(last=False)
    return fr


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
    regions: OrderedDict = hull.__dict__.setdefault("_regions", OrderedDict())
    for key in regions:
        if key[0] < need_lo and need_hi < key[1]:
            regions.move_to_end(key)
            return key, regions[key]
    room = max(REGION_ROOM * (hi - lo), 0.02 * length)
    a, b = need_lo - room, need_hi + room
    if b - a > REGION_MAX_SHARE * length:
        return None, hull.manifold
    body = hull.manifold
    if a > xa:
        body = body.trim_by_plane((1.0, 0.0, 0.0), a)
    if b < xb:
        body = body.trim_by_plane((-1.0, 0.0, 0.0), -b)
    regions[(a, b)] = body
    while len(regions) > REGION_CACHE:
        regions.popitem(last=False)
    return (a, b), body


def _face_reach(hull) -> float:
    """The longest extent of a face along ``x``, m (kept on the hull)."""
    reach = hull.__dict__.get("_face_reach")
    if reach is None:
        x = hull.vertices[:, 0][hull.faces]
        reach = float((x.max(axis=1) - x.min(axis=1)).max())
        hull.__dict__["_face_reach"] = reach
    return reach


def _frame(hull, pitch: float) -> Frame:
    g = np.asarray(hull.cg, dtype=np.float64)
    c, s = np.cos(pitch), np.sin(pitch)
    # side view: the silhouette edges turned by the pitch, in (X, Z) relative to the cg;
    # the lowest and highest points at any pitch are on them
    a, b = silhouette_edges(hull)
    ta, tb = _turn(a - g, c, s), _turn(b - g, c, s)
    lowest = float(min(ta[:, 1].min(), tb[:, 1].min()))
    highest = float(max(ta[:, 1].max(), tb[:, 1].max()))
    # centre the cutter's coordinates on the body (manifold3d's sections are single
    # precision): the bounding-box centre, in the pitched frame relative to the cg
    box = hull.bounds.mean(axis=0) - g
    ox = box[0] * c - box[2] * s
    oz = box[0] * s + box[2] * c
    oy = box[1] + g[1]
    # rows map a body point to (Y, Z, X) relative to that centre; manifold3d cuts at Z = X.
    # Scaled to a unit size too: manifold3d rounds its sections to a fixed grid (Clipper2,
    # 1e-8), so a tiny body would be cut into nothing and a huge one coarsely
    scale = 1.0 / hull.size
    cut_matrix = scale * np.array(
        [
            [0.0, 1.0, 0.0, -oy],
            [s, 0.0, c, -(s * g[0] + c * g[2]) - oz],
            [c, 0.0, -s, -(c * g[0] - s * g[2]) - ox],
        ]
    )
    keel = _lower_envelope(ta, tb)
    return Frame(pitch, g, lowest, highest, keel, hull, cut_matrix, np.array([oy, oz, ox]), scale)


def _turn(r: np.ndarray, c: float, s: float) -> np.ndarray:
    """(X, Z) of body offsets ``r`` (n, 3) turned nose up by the pitch (cos, sin)."""
    return np.stack([r[:, 0] * c - r[:, 2] * s, r[:, 0] * s + r[:, 2] * c], axis=1)


def silhouette_edges(hull) -> tuple[np.ndarray, np.ndarray]:
    """The edges of the body's outline seen from the side, as end points (e, 3) in m.

    An edge is on the outline seen along ``y`` when one of its two faces faces port and the
    other starboard (or either is edge-on). Turning the body about ``y`` (its pitch) does not
    change which faces face which way, so these edges serve every pitch: the keel line at
    any pitch is the lower envelope of their side views, and the body's lowest and highest
    points are among their ends. Kept on the hull.
    """
    cached = hull.__dict__.get("_silhouette")
    if cached is not None:
        return cached
    v, f = hull.vertices, hull.faces
    ny = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])[:, 1]
    directed = f[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    lo, hi = directed.min(axis=1), directed.max(axis=1)
    order = np.argsort(lo.astype(np.int64) * len(v) + hi)
    face = np.repeat(np.arange(len(f)), 3)[order]
    # a closed manifold uses each edge twice: the two uses are neighbours once sorted
    side = (np.sign(ny[face[0::2]]) * np.sign(ny[face[1::2]])) <= 0
    ends = directed[order[0::2][side]]
    out = (v[ends[:, 0]], v[ends[:, 1]])
    hull.__dict__["_silhouette"] = out
    return out


def _lower_envelope(a: np.ndarray, b: np.ndarray) -> KeelLine:
    """The lower envelope ``z(x)`` of segments from ``a`` to ``b`` ((e, 2) arrays of x, z).

    Evaluated exactly at every end point; where two segments cross between end points the
    envelope is refined at the middle of that interval (the crossing point itself is not
    found, so there the line may lie a little high).
    """
    xs = np.unique(np.concatenate([a[:, 0], b[:, 0]]))
    z = _envelope_at(a, b, xs)
    mid = 0.5 * (xs[1:] + xs[:-1])
    zm = _envelope_at(a, b, mid)
    lower = zm < 0.5 * (z[1:] + z[:-1]) - 1e-12 * (1.0 + np.abs(zm))
    # no segment over an interval: a gap between parts one behind the other, where the
    # line is infinitely high (not a straight line from one part's keel to the next's)
    lower |= np.isinf(zm)
    if lower.any():
        xs = np.concatenate([xs, mid[lower]])
        z = np.concatenate([z, zm[lower]])
        order = np.argsort(xs)
        xs, z = xs[order], z[order]
    return KeelLine(xs, z)


def _envelope_at(a: np.ndarray, b: np.ndarray, xs: np.ndarray) -> np.ndarray:
    """Lowest height of the segments over each of the sorted abscissae ``xs``."""
    lo = np.minimum(a[:, 0], b[:, 0])
    hi = np.maximum(a[:, 0], b[:, 0])
    i0 = np.searchsorted(xs, lo, side="left")
    i1 = np.searchsorted(xs, hi, side="right")  # abscissae i0 .. i1-1 lie on the segment
    count = i1 - i0
    seg = np.repeat(np.arange(len(a)), count)
    idx = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count) + i0[seg]
    xa, za, xb, zb = a[seg, 0], a[seg, 1], b[seg, 0], b[seg, 1]
    x = xs[idx]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(xb != xa, (x - xa) / (xb - xa), 0.0)
    z_on = np.where(xb != xa, za + t * (zb - za), np.minimum(za, zb))
    z = np.full(len(xs), np.inf)
    np.minimum.at(z, idx, z_on)
    return z
