"""A generated light-aircraft export as a modelling tool writes it: open, many shells.

:func:`light_aircraft` builds, in metres, a 7 m fuselage shell (the generic fuselage of
:func:`hullslice.shapes.fuselage` at 7/37.6 scale) with a few holes (windows, a hatch), an
antenna welded to its crown at one vertex (an open cone sharing a vertex of the skin, as
exporters write parts that touch), a fin sheet welded to it along one edge, a closed wing
wound inside out that passes through the fuselage, and many small open parts around it
(single triangles, open boxes, open tubes).
"""

from __future__ import annotations

import numpy as np
import trimesh

from hullslice import shapes

#: Length of the fuselage shell, m.
LENGTH = 7.0
SCALE = LENGTH / 37.6
# holes of the fuselage shell: centre (m) and radius (m)
HOLES = (
    ((3.5, 0.37, 0.45), 0.12),  # a window on the side
    ((4.2, -0.37, 0.45), 0.12),  # one on the other side
    ((2.0, 0.0, 0.77), 0.15),  # a hatch on the crown
)


def fuselage_shell() -> tuple[np.ndarray, np.ndarray]:
    """The fuselage with its holes: vertices (m) and faces."""
    v, f = shapes.fuselage(scale=SCALE, stations=60, points=32)
    centre = v[f].mean(axis=1)
    keep = np.ones(len(f), dtype=bool)
    for point, radius in HOLES:
        keep &= np.linalg.norm(centre - np.array(point), axis=1) > radius
    return v, f[keep]


def closed_fuselage() -> tuple[np.ndarray, np.ndarray]:
    """The same fuselage shell without holes (the reference body)."""
    return shapes.fuselage(scale=SCALE, stations=60, points=32)


def _open_box(rng, centre, size) -> tuple[np.ndarray, np.ndarray]:
    b = trimesh.creation.box(extents=size)
    f = np.asarray(b.faces)[2:]  # one side missing
    return np.asarray(b.vertices) + centre, f


def _open_tube(centre, radius, height) -> tuple[np.ndarray, np.ndarray]:
    c = trimesh.creation.cylinder(radius=radius, height=height, sections=12)
    v, f = np.asarray(c.vertices), np.asarray(c.faces)
    normals = np.asarray(c.face_normals)
    side = np.abs(normals[:, 2]) < 0.5  # the caps taken away
    return v + centre, f[side]


def light_aircraft(seed: int = 7, parts: int = 60) -> tuple[np.ndarray, np.ndarray]:
    """The whole export: vertices (m) and faces, as one triangle list."""
    rng = np.random.default_rng(seed)
    v, f = fuselage_shell()
    pieces = [(v, f)]
    # an antenna on the crown: an open cone whose base circle's first point is a vertex of
    # the skin (welded to it at that vertex)
    top = int(np.argmax(v[:, 2] - 10.0 * np.abs(v[:, 0] - 3.0)))
    tip = v[top] + np.array([0.0, 0.0, 0.25])
    ring = v[top] + 0.03 * np.array(
        [[np.cos(a) - 1.0, np.sin(a), 0.0] for a in np.linspace(0, 2 * np.pi, 9)[:-1]]
    )
    av = np.vstack([ring, tip])
    af = np.array([[i, (i + 1) % 8, 8] for i in range(8)])
    pieces.append((av, af))
    # a fin: a flat sheet welded to the crown along one edge of the skin (that edge then
    # has three faces, and the fuselage does not close together with it)
    centre = v[f].mean(axis=1)
    crown = f[np.argmax(centre[:, 2] - 10.0 * np.abs(centre[:, 0] - 1.0))]
    a, b = v[crown[0]], v[crown[1]]
    up = np.array([0.0, 0.0, 0.5])
    pieces.append((np.array([a, b, a + up, b + up]), np.array([[0, 1, 2], [1, 3, 2]])))
    # a closed wing through the fuselage, wound inside out (a mirrored part)
    wing = trimesh.creation.box(extents=(1.2, 9.0, 0.15))
    pieces.append(
        (np.asarray(wing.vertices) + np.array([3.2, 0.0, 0.2]), np.asarray(wing.faces)[:, ::-1])
    )
    for i in range(parts):  # small open parts around the aircraft
        centre = rng.uniform((-1.0, -5.0, -0.5), (8.0, 5.0, 2.0))
        kind = i % 3
        if kind == 0:
            pieces.append((centre + rng.normal(0.0, 0.05, (3, 3)), np.array([[0, 1, 2]])))
        elif kind == 1:
            pieces.append(_open_box(rng, centre, rng.uniform(0.05, 0.3, 3)))
        else:
            pieces.append(_open_tube(centre, 0.03, rng.uniform(0.1, 0.4)))
    vs, fs, offset = [], [], 0
    for pv, pf in pieces:
        vs.append(np.asarray(pv, dtype=np.float64))
        fs.append(np.asarray(pf, dtype=np.int64) + offset)
        offset += len(pv)
    return np.vstack(vs), np.vstack(fs)
