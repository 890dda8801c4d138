"""Closing an open mesh into closed bodies: ``repair="close"`` (``--repair close``).

Never done unasked: an open mesh is refused unless the caller asks for this repair, and the
repair reports what it did (:class:`CloseReport`, one :class:`~hullslice.errors.
MeshRepairWarning`). The passes, each with its own figures:

1. **Stitch.** Copies of one vertex that differ by rounding are merged, over the smallest
   distance of the loader's ladder (``TOL.merge`` to ``TOL.merge_max`` of the mesh's size,
   whatever its distance from the origin) that leaves the fewest edges with a single face;
   no vertex moves by more than ``TOL.merge_edge`` of its shortest edge (farther is not
   rounding).
2. **Fill.** Every hole (a loop of edges with a single face) is filled by MeshFix's hole
   filler (``pymeshfix``, the optional extra ``hullslice[repair]``): a triangulation of the
   loop, refined and smoothed to the surrounding faces' size. Only the fill is used, not
   MeshFix's whole clean-up, which takes away sharp tips and small parts of a good hull.
   Each shell (faces sharing vertices) is filled on its own; one that does not close as a
   whole, because parts are welded to it at a vertex or an edge, is split into the
   surfaces that hang together across edges of two faces and each is filled on its own
   (:mod:`hullslice.repair.shells`): a shell that closes alone is never dropped because
   another welded to it does not.
3. **Drop.** A shell that is still open, or encloses no volume (a single sheet, a loose
   triangle) is dropped, and the warning names the largest dropped ones with their size;
   a shell wound inside out (a negative volume once closed) is turned outward.

What was measured (``tests/test_aircraft_meshes.py``, ``benchmarks/repair.py``): the
generic fuselage (``hullslice.shapes.fuselage``, 2 m radius) with holes of 0.3 to 0.8 m
radius closes to within 0.02 % of its volume; three holes of 1 to 1.5 m lose 0.1 % at 10k
faces and 0.4 % at 128k (the fill of a finer mesh is flatter); a 100k-face open mesh closes
in under a second.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..constants import TOL
from ..errors import MeshError
from ..reduce import bounds, row_max, row_min
from ..topology import (
    drop_repeated_faces,
    drop_unused_vertices,
    edge_use,
    merge_groups,
    moves_within_rounding,
)
from .shells import close_each

__all__ = ["CloseReport", "close_mesh", "shell_outcomes"]


@dataclass(frozen=True)
class CloseReport:
    """What ``repair="close"`` did (lengths in the mesh's own units, scaled later).

    Attributes
    ----------
    holes : int
        Holes (loops of edges with a single face) filled in the shells kept.
    open_edges : int
        Edges with a single face before the repair, in all shells.
    stitched : int
        Vertices merged with a copy that differed by rounding.
    area_added : float
        Surface added by the fill (mesh units squared).
    shells : int
        Shells (after the stitch, a shell that did not close with the parts welded to it
        counted as its parts).
    dropped : int
        Open shells dropped (still open after the fill, or enclosing no volume).
    flipped : int
        Shells turned outward (wound inside out: a negative volume once closed).
    volume_before : float or None
        Volume of the shells that were closed before the repair (mesh units cubed), None if
        none was.
    volume_after : float
        Volume of the kept shells after it.
    seconds : float
        Time taken.
    largest_dropped : tuple of (length, beam, height, faces, open edges)
        The largest shells dropped (by the diagonal of their box, mesh units), up to three.
    split : int
        Shells kept that are parts of a shell that did not close as a whole (parts welded
        to one another at a vertex or an edge), each closed on its own.
    """

    holes: int
    open_edges: int
    stitched: int
    area_added: float
    shells: int
    dropped: int
    flipped: int
    volume_before: float | None
    volume_after: float
    seconds: float
    largest_dropped: tuple[tuple[float, float, float, int, int], ...] = ()
    split: int = 0

    def message(self, scale: float = 1.0) -> str:
        """One line for the warning, lengths times ``scale`` (m per mesh unit)."""
        parts = [
            f"closed {self.holes} hole{'s' if self.holes != 1 else ''} "
            f"({self.open_edges} edges with a single face), adding "
            f"{self.area_added * scale**2:.4g} m^2 of surface"
        ]
        if self.stitched:
            parts.append(f"merged {self.stitched} vertices that differed by rounding")
        if self.split:
            one = self.split == 1
            parts.append(
                f"closed {self.split} shell{'' if one else 's'} on {'its' if one else 'their'} "
                f"own that did not close with the parts welded to {'it' if one else 'them'}"
            )
        if self.dropped:
            largest = ", ".join(
                f"{_extent_text((a, b, c), scale)} ({_count(nf, 'face')}, "
                f"{_count(ne, 'open edge')})"
                for a, b, c, nf, ne in self.largest_dropped
            )
            parts.append(
                f"dropped {self.dropped} of {self.shells} shells that could not be closed "
                f"(open sheets or no volume; the largest: {largest})"
            )
        if self.flipped:
            parts.append(f"turned {_count(self.flipped, 'inside-out shell')} outward")
        before = (
            f"{self.volume_before * scale**3:.6g} m^3 in the shells closed before"
            if self.volume_before is not None
            else "undefined before"
        )
        parts.append(f"volume {before}, {self.volume_after * scale**3:.6g} m^3 after")
        return "repair close: " + "; ".join(parts) + f" ({self.seconds:.2f} s)"


def _open_count(f: np.ndarray) -> tuple[int, int]:
    counts, _ = edge_use(f)
    return int((counts == 1).sum()), int((counts > 2).sum())


def _stitch(v: np.ndarray, f: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """Merge copies of the vertices on open edges over the ladder's distance (relative to
    the mesh's size, not to its distance from the origin) that leaves the fewest open edges,
    moving no vertex by more than ``TOL.merge_edge`` of its shortest edge (only the rim's
    vertices: a fine part elsewhere is never collapsed)."""
    from scipy.spatial import cKDTree

    n_open, n_many = _open_count(f)
    if n_open == 0:
        return v, f, 0
    directed = f[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    key = row_min(directed) * (int(f.max()) + 1) + row_max(directed)
    _, inverse, counts = np.unique(key, return_inverse=True, return_counts=True)
    rim = np.unique(directed[counts[inverse.reshape(-1)] == 1])  # vertices on open edges
    tree = cKDTree(v[rim])
    scale = float(np.linalg.norm(np.subtract(*bounds(v)[::-1])))
    best = (n_open, f, 0)
    tol = TOL.merge * scale
    while tol <= TOL.merge_max * scale * (1.0 + 1e-9):
        pairs = tree.query_pairs(tol, output_type="ndarray")
        if len(pairs):
            k = len(rim)
            ncomp, labels, first = merge_groups(v[rim], pairs)
            target = np.arange(len(v))
            target[rim] = rim[first[labels]]
            if not moves_within_rounding(v, f, target):
                break  # past rounding: a larger distance would only move more
            f2 = target[f]
            deg = (f2[:, 0] == f2[:, 1]) | (f2[:, 1] == f2[:, 2]) | (f2[:, 2] == f2[:, 0])
            f2, _ = drop_repeated_faces(f2[~deg])
            if len(f2):
                c2, _ = edge_use(f2)
                o2, m2 = int((c2 == 1).sum()), int((c2 > 2).sum())
                if o2 < best[0] and m2 <= n_many:
                    best = (o2, f2, k - ncomp)
                    if o2 == 0:
                        break
        tol *= 10.0
    return v, best[1], best[2]


def _meshfix():
    from ..extras import need

    return need("repair", "pymeshfix", "repair close")


def close_mesh(vertices: np.ndarray, faces: np.ndarray, name: str = "hull"):
    """Close an open, multi-shell surface into closed shells.

    Parameters
    ----------
    vertices : (n, 3) float
        In any length unit (the repair does not depend on it), copies merged.
    faces : (m, 3) int
    name : str
        For messages.

    Returns
    -------
    vertices, faces, report : (n', 3) float, (m', 3) int, CloseReport or None
        The closed shells; the report is None when the mesh had no hole.

    Raises
    ------
    MeshError
        Nothing is left that encloses a volume.
    """
    import scipy.sparse.csgraph
    import scipy.spatial  # noqa: F401  (imported before the clock starts: once per process)

    start = time.perf_counter()
    v = np.asarray(vertices, dtype=np.float64)
    f = np.asarray(faces, dtype=np.int64)
    v, f, stitched = _stitch(v, f)
    n_open, _ = _open_count(f)
    if n_open == 0 and not stitched:
        return v, f, None
    v, f = drop_unused_vertices(v, f)
    pymeshfix = _meshfix() if n_open else None
    # each shell on its own (closed ones as they are, turned outward if need be), so that
    # the holes and the surface added are counted on the shells that are kept
    outcomes = list(close_each(v, f, pymeshfix))
    return _assemble(name, outcomes, n_open, stitched, start)


def shell_outcomes(vertices: np.ndarray, faces: np.ndarray) -> tuple[list, int, bool]:
    """What ``repair="close"`` would do with each shell, without doing it: the outcomes
    (:class:`~hullslice.repair.shells.Outcome`, after the stitch), the vertices merged by
    the stitch, and whether the fill could be tried (pymeshfix installed; without it the
    open shells are reported open)."""
    v = np.asarray(vertices, dtype=np.float64)
    f = np.asarray(faces, dtype=np.int64)
    v, f, stitched = _stitch(v, f)
    v, f = drop_unused_vertices(v, f)
    try:
        pymeshfix = _meshfix()
    except ImportError:
        pymeshfix = None
    return list(close_each(v, f, pymeshfix)), stitched, pymeshfix is not None


def _assemble(name: str, outcomes: list, n_open: int, stitched: int, start: float):
    """The closed shells of ``outcomes`` as one mesh, and the report."""
    kept = [o for o in outcomes if o.closes]
    dropped = [o for o in outcomes if not o.closes]
    was_closed = [o.volume for o in outcomes if o.open_edges == 0 and o.volume is not None]
    if not kept:
        raise MeshError(
            f"mesh {name!r}: repair close left nothing that encloses a volume "
            f"({len(outcomes)} shells, {len(dropped)} could not be closed, the largest "
            f"{_extent_text(max(dropped, key=_diagonal).extents)}): the surface is not a "
            "body; remesh it"
        )
    pieces_v, pieces_f, offset = [], [], 0
    for o in kept:
        assert o.closed_vertices is not None and o.closed_faces is not None
        pieces_v.append(o.closed_vertices)
        pieces_f.append(o.closed_faces + offset)
        offset += len(o.closed_vertices)
    largest = sorted(dropped, key=_diagonal, reverse=True)[:3]
    report = CloseReport(
        holes=sum(o.holes for o in kept),
        open_edges=n_open,
        stitched=stitched,
        area_added=sum(o.area_added for o in kept),
        shells=len(outcomes),
        dropped=len(dropped),
        flipped=sum(o.flipped for o in kept),
        volume_before=float(sum(was_closed)) if was_closed else None,
        volume_after=float(sum(o.volume or 0.0 for o in kept)),
        seconds=time.perf_counter() - start,
        largest_dropped=tuple(_described(o) for o in largest),
        split=sum(o.split for o in kept),
    )
    return np.vstack(pieces_v), np.vstack(pieces_f), report


def _count(n: int, what: str) -> str:
    return f"{n} {what}{'' if n == 1 else 's'}"


def _described(o) -> tuple[float, float, float, int, int]:
    e = o.extents
    return (float(e[0]), float(e[1]), float(e[2]), len(o.faces), o.open_edges)


def _diagonal(o) -> float:
    return float(np.linalg.norm(o.extents))


def _extent_text(e, scale: float = 1.0) -> str:
    return " x ".join(f"{x * scale:.3g}" for x in e) + " m"
