"""The arrays the fused evaluation's compiled loops read (:mod:`hullslice.forces.fused`):
a frame's keel line, a kept cut's waterline table, and what the one-call stage reads of a
hull. Built once per frame, table or hull and kept by the fused evaluation."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from .. import planecut_loops
from ..constants import TOL
from ..geometry import CUTTER_SIZE, MERGE, side_outline_points, silhouette_edges
from ..kernel.keel import END_FACE_SLOPE, STEEP_SLOPE
from ..planecut import plane_index

__all__ = ["keel_arrays", "stage_arrays", "table_arrays"]


def stage_arrays(hull, tol: float, n: int) -> tuple:
    """What :func:`~hullslice.planecut_loops.stage_loops` reads of a hull, in its order:
    all of its arguments up to ``reach_z`` but the ends' order (the fifth), the scratch
    array (the twenty-second), the ranges' guesses (the twenty-third) and the outline's
    hint (the twenty-fourth), which are each thread's own."""
    a, b = silhouette_edges(hull)
    index = plane_index(hull)
    g = np.asarray(hull.cg, dtype=np.float64)
    return (
        a, b, *side_outline_points(hull), g,
        np.ascontiguousarray(hull.bounds, dtype=np.float64), CUTTER_SIZE / hull.size,
        TOL.keel_merge * hull.size, END_FACE_SLOPE, STEEP_SLOPE, index.key, index.bin_start,
        index.bin_zlo, index.bin_zhi, index.bin_reach, index.margin, index.key_span,
        index.key_x0, index.corners, index.ends, planecut_loops.K_OUT, planecut_loops.K_IN,
        MERGE * CUTTER_SIZE, tol, n, index.xmin, *index.reach(g),
    )  # fmt: skip


def _padded(rows, width: int, fill: float = np.nan) -> np.ndarray:
    out = np.full((len(rows), max(width, 1)), fill)
    for i, row in enumerate(rows):
        out[i, : len(row)] = row
    return out


def keel_arrays(fr, pack: Callable | None = None) -> dict[str, Any]:
    """The loops' arrays of a frame's keel line; by ``pack``
    (:func:`~hullslice.keel_loops.keel_arrays_loops`, compiled) where given."""
    keel = fr.keel
    runs = keel._runs
    k = len(keel.x)
    if pack is not None:
        chords, none = runs.chords, np.empty(0)
        h, lo, hi = (none, none, none) if chords is None else chords[1:]
        arrays = pack(keel.x, keel.z, runs.steep, runs.mid, runs.cont, runs.bend, runs.starts,
                      runs.offsets, h, lo, hi)  # fmt: skip
        return {"keel": arrays[0], "runs": arrays[1], "chords": arrays[2],
                "has_chords": 0.0 if chords is None else 1.0}  # fmt: skip
    steep = np.asarray(runs.steep, dtype=np.float64)[: k - 1]
    chords = runs.chords
    f = max(len(runs.mid), len(runs.offsets))
    low_from_first = np.minimum.accumulate(keel.z)
    low_from_last = np.minimum.accumulate(keel.z[::-1])[::-1]
    return {
        "keel": _padded([keel.x, keel.z, steep, low_from_first, low_from_last], k, 0.0),
        "runs": _padded([runs.mid, runs.cont, runs.bend, runs.starts, runs.offsets], f),
        "has_chords": 0.0 if chords is None else 1.0,
        "chords": (
            np.zeros((3, k)) if chords is None else _padded([chords[1], chords[2], chords[3]], k)
        ),
    }


def table_arrays(table) -> dict[str, Any]:
    """The loops' arrays of a kept cut's waterline table and its outline's stations."""
    t = table
    ints = [t.bp_key, t.bp_start, t.v_start, t.e_start]
    width = max(len(a) for a in ints)
    tkey = np.zeros((4, width), dtype=np.int64)
    for i, a in enumerate(ints):
        tkey[i, : len(a)] = a
    e_v = np.repeat(np.arange(len(t.exact)), np.diff(t.e_start))  # each entry's interval
    columns = [t.wet.astype(np.float64), t.keel, t.intercept, t.slope, t.const]
    columns.append(t.exact[e_v].astype(np.float64))
    o = t.outline
    return {
        "tkey": tkey,
        "heights": np.ascontiguousarray(t.heights, dtype=np.float64),
        "tvals": np.ascontiguousarray(np.column_stack(columns)),
        "stations": np.ascontiguousarray(np.stack([o.zmin, o.z_chine, o.area])),
        "n_cut": o.n_stations,
    }
