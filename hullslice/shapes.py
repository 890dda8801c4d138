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
    sides: float = 0.0,
):
    """A prism of uniform wedge section: a 2D wedge extended along ``x``.

    Parameters
    ----------
    length : float
        Length in m (default 1.0).
    beam : float
        Width at the chines in m (default 0.2).
    deadrise_deg : float
        Deadrise angle in degrees (default 30).
    stations : int
        Number of stations along the length (default 11).
    sides : float
        Height in m of vertical sides above the chines (default 0: a flat deck at the
        chines). With sides the chines are knuckles, as on the drop-test wedge of Zhao,
        Faltinsen & Aarsnes (1996).

    Returns
    -------
    vertices, faces
        See :func:`prism_from_sections`; the chines are at ``z = 0``, the keel at
        ``z = -(beam / 2) tan(deadrise)``, the deck at ``z = sides``.
    """
    half = beam / 2
    h = half * np.tan(np.radians(deadrise_deg))
    x = np.linspace(0.0, length, int(stations))
    if sides > 0.0:
        sec = np.array([[-half, sides], [-half, 0.0], [0.0, -h], [half, 0.0], [half, sides]])
    else:
        sec = np.array([[-half, 0.0], [0.0, -h], [half, 0.0]])
    return prism_from_sections(x, np.broadcast_to(sec, (len(x), len(sec), 2)))


#: Proportions of a generic narrow-body transport fuselage (about an A320's), full scale.
NARROW_BODY = {
    "length": 37.6,  # m, nose tip to tail tip
    "height": 4.14,  # m, of the constant section
    "width": 3.95,  # m, of the constant section
    "nose_length": 6.5,  # m
    "tail_length": 11.5,  # m, the upswept tail cone
    "tail_upsweep": 0.75,  # height of the tail tip's bottom, fraction of the height
    "tail_top_drop": 0.10,  # drop of the tail tip's top, fraction of the height
    "nose_droop": 0.15,  # drop of the nose tip below the centre line, fraction of the height
}


def fuselage(
    scale: float = 1.0,
    stations: int = 400,
    points: int = 160,
    **proportions: float,
):
    """A generic transport-aircraft fuselage: nose, constant section, upswept tail cone.

    Cross-sections are ellipses between a bottom line and a top line. The nose is an
    elliptic ogive drooping slightly below the centre line; the tail cone's bottom sweeps
    up smoothly (zero slope where it starts) to a small tail tip. ``x`` runs from the tail
    tip (0) to the nose tip (length), ``z = 0`` is the bottom of the constant section.

    Parameters
    ----------
    scale : float
        Geometric scale (1 full scale, 0.1 a 1:10 model).
    stations : int
        Number of sections along the body (default 400, clustered at the nose and tail: about
        0.15 m apart in the middle at full scale, finer at the ends).
    points : int
        Points around each section (default 160).
    **proportions
        Overrides of :data:`NARROW_BODY` (full-scale metres or fractions).

    Returns
    -------
    vertices, faces
        See :func:`prism_from_sections`.
    """
    p = {**NARROW_BODY, **proportions}
    L, H, B = p["length"], p["height"], p["width"]
    ln, lt = p["nose_length"], p["tail_length"]
    # stations clustered towards both ends (cosine spacing)
    u = 0.5 - 0.5 * np.cos(np.linspace(0.0, np.pi, int(stations)))
    x = u * L
    bottom = np.zeros_like(x)
    top = np.full_like(x, H)
    half_w = np.full_like(x, B / 2)
    tail = x < lt
    s = (lt - x[tail]) / lt  # 0 where the cone starts, 1 at the tail tip
    bottom[tail] = p["tail_upsweep"] * H * s**1.6
    top[tail] = H - p["tail_top_drop"] * H * s**2
    half_w[tail] = B / 2 * (1.0 - 0.88 * s**1.3)
    nose = x > L - ln
    s = (x[nose] - (L - ln)) / ln  # 0 where the nose starts, 1 at the tip
    r = np.sqrt(np.clip(1.0 - s**2, 0.0, None))
    centre = H / 2 - p["nose_droop"] * H * s**2
    half_h = H / 2 * r
    bottom[nose] = centre - half_h
    top[nose] = centre + half_h
    half_w[nose] = B / 2 * r
    # keep a small finite tip at both ends so that the end caps are proper faces
    tip = 0.02 * H
    mid = 0.5 * (top + bottom)
    half_h = np.maximum(0.5 * (top - bottom), tip)
    half_w = np.maximum(half_w, tip)
    t = np.linspace(0.0, 2.0 * np.pi, int(points), endpoint=False) - np.pi / 2  # keel first
    sec = np.stack(
        [
            np.cos(t)[None, :] * half_w[:, None],
            mid[:, None] + np.sin(t)[None, :] * half_h[:, None],
        ],
        axis=2,
    )
    return prism_from_sections(x * scale, sec * scale)


def circular_cylinder(
    length: float = 1.0, radius: float = 0.5, points: int = 720, stations: int = 3
):
    """A circular cylinder along ``x`` with its lowest line at ``z = 0``.

    Parameters
    ----------
    length, radius : float
        In m (defaults 1.0 and 0.5).
    points : int
        Points around the circle (default 720), one at the bottom.
    stations : int
        Number of sections along the length (default 3).
    """
    t = np.linspace(0.0, 2.0 * np.pi, int(points), endpoint=False) - np.pi / 2
    sec = np.stack([radius * np.cos(t), radius + radius * np.sin(t)], axis=1)
    x = np.linspace(0.0, length, int(stations))
    return prism_from_sections(x, np.broadcast_to(sec, (len(x), len(t), 2)))


def asymmetric_wedge_prism(
    length: float = 1.0,
    half_beam: float = 0.1,
    deadrise_port_deg: float = 20.0,
    deadrise_stbd_deg: float = 40.0,
    stations: int = 3,
):
    """A prism whose wedge section has a different deadrise on each side.

    The keel is at ``y = 0``, ``z = 0``; the port side rises at ``deadrise_port_deg`` to
    ``y = half_beam``, the starboard side at ``deadrise_stbd_deg`` to ``y = -half_beam``;
    a flat deck closes the section at the height of the higher side.
    """
    hp = half_beam * np.tan(np.radians(deadrise_port_deg))
    hs = half_beam * np.tan(np.radians(deadrise_stbd_deg))
    top = max(hp, hs)
    corners = [(0.0, 0.0), (half_beam, hp), (half_beam, top), (-half_beam, top), (-half_beam, hs)]
    # counter-clockwise about +x; a side that reaches the deck has no vertical part
    sec = np.array([c for i, c in enumerate(corners) if c != corners[i - 1]])
    x = np.linspace(0.0, length, int(stations))
    return prism_from_sections(x, np.broadcast_to(sec, (len(x), len(sec), 2)))
