"""The separate bodies (shells) of a mesh, and choosing which of them make the hull.

A mesh exported from a CAD or modelling tool often holds more than the fuselage: wings,
engines, tail planes, wheels, a propeller, each a surface of its own. A **body** here is a
connected set of faces (faces that share a vertex, after copies of one vertex have been
merged). Bodies are numbered from 1 by decreasing volume, so ``keep="largest"`` is body 1;
the volume of an open body is not defined and it is ranked by the volume its surface
encloses about its own centre, an estimate.

:func:`find_bodies` labels the faces and describes each body; :func:`parse_keep` reads a
``keep`` value (``"largest"``, ``"1,3"``, an int or a list of ints); :func:`keep_faces`
selects the faces of the chosen bodies; :func:`cut_to_box` keeps the part of a closed hull
inside a box, with manifold3d.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .errors import InputError, MeshError
from .reduce import bounds, row_max, row_min
from .topology import mesh_arrays

__all__ = ["Body", "box_note", "cut_to_box", "find_bodies", "keep_faces", "parse_box", "parse_keep"]


@dataclass(frozen=True)
class Body:
    """One separate body of a mesh.

    Attributes
    ----------
    number : int
        1 for the largest, then by decreasing volume.
    faces : int
        Its number of triangles.
    closed : bool
        Every edge of it is shared by two faces (before any repair of the hull as a whole).
    volume : float or None
        Enclosed volume in m^3 when closed, else None.
    size_volume : float
        The volume it is ranked by, m^3 (for an open body, an estimate).
    bounds_min, bounds_max : (3,) float
        Its bounding box in m, body frame.
    """

    number: int
    faces: int
    closed: bool
    volume: float | None
    size_volume: float
    bounds_min: tuple[float, float, float]
    bounds_max: tuple[float, float, float]

    @property
    def extents(self) -> tuple[float, float, float]:
        """Length, beam and height of its bounding box in m."""
        lo, hi = self.bounds_min, self.bounds_max
        return (float(hi[0] - lo[0]), float(hi[1] - lo[1]), float(hi[2] - lo[2]))

    def as_dict(self) -> dict:
        return {
            "number": self.number,
            "faces": self.faces,
            "closed": self.closed,
            "volume": self.volume,
            "bounds_min": list(self.bounds_min),
            "bounds_max": list(self.bounds_max),
            "extents": list(self.extents),
        }


def face_labels(vertices: np.ndarray, faces: np.ndarray) -> tuple[int, np.ndarray]:
    """The connected body of every face (faces sharing a vertex are connected).

    Returns
    -------
    n : int
        Number of bodies.
    labels : (m,) int
        The body of each face, ``0 .. n - 1`` in no particular order.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    nv = len(vertices)
    rows = faces[:, [0, 1, 2]].ravel()
    cols = faces[:, [1, 2, 0]].ravel()
    graph = coo_matrix((np.ones(len(rows), dtype=np.int8), (rows, cols)), shape=(nv, nv))
    _, vlabels = connected_components(graph, directed=False)
    labels = vlabels[faces[:, 0]]
    # vertices used by no face form bodies of their own: renumber the used labels only
    used, labels = np.unique(labels, return_inverse=True)
    return len(used), labels.reshape(-1)


def open_faces(faces: np.ndarray) -> np.ndarray:
    """(m,) bool: the faces with an edge not shared by exactly two faces (open or worse)."""
    f = np.asarray(faces, dtype=np.int64)
    directed = f[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    key = row_min(directed) * (int(f.max()) + 1) + row_max(directed)
    _, inverse, counts = np.unique(key, return_inverse=True, return_counts=True)
    return (counts[inverse.reshape(-1)] != 2).reshape(-1, 3).any(axis=1)


def find_bodies(vertices: np.ndarray, faces: np.ndarray) -> tuple[list[Body], np.ndarray]:
    """The bodies of a mesh, largest first, and the body number (from 1) of every face.

    Parameters
    ----------
    vertices : (n, 3) float
        In m, body frame (copies of one vertex merged, else every triangle is a body).
    faces : (m, 3) int

    Returns
    -------
    bodies : list of Body
    numbers : (m,) int
        The number of the body each face belongs to.
    """
    v = np.asarray(vertices, dtype=np.float64)
    f = np.asarray(faces, dtype=np.int64)
    n, labels = face_labels(v, f)
    # closed: every edge of the body used twice (an edge belongs to one body only)
    closed = np.bincount(labels, weights=open_faces(f), minlength=n) == 0
    # volume about each body's own centre (exact when closed, an estimate when open)
    nverts = np.bincount(labels, minlength=n) * 3.0
    centre = (
        np.stack(
            [np.bincount(labels, weights=v[f][:, :, k].sum(axis=1), minlength=n) for k in range(3)],
            axis=1,
        )
        / nverts[:, None]
    )
    o = centre[labels]
    a, b, c = v[f[:, 0]] - o, v[f[:, 1]] - o, v[f[:, 2]] - o
    vol = np.bincount(labels, weights=np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0, minlength=n)
    size = np.abs(vol)
    order = np.argsort(-size, kind="stable")
    number = np.empty(n, dtype=np.int64)
    number[order] = np.arange(1, n + 1)
    lo_b = np.full((n, 3), np.inf)
    hi_b = np.full((n, 3), -np.inf)
    corners = v[f].reshape(-1, 3)
    corner_label = np.repeat(labels, 3)
    np.minimum.at(lo_b, corner_label, corners)
    np.maximum.at(hi_b, corner_label, corners)
    nfaces = np.bincount(labels, minlength=n)
    bodies = [
        Body(
            number=int(number[i]),
            faces=int(nfaces[i]),
            closed=bool(closed[i]),
            volume=float(size[i]) if closed[i] else None,
            size_volume=float(size[i]),
            bounds_min=(float(lo_b[i][0]), float(lo_b[i][1]), float(lo_b[i][2])),
            bounds_max=(float(hi_b[i][0]), float(hi_b[i][1]), float(hi_b[i][2])),
        )
        for i in order
    ]
    return bodies, number[labels]


def parse_keep(keep) -> str | tuple[int, ...] | None:
    """A ``keep`` value: None (all bodies), ``"largest"``, or body numbers (from 1).

    Accepts ``"largest"``, ``"all"``, ``"1,3"``, an int or a sequence of ints.
    """
    if keep is None:
        return None
    if isinstance(keep, str):
        text = keep.strip().lower()
        if text == "largest":
            return "largest"
        if text == "all":
            return None
        parts = [p.strip() for p in text.split(",") if p.strip()]
    elif isinstance(keep, int | np.integer) and not isinstance(keep, bool):
        parts = [str(int(keep))]
    elif isinstance(keep, Sequence):
        parts = [str(p) for p in keep]
    else:
        parts = []
    try:
        numbers = tuple(int(p) for p in parts)
    except ValueError:
        numbers = ()
    if not numbers or any(n < 1 for n in numbers):
        raise InputError(
            f"keep {keep!r} is not 'largest' or body numbers from 1 (e.g. --keep 1,3); "
            "'hullslice info MESH' lists the bodies"
        )
    return tuple(sorted(set(numbers)))


def keep_faces(
    bodies: list[Body], numbers: np.ndarray, keep, name: str
) -> tuple[np.ndarray, tuple[int, ...]]:
    """The faces of the kept bodies, as a boolean mask, and the kept body numbers."""
    choice = parse_keep(keep)
    if choice is None:
        return np.ones(len(numbers), dtype=bool), tuple(b.number for b in bodies)
    kept: tuple[int, ...] = (1,) if isinstance(choice, str) else choice
    missing = [k for k in kept if k > len(bodies)]
    if missing:
        raise InputError(
            f"keep {missing[0]}: mesh {name!r} has {len(bodies)} "
            f"bod{'y' if len(bodies) == 1 else 'ies'} (numbered 1 to {len(bodies)}, largest "
            "first; 'hullslice info MESH' lists them): give numbers from that list"
        )
    return np.isin(numbers, kept), kept


def parse_box(box) -> np.ndarray | None:
    """A box ``XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX`` (text or six numbers, m) as a (2, 3) array."""
    if box is None:
        return None
    items = box.split(",") if isinstance(box, str) else list(box)
    try:
        values = np.array([float(x) for x in items], dtype=np.float64)
    except (TypeError, ValueError):
        values = np.array([])
    if values.shape != (6,) or not np.all(np.isfinite(values)):
        raise InputError(
            f"keep box {box!r} is not six numbers XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX (m, body frame "
            "after scaling), e.g. --keep-box=-1,40,-2.5,2.5,-1,5"
        )
    lo, hi = values[0::2], values[1::2]
    if np.any(hi <= lo):
        axis = "xyz"[int(np.flatnonzero(hi <= lo)[0])]
        raise InputError(
            f"keep box {box!r}: its {axis} range is empty ({axis}MAX must be larger than {axis}MIN)"
        )
    return np.array([lo, hi])


def cut_to_box(vertices: np.ndarray, faces: np.ndarray, manifold, box, name: str):
    """The part of a closed body inside a box, cut by manifold3d.

    Parameters
    ----------
    vertices, faces
        The body (m, body frame), for the message.
    manifold : manifold3d.Manifold
        The body.
    box : (2, 3) float
        Lowest and highest corners of the box in m, body frame.

    Returns
    -------
    vertices, faces, volume_in, volume_all
        The cut body's arrays and its volume against the whole body's, m^3.

    Raises
    ------
    InputError
        The box holds none of the body.
    """
    import manifold3d

    lo, hi = np.asarray(box, dtype=np.float64)
    cube = manifold3d.Manifold.cube(tuple(hi - lo)).translate(tuple(lo))
    part = manifold ^ cube
    if part.is_empty() or part.volume() <= 0.0:
        bmin, bmax = bounds(vertices)
        spans = ", ".join(f"{a} {bmin[k]:.6g} to {bmax[k]:.6g}" for k, a in enumerate("xyz"))
        raise InputError(
            f"keep box {','.join(f'{x:g}' for x in np.ravel(np.asarray(box).T))} keeps nothing "
            f"of mesh {name!r}, which spans {spans} m (body frame, after scaling): give a box "
            "that overlaps it"
        )
    v, f = mesh_arrays(part)
    if len(f) == 0:
        raise MeshError(f"mesh {name!r}: the box cut left no faces")
    return v, f, float(part.volume()), float(manifold.volume())


def box_note(box, inside: float, whole: float) -> str:
    """The repair note of a box cut: the box (m, body frame) and the volume kept of the
    whole body's (m^3)."""
    lo, hi = box
    return (
        f"kept the part inside the box x {lo[0]:g} to {hi[0]:g}, y {lo[1]:g} to {hi[1]:g}, "
        f"z {lo[2]:g} to {hi[2]:g} m: {inside:.6g} of {whole:.6g} m^3"
    )
