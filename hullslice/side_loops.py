"""The keel line read off the body's side outline, by loops written for a compiler:
numba's, when installed (compiled by :func:`hullslice.planecut_loops.compiled`, which
holds them by name).

Where the silhouette edges' side views make one polygon (the body's side outline,
:func:`hullslice.kernel.envelope.side_outline`), the keel line at a pitch is its lower
side where that side runs forward (:func:`lower_side_loops`): its points are the line's
break points, instead of the edges' lowest heights walked for over every end abscissa
(:func:`hullslice.keel_loops.lowest_walk_loops`). The same numbers as numpy's
:func:`hullslice.kernel.envelope.lower_envelope` with its ``side``.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["lower_side_loops", "turned_outline_loops"]


def turned_outline_loops(outline, gx, gz, c, s):
    """The body's side outline (``outline``, (2, m): the ``x`` and ``z`` of
    :func:`hullslice.kernel.envelope.side_outline`'s points, counter-clockwise) turned nose
    up by a pitch (``c``, ``s``: its cosine and sine) about ``(gx, gz)`` as
    :func:`~hullslice.keel_loops.side_ends_loops` turns the edges' ends. Returns ``(ok, x,
    z, il, ir, low, high)``: the turned points, the leftmost and the rightmost, and the
    lowest and highest heights; ``ok`` False where the leftmost or rightmost point is not
    one point (a face vertical in the side view), a point is not finite, or there are
    fewer than three."""
    m = outline.shape[1]
    xt, zt = np.empty(m), np.empty(m)
    il = ir = 0
    ties_l = ties_r = 0
    low = high = 0.0
    for i in range(m):
        rx, rz = outline[0, i] - gx, outline[1, i] - gz
        x = rx * c - rz * s
        v = rx * s + rz * c
        if not (math.isfinite(x) and math.isfinite(v)):
            return False, xt, zt, 0, 0, 0.0, 0.0
        xt[i] = x
        zt[i] = v
        if i == 0:
            low = high = v
            continue
        low = low if low <= v else v
        high = high if high >= v else v
        if x < xt[il]:
            il, ties_l = i, 0
        elif x == xt[il]:
            ties_l += 1
        if x > xt[ir]:
            ir, ties_r = i, 0
        elif x == xt[ir]:
            ties_r += 1
    return m >= 3 and not (ties_l or ties_r), xt, zt, il, ir, low, high


def lower_side_loops(outline, gx, gz, c, s):
    """The lower side of the body's side outline turned by a pitch
    (:func:`turned_outline_loops`, the same arguments): its points from the leftmost to
    the rightmost, as :func:`hullslice.kernel.envelope.lower_side`, and the outline's
    lowest and highest heights. Returns ``(ok, x, z, low, high)``; ``ok`` False where that
    side does not run forward all the way (a face leaning over an end: the envelope jumps
    there) or the turned outline is not ``ok``."""
    none = np.empty(0)
    ok, xt, zt, il, ir, low, high = turned_outline_loops(outline, gx, gz, c, s)
    if not ok:
        return False, none, none, 0.0, 0.0
    m = len(xt)
    k = ir - il if ir >= il else ir - il + m
    x_out, z_out = np.empty(k + 1), np.empty(k + 1)
    j = il
    for t in range(k + 1):
        x_out[t] = xt[j]
        z_out[t] = zt[j]
        if t > 0 and not x_out[t] > x_out[t - 1]:
            return False, none, none, 0.0, 0.0
        j = j + 1 if j + 1 < m else 0
    return True, x_out, z_out, low, high
