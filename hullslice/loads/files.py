"""Files of the structural loads that finite-element and post-processing tools read.

:func:`write_loads` writes a run's face pressures and frame loads into a folder:

``pressure.pvd`` and ``pressure_NNNNN.vtu``
    The mesh (in its own frame, m) at each kept instant with the face field ``pressure``
    (Pa), VTK XML written by meshio; ParaView opens the ``.pvd`` as a time series.
``peak.vtu``
    The mesh with ``peak_pressure`` (Pa), the largest pressure of each face over the kept
    instants, and ``peak_time`` (s; -1 on a face that stays dry).
``faces.csv``
    One row per face: its index, centroid ``x, y, z`` (m, the mesh's frame), unit outward
    normal ``nx, ny, nz`` and area (m^2).
``face_pressures.csv``
    One row per kept instant and wetted face: ``t`` (s), ``face`` and ``pressure`` (Pa).
    With ``faces.csv`` this is the load any finite-element pre-processor can map onto its
    own elements (by nearest centroid or by projection). Nastran ``PLOAD4`` cards are not
    written: they name the finite-element model's own element numbers, which the hull's
    mesh does not know.
``frames.csv``
    With frames given: ``t`` (s), ``bay``, ``x_aft``, ``x_fore`` (m), ``vertical`` and
    ``horizontal`` (N), the frame bays' loads (:mod:`hullslice.loads.frames`).
``loads.json``
    What is in the folder: the instants, the units, the run's solver and the mapping.

Only one instant's face pressures are held in memory at a time.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np

from .._version import __version__
from ..extras import need
from .faces import FacePeak, face_geometry
from .frames import FrameLoads

__all__ = ["MANIFEST", "require_meshio", "write_loads"]

#: The name of the file that says a folder holds hullslice's loads.
MANIFEST = "loads.json"


def require_meshio():
    """meshio, or the one-line install hint."""
    return need("formats", "meshio", "--pressures-out (the face pressures' VTK files)")


def _vtu(meshio, hull, path: Path, fields: dict[str, np.ndarray]) -> None:
    mesh = meshio.Mesh(
        np.asarray(hull.vertices, dtype=np.float64),
        [("triangle", np.asarray(hull.faces, dtype=np.int64))],
        cell_data={k: [np.asarray(v, dtype=np.float64)] for k, v in fields.items()},
    )
    meshio.write(str(path), mesh, file_format="vtu")


def _pvd(entries: list[tuple[float, str]]) -> str:
    rows = "\n".join(
        f'    <DataSet timestep="{t!r}" group="" part="0" file="{name}"/>' for t, name in entries
    )
    return (
        '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n'
        f"{rows}\n  </Collection>\n</VTKFile>\n"
    )


def write_loads(history, hull, folder: str | os.PathLike, frames: FrameLoads | None = None):
    """Write a run's face pressures (and frame loads) into ``folder`` (which exists).

    Parameters
    ----------
    history : History
        A run that kept its sections with a solver that gives pressures.
    hull : Hull
        Its body.
    folder : path
        Where to write (see the module notes for the files).
    frames : FrameLoads, optional
        The frame bays' loads to write as ``frames.csv``.

    Returns
    -------
    files : list of str
        The files written, relative to ``folder``.
    peak : FacePeak
        Each face's peak pressure over the instants and its time.
    """
    meshio = require_meshio()
    out = Path(folder)
    geom = face_geometry(hull)
    written: list[str] = []
    n = len(geom)
    peak = FacePeak(n)
    entries: list[tuple[float, str]] = []
    with open(out / "face_pressures.csv", "w", encoding="utf-8", newline="") as table:
        table.write("t,face,pressure\n")
        for i, fp in enumerate(history.face_pressures(hull)):
            name = f"pressure_{i:05d}.vtu"
            _vtu(meshio, hull, out / name, {"pressure": fp.pressure})
            entries.append((fp.t, name))
            wet = np.nonzero(fp.pressure)[0]
            rows = np.column_stack([np.full(len(wet), fp.t), wet, fp.pressure[wet]])
            np.savetxt(table, rows, fmt=("%.9g", "%d", "%.9g"), delimiter=",")
            peak.add(fp)
    written += [name for _, name in entries] + ["face_pressures.csv"]
    (out / "pressure.pvd").write_text(_pvd(entries), encoding="utf-8")
    when = np.where(np.isnan(peak.t), -1.0, peak.t)
    _vtu(meshio, hull, out / "peak.vtu", {"peak_pressure": peak.pressure, "peak_time": when})
    faces = np.column_stack([np.arange(n), geom.centroid, geom.normal, geom.area])
    header = "face,x,y,z,nx,ny,nz,area"
    np.savetxt(out / "faces.csv", faces, fmt=["%d"] + ["%.9g"] * 7, delimiter=",",
               header=header, comments="")  # fmt: skip
    written += ["pressure.pvd", "peak.vtu", "faces.csv"]
    if frames is not None:
        with open(out / "frames.csv", "w", encoding="utf-8", newline="") as f:
            f.write(",".join(frames.COLUMNS) + "\n")
            for r in frames.records():
                f.write(",".join(repr(r[c]) if c != "bay" else str(r[c]) for c in frames.COLUMNS))
                f.write("\n")
        written.append("frames.csv")
    manifest = {
        "hullslice": __version__,
        "mesh": hull.name,
        "faces": n,
        "instants": [t for t, _ in entries],
        "solver": history.settings.get("solver"),
        "solver_options": history.settings.get("solver_options"),
        "units": {"pressure": "Pa", "t": "s", "length": "m", "area": "m^2", "load": "N"},
        "mapping": "each face: the mean of its section's pressure over the face, linear "
        "between stations, plus the hydrostatic pressure where the slices hold it",
        "files": written,
    }
    text = json.dumps(manifest, indent=1, default=str)
    (out / MANIFEST).write_text(text + "\n", encoding="utf-8")
    return [*written, MANIFEST], peak
