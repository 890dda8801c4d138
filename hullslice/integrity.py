"""Is a closed mesh one body whose sections mean what they say? The self-intersection check.

A mesh can be closed, manifold and consistently oriented and still pass through itself (a
corner pushed through the opposite face, a keel pushed through the deck). manifold3d takes
such a mesh as it is: its volume is the integral of the winding number over space, while
its sections count each point once, so the sections' mass per metre no longer adds up to
the mass, and where the surface folds back the "body" has no sections at all.

The check compares, at :data:`STATIONS` stations along the body, two areas of the same
section:

- the area manifold3d gives (the region inside the contours, overlaps counted once and
  inverted parts not at all), which the cut uses for the mass per metre;
- the signed area of the faces' crossing segments (each segment oriented by its face's
  outward normal), which is the rate of change of the mesh's volume along the body: the
  integral of the winding number over the plane.

They agree to rounding wherever every point of the plane is inside the body once or not
at all, whatever the shape, so no integration error enters. Where they differ by more than
:data:`REL_TOL` of the largest section, the mesh intersects itself there, and loading it
raises a :class:`~hullslice.errors.MeshError` that says where and by how much.
"""

from __future__ import annotations

import numpy as np

from .errors import MeshError
from .reduce import bounds, row_max, row_min

__all__ = ["ABS_TOL", "REL_TOL", "STATIONS", "check_sections_match_volume", "signed_section_areas"]

#: Stations at which the sections are compared (mid-points of equal parts of the length).
STATIONS = 64

#: Largest difference of the two areas of a section, relative to the largest section
#: (manifold3d cuts in single precision: about 1e-7).
REL_TOL = 1e-4

#: And at least this share of the body's size squared: manifold3d's section points are
#: exact to about 1e-9 of the size, so a section's area to about its perimeter times that
#: (a few 1e-9 of the size squared), whatever its area. A nearly flat body (a wedge prism
#: of 0.01 deg deadrise) has sections so thin that this exceeds REL_TOL of them.
ABS_TOL = 1e-8


def signed_section_areas(v: np.ndarray, f: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Signed areas of the sections of a closed oriented surface at planes ``x = x_k``.

    Parameters
    ----------
    v : (n, 3) float
        Vertices.
    f : (m, 3) int
        Triangles, counter-clockwise seen from outside.
    x : (k,) float
        Stations.

    Returns
    -------
    (k,) float
        At each station the integral over the plane of the surface's winding number (the
        area for a body that does not intersect itself), from the segments where the faces
        cross the plane. A vertex on the plane counts as below it, for every face alike.
    """
    tx = v[:, 0][f]  # (m, 3): only the faces a plane crosses are gathered whole
    lo, hi = row_min(tx), row_max(tx)
    del tx
    out = np.zeros(len(x))
    for k, h in enumerate(np.asarray(x, dtype=np.float64)):
        cross = np.flatnonzero((lo <= h) & (hi > h))
        if len(cross) == 0:
            continue
        t = v[f[cross]]
        normal = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
        above = t[:, :, 0] > h
        pts = np.zeros((len(cross), 2, 2))
        found = np.zeros(len(cross), dtype=np.int64)
        for a, b in ((0, 1), (1, 2), (2, 0)):
            edge = above[:, a] != above[:, b]
            if not edge.any():
                continue
            pa, pb = t[edge, a], t[edge, b]
            s = (h - pa[:, 0]) / (pb[:, 0] - pa[:, 0])
            p = pa[:, 1:] + s[:, None] * (pb[:, 1:] - pa[:, 1:])
            rows = np.flatnonzero(edge)
            slot = np.minimum(found[rows], 1)
            pts[rows, slot] = p
            found[rows] += 1
        ok = found == 2
        p, q = pts[ok, 0], pts[ok, 1]
        n = normal[ok]
        # counter-clockwise in (y, z) seen from +x: along (-n_z, n_y), the outward normal
        # turned a quarter turn
        d = q - p
        swap = d[:, 0] * -n[:, 2] + d[:, 1] * n[:, 1] < 0
        p[swap], q[swap] = q[swap], p[swap].copy()
        out[k] = 0.5 * float(np.sum(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]))
    return out


def check_sections_match_volume(v: np.ndarray, f: np.ndarray, manifold, name: str) -> None:
    """Refuse a mesh that intersects itself (see the module's documentation).

    Parameters
    ----------
    v : (n, 3) float
        Vertices, m.
    f : (m, 3) int
        Triangles, oriented outward.
    manifold : manifold3d.Manifold
        The same mesh.
    name : str
        For the message.

    Raises
    ------
    MeshError
        The two areas of a section differ by more than :data:`REL_TOL` of the largest
        and :data:`ABS_TOL` of the body's size squared.
    """
    lo, hi = bounds(v)
    size = float(np.linalg.norm(hi - lo))
    length = float(hi[0] - lo[0])
    if length <= 0.0:
        return
    centre = (lo + hi) / 2
    # mid-points of equal parts, shifted off any regular spacing of the mesh's vertices
    x = lo[0] + length * (np.arange(STATIONS) + 0.5 + 0.0042) / STATIONS
    # manifold3d cuts along z: the body brought to unit size, x turned to z (a rotation)
    unit = manifold.translate(tuple(-centre)).scale((1.0 / size,) * 3)
    turned = unit.transform(np.array([[0.0, 1, 0, 0], [0, 0, 1, 0], [1, 0, 0, 0]]))
    union = np.array([turned.slice(float((h - centre[0]) / size)).area() for h in x])
    signed = signed_section_areas((v - centre) / size, f, (x - centre[0]) / size)
    largest = float(max(np.abs(union).max(), np.abs(signed).max()))
    gap = np.abs(union - signed)
    k = int(np.argmax(gap))
    if largest > 0.0 and gap[k] > max(REL_TOL * largest, ABS_TOL):
        scale2 = size**2
        volume = float(manifold.volume())
        ratio = float(union.sum()) * length / STATIONS * scale2 / volume if volume else np.inf
        raise MeshError(
            f"mesh {name!r} intersects itself: at x = {x[k]:.6g} m its section inside the "
            f"contours is {union[k] * scale2:.6g} m^2 but its faces enclose "
            f"{signed[k] * scale2:.6g} m^2 (parts pass through each other or fold back); "
            f"the sections add up to {ratio:.3g} times the volume, so mass per metre and "
            "forces would be wrong. Repair the mesh in your CAD tool (a boolean union of the "
            "body with itself removes the overlap)"
        )
