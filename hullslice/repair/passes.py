"""Checking a mesh and repairing what is safe, as a chain of named passes.

Every hull goes through :data:`PASSES` in order (:func:`check_and_repair`). A pass is
either a **check**, which always runs and raises a :class:`~hullslice.errors.MeshError`
saying what is wrong (finite coordinates, a closed surface, a volume), or a **fix**, which
changes the mesh where that can be done without guessing and reports it in one note: the
note goes to the hull's ``source["repairs"]`` and into a
:class:`~hullslice.errors.MeshRepairWarning`. With ``fix=False`` (``--no-fix``) no fix is
made: a mesh that would need one is refused with a ``MeshError`` naming the pass.

The fixes, in order: degenerate faces dropped, repeated faces dropped, vertices that differ
by rounding merged to close the surface, faces re-oriented to agree with their neighbours,
an inside-out body turned outward, overlapping shells taken as their union. Closing holes
(``repair="close"``) is another matter, never done unasked: :mod:`hullslice.repair.close`.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..constants import TOL
from ..errors import MeshError, MeshRepairWarning, OpenMeshError
from ..integrity import check_sections_match_volume
from ..reduce import bounds
from ..topology import (
    check_finite,
    drop_repeated_faces,
    drop_unused_vertices,
    edge_use,
    flipped,
    merge_close,
    mesh_arrays,
    orient_consistently,
    shell_sizes,
    shell_volumes,
    to_manifold,
    unique_rows,
)

__all__ = ["PASSES", "MeshState", "Pass", "check_and_repair"]

#: Farthest a mesh may lie from the origin, in multiples of its size: beyond, its coordinates
#: keep fewer than 10 significant digits of the body in double precision, and manifold3d's
#: tolerances, relative to the coordinates, merge its features.
MAX_OFFSET = 1e6


@dataclass
class MeshState:
    """The mesh as the passes hand it on (vertices in m, body frame)."""

    name: str
    vertices: np.ndarray  # (n, 3) float
    faces: np.ndarray  # (m, 3) int
    size: float = 0.0  # diagonal of the bounding box, m
    manifold: Any = None  # the manifold3d.Manifold, once built
    _edges: tuple | None = field(default=None, repr=False)

    def edge_use(self) -> tuple[np.ndarray, np.ndarray]:
        """Faces using each edge and those running from low to high index (see
        :func:`hullslice.topology.edge_use`), for the current faces."""
        if self._edges is None or self._edges[0] is not self.faces:
            self._edges = (self.faces, *edge_use(self.faces))
        return self._edges[1], self._edges[2]


@dataclass(frozen=True)
class Pass:
    """One step of :func:`check_and_repair`.

    Attributes
    ----------
    name : str
        How messages name it.
    run : callable
        ``run(state) -> note or None``: checks or changes ``state``; the note (a fix's
        report) is None when nothing was changed. Its docstring says what it does.
    fixes : bool
        True for a fix (turned off by ``fix=False``), False for a check (always run).
    """

    name: str
    run: Callable[[MeshState], str | None]
    fixes: bool

    @property
    def doc(self) -> str:
        """What the pass checks or fixes, and what it reports."""
        return (self.run.__doc__ or "").strip()


# -- checks ---------------------------------------------------------------------------------


def _drop_unused_vertices(s: MeshState) -> None:
    """Drops the vertices no face uses (they carry no geometry, so later counts mean
    something); reports nothing."""
    s.vertices, s.faces = drop_unused_vertices(s.vertices, s.faces)


def _check_extent(s: MeshState) -> None:
    """Refuses a mesh at one point, or so far from the origin that its coordinates do not
    resolve it."""
    v, name = s.vertices, s.name
    size = float(np.linalg.norm(np.subtract(*bounds(v)[::-1])))
    if size == 0.0:
        raise MeshError(f"mesh {name!r}: all vertices are at one point")
    reach = float(np.abs(v).max())
    if reach > MAX_OFFSET * size:
        raise MeshError(
            f"mesh {name!r} lies {reach:.3g} m from the origin, {reach / size:.3g} times its "
            f"size ({size:.3g} m): coordinates that far out do not resolve the body (a binary "
            "STL keeps 7 digits, a double 16); move the body near the origin in your CAD tool"
        )
    s.size = size


def _merge_exact_copies(s: MeshState) -> None:
    """Merges exactly equal vertices (every STL is a triangle soup on disk): nothing
    changes but the indices; reports nothing."""
    uniq, inverse = unique_rows(s.vertices)
    if len(uniq) < len(s.vertices):
        s.vertices, s.faces = uniq, inverse[s.faces]


def _check_faces_left(s: MeshState) -> None:
    """Refuses a mesh whose faces were all degenerate."""
    if len(s.faces) == 0:
        raise MeshError(f"mesh {s.name!r} has only degenerate faces")


def _check_closed(s: MeshState) -> None:
    """Refuses an open surface (an edge with one face) and a non-manifold one (an edge with
    more than two)."""
    counts, _ = s.edge_use()
    name = s.name
    open_edges = int((counts == 1).sum())
    if open_edges:
        raise OpenMeshError(
            f"mesh {name!r} is open: {open_edges} edges belong to a single face (holes in "
            "the surface); load it with --repair close (repair='close') to fill them and "
            "drop what cannot be closed ('hullslice info MESH' lists the shells and which "
            "would close), or close them in your CAD tool"
        )
    nonmanifold = int((counts > 2).sum())
    if nonmanifold:
        raise OpenMeshError(
            f"mesh {name!r} is not manifold: {nonmanifold} edges are shared by more than two "
            "faces; separate the touching bodies or remesh"
        )


def _check_volume(s: MeshState) -> None:
    """Refuses a flat or zero-thickness surface (every shell encloses less than
    ``TOL.flat`` times the cube of its own size), and builds the manifold3d ``Manifold``
    (refusing what manifold3d refuses)."""
    from ..parts import face_labels

    n, labels = face_labels(s.vertices, s.faces)
    vols = np.abs(shell_volumes(s.vertices, s.faces, labels, n))
    sizes = shell_sizes(s.vertices, s.faces, labels, n)
    if not np.any(vols > TOL.flat * sizes**3):
        vol = float(vols.sum())
        raise MeshError(
            f"mesh {s.name!r} encloses no volume ({vol:.3g} m^3 in a box of diagonal "
            f"{s.size:.6g} m): it is a flat or zero-thickness surface, not a body"
        )
    if vols.sum() <= TOL.flat * s.size**3:
        # bodies, but small for the box they span: shells far apart (a stray part)
        big = int(np.argmax(vols))
        warnings.warn(
            f"mesh {s.name!r}: its {n} shells spread over {s.size:.3g} m, "
            f"{s.size / sizes[big]:.3g} times the largest ({sizes[big]:.3g} m across, "
            f"{vols[big]:.3g} m^3): a part far from the body? --keep largest keeps the "
            "largest alone ('hullslice info MESH' lists the shells)",
            MeshRepairWarning,
            stacklevel=4,
        )
    s.manifold = to_manifold(s.vertices, s.faces, s.name)


def _check_body(s: MeshState) -> None:
    """Refuses a body with no volume, or one that passes through itself (its sections'
    areas do not add up to its volume)."""
    if s.manifold.volume() <= 0.0:
        raise MeshError(f"mesh {s.name!r} encloses no volume")
    check_sections_match_volume(s.vertices, s.faces, s.manifold, s.name)


# -- fixes ----------------------------------------------------------------------------------


def _drop_degenerate_faces(s: MeshState) -> str | None:
    """Drops the faces that repeat a vertex (no area, no orientation); reports how many."""
    f = s.faces
    degenerate = (f[:, 0] == f[:, 1]) | (f[:, 1] == f[:, 2]) | (f[:, 2] == f[:, 0])
    if not degenerate.any():
        return None
    s.faces = f[~degenerate]
    return f"removed {int(degenerate.sum())} degenerate faces (a repeated vertex)"


def _drop_repeated_faces(s: MeshState) -> str | None:
    """Drops the copies of a triangle written again with the same winding; reports how
    many."""
    s.faces, n_copies = drop_repeated_faces(s.faces)
    if not n_copies:
        return None
    return f"removed {n_copies} repeated faces (the same triangle written again)"


def _merge_close_vertices(s: MeshState) -> str | None:
    """Closes an open surface whose vertices that should be shared differ by rounding:
    merges them over the smallest distance (``TOL.merge`` to ``TOL.merge_max`` of the
    mesh's size, by tens, whatever its distance from the origin) that closes it, moving no
    vertex by more than ``TOL.merge_edge`` of its shortest edge; reports how many and the
    distance."""
    counts, _ = s.edge_use()
    if not (counts == 1).any():
        return None
    v, f = s.vertices, s.faces
    scale = s.size
    tol = TOL.merge * scale
    while tol <= TOL.merge_max * scale * (1.0 + 1e-9):
        merged = merge_close(v, f, tol)
        if merged is None:  # past rounding: a larger distance would only merge more
            break
        v2, f2, n_merged = merged
        if n_merged:
            f2, _ = drop_repeated_faces(f2)
            if len(f2):
                counts2, n_forward2 = edge_use(f2)
                if np.all(counts2 == 2):
                    s.vertices, s.faces = v2, f2
                    s._edges = (f2, counts2, n_forward2)
                    return (
                        f"merged {n_merged} vertices closer than {tol:.3g} m to close the "
                        "surface (copies of one vertex that differ by rounding)"
                    )
        tol *= 10.0
    return None


def _orient_faces(s: MeshState) -> str | None:
    """Flips the fewest faces so that every edge is used once each way (neighbours agree);
    reports how many were flipped."""
    _, n_forward = s.edge_use()
    if not int((n_forward != 1).sum()):
        return None
    s.faces, n_flipped = orient_consistently(s.faces, s.name)
    return f"re-oriented {n_flipped} faces whose winding disagreed with their neighbours"


def _turn_outward(s: MeshState) -> str | None:
    """Flips every face of a body wound inside out (negative volume); reports it."""
    if s.manifold.volume() >= 0.0:
        return None
    s.faces = s.faces[:, ::-1].copy()
    s.manifold = to_manifold(s.vertices, s.faces, s.name)
    return "the mesh was inside out (negative volume); all faces were flipped"


def _union_overlapping_shells(s: MeshState) -> str | None:
    """Takes shells that overlap one another as their union (cavities kept); a shell wound
    inside out that is not inside the others (not a cavity) is turned outward first;
    reports the shells' summed volume and the union's."""
    import manifold3d

    parts = s.manifold.decompose()
    if len(parts) <= 1:
        return None
    vols = np.array([p.volume() for p in parts])
    shells = [p for p, vol in zip(parts, vols, strict=True) if vol > 0]
    cavities = []
    turned = 0
    if shells:
        outer = manifold3d.Manifold.batch_boolean(shells, manifold3d.OpType.Add)
    for p, vol in zip(parts, vols, strict=True):
        if vol >= 0:
            continue
        solid = flipped(p)
        # a cavity lies inside the solid shells: all of its volume is theirs too
        inside = bool(shells) and (outer ^ solid).volume() >= -vol * (1.0 - TOL.volume)
        if inside:
            cavities.append(solid)
        else:
            shells.append(solid)
            turned += 1
    total = float(sum(p.volume() for p in shells))
    union = manifold3d.Manifold.batch_boolean(shells, manifold3d.OpType.Add)
    if not turned and not (len(shells) > 1 and union.volume() < total * (1.0 - TOL.volume)):
        return None
    body = union
    if cavities:
        body = manifold3d.Manifold.batch_boolean([union, *cavities], manifold3d.OpType.Subtract)
    s.vertices, s.faces = mesh_arrays(body)
    s.manifold = to_manifold(s.vertices, s.faces, s.name)
    outward = (
        f"{turned} inside-out shell{'s' if turned != 1 else ''} (not inside another) turned "
        "outward; "
        if turned
        else ""
    )
    return (
        f"{outward}{len(shells)} shells overlap (their volumes add to {total:.6g} m^3, "
        f"their union is {union.volume():.6g} m^3); the body is taken as their union"
    )


def _check(run: Callable[[MeshState], None]) -> Callable[[MeshState], str | None]:
    """A check as a pass: it reports nothing."""

    def step(s: MeshState) -> None:
        run(s)

    step.__doc__ = run.__doc__
    return step


#: The passes every hull goes through, in order.
PASSES: tuple[Pass, ...] = (
    Pass("drop unused vertices", _check(_drop_unused_vertices), fixes=False),
    Pass("extent", _check(_check_extent), fixes=False),
    Pass("merge exact copies", _check(_merge_exact_copies), fixes=False),
    Pass("drop degenerate faces", _drop_degenerate_faces, fixes=True),
    Pass("faces left", _check(_check_faces_left), fixes=False),
    Pass("drop repeated faces", _drop_repeated_faces, fixes=True),
    Pass("merge close vertices", _merge_close_vertices, fixes=True),
    Pass("closed", _check(_check_closed), fixes=False),
    Pass("orient faces", _orient_faces, fixes=True),
    Pass("volume", _check(_check_volume), fixes=False),
    Pass("turn outward", _turn_outward, fixes=True),
    Pass("union overlapping shells", _union_overlapping_shells, fixes=True),
    Pass("body", _check(_check_body), fixes=False),
)


def check_and_repair(
    vertices: Any, faces: Any, name: str, *, fix: bool = True
) -> tuple[np.ndarray, np.ndarray, Any, list[str]]:
    """Validate a mesh, repair what is safe, and build its manifold3d ``Manifold``.

    Parameters
    ----------
    vertices : (n, 3) float
        In m, body frame.
    faces : (m, 3) int
        Triangle vertex indices.
    name : str
        For messages.
    fix : bool
        False: make no fix; a mesh that needs one raises a ``MeshError`` naming the pass.

    Returns
    -------
    vertices, faces, manifold, notes
        The checked (and repaired) arrays, the ``Manifold``, and one note per fix made,
        each also given as a :class:`~hullslice.errors.MeshRepairWarning`.

    Raises
    ------
    MeshError
        What a check refuses, or (with ``fix=False``) a mesh that needs a fix.
    """
    state = MeshState(name, *_checked_arrays(vertices, faces, name))
    notes: list[str] = []
    for step in PASSES:
        note = step.run(state)
        if note is None:
            continue
        if not fix:
            raise MeshError(
                f"mesh {name!r} needs a repair, and fix=False (--no-fix) turns repairs off: "
                f"the pass {step.name!r} would fix it ({note}); load it without --no-fix, "
                "or repair it in your CAD tool"
            )
        notes.append(note)
        warnings.warn(f"mesh {name!r}: {note}", MeshRepairWarning, stacklevel=3)
    return state.vertices, state.faces, state.manifold, notes


def _checked_arrays(vertices: Any, faces: Any, name: str) -> tuple[np.ndarray, np.ndarray]:
    """The arrays as float64 and int64, refused when not a triangle mesh: wrong shapes, no
    faces, indices that are not whole numbers or not vertices, coordinates not finite."""
    v = np.array(vertices, dtype=np.float64)
    if v.ndim != 2 or v.shape[1] != 3:
        raise MeshError(f"mesh {name!r}: vertices have shape {v.shape}, expected (n, 3)")
    try:
        f = np.array(faces)
    except (TypeError, ValueError) as exc:
        raise MeshError(f"mesh {name!r}: faces are not an (m, 3) integer array") from exc
    if f.ndim != 2 or f.shape[1] != 3:
        raise MeshError(f"mesh {name!r}: faces have shape {f.shape}, expected (m, 3) triangles")
    if len(v) == 0 or len(f) == 0:
        raise MeshError(f"mesh {name!r} is empty ({len(v)} vertices, {len(f)} faces)")
    if not np.issubdtype(f.dtype, np.integer):
        if not np.all(np.isfinite(f)) or np.any(f != np.round(f)):
            raise MeshError(f"mesh {name!r}: face indices are not whole numbers")
    f = f.astype(np.int64)
    check_finite(v, name)
    if f.min() < 0 or f.max() >= len(v):
        badf = np.flatnonzero((f < 0).any(axis=1) | (f >= len(v)).any(axis=1))
        raise MeshError(
            f"mesh {name!r}: face {badf[0]} refers to vertex {f[badf[0]].tolist()} but the "
            f"mesh has only {len(v)} vertices (indices 0 to {len(v) - 1}); the file is corrupt"
        )
    return v, f
