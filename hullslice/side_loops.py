"""The keel line read off the body's side outline, by loops written for a compiler:
numba's, when installed (compiled by :func:`hullslice.planecut_loops.compiled`, which
holds them by name).

Where the silhouette edges' side views make one polygon (the body's side outline,
:func:`hullslice.kernel.envelope.side_outline`), the keel line at a pitch is its lower
side where that side runs forward: the lowest heights over the silhouette edges' end
abscissae are read off it (:func:`chain_at_loops`) instead of walked for among the edges
(:func:`hullslice.keel_loops.lowest_walk_loops`), and where the outline's points are all
the edges' ends, the abscissae too (:func:`outline_keel_loops`). The same numbers as
numpy's :func:`hullslice.kernel.envelope.lower_envelope` with its ``side``.
"""

from __future__ import annotations

import math

import numpy as np

from .keel_loops import SORT_MOVES

__all__ = ["chain_at_loops", "lower_side_loops", "outline_keel_loops", "turned_outline_loops"]


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
    the rightmost, as :func:`hullslice.kernel.envelope.lower_side`. Returns ``(ok, x,
    z)``; ``ok`` False where that side does not run forward all the way (a face leaning
    over an end: the envelope jumps there) or the turned outline is not ``ok``."""
    none = np.empty(0)
    ok, xt, zt, il, ir, _, _ = turned_outline_loops(outline, gx, gz, c, s)
    if not ok:
        return False, none, none
    m = len(xt)
    k = ir - il if ir >= il else ir - il + m
    x_out, z_out = np.empty(k + 1), np.empty(k + 1)
    j = il
    for t in range(k + 1):
        x_out[t] = xt[j]
        z_out[t] = zt[j]
        if t > 0 and not x_out[t] > x_out[t - 1]:
            return False, none, none
        j = j + 1 if j + 1 < m else 0
    return True, x_out, z_out


def outline_keel_loops(outline, gx, gz, c, s):
    """The keel line's abscissae and lowest heights at a pitch (``c``, ``s``) read off the
    body's side ``outline`` alone (:func:`turned_outline_loops`, the same arguments), where
    its points are all the silhouette edges' ends
    (:func:`hullslice.geometry.side_outline_points`' ``whole``): the abscissae of its lower
    side (from the leftmost point to the rightmost, running forward) and of its upper side
    (sorted from the order it runs back in, as
    :func:`~hullslice.keel_loops.sorted_loops` sorts: a few moves a point) merged, each
    once (the same as :func:`~hullslice.keel_loops.side_ends_loops`' ``xs``), the heights
    there as :func:`chain_at_loops` reads them off the lower side, and the points' lowest
    and highest heights (the ends'). Returns ``(status, xs, z, low, high)``: status 0, or
    1 where the turned outline is not ``ok`` or its lower side does not run forward all
    the way (:func:`lower_side_loops` does not serve either), 2 where the upper side is far
    from running back (more than :data:`SORT_MOVES` moves a point): then the ends are
    turned one by one."""
    none = np.empty(0)
    ok, xt, zt, il, ir, low, high = turned_outline_loops(outline, gx, gz, c, s)
    if not ok:
        return 1, none, none, 0.0, 0.0
    m = len(xt)
    k = ir - il if ir >= il else ir - il + m  # the lower side's intervals
    j = il
    for _ in range(k):  # the lower side runs forward
        n = j + 1 if j + 1 < m else 0
        if not xt[n] > xt[j]:
            return 1, none, none, 0.0, 0.0
        j = n
    # the upper side's points between its ends, from the leftmost on (it runs back from
    # the rightmost), sorted by insertion
    nu = m - k - 1
    up = np.empty(nu)
    j = il
    moves = 0
    for t in range(nu):
        j = j - 1 if j > 0 else m - 1
        x = xt[j]
        h = t - 1
        while h >= 0 and up[h] > x:
            up[h + 1] = up[h]
            h -= 1
        up[h + 1] = x
        moves += t - 1 - h
        if moves > SORT_MOVES * nu:
            return 2, none, none, 0.0, 0.0
    xs, z = np.empty(m), np.empty(m)
    n_out = 0
    p = il  # the lower side's point
    q = 0  # the upper side's next abscissa
    for _ in range(k + 1):
        x_next = xt[p]
        while q < nu and up[q] < x_next:  # between p's and the one before: read off
            xq = up[q]
            if xs[n_out - 1] != xq:  # not level with the one before (il's is the least)
                b = p - 1 if p > 0 else m - 1
                xs[n_out] = xq
                z[n_out] = zt[b] + (xq - xt[b]) / (xt[p] - xt[b]) * (zt[p] - zt[b])
                n_out += 1
            q += 1
        while q < nu and up[q] == x_next:  # level with p: one abscissa
            q += 1
        xs[n_out] = x_next
        pn = p + 1 if p + 1 < m else 0
        # a point's own height, as chain_at_loops reads it off the segment it starts
        # (plus nothing, its sign of zero that sum's), the last one's as it is
        z[n_out] = zt[p] if p == ir else zt[p] + 0.0 * (zt[pn] - zt[p])
        n_out += 1
        p = pn
    return 0, xs[:n_out], z[:n_out], low, high


def chain_at_loops(cx, cz, x):
    """The heights of the lower side ``cx``, ``cz`` (:func:`lower_side_loops`) at the
    sorted abscissae ``x``, all within its ends, as
    :func:`hullslice.kernel.envelope.chain_at`: a point's own height at its abscissa,
    between two points the walk's arithmetic (``z0 + (x - x0) / dx * dz`` from the one
    behind)."""
    m = len(cx)
    out = np.empty(len(x))
    k = 0
    for i in range(len(x)):
        xi = x[i]
        while k + 2 < m and cx[k + 1] <= xi:
            k += 1
        if xi == cx[k + 1]:
            out[i] = cz[k + 1]
        else:
            out[i] = cz[k] + (xi - cx[k]) / (cx[k + 1] - cx[k]) * (cz[k + 1] - cz[k])
    return out
