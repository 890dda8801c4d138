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

from .outline_loops import K_HI, K_LO, MAG

__all__ = ["lower_side_loops", "turned_outline_loops"]


def turned_outline_loops(outline, gx, gz, c, s):
    """The body's side outline (``outline``, (2, m): the ``x`` and ``z`` of
    :func:`hullslice.kernel.envelope.side_outline`'s points, counter-clockwise) turned nose
    up by a pitch (``c``, ``s``: its cosine and sine) about ``(gx, gz)`` as
    :func:`~hullslice.keel_loops.side_ends_loops` turns the edges' ends. Returns ``(ok, x,
    z, il, ir, low, high)``: the turned points, the leftmost and the rightmost (the first
    of the lowest abscissa, and of the highest), and the lowest and highest heights (the
    first of each, a zero's sign its); ``ok`` False where the leftmost or rightmost point
    is not one point (a face vertical in the side view), a point is not finite (nothing
    else is meaningful then), or there are fewer than three. The extremes are found by
    their order keys (:data:`hullslice.outline_loops.MAG`), in passes the compiler turns
    into vector instructions, and their points by the doubles' own comparisons."""
    m = outline.shape[1]
    xt, zt = np.empty(m), np.empty(m)
    ox, oz = outline[0], outline[1]
    finite = True
    for i in range(m):  # the turn: no branch
        rx, rz = ox[i] - gx, oz[i] - gz
        x = rx * c - rz * s
        v = rx * s + rz * c
        xt[i] = x
        zt[i] = v
        finite = finite & (abs(x) < math.inf) & (abs(v) < math.inf)
    if m == 0 or not finite:
        return False, xt, zt, 0, 0, 0.0, 0.0
    bx, bz = xt.view(np.int64), zt.view(np.int64)
    x_lo, x_hi, z_lo, z_hi = K_HI, K_LO, K_HI, K_LO
    for i in range(m):
        kx = bx[i] ^ ((bx[i] >> 63) & MAG)
        kz = bz[i] ^ ((bz[i] >> 63) & MAG)
        x_lo = min(kx, x_lo)
        x_hi = max(kx, x_hi)
        z_lo = min(kz, z_lo)
        z_hi = max(kz, z_hi)
    ext = np.array([x_lo, x_hi, z_lo, z_hi])
    # the keys' doubles (the map is its own inverse; outline_loops.unkey_loops's, written
    # here: a helper from another file would leave this file's compiled cache stale)
    ext ^= (ext >> 63) & MAG
    value = ext.view(np.float64)
    left, right = value[0], value[1]
    n_l = n_r = 0
    for i in range(m):  # the doubles equal to the extremes (a zero either sign)
        n_l += xt[i] == left
        n_r += xt[i] == right
    il = 0
    while xt[il] != left:
        il += 1
    ir = 0
    while xt[ir] != right:
        ir += 1
    low, high = value[2], value[3]
    j = 0
    while zt[j] != low:  # the first of the lowest: its zero's sign
        j += 1
    low = zt[j]
    j = 0
    while zt[j] != high:
        j += 1
    high = zt[j]
    return m >= 3 and n_l == 1 and n_r == 1, xt, zt, il, ir, low, high


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
    n1 = min(k + 1, m - il)  # from the leftmost to the outline's end, then from its start
    x_out[:n1], z_out[:n1] = xt[il : il + n1], zt[il : il + n1]
    x_out[n1:], z_out[n1:] = xt[: k + 1 - n1], zt[: k + 1 - n1]
    forward = True
    a, b = x_out[1:], x_out[:-1]
    for t in range(k):  # no branch
        forward = forward & (a[t] > b[t])
    if not forward:
        return False, none, none, 0.0, 0.0
    return True, x_out, z_out, low, high
