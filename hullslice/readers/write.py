"""Writing a mesh out: binary STL, OBJ and Cart3D ``.tri`` by hullslice, PLY, OFF, GLB and
3MF through trimesh (the extra ``hullslice[formats]``).

Every file is written completely or not at all (:func:`hullslice.atomic.write_atomic`).
OBJ and ``.tri`` hold every coordinate to the last bit (the shortest text that reads back
as the same float64); a binary STL holds float32, as the format does. Each file follows
its format's conventions: a 3MF declares the unit it is written in (``unit="meter"`` for
metres), a GLB is +Y up (the body's x forward stays +X, its z up becomes +Y), as their
specifications say, so that hullslice and other tools read them back the same.
"""

from __future__ import annotations

import io
import os
import zipfile
from collections.abc import Callable
from pathlib import Path

import numpy as np

from ..atomic import write_atomic
from ..axes import axis_matrix, unit_scale
from ..errors import InputError
from ..paths import printable
from .extra import _3MF_UNITS, to_trimesh
from .stl import _STL_RECORD

__all__ = ["WRITERS", "write_mesh"]


def _stl(v: np.ndarray, f: np.ndarray, name: str) -> bytes:
    corners = v[f]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    length = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.divide(normals, length, out=np.zeros_like(normals), where=length > 0)
    data = np.zeros(len(f), dtype=_STL_RECORD)  # the reader's own record
    data["normal"] = normals
    data["corners"] = corners
    header = f"hullslice mesh {printable(name)}".encode("ascii", "replace")[:80].ljust(80, b" ")
    return header + len(f).to_bytes(4, "little") + data.tobytes()


def _obj(v: np.ndarray, f: np.ndarray, name: str) -> str:
    lines = [f"# hullslice mesh {printable(name)}", f"o {printable(name).replace(' ', '_')}"]
    lines += [f"v {x!r} {y!r} {z!r}" for x, y, z in v.tolist()]
    lines += [f"f {i} {j} {k}" for i, j, k in (f + 1).tolist()]
    return "\n".join(lines) + "\n"


def _tri(v: np.ndarray, f: np.ndarray, name: str) -> str:
    lines = [f"{len(v)} {len(f)}"]
    lines += [f"{x!r} {y!r} {z!r}" for x, y, z in v.tolist()]
    lines += [f"{i} {j} {k}" for i, j, k in (f + 1).tolist()]
    lines += ["1"] * len(f)  # one component
    return "\n".join(lines) + "\n"


#: hullslice's length units by their 3MF names (the ``unit`` a written 3MF declares).
_3MF_UNIT_NAMES = {unit: name for name, (unit, factor) in _3MF_UNITS.items() if factor == 1.0}


def _declare_3mf_unit(data: bytes, units: str) -> bytes:
    """The 3MF archive ``data`` (written by trimesh, which always declares millimetres)
    with its model declaring ``units`` instead."""
    unit = _3MF_UNIT_NAMES[units]
    out = io.BytesIO()
    with zipfile.ZipFile(io.BytesIO(data)) as zin, zipfile.ZipFile(out, "w") as zout:
        for item in zin.infolist():
            content = zin.read(item.filename)
            if item.filename.lower().endswith(".model"):
                content = content.replace(b'unit="millimeter"', f'unit="{unit}"'.encode(), 1)
            zout.writestr(item, content)
    return out.getvalue()


def _with_trimesh(ext: str) -> Callable[..., bytes | str]:
    def write(v: np.ndarray, f: np.ndarray, name: str, units: str = "m") -> bytes | str:
        from .extra import need

        if ext == "3mf":
            need("lxml", "writing 3MF files")
            need("networkx", "writing 3MF files")
        if ext == "glb":  # glTF is +Y up: mesh = R^T body, R taking a +Y-up mesh to the body
            v = v @ axis_matrix("+x", "+y")
        options = {"digits": 17} if ext == "off" else {}
        out = to_trimesh(v, f).export(file_type=ext, **options)
        out = out if isinstance(out, (bytes, str)) else bytes(out)
        if ext == "3mf":
            out = _declare_3mf_unit(out.encode() if isinstance(out, str) else out, units)
        return out

    return write


#: The writer of each format, by file extension: ``(vertices, faces, name)`` to the
#: file's bytes or text (the 3MF writer also takes the unit written, to declare it).
WRITERS: dict[str, Callable[..., bytes | str]] = {
    "stl": _stl,
    "obj": _obj,
    "tri": _tri,
    **{ext: _with_trimesh(ext) for ext in ("ply", "off", "glb", "3mf")},
}


def write_mesh(
    vertices: np.ndarray,
    faces: np.ndarray,
    path: str | os.PathLike,
    format: str | None = None,
    *,
    name: str = "hull",
    units: str = "m",
) -> Path:
    """Write a triangle mesh to a file, completely or not at all.

    Parameters
    ----------
    vertices : (n, 3) float
        Vertex coordinates in m.
    faces : (m, 3) int
        Triangles as indices into ``vertices``.
    path : str or path-like
        The file to write; its extension gives the format unless ``format`` does.
    format : str, optional
        ``stl`` (binary, float32), ``obj``, ``tri`` (Cart3D), or with the extra
        ``hullslice[formats]`` ``ply``, ``off``, ``glb`` (+Y up, as glTF is), ``3mf``
        (declaring ``units``).
    name : str
        The mesh's name, in the file's header where the format has one.
    units : str
        Length unit of the coordinates written: ``m, cm, mm, in, ft`` (default ``m``).

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    InputError
        A format hullslice does not write, or a path that cannot be written.
    MissingDependencyError
        A format of the extra without trimesh installed.
    """
    ext = (format or Path(path).suffix).strip().lower().lstrip(".")
    if ext not in WRITERS:
        raise InputError(
            f"cannot write {printable(path)!r}: hullslice writes meshes as "
            f"{', '.join(WRITERS)} (by the file's extension); name it .stl or .obj"
        )
    v = np.asarray(vertices, dtype=np.float64) / unit_scale(units)
    f = np.asarray(faces, dtype=np.int64)
    key = str(units).strip().lower()
    data = WRITERS[ext](v, f, name, key) if ext == "3mf" else WRITERS[ext](v, f, name)
    try:
        return write_atomic(path, data)
    except OSError as exc:
        raise InputError(f"cannot write {printable(path)!r}: {exc.strerror or exc}") from None
