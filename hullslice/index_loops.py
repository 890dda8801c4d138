"""The plane index's searches by loops, written for a compiler: numba's, when installed
(compiled by :func:`hullslice.planecut_loops.compiled`, which holds them by name).

:func:`range_loops` finds the candidate faces of stations at a pitch as
:meth:`hullslice.planecut.PlaneIndex.ranges` does with numpy: the same indices.
"""

from __future__ import annotations

import numpy as np

from .keel_loops import search_loops

__all__ = ["gallop_loops", "near_loops", "range_loops"]


def range_loops(
    key, bin_start, bin_zlo, bin_zhi, bin_reach, x_rel, gx, gz, c, s, margin, span, x0, guess, g0,
):  # fmt: skip
    """:meth:`hullslice.planecut.PlaneIndex.ranges` by loops, with the same arithmetic:
    for each station ``i`` and bin ``b``, the body ``x`` of the plane at the bin's lowest
    and highest ``z`` widened by the bin's reach and ``margin``, as keys (``b * span`` plus
    the ``x`` from ``x0``, clipped to half the span), and the first of the bin's faces
    whose key is not below the lower key and the first whose key is above the upper one,
    searched among the bin's own faces ``bin_start[b] .. bin_start[b + 1] - 1`` (a bin's
    keys lie in its own band: the same indices as a search of all the keys). Returns
    ``(first, last)``, (stations, bins).

    ``guess`` ((k, bins, 2), or empty) holds indices found before (by an earlier stage)
    for the stations ``g0``, ``g0 + 1``, ... as ``guess[g0 + i]``: each search starts
    there (:func:`near_loops`; the same indices, found in a few probes when the pitch has
    hardly changed), and they are updated."""
    nb = len(bin_zlo)
    n_st = len(x_rel)
    first = np.empty((n_st, nb), dtype=np.int64)
    last = np.empty((n_st, nb), dtype=np.int64)
    half = 0.5 * span
    for b in range(nb):
        za = (bin_zlo[b] - gz) * s
        zb = (bin_zhi[b] - gz) * s
        base = b * span
        end = bin_start[b + 1]
        lo_was, hi_was = np.inf, np.inf
        for i in range(n_st):
            xa = gx + (x_rel[i] + za) / c
            xb = gx + (x_rel[i] + zb) / c
            lo = min(max(min(xa, xb) - bin_reach[b] - margin - x0, 0.0), half) + base
            hi = min(max(max(xa, xb) + margin - x0, 0.0), half) + base
            # from the station before where its bounds were no higher (every key before
            # its indices is below these bounds too): a short gallop, not a whole search
            at = first[i - 1, b] if lo_was <= lo else bin_start[b]
            k = g0 + i
            if k < len(guess):  # or near the indices an earlier stage found
                first[i, b] = near_loops(key, at, end, lo, False, guess[k, b, 0])
            else:
                first[i, b] = gallop_loops(key, at, end, lo, False)
            at = max(first[i, b], last[i - 1, b]) if hi_was <= hi else first[i, b]
            if k < len(guess):
                last[i, b] = near_loops(key, at, end, hi, True, guess[k, b, 1])
                guess[k, b, 0], guess[k, b, 1] = first[i, b], last[i, b]
            else:
                last[i, b] = gallop_loops(key, at, end, hi, True)
            lo_was, hi_was = lo, hi
    return first, last


def gallop_loops(a, lo, hi, v, right):
    """:func:`~hullslice.keel_loops.search_loops` of ``v`` in the sorted ``a[lo:hi]``
    (every value before ``lo`` below ``v``), probing from ``lo`` in steps of 1, 2, 4, ...
    before the binary search: the same index, found in a few probes near ``lo`` when it is
    near."""
    step = 1
    while True:
        probe = lo + step - 1
        if probe >= hi:
            break
        if a[probe] < v or (right and a[probe] == v):
            lo = probe + 1
            step *= 2
        else:
            hi = probe + 1  # the index is at most the probe
            break
    return search_loops(a, lo, hi, v, right)


def near_loops(a, lo, hi, v, right, g):
    """:func:`gallop_loops` of ``v`` in the sorted ``a[lo:hi]`` (every value before ``lo``
    below ``v``), probing from the guess ``g`` in steps of 1, 2, 4, ... down or up (a guess
    outside ``lo .. hi`` is not used): the same index."""
    if g <= lo or g > hi:
        return gallop_loops(a, lo, hi, v, right)
    x = a[g - 1]
    if x < v or (right and x == v):  # every value before g is below v: from g up
        return gallop_loops(a, g, hi, v, right)
    top, step = g - 1, 1  # the index is at most top
    while True:
        probe = top - step
        if probe < lo:
            return search_loops(a, lo, top, v, right)
        x = a[probe]
        if x < v or (right and x == v):
            return search_loops(a, probe + 1, top, v, right)
        top, step = probe, 2 * step
