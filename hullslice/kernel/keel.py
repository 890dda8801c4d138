"""The keel line: the lower edge of a body's side view at one pitch, ``Z_k(X)``, as a polyline.

Built from the side views of the body's silhouette edges (their lower envelope, exact at
every end point) and evaluated with a continuous slope and a curvature averaged over a
slice. Pure numpy.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["END_FACE_SLOPE", "KeelLine", "lower_envelope"]

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
    #: Middles and slopes of the bottom's facets (see :meth:`at`).
    _facets: tuple[np.ndarray, np.ndarray] = field(init=False, repr=False)
    #: The bottom's extent ``(x0, x1)`` and the end faces' facet middles and slopes.
    _end_faces: tuple[tuple[float, float], tuple] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        facets, ends = _facets_of(self.x, self.z)
        object.__setattr__(self, "_facets", facets)  # frozen: set once here
        object.__setattr__(self, "_end_faces", ends)

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

    def below(self, level: float) -> tuple[float, float] | None:
        """The ``x`` range where the keel is below ``level`` (relative), or None."""
        x, z = self.x, self.z
        under = z < level
        first = int(under.argmax())
        if not under[first]:
            return None
        last = len(z) - 1 - int(under[::-1].argmax())

        def crossing(i: int) -> float:  # where the segment i, i + 1 meets the level
            if not np.isfinite(z[i]):  # a gap between parts (z = inf) before point i + 1
                return float(x[i + 1])
            if not np.isfinite(z[i + 1]):  # a gap after point i
                return float(x[i])
            t = (level - z[i]) / (z[i + 1] - z[i])
            return float(x[i] + t * (x[i + 1] - x[i]))

        # the first and last points under the level, or where the line goes under it
        lo = crossing(first - 1) if first > 0 else float(x[0])
        hi = crossing(last) if last < len(z) - 1 else float(x[-1])
        return min(lo, float(x[first])), max(hi, float(x[last]))


def _facets_of(x: np.ndarray, z: np.ndarray) -> tuple[tuple, tuple]:
    """Middles and slopes of the bottom's facets: the keel line without its end faces
    (its first or last facets steeper than :data:`END_FACE_SLOPE`: a transom, a blunt
    bow or tail), whose slopes do not blend into the bottom's; and the bottom's extent
    ``(x0, x1)`` with the end faces' facet middles and slopes before and after it."""
    mid, slopes = 0.5 * (x[1:] + x[:-1]), np.diff(z) / np.diff(x)
    idx = np.flatnonzero(np.isfinite(slopes))  # not the facets into a gap between parts
    if not len(idx):
        empty = (np.empty(0), np.empty(0))
        return (mid[:1], np.zeros(1)), ((float(x[0]), float(x[-1])), (empty, empty))
    mid, slopes = mid[idx], slopes[idx]
    steep = np.abs(slopes) > END_FACE_SLOPE
    lo, hi = 0, len(slopes)
    while lo < hi - 1 and steep[lo]:
        lo += 1
    while hi - 1 > lo and steep[hi - 1]:
        hi -= 1
    facets = (mid[lo:hi], slopes[lo:hi])
    ends = (
        (float(x[idx[lo]]), float(x[idx[hi - 1] + 1])),
        ((mid[:lo], slopes[:lo]), (mid[hi:], slopes[hi:])),
    )
    return facets, ends


def lower_envelope(a: np.ndarray, b: np.ndarray) -> KeelLine:
    """The lower envelope ``z(x)`` of segments from ``a`` to ``b`` ((e, 2) arrays of x, z).

    Evaluated exactly at every end point; where two segments cross between end points the
    envelope is refined at the middle of that interval (the crossing point itself is not
    found, so there the line may lie a little high).
    """
    xs = np.concatenate([a[:, 0], b[:, 0]])
    xs.sort()
    if len(xs) > 1:  # np.unique's values, without its bookkeeping (NaNs, sorted last, as one)
        new = xs[1:] != xs[:-1]
        if np.isnan(xs[-1]):
            new &= ~np.isnan(xs[:-1])
        xs = xs[np.concatenate([[True], new])]
    segments = _Segments(a, b)
    z = segments.lowest(xs)
    mid = 0.5 * (xs[1:] + xs[:-1])
    zm = segments.lowest(mid)
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


class _Segments:
    """Segments from ``a`` to ``b`` ((e, 2) arrays of x, z), their columns apart."""

    def __init__(self, a: np.ndarray, b: np.ndarray) -> None:
        self.xa, self.za = np.ascontiguousarray(a[:, 0]), np.ascontiguousarray(a[:, 1])
        self.xb, self.zb = np.ascontiguousarray(b[:, 0]), np.ascontiguousarray(b[:, 1])
        self.lo = np.minimum(self.xa, self.xb)
        self.hi = np.maximum(self.xa, self.xb)
        self.dx = self.xb - self.xa
        self.dz = self.zb - self.za
        self.vertical = self.dx == 0.0
        self.z_vertical = np.minimum(self.za, self.zb)

    def lowest(self, xs: np.ndarray) -> np.ndarray:
        """Lowest height of the segments over each of the sorted abscissae ``xs``."""
        i0 = np.searchsorted(xs, self.lo, side="left")
        i1 = np.searchsorted(xs, self.hi, side="right")  # abscissae i0 .. i1-1 on a segment
        count = np.maximum(i1 - i0, 0)
        total = int(count.sum())
        z = np.full(len(xs), np.inf)
        if total == 0:
            return z
        seg = np.repeat(np.arange(len(count)), count)
        # each pair's abscissa: i0 of its segment plus its rank within the segment
        step = np.ones(total, dtype=np.int64)
        starts = np.cumsum(count) - count
        has = count > 0
        step[starts[has]] = i0[has] - np.concatenate([[0], (i0 + count - 1)[has][:-1]])
        idx = np.cumsum(step)
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (xs[idx] - self.xa[seg]) / self.dx[seg]
        z_on = self.za[seg] + t * self.dz[seg]
        vertical = self.vertical[seg]
        if vertical.any():
            z_on[vertical] = self.z_vertical[seg[vertical]]
        np.minimum.at(z, idx, z_on)
        return z
