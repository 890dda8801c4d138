"""Rebuild the sample meshes in this folder from their definitions in ``hullslice.shapes``.

    python meshes/make_meshes.py

paper_prism.stl   the paper's validation prism (L = 0.35 m, W = 0.2 m, deadrise 45 to 10 deg),
                  one station every 0.25 mm so that its twisted sides are that body
wedge_prism.stl   a prism of uniform 30-degree wedge section, 1 m long, 0.2 m beam
fuselage_full.obj a generic narrow-body transport fuselage, full scale (37.6 m, 3.95 m wide):
                  nose, constant section, upswept tail cone; x from the tail tip to the nose
fuselage_model.obj the same at 1:10 model scale (3.76 m)
dirty/dirty_aircraft.stl an aircraft as a modelling tool exports it, to practise on: in its own
                  units (14.7 long for 37.6 m), nose towards -x, a coarse fuselage with four
                  holes, a wing, tail planes and a fin through it, two nacelles, and 20 loose
                  triangles (see the README's "Bringing your own aircraft mesh")
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh

from hullslice import shapes

HERE = Path(__file__).resolve().parent


def write(name: str, vertices, faces) -> None:
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    if not (mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0):
        raise SystemExit(f"{name}: the generated mesh is not a closed, outward body")
    path = HERE / name
    tmp = path.with_suffix(path.suffix + ".tmp")
    kw = {"digits": 6} if path.suffix == ".obj" else {}  # micrometres at full scale
    mesh.export(tmp, file_type=path.suffix.lstrip("."), **kw)
    tmp.replace(path)
    print(f"{name}: {len(faces)} faces, volume {mesh.volume:.7g} m^3")


def dirty_aircraft() -> trimesh.Trimesh:
    """The dirty sample: deterministic, about 7,000 faces."""
    v, f = shapes.fuselage(stations=80, points=40)
    centre = v[f].mean(axis=1)
    keep = np.ones(len(f), dtype=bool)
    for point, radius in [((20, 0, 0), 0.4), ((10, 1.9, 2), 0.8), ((30, -1.5, 3.5), 1.2),
                          ((33, 0, 3.4), 0.5)]:  # fmt: skip
        keep &= np.linalg.norm(centre - np.array(point), axis=1) > radius
    parts = [trimesh.Trimesh(v, f[keep], process=False)]
    for extents, at in [((6, 34, 0.5), (17, 0, 1)), ((4, 12, 0.25), (2.5, 0, 3.6)),
                        ((5, 0.3, 6), (3, 0, 6))]:  # fmt: skip
        parts.append(trimesh.creation.box(extents=extents).apply_translation(at))
    for y in (-6.0, 6.0):
        nacelle = trimesh.creation.cylinder(radius=0.9, height=4.0, sections=24)
        nacelle.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, (0, 1, 0)))
        parts.append(nacelle.apply_translation((16.0, y, -0.4)))
    rng = np.random.default_rng(7)
    for _ in range(20):
        c = rng.uniform((-5, -15, -3), (45, 15, 8))
        parts.append(trimesh.Trimesh(c + rng.normal(0, 0.2, (3, 3)), [[0, 1, 2]], process=False))
    m = trimesh.util.concatenate(parts)
    m.apply_transform(np.diag([-1.0, -1.0, 1.0, 1.0]))  # nose towards -x (a half turn)
    m.apply_scale(14.7 / 37.6)
    return m


def main() -> None:
    write("paper_prism.stl", *shapes.paper_prism())
    write("wedge_prism.stl", *shapes.wedge_prism())
    write("fuselage_full.obj", *shapes.fuselage(scale=1.0))
    write("fuselage_model.obj", *shapes.fuselage(scale=0.1))
    dirty = dirty_aircraft()
    (HERE / "dirty").mkdir(exist_ok=True)  # apart from the clean meshes, which load as they are
    dirty.export(HERE / "dirty" / "dirty_aircraft.stl")
    print(f"dirty/dirty_aircraft.stl: {len(dirty.faces)} faces, open, several bodies")


if __name__ == "__main__":
    main()
