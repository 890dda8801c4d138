"""Closing the shells of an open mesh one at a time, and what each one gives.

A **shell** here starts as a connected set of faces (faces that share a vertex). Each open
one is filled by MeshFix's hole filler as a whole (:func:`fill`). When that fails (the
result is still open, or encloses no volume) because parts that touch are welded to it (a
fin sheet sharing an edge of the skin, an antenna sharing a vertex), the shell is split
into the surfaces that hang together across edges of exactly two faces
(:func:`edge_shells`), each with its own copies of the shared vertices, and each is filled
on its own: a fuselage that closes alone is never dropped because a part welded to it does
not close. :func:`close_each` gives the outcome of every shell (:class:`Outcome`), which
``repair="close"`` assembles (:mod:`hullslice.repair.close`) and ``hullslice info`` lists.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from ..constants import TOL
from ..parts import face_labels, open_faces
from ..reduce import bounds, row_max, row_min
from ..topology import drop_unused_vertices, shell_volumes, unique_rows

__all__ = ["Outcome", "close_each", "edge_shells", "fill"]


@dataclass(frozen=True)
class Outcome:
    """One shell of an open mesh and what filling its holes gave.

    Attributes
    ----------
    vertices, faces : arrays
        The shell as it was (its own vertex copies).
    open_edges : int
        Its edges with a single face.
    closed_vertices, closed_faces : arrays or None
        The closed shell, turned outward (None when it did not close).
    holes : int
        Holes filled (0 for a shell closed before).
    flipped : bool
        It was wound inside out (negative volume once closed) and was turned outward.
    volume : float or None
        The volume it encloses once closed (mesh units cubed), None when it did not close.
    split : bool
        It is a part of a shell that did not close as a whole.
    """

    vertices: np.ndarray
    faces: np.ndarray
    open_edges: int
    closed_vertices: np.ndarray | None
    closed_faces: np.ndarray | None
    holes: int
    flipped: bool
    volume: float | None
    split: bool = False

    @property
    def closes(self) -> bool:
        return self.closed_faces is not None

    @property
    def extents(self) -> np.ndarray:
        """(3,) float: the shell's bounding box, mesh units."""
        used = self.vertices[np.unique(self.faces)]
        lo, hi = bounds(used)
        return hi - lo

    @property
    def area_added(self) -> float:
        if self.closed_vertices is None or self.closed_faces is None or self.holes == 0:
            return 0.0
        return _area(self.closed_vertices, self.closed_faces) - _area(self.vertices, self.faces)


def _area(v: np.ndarray, f: np.ndarray) -> float:
    cross = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    return float(np.linalg.norm(cross, axis=1).sum() / 2)


def _volume(v: np.ndarray, f: np.ndarray) -> float:
    if len(f) == 0:
        return 0.0
    return float(shell_volumes(v, f, np.zeros(len(f), dtype=np.int64), 1)[0])


def fill(pymeshfix, v: np.ndarray, f: np.ndarray, size: float):
    """The shell ``v, f`` with its holes filled by MeshFix: ``(vertices, faces, holes,
    volume)`` with the signed volume, or None when the result is open, not manifold, or
    encloses no volume (under ``1e3 * TOL.flat`` of the cube of ``size``, the shell's own
    box's diagonal)."""
    tm = pymeshfix.PyTMesh()
    tm.set_quiet(1)
    # MeshFix works about the shell's own centre: its result does not depend on where the
    # shell lies
    centre = 0.5 * np.add(*bounds(v))
    tm.load_array(
        np.array(v - centre, dtype=np.float64, order="C"), np.array(f, dtype=np.int32, order="C")
    )
    loops = int(tm.n_boundaries)
    tm.fill_small_boundaries(nbe=0, refine=True)
    fv, ff = tm.return_arrays()
    fv = np.asarray(fv, dtype=np.float64) + centre
    ff = np.asarray(ff, dtype=np.int64)
    # the fill may put a new vertex exactly on an old one, leaving triangles with a
    # repeated corner: no area, part of the fill
    fv, inverse = unique_rows(fv)
    ff = inverse[ff] if len(ff) else ff.reshape(0, 3)
    ff = ff[(ff[:, 0] != ff[:, 1]) & (ff[:, 1] != ff[:, 2]) & (ff[:, 2] != ff[:, 0])]
    if len(ff) == 0 or open_faces(ff).any():
        return None
    vol = _volume(fv, ff)
    if abs(vol) <= 1e3 * TOL.flat * size**3:
        return None
    return fv, ff, loops, vol


def edge_shells(f: np.ndarray) -> tuple[int, np.ndarray]:
    """The surfaces of ``f`` that hang together across edges used by exactly two faces:
    their number and the surface of every face (a non-manifold edge, or an open one, does
    not join the faces on it)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    m = len(f)
    directed = f[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    owner = np.repeat(np.arange(m), 3)
    key = row_min(directed) * (int(f.max()) + 1) + row_max(directed)
    order = np.argsort(key, kind="stable")
    sk = key[order]
    start = np.ones(len(sk), dtype=bool)
    start[1:] = sk[1:] != sk[:-1]
    group = np.cumsum(start) - 1
    counts = np.bincount(group)
    two = counts[group] == 2
    first = order[two & start]
    second = order[two & ~start]
    graph = coo_matrix((np.ones(len(first)), (owner[first], owner[second])), shape=(m, m))
    return connected_components(graph, directed=False)


def _outcome(pymeshfix, v, f, split: bool = False) -> Outcome:
    """One shell closed, or not: its volume is judged against its own size, not against
    the whole mesh's (a part far away does not make a small shell flat)."""
    used = v[np.unique(f)]
    size = float(np.linalg.norm(np.subtract(*bounds(used)[::-1])))
    n_open = int((np.bincount(_edge_groups(f)) == 1).sum())
    if n_open == 0 and not open_faces(f).any():
        vol = _volume(v, f)
        flip = vol < 0
        cf = f[:, ::-1] if flip else f
        return Outcome(v, f, 0, v, cf, 0, bool(flip), abs(vol), split)
    done = fill(pymeshfix, v, f, size) if pymeshfix is not None else None
    if done is None:
        return Outcome(v, f, n_open, None, None, 0, False, None, split)
    fv, ff, loops, vol = done
    if vol < 0:
        ff = ff[:, ::-1]
    return Outcome(v, f, n_open, fv, ff, loops, bool(vol < 0), abs(vol), split)


def _edge_groups(f: np.ndarray) -> np.ndarray:
    directed = f[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    key = row_min(directed) * (int(f.max()) + 1) + row_max(directed)
    _, inverse = np.unique(key, return_inverse=True)
    return inverse.reshape(-1)


def close_each(v: np.ndarray, f: np.ndarray, pymeshfix) -> Iterator[Outcome]:
    """The outcome of every shell of ``v, f`` (copies of vertices merged), closed shells as
    they are; ``pymeshfix`` None fills nothing (every open shell is reported open)."""
    n, labels = face_labels(v, f)
    order = np.argsort(labels, kind="stable")
    bounds = np.searchsorted(labels[order], np.arange(n + 1))
    for s in range(n):
        sv, sf = drop_unused_vertices(v, f[order[bounds[s] : bounds[s + 1]]])
        whole = _outcome(pymeshfix, sv, sf)
        if whole.closes:
            yield whole
            continue
        k, parts = edge_shells(sf)
        if k == 1:
            yield whole
            continue
        for p in range(k):
            pv, pf = drop_unused_vertices(sv, sf[parts == p])
            yield _outcome(pymeshfix, pv, pf, split=True)
