"""Rebuild the sample meshes in this folder from their definitions in ``hullslice.shapes``.

    python meshes/make_meshes.py

paper_prism.stl   the paper's validation prism (L = 0.35 m, W = 0.2 m, deadrise 45 to 10 deg),
                  one station every 0.25 mm so that its twisted sides are that body
wedge_prism.stl   a prism of uniform 30-degree wedge section, 1 m long, 0.2 m beam
fuselage_full.obj a generic narrow-body transport fuselage, full scale (37.6 m, 3.95 m wide):
                  nose, constant section, upswept tail cone; x from the tail tip to the nose
fuselage_model.obj the same at 1:10 model scale (3.76 m)
"""

from __future__ import annotations

from pathlib import Path

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


def main() -> None:
    write("paper_prism.stl", *shapes.paper_prism())
    write("wedge_prism.stl", *shapes.wedge_prism())
    write("fuselage_full.obj", *shapes.fuselage(scale=1.0))
    write("fuselage_model.obj", *shapes.fuselage(scale=0.1))


if __name__ == "__main__":
    main()
