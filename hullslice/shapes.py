"""Closed triangle meshes of reference bodies, built from their definitions.

Every function returns ``(vertices, faces)`` in metres, body frame (x forward, y port,
z up), faces counter-clockwise seen from outside; ``meshes/make_meshes.py`` writes them to
the sample files.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "PAPER_PRISM",
    "paper_prism",
    "prism_from_sections",
    "wedge_prism",
]

#: The paper's validation prism (Section 2.2): length, width, keel depth below the deck at
#: each end (deadrise 45 deg and 10 deg, tan(beta) = h / (W / 2)), and mass.
PAPER_PRISM = {
    "length": 0.35,
    "width": 0.2,
    "h_start": 0.1,
    "h_end": 0.1 * np.tan(np.radians(10.0)),
    "mass": 1.0,
}


def prism_from_sections(
    x: np.ndarray, sections: np.ndarray, flip_diagonals: bool = False
) -> tuple[np.ndarray, np.ndarray]:
    """A closed body lofted through convex polygonal cross-sections.

    Parameters
    ----------
    x : (s,) float
        Station positions along the body, increasing, in m.
    sections : (s, k, 2) float
        At each station the ``(y, z)`` corners of its section, counter-clockwise seen from
        the front (+x), all with the same number ``k`` of corners.
    flip_diagonals : bool
        Split each side quadrilateral along its other diagonal (a different triangulation
        of the same stations).

    Returns
    -------
    vertices : (s * k, 3) float
    faces : (m, 3) int
    """
    x = np.asarray(x, dtype=np.float64)
    sec = np.asarray(sections, dtype=np.float64)
    s, k, _ = sec.shape
    verts = np.concatenate([np.repeat(x, k)[:, None], sec.reshape(-1, 2)], axis=1)
    idx = np.arange(s * k).reshape(s, k)
    faces = []
    for j in range(k):
        jn = (j + 1) % k
        a, b = idx[:-1, j], idx[:-1, jn]  # edge at the aft station
        c, d = idx[1:, jn], idx[1:, j]  # same edge at the next station
        # sections run counter-clockwise about +x, so a, b, c, d is the quad's outward order
        if flip_diagonals:
            faces += [np.stack([a, b, d], 1), np.stack([b, c, d], 1)]
        else:
            faces += [np.stack([a, b, c], 1), np.stack([a, c, d], 1)]
    # end caps (fans over convex sections): the aft one faces -x, the fore one +x
    for j in range(1, k - 1):
        faces.append(np.array([[idx[0, 0], idx[0, j + 1], idx[0, j]]]))
        faces.append(np.array([[idx[-1, 0], idx[-1, j], idx[-1, j + 1]]]))
    return verts, np.concatenate(faces).astype(np.int64)


def paper_prism(stations: int = 1401, flip_diagonals: bool = False):
    """The paper's prism: triangular sections, keel depth varying linearly along the body.

    The deck is flat at ``z = 0`` from ``y = -W/2`` to ``W/2``; the keel lies on the centre
    line at depth ``h(x)``, from ``h = 0.1 m`` (45 deg deadrise) at ``x = 0`` to
    ``0.1 tan(10 deg)`` (10 deg) at ``x = L``. The sides are twisted (ruled) surfaces, so
    they are sampled at ``stations`` stations (default 1401, one every 0.25 mm: the
    triangulated sides then differ from the ruled surface by at most about 5e-6 m).

    Returns
    -------
    vertices, faces
        See :func:`prism_from_sections`.
    """
    p = PAPER_PRISM
    x = np.linspace(0.0, p["length"], int(stations))
    h = p["h_start"] + (p["h_end"] - p["h_start"]) * x / p["length"]
    half = p["width"] / 2
    # corners counter-clockwise about +x: starboard deck, keel, port deck
    sec = np.stack(
        [
            np.stack([np.full_like(h, -half), np.zeros_like(h)], 1),
            np.stack([np.zeros_like(h), -h], 1),
            np.stack([np.full_like(h, half), np.zeros_like(h)], 1),
        ],
        axis=1,
    )
    return prism_from_sections(x, sec, flip_diagonals)


def wedge_prism(
    length: float = 1.0,
    beam: float = 0.2,
    deadrise_deg: float = 30.0,
    stations: int = 11,
):
    """A prism of uniform wedge section: a 2D wedge extended along ``x``.

    Parameters
    ----------
    length : float
        Length in m (default 1.0).
    beam : float
        Width of the flat deck in m (default 0.2).
    deadrise_deg : float
        Deadrise angle in degrees (default 30).
    stations : int
        Number of stations along the length (default 11).

    Returns
    -------
    vertices, faces
        See :func:`prism_from_sections`; the deck is at ``z = 0``, the keel at
        ``z = -(beam / 2) tan(deadrise)``.
    """
    half = beam / 2
    h = half * np.tan(np.radians(deadrise_deg))
    x = np.linspace(0.0, length, int(stations))
    sec = np.array([[-half, 0.0], [0.0, -h], [half, 0.0]])
    return prism_from_sections(x, np.broadcast_to(sec, (len(x), 3, 2)))
