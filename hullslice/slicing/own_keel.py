"""The keel lines of a body's separate pieces.

The keel line is the lowest point of the whole body at each station, one line for the
body. On a body of separate pieces (a catamaran's floats, a seaplane's floats, an
aircraft whose nacelles are shells of their own) the line along a piece beside a lower one
is the lower one's, and near where two pieces' keels cross in the side view it turns from
one to the other. Each piece then gets a keel line of its own (the lower envelope of its
own silhouette edges, as the body's), and each wetted entry takes its slope, curvature and
height from its piece's line, measured as the body's are (the chord over the slice, the
curvature over the same window). An entry's piece is the one whose ``y`` extent holds its
keel and whose line at the slice is nearest its keel's height.

A body of one piece (one connected surface, however many parts its sections show, such as
a whole aircraft meshed as one surface) keeps the body's one line.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..caching import Entry, Once
from ..geometry import Frame, keel_line_of, silhouette_ends
from ..kernel.keel import KeelLine
from ..parts import face_labels
from ..reduce import row_max, row_min

__all__ = ["Pieces", "own_keels", "pieces", "widest_beam"]


@dataclass(frozen=True)
class Pieces:
    """A body's connected pieces.

    Attributes
    ----------
    n : int
        Their number.
    edges : list of (k,) int
        Each piece's silhouette edges (indices into
        :func:`~hullslice.geometry.silhouette_edges`); none for a body of one piece.
    y_min, y_max : (n,) float
        Each piece's lateral extent, m (body frame, as the sections' ``y``).
    outlined : (n,) bool
        The pieces with silhouette edges (a piece's keel line is made of them).
    """

    n: int
    edges: list[np.ndarray]
    y_min: np.ndarray
    y_max: np.ndarray
    outlined: np.ndarray


#: A body's pieces (kept on the hull).
PIECES: Entry[Once[Pieces]] = Entry("pieces", Once, geometry=True)
#: A frame's keel lines of the pieces, by piece (made when an entry may be the piece's).
PIECE_LINES: Entry[dict[int, KeelLine]] = Entry("pieces' keel lines", dict)


def pieces(hull) -> Pieces:
    """The body's connected pieces (faces sharing a vertex; see
    :func:`~hullslice.parts.face_labels`). Kept on the hull."""

    def make() -> Pieces:
        v, f = hull.vertices, hull.faces
        n, labels = face_labels(v, f)
        if n < 2:  # a body of one piece keeps the body's line
            y = v[:, 1][f]
            return Pieces(n, [], np.array([y.min()]), np.array([y.max()]), np.zeros(n, bool))
        vertex = np.full(len(v), -1)
        vertex[f.ravel()] = np.repeat(labels, 3)
        y = v[:, 1][f]
        y_min, y_max = np.full(n, np.inf), np.full(n, -np.inf)
        np.minimum.at(y_min, labels, row_min(y))
        np.maximum.at(y_max, labels, row_max(y))
        label = vertex[silhouette_ends(hull)[:, 0]]
        edges = [np.flatnonzero(label == k) for k in range(n)]
        outlined = np.array([len(e) > 0 for e in edges])
        return Pieces(n, edges, y_min, y_max, outlined)

    return hull.cache[PIECES].get(make)


def widest_beam(hull) -> float:
    """The beam (``y`` extent, m) of the body's widest piece: the body's own for a body of
    one piece, a float's for a catamaran of separate floats."""
    parts = pieces(hull)
    return float((parts.y_max - parts.y_min).max()) if parts.n else 0.0


def own_keels(
    hull,
    fr: Frame,
    props: Mapping[str, np.ndarray],
    *,
    x: np.ndarray,
    chord: np.ndarray,
    window: np.ndarray,
    level: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None:
    """Each wetted entry's keel from its own piece's line, on a body of several pieces.

    Parameters
    ----------
    hull, fr : Hull, Frame
        The body and its frame at the pitch.
    props : mapping of (n,) arrays
        The entries' ``station`` (their slice), ``penetration`` and ``y_keel`` (m).
    x, chord, window : (s,) float
        Each slice's station relative to the centre of gravity, the width of its keel's
        chord and of its curvature's window, m.
    level : float
        The water's height above the centre of gravity in the pitched frame, m.

    Returns
    -------
    (entry, slope, curvature, height) or None
        The wetted entries, and their keel's slope ``dz/dx`` (1), curvature (1/m) and
        height relative to the centre of gravity (m); None on a body of one piece.
    """
    parts = pieces(hull)
    if parts.n < 2:
        return None
    p = props["penetration"]
    entry = np.flatnonzero(p > 0.0)
    if not len(entry):
        return None
    s = props["station"][entry]
    xs, y, z = x[s], props["y_keel"][entry], level - p[entry]
    # each entry's piece: its y extent holds the keel, its line is nearest the keel there
    holds = (parts.y_min[:, None] <= y) & (y <= parts.y_max[:, None])
    candidates = np.flatnonzero(holds.any(axis=1) & parts.outlined)
    if not len(candidates):
        return None
    lines = fr.cache[PIECE_LINES]
    for k in candidates.tolist():
        if k not in lines:
            lines.setdefault(k, keel_line_of(hull, fr.pitch, parts.edges[k], k))
    heights = np.stack([lines[k].height(xs) for k in candidates.tolist()])
    with np.errstate(invalid="ignore"):
        gap = np.abs(heights - z)
    miss = np.where(holds[candidates] & np.isfinite(gap), gap, np.inf)
    pick = np.argmin(miss, axis=0)
    found = np.isfinite(miss[pick, np.arange(len(entry))])
    height = heights[pick, np.arange(len(entry))][found]
    entry, pick, s = entry[found], pick[found], s[found]
    slope, curvature = np.empty(len(entry)), np.empty(len(entry))
    for j in np.unique(pick):
        mine = pick == j
        line = lines[int(candidates[j])]
        slope[mine] = line.mean_slope(x[s[mine]], chord[s[mine]])
        curvature[mine] = line.mean_curvature(x[s[mine]], window[s[mine]])
    return entry, slope, curvature, height
