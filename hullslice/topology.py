"""Array operations on triangle meshes: shared edges, exact duplicates, orientation, volume.

The checks and repairs of :mod:`hullslice.repair` and the preparation of a file's arrays
(:mod:`hullslice.prepare`) are built from these. Vertices are ``(n, 3)`` float arrays (any
length unit), faces ``(m, 3)`` integer arrays of vertex indices.
"""

from __future__ import annotations

import numpy as np

from .constants import TOL
from .errors import MeshError
from .reduce import row_max, row_min

__all__ = [
    "MAX_MERGE_PAIRS",
    "check_finite",
    "drop_repeated_faces",
    "drop_unused_vertices",
    "edge_use",
    "flipped",
    "group",
    "manifold_arrays",
    "merge_close",
    "merge_exact_copies",
    "merge_groups",
    "mesh_arrays",
    "moves_within_rounding",
    "orient_consistently",
    "second_moment",
    "shell_sizes",
    "shell_volumes",
    "shortest_edges",
    "signed_volume",
    "to_manifold",
    "triangle_outline",
    "unique_edges",
    "unique_rows",
    "volume_centroid",
]


def group(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Group equal keys: one index of each group, the group of every key, the group sizes.

    Like ``np.unique(..., return_index, return_inverse, return_counts)`` but with an
    unstable sort, several times faster on millions of keys.
    """
    order = np.argsort(keys)
    sk = keys[order]
    start = np.empty(len(sk), dtype=bool)
    start[:1] = True
    np.not_equal(sk[1:], sk[:-1], out=start[1:])
    group = np.cumsum(start) - 1
    inverse = np.empty(len(keys), dtype=np.int64)
    inverse[order] = group
    bounds = np.append(np.flatnonzero(start), len(sk))
    return order[start], inverse, np.diff(bounds)


def edge_use(faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """How many faces use each undirected edge, and how many of them run from low to high index.

    In a closed, consistently oriented surface every edge is used twice, once each way.
    """
    directed = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    lo = row_min(directed)
    hi = row_max(directed)
    _, inverse, counts = group(lo * (int(faces.max()) + 1) + hi)
    n_forward = np.bincount(inverse, weights=directed[:, 0] < directed[:, 1])
    return counts, n_forward


def unique_rows(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Exactly equal rows of an (n, 3) float array merged: unique rows and the inverse index.

    Rows are hashed to one 64-bit integer each (a 1D sort is much faster than a sort of
    rows); a hash collision, checked for, falls back to sorting the rows themselves.
    """
    v = np.ascontiguousarray(v + 0.0)  # -0.0 and 0.0 are the same point
    bits = v.view(np.uint64)
    h = np.zeros(len(v), dtype=np.uint64)
    with np.errstate(over="ignore"):
        for k in range(v.shape[1]):  # splitmix64 finaliser over the three coordinates
            h ^= bits[:, k]
            h ^= h >> np.uint64(30)
            h *= np.uint64(0xBF58476D1CE4E5B9)
            h ^= h >> np.uint64(27)
            h *= np.uint64(0x94D049BB133111EB)
            h ^= h >> np.uint64(31)
    first, inverse, _ = group(h)
    if not np.array_equal(v[first][inverse], v):
        raw = v.view(np.dtype((np.void, v.dtype.itemsize * v.shape[1]))).ravel()
        _, first, inverse = np.unique(raw, return_index=True, return_inverse=True)
    return v[first], inverse.reshape(-1)


#: Most pairs of vertices closer than the merge distance, per vertex, for the merge to be of
#: copies of vertices (a cone's tip written once per face makes many): more, and the
#: distance is not rounding but the mesh's own spacing (and the pairs would fill memory).
MAX_MERGE_PAIRS = 8


def shortest_edges(v: np.ndarray, f: np.ndarray) -> np.ndarray:
    """(n,) float: the length of the shortest edge at each vertex (inf for a vertex no
    face uses)."""
    e = f[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    length = np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1)
    out = np.full(len(v), np.inf)
    np.minimum.at(out, e[:, 0], length)
    np.minimum.at(out, e[:, 1], length)
    return out


def merge_groups(v: np.ndarray, pairs: np.ndarray) -> tuple[int, np.ndarray, np.ndarray]:
    """Vertices linked by ``pairs`` (k, 2) as groups: their number, the group of every
    vertex, and each group's first vertex (its representative)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    n = len(v)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    ncomp, labels = connected_components(graph, directed=False)
    first = np.full(ncomp, n, dtype=np.int64)
    np.minimum.at(first, labels, np.arange(n))
    return ncomp, labels, first


def moves_within_rounding(v: np.ndarray, f: np.ndarray, target: np.ndarray) -> bool:
    """True when moving every vertex ``i`` onto ``target[i]`` moves none by more than
    ``TOL.merge_edge`` of its shortest edge (a merge of copies that differ by rounding)."""
    moved = np.flatnonzero(target != np.arange(len(v)))
    if not len(moved):
        return True
    shift = np.linalg.norm(v[moved] - v[target[moved]], axis=1)
    return bool(np.all(shift <= TOL.merge_edge * shortest_edges(v, f)[moved]))


def merge_close(
    v: np.ndarray, f: np.ndarray, tol: float
) -> tuple[np.ndarray, np.ndarray, int] | None:
    """Merge vertices closer than ``tol``; returns new arrays and the number merged, or
    None when the vertices within ``tol`` of one another are not copies of a vertex: more
    pairs than :data:`MAX_MERGE_PAIRS` per vertex (counted before any is listed, so that
    memory stays in proportion to the mesh), a face with two corners among them, or a
    vertex moved by more than ``TOL.merge_edge`` of its shortest edge."""
    from scipy.spatial import cKDTree

    tree = cKDTree(v)
    n_pairs = (int(tree.count_neighbors(tree, tol)) - len(v)) // 2
    if n_pairs > MAX_MERGE_PAIRS * len(v):
        return None
    pairs = tree.query_pairs(tol, output_type="ndarray")
    if len(pairs) == 0:
        return v, f, 0
    ncomp, labels, first = merge_groups(v, pairs)
    g = labels[f]
    if np.any((g[:, 0] == g[:, 1]) | (g[:, 1] == g[:, 2]) | (g[:, 2] == g[:, 0])):
        return None  # a face would collapse: the distance is larger than some edge
    if not moves_within_rounding(v, f, first[labels]):
        return None  # not rounding: a vertex would move by a fair part of its edges
    return v[first], g, len(v) - ncomp


def drop_repeated_faces(f: np.ndarray) -> tuple[np.ndarray, int]:
    """Faces without repeats of the same triangle with the same winding, and how many went."""
    # rotate each triangle so that its smallest index comes first: the winding is kept
    r = np.argmin(f, axis=1)
    rolled = f[np.arange(len(f))[:, None], (r[:, None] + np.arange(3)) % 3]
    top = int(f.max()) + 1 if len(f) else 1
    if top <= 1 << 21:  # the three indices packed into one integer: grouped exactly
        r0, r1, r2 = (rolled[:, k].astype(np.int64) for k in range(3))
        key = (r0 << 42) | (r1 << 21) | r2
        _, inverse, counts = group(key)
        n_unique = len(counts)
    else:
        unique, inverse = unique_rows(rolled.astype(np.float64))  # exact below 2^53 vertices
        n_unique = len(unique)
    if n_unique == len(f):
        return f, 0
    first = np.full(n_unique, len(f))
    np.minimum.at(first, inverse, np.arange(len(f)))
    return f[np.sort(first)], len(f) - n_unique


def drop_unused_vertices(v: np.ndarray, f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The vertices some face uses, and the faces renumbered to them (as given when all
    are used)."""
    used = np.zeros(len(v), dtype=bool)
    used[f.ravel()] = True
    if used.all():
        return v, f
    remap = np.cumsum(used) - 1
    return v[used], remap[f]


def signed_volume(v: np.ndarray, f: np.ndarray) -> float:
    """Volume enclosed by an oriented closed surface (divergence theorem), m^3."""
    o = v.mean(axis=0)
    a, b, c = v[f[:, 0]] - o, v[f[:, 1]] - o, v[f[:, 2]] - o
    return float(np.einsum("ij,ij->", a, np.cross(b, c)) / 6.0)


def shell_volumes(v: np.ndarray, f: np.ndarray, labels: np.ndarray, n: int) -> np.ndarray:
    """(n,) float: the signed volume each shell (faces labelled ``0 .. n - 1``) encloses,
    about its own mean corner (exact for a closed shell, whatever its distance from the
    origin or from the other shells)."""
    counts = np.maximum(np.bincount(labels, minlength=n), 1) * 3.0
    tri = v[f]
    centre = (
        np.stack(
            [np.bincount(labels, weights=tri[:, :, k].sum(axis=1), minlength=n) for k in range(3)],
            axis=1,
        )
        / counts[:, None]
    )
    o = centre[labels]
    a, b, c = tri[:, 0] - o, tri[:, 1] - o, tri[:, 2] - o
    return np.bincount(labels, weights=np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0, minlength=n)


def shell_sizes(v: np.ndarray, f: np.ndarray, labels: np.ndarray, n: int) -> np.ndarray:
    """(n,) float: the diagonal of each shell's bounding box."""
    tri = v[f]
    counts = np.bincount(labels, minlength=n)
    if n == 0 or counts.min() == 0:  # a label without faces: its box empty, infinite
        corners = tri.reshape(-1, 3)
        owner = np.repeat(labels, 3)
        lo = np.full((n, 3), np.inf)
        hi = np.full((n, 3), -np.inf)
        np.minimum.at(lo, owner, corners)
        np.maximum.at(hi, owner, corners)
        return np.linalg.norm(hi - lo, axis=1)
    # the faces shell by shell, each shell's corners reduced as one run (the same minima
    # and maxima as taken corner by corner)
    order = np.argsort(labels, kind="stable") if n > 1 else slice(None)
    starts = np.concatenate(([0], np.cumsum(counts)[:-1]))
    lo = np.minimum.reduceat(row_min(tri)[order], starts, axis=0)
    hi = np.maximum.reduceat(row_max(tri)[order], starts, axis=0)
    return np.linalg.norm(hi - lo, axis=1)


def check_finite(v: np.ndarray, name: str) -> None:
    bad = ~np.isfinite(v)
    if bad.any():
        rows = np.flatnonzero(bad.any(axis=1))
        raise MeshError(
            f"mesh {name!r}: {len(rows)} vertices have NaN or infinite coordinates "
            f"(first: vertex {rows[0]} = {v[rows[0]].tolist()}); fix the export"
        )


def manifold_arrays(v: np.ndarray, f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The arrays as manifold3d takes them: fresh, owned, writeable, C-contiguous copies,
    float64 ``(n, 3)`` vertices and uint64 ``(m, 3)`` faces.

    Every array handed to manifold3d goes through here. manifold3d (nanobind) refuses a
    read-only array, one of another dtype or a strided view; the hull's own arrays are
    read-only, what manifold3d hands back are views of its memory, and
    ``np.ascontiguousarray`` returns such an array uncopied when it is already contiguous.
    """
    vc = np.array(np.reshape(v, (-1, 3)), dtype=np.float64, order="C", copy=True)
    fc = np.array(np.reshape(f, (-1, 3)), dtype=np.uint64, order="C", copy=True)
    return vc, fc


def mesh_arrays(manifold) -> tuple[np.ndarray, np.ndarray]:
    """The vertices (float64 ``(n, 3)``) and faces (int64 ``(m, 3)``) of a manifold3d
    ``Manifold``, as owned, writeable copies (not views of manifold3d's memory)."""
    mesh = manifold.to_mesh64()
    v = np.array(np.asarray(mesh.vert_properties)[:, :3], dtype=np.float64, order="C", copy=True)
    f = np.array(np.reshape(mesh.tri_verts, (-1, 3)), dtype=np.int64, order="C", copy=True)
    return v, f


def to_manifold(v: np.ndarray, f: np.ndarray, name: str):
    """A manifold3d ``Manifold`` of the arrays (copied by :func:`manifold_arrays`), refused
    with a ``MeshError`` when manifold3d refuses it."""
    import manifold3d

    vc, fc = manifold_arrays(v, f)
    man = manifold3d.Manifold(manifold3d.Mesh64(vert_properties=vc, tri_verts=fc))
    status = man.status()
    if status != manifold3d.Error.NoError:
        raise MeshError(
            f"mesh {name!r} was refused by manifold3d ({status.name}): it is not a closed, "
            "consistently oriented 2-manifold; repair it in your CAD tool"
        )
    return man


def triangle_outline(tri: np.ndarray):
    """A manifold3d ``CrossSection``: the union of the 2D triangles ``tri`` (m, 3, 2), each
    turned counter-clockwise (the outline of a surface projected on a plane, open or not);
    the contours are handed over as copies (:func:`manifold_arrays`'s rule)."""
    import manifold3d

    t = np.array(tri, dtype=np.float64, order="C", copy=True)
    d1, d2 = t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]
    cross = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    t = t[cross != 0.0]
    cw = cross[cross != 0.0] < 0.0
    t[cw] = t[cw][:, ::-1]
    contours = [np.array(c, dtype=np.float64, order="C", copy=True) for c in t]
    return manifold3d.CrossSection(contours, manifold3d.FillRule.Positive)


def orient_consistently(faces: np.ndarray, name: str) -> tuple[np.ndarray, int]:
    """Flip the fewest faces so that neighbours traverse every shared edge in opposite ways.

    Faces are the nodes of a graph whose edges are the mesh's edges (each shared by two
    faces, checked before); an edge says whether its two faces agree. A breadth-first tree
    of each connected part gives every face its parity to the root, found for all faces at
    once by pointer jumping. In each part, the parity seen by fewer faces is flipped.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import breadth_first_order, connected_components

    m = len(faces)
    directed = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    owner = np.repeat(np.arange(m), 3)
    lo, hi = row_min(directed), row_max(directed)
    order = np.argsort(lo * (int(faces.max()) + 1) + hi, kind="stable")
    a, b = order[0::2], order[1::2]  # the two uses of each edge, side by side
    fa, fb = owner[a], owner[b]
    disagree = (directed[a, 0] == directed[b, 0]).astype(np.int8)  # same direction
    # weights 1 (agree) and 3 (disagree) stay apart when two faces share two edges
    graph = coo_matrix((1 + 2 * disagree, (fa, fb)), shape=(m, m)).tocsr()
    graph = (graph + graph.T).tocsr()
    ncomp, labels = connected_components(graph, directed=False)
    pred = np.arange(m)
    for c in range(ncomp):
        root = int(np.flatnonzero(labels == c)[0])
        _, p = breadth_first_order(graph, root, directed=False, return_predecessors=True)
        members = p >= 0
        pred[members] = p[members]
    # parity of each face relative to its tree parent
    parity = (np.asarray(graph[np.arange(m), pred]).ravel() % 3 == 0).astype(np.int8)
    parity[pred == np.arange(m)] = 0
    jump = pred.copy()
    while np.any(jump != jump[jump]):  # pointer jumping: XOR of parities up to the root
        parity ^= parity[jump]
        jump = jump[jump]
    parity ^= parity[jump]
    flip = parity.astype(bool)
    if np.any(disagree.astype(bool) ^ flip[fa] ^ flip[fb]):
        raise MeshError(
            f"mesh {name!r}: the faces cannot be oriented consistently "
            "(a non-orientable surface); remesh the hull"
        )
    counts = np.bincount(labels, minlength=ncomp)
    flipped_per = np.bincount(labels, weights=flip, minlength=ncomp)
    swap = flipped_per > counts / 2  # flip the other set in this part: fewer faces
    flip ^= swap[labels]
    out = faces.copy()
    out[flip] = out[flip][:, ::-1]
    return out, int(flip.sum())


def flipped(manifold):
    """The same surface with every face reversed (a cavity turned into a solid)."""
    v, f = mesh_arrays(manifold)
    return to_manifold(v, f[:, ::-1], "cavity")


def unique_edges(faces: np.ndarray, n: int) -> np.ndarray:
    """(e, 2) int: the unique undirected edges of ``faces`` (over ``n`` vertices) as vertex
    index pairs (low, high)."""
    e = np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    key = np.unique(e[:, 0] * n + e[:, 1])
    return np.stack([key // n, key % n], axis=1)


def volume_centroid(v: np.ndarray, f: np.ndarray) -> np.ndarray:
    """(3,) float: centre of the volume enclosed by a closed oriented surface."""
    tri = v[f]
    # signed volumes of the tetrahedra (origin, triangle), shifted for accuracy
    o = v.mean(axis=0)
    a, b, c = tri[:, 0] - o, tri[:, 1] - o, tri[:, 2] - o
    vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    cen = (a + b + c) / 4.0
    return o + (vol[:, None] * cen).sum(axis=0) / vol.sum()


def second_moment(v: np.ndarray, f: np.ndarray, origin: np.ndarray) -> np.ndarray:
    """(3, 3) float: the volume integrals of ``r_i r_j`` with ``r = v - origin`` over the
    volume a closed oriented surface encloses (units of ``v`` to the fifth)."""
    tri = v[f] - origin
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    # tetrahedron (0, a, b, c): integral of r r^T = V/20 (sum v v^T + s s^T), s = a + b + c
    s = a + b + c
    outer = (
        np.einsum("i,ij,ik->jk", vol, a, a)
        + np.einsum("i,ij,ik->jk", vol, b, b)
        + np.einsum("i,ij,ik->jk", vol, c, c)
        + np.einsum("i,ij,ik->jk", vol, s, s)
    )
    return outer / 20.0


def merge_exact_copies(v: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Exactly equal vertices merged when the faces are valid indices (of an integer type,
    in range); otherwise the arrays unchanged, for the checks to report what is wrong."""
    f = np.asarray(faces)
    if len(v) and np.isfinite(v).all() and f.ndim == 2 and np.issubdtype(f.dtype, np.integer):
        uniq, inverse = unique_rows(v)
        if f.size and f.min() >= 0 and f.max() < len(inverse):
            return uniq, inverse[f]
    return v, faces
