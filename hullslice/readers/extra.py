"""PLY, OFF, GLB/glTF and 3MF through trimesh, Gmsh ``.msh`` through meshio: the readers
of the optional extra ``hullslice[formats]``.

Each reader takes the bytes of the file (bounded by the size limit) and hands them to the
library as data, never as a path: no other file is opened (a glTF whose buffers are
separate files is refused: export it as ``.glb``), and a 3MF archive is refused when it
would unpack to more than :data:`~hullslice.readers.base.MAX_UNPACKED_BYTES` (counted as
its members are inflated, not as its directory says) or holds more model XML than
:data:`~hullslice.readers.base.MAX_3MF_MODEL_BYTES` (which bounds the parse's memory). The vertices
and faces are returned as in the file, without the library's own merging or repair, so that
hullslice's checks apply to them as to any other format.

What a format declares comes with them (:class:`~hullslice.readers.base.Conventions`): a
3MF's ``unit`` (millimetres when it names none, as the 3MF specification says; microns
are converted to millimetres), and glTF's axes, +Y up by its specification, with
coordinates stored as float32.
"""

from __future__ import annotations

import io
import json
import tempfile
import zipfile
from types import ModuleType
from typing import IO, Any

import numpy as np

from ..extras import need as _need
from .base import (
    MAX_3MF_MODEL_BYTES,
    MAX_UNPACKED_BYTES,
    NO_CONVENTIONS,
    Conventions,
    FormatError,
    Reader,
)

__all__ = ["EXTRA_READERS", "need", "require_format", "to_trimesh", "trimesh_arrays"]

#: What each format of the extra needs, by extension.
_NEEDS = {
    "ply": ("trimesh",),
    "off": ("trimesh",),
    "glb": ("trimesh",),
    "gltf": ("trimesh",),
    "3mf": ("trimesh", "lxml", "networkx"),
    "msh": ("meshio",),
}


def need(module: str, what: str) -> ModuleType:
    """Import an optional dependency, or raise the one-line hint naming what to install.

    Raises
    ------
    MissingDependencyError
        ``module`` is not installed.
    """
    return _need("formats", module, what)


def require_format(ext: str, writing: bool = False) -> None:
    """Import every library a format of the extra needs (none for STL, OBJ and .tri), or
    raise the one-line hint: before any work, for a file to read or (``writing``) write.

    Raises
    ------
    MissingDependencyError
        A library of the format is not installed.
    """
    key = ext.strip().lower().lstrip(".")
    what = "Gmsh .msh files" if key == "msh" else f"{key.upper()} files"
    for module in _NEEDS.get(key, ()):
        need(module, f"{'writing' if writing else 'reading'} {what}")


def _data(fh: IO[bytes], size: int) -> bytes:
    data = fh.read(size)
    if len(data) != size:
        raise FormatError(f"it holds {len(data)} bytes where {size} were expected")
    return data


def _check_zip(data: bytes) -> None:
    """Refuse a 3MF archive that is not a zip file, unpacks to too much, or holds more model
    XML than :data:`~hullslice.readers.base.MAX_3MF_MODEL_BYTES`.

    The directory's sizes are checked first (a quick refusal), then every member is
    inflated here in blocks, counting the bytes it gives and keeping none: a member that
    gives more than its directory entry says is cut at that size and fails its CRC check,
    so no more than the declared sizes, within the limits, is ever inflated, here or by
    trimesh after."""
    try:
        with zipfile.ZipFile(io.BytesIO(data)) as z:
            infos = z.infolist()
            unpacked = sum(i.file_size for i in infos)
            if unpacked > MAX_UNPACKED_BYTES:
                raise FormatError(
                    f"it unpacks to {unpacked / 1024**3:.1f} GiB, more than the "
                    f"{MAX_UNPACKED_BYTES / 1024**3:.0f} GiB hullslice reads: decimate the mesh"
                )
            _check_model_size(sum(i.file_size for i in infos if _is_model(i)))
            produced = model = 0
            for info in infos:
                with z.open(info) as member:
                    while block := member.read(1 << 20):
                        produced += len(block)
                        model += len(block) if _is_model(info) else 0
                        if produced > MAX_UNPACKED_BYTES:  # pragma: no cover - cut by zipfile
                            raise FormatError("it unpacks to more than its directory says")
                        _check_model_size(model)
    except (zipfile.BadZipFile, zipfile.LargeZipFile) as exc:
        raise FormatError(
            f"a 3MF is a zip archive and this one is not, or is corrupt ({exc}): a member "
            "gives other data than its directory entry says; export it again"
        ) from None
    except (ValueError, EOFError, OSError) as exc:
        if isinstance(exc, FormatError):
            raise
        raise FormatError(f"a 3MF is a zip archive and this one is not ({exc})") from None


def _is_model(info: zipfile.ZipInfo) -> bool:
    return info.filename.lower().endswith(".model")


def _check_model_size(size: int) -> None:
    if size > MAX_3MF_MODEL_BYTES:
        raise FormatError(
            f"its model XML is {size / 1024**2:.0f} MiB, more than the "
            f"{MAX_3MF_MODEL_BYTES / 1024**2:.0f} MiB hullslice parses (about 1.5 million "
            "triangles; parsing takes about 17 times the XML's size in memory): export the "
            "mesh as binary STL, or decimate it"
        )


def _check_gltf(data: bytes) -> None:
    """Refuse a glTF whose buffers are separate files (hullslice opens no other file)."""
    try:
        tree = json.loads(data)
    except (ValueError, UnicodeDecodeError) as exc:
        raise FormatError(f"a .gltf is JSON text and this one is not ({exc})") from None
    buffers = tree.get("buffers", []) if isinstance(tree, dict) else []
    for b in buffers if isinstance(buffers, list) else []:
        uri = b.get("uri") if isinstance(b, dict) else None
        if isinstance(uri, str) and not uri.startswith("data:"):
            raise FormatError(
                f"its buffer {uri[:60]!r} is a separate file, which hullslice does not "
                "open: export the mesh as .glb (one binary file) or with embedded buffers"
            )


#: A 3MF's ``unit`` attribute (its specification's names) to a length unit of hullslice
#: and the factor to it (microns are converted to millimetres).
_3MF_UNITS = {
    "micron": ("mm", 1e-3),
    "millimeter": ("mm", 1.0),
    "centimeter": ("cm", 1.0),
    "meter": ("m", 1.0),
    "inch": ("in", 1.0),
    "foot": ("ft", 1.0),
}


def _3mf_unit(mesh: Any) -> tuple[str, str, float]:
    """The unit a 3MF declares, as trimesh read it: (hullslice unit, the file's name for
    it, factor from the file's coordinates to that unit)."""
    meta = getattr(mesh, "metadata", None) or {}
    name = str(meta.get("units") or getattr(mesh, "units", None) or "millimeter")
    key = name.strip().lower()
    key = {"millimeters": "millimeter"}.get(key, key)  # trimesh's name for the default
    if key not in _3MF_UNITS:
        raise FormatError(
            f"its unit {name[:40]!r} is not one of the 3MF units ({', '.join(_3MF_UNITS)})"
        )
    unit, factor = _3MF_UNITS[key]
    return unit, key, factor


def _trimesh_reader(ext: str) -> Reader:
    def read(
        fh: IO[bytes], size: int
    ) -> tuple[np.ndarray, np.ndarray] | tuple[np.ndarray, np.ndarray, Conventions]:
        trimesh = need("trimesh", f"reading {ext.upper()} files")
        for module in _NEEDS[ext][1:]:
            need(module, f"reading {ext.upper()} files")
        data = _data(fh, size)
        if ext == "3mf":
            _check_zip(data)
        elif ext == "gltf":
            _check_gltf(data)
        try:
            mesh = trimesh.load(io.BytesIO(data), file_type=ext, force="mesh", process=False)
        except MemoryError:
            raise
        except Exception as exc:  # a third-party parser: any failure is the file's
            raise FormatError(f"trimesh cannot read it ({_reason(exc)})") from None
        v, f = trimesh_arrays(mesh)
        if ext == "3mf":
            unit, name, factor = _3mf_unit(mesh)
            return v * factor, f, Conventions(units=unit, unit_name=name)
        if ext in ("glb", "gltf"):  # glTF: metres, +Y up, float32 positions
            return v, f, Conventions(up="+y", float32=True)
        return v, f, NO_CONVENTIONS

    read.__doc__ = f"{ext.upper()} through trimesh (the extra hullslice[formats])."
    return read


def read_msh(fh: IO[bytes], size: int) -> tuple[np.ndarray, np.ndarray]:
    """Gmsh ``.msh`` (versions 2.2 and 4, ASCII or binary) through meshio: its triangles,
    or the boundary of its tetrahedra when it has no triangles."""
    need("meshio", "reading Gmsh .msh files")
    from meshio.gmsh.main import read_buffer

    try:
        fh.fileno()  # numpy reads meshio's blocks from a real file only
        _check_msh_counts(fh, size)
        mesh = _meshio_read(read_buffer, fh, size)
    except (OSError, AttributeError, io.UnsupportedOperation):
        with tempfile.TemporaryFile() as tmp:
            tmp.write(_data(fh, size))
            tmp.seek(0)
            _check_msh_counts(tmp, size)
            mesh = _meshio_read(read_buffer, tmp, size)
    tris = [c.data for c in mesh.cells if c.type == "triangle"]
    if tris:
        return np.asarray(mesh.points, dtype=np.float64), np.concatenate(tris).astype(np.int64)
    tets = [c.data for c in mesh.cells if c.type == "tetra"]
    if not tets:
        return np.asarray(mesh.points, dtype=np.float64), np.empty((0, 3), dtype=np.int64)
    v = np.asarray(mesh.points, dtype=np.float64)
    return v, _tet_boundary(v, np.concatenate(tets).astype(np.int64))


#: Fewest bytes a node takes in a Gmsh file (ASCII ``1 0 0 0`` and its line break).
_MSH_NODE_BYTES = 8
#: Header lines looked through for ``$Nodes`` (the sections before it are short).
_MSH_HEADER_LINES = 10_000
#: A file below this size that meshio runs out of memory on declares more than it holds.
_MSH_SMALL_BYTES = 64 * 1024**2


def _check_msh_counts(fh: IO[bytes], size: int) -> None:
    """Refuse a Gmsh file whose ``$Nodes`` section declares more nodes than its bytes can
    hold (meshio would allocate for the declared count first)."""
    start = fh.tell()
    try:
        for _ in range(_MSH_HEADER_LINES):
            line = fh.readline(4096)
            if not line:
                return
            if line.strip() == b"$Nodes":
                head = fh.readline(4096).split()
                try:
                    # 2.2: the count; 4: blocks, count, smallest and largest tag
                    n = int(head[1] if len(head) == 4 else head[0])
                except (ValueError, IndexError):
                    return  # meshio says what is wrong with it
                if n * _MSH_NODE_BYTES > size:
                    raise FormatError(
                        f"its $Nodes section declares {n} nodes, at least "
                        f"{n * _MSH_NODE_BYTES} bytes, but the file has {size} bytes: it is "
                        "cut short, or its counts are wrong; export it again"
                    )
                return
    finally:
        fh.seek(start)


def _meshio_read(read_buffer, fh, size: int) -> Any:
    try:
        return read_buffer(fh)
    except MemoryError:
        if size < _MSH_SMALL_BYTES:  # no file of this size needs the machine's memory
            raise FormatError(
                f"meshio ran out of memory on {size} bytes: the file declares more nodes or "
                "elements than it holds (cut short, or its counts are wrong); export it again"
            ) from None
        raise
    except Exception as exc:  # a third-party parser: any failure is the file's
        raise FormatError(f"meshio cannot read it as Gmsh ({_reason(exc)})") from None


def _tet_boundary(v: np.ndarray, tets: np.ndarray) -> np.ndarray:
    """The faces of ``tets`` that belong to one tetrahedron only, facing out."""
    if len(tets) and (tets.min() < 0 or tets.max() >= len(v)):
        raise FormatError("a tetrahedron refers to a node that does not exist")
    a, b, c, d = (v[tets[:, k]] for k in range(4))
    flip = np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) < 0
    tets = tets.copy()
    tets[flip, 2], tets[flip, 3] = tets[flip, 3], tets[flip, 2].copy()
    faces = tets[:, [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]]].reshape(-1, 3)
    _, inverse, count = np.unique(
        np.sort(faces, axis=1), axis=0, return_inverse=True, return_counts=True
    )
    return faces[count[inverse.ravel()] == 1]


def _reason(exc: BaseException) -> str:
    text = " ".join(str(exc).split())[:160]
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def trimesh_arrays(mesh: Any) -> tuple[np.ndarray, np.ndarray]:
    """The vertices and triangles of a ``trimesh.Trimesh`` (or of a ``trimesh.Scene``, its
    meshes placed and joined), as float64 and int64 arrays.

    Raises
    ------
    InputError
        ``mesh`` is neither.
    """
    from ..errors import InputError

    if hasattr(mesh, "graph") and hasattr(mesh, "dump"):  # a Scene: placed and joined
        mesh = mesh.to_geometry() if hasattr(mesh, "to_geometry") else mesh.dump(concatenate=True)
    if not (hasattr(mesh, "vertices") and hasattr(mesh, "faces")):
        raise InputError(
            f"expected a trimesh.Trimesh or trimesh.Scene, got {type(mesh).__name__}: give a "
            "triangle mesh"
        )
    v = np.array(mesh.vertices, dtype=np.float64).reshape(-1, 3)
    f = np.array(mesh.faces, dtype=np.int64).reshape(-1, 3)
    return v, f


def to_trimesh(vertices: np.ndarray, faces: np.ndarray) -> Any:
    """A ``trimesh.Trimesh`` of copies of the arrays, unprocessed (same vertex order)."""
    trimesh = need("trimesh", "Hull.to_trimesh")
    return trimesh.Trimesh(vertices=vertices.copy(), faces=faces.copy(), process=False)


#: The readers of the extra, by extension.
EXTRA_READERS: dict[str, Reader] = {
    **{ext: _trimesh_reader(ext) for ext in ("ply", "off", "glb", "gltf", "3mf")},
    "msh": read_msh,
}
