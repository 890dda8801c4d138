"""Mesh file readers, one module a format, in a table keyed by the file's extension.

:func:`read_mesh` reads a path or an open binary file with the reader of its format
(:data:`READERS`): only the geometry is read, by hullslice's own parsers; nothing in a file
is executed, no other file is opened, and memory stays in proportion to the file's size,
which is bounded by :data:`~hullslice.readers.base.MAX_FILE_BYTES` (a binary STL whose
header claims more triangles than the file holds is refused before anything is
allocated). The same checks apply whatever the format and however the file is given.

STL, OBJ and Cart3D ``.tri`` are read by hullslice's own parsers. PLY, OFF, GLB/glTF and
3MF (through trimesh) and Gmsh ``.msh`` (through meshio) are read with the optional extra
``hullslice[formats]`` (:mod:`hullslice.readers.extra`): without it such a file gives one
line naming what to install. Every format's vertices and faces then go through the same
checks and repairs.

A new format is a module with a function ``read(fh, size) -> (vertices, faces)`` (see
:class:`~hullslice.readers.base.Reader`) and a row in :data:`READERS`; a format that
declares its unit, axes or precision returns a third item,
:class:`~hullslice.readers.base.Conventions`, which :func:`read_mesh_file` passes on.
:func:`~hullslice.readers.write.write_mesh` writes a mesh back out.
"""

from __future__ import annotations

import io
import os
from dataclasses import replace
from pathlib import Path
from typing import IO, Any

import numpy as np

from ..errors import InputError, MeshError
from .base import MAX_FILE_BYTES, NO_CONVENTIONS, Conventions, FormatError, Reader
from .extra import EXTRA_READERS
from .obj import read_obj
from .stl import read_stl
from .tri import read_tri

__all__ = [
    "EXTRA_FORMATS",
    "MAX_FILE_BYTES",
    "READERS",
    "SUPPORTED_FORMATS",
    "Conventions",
    "Reader",
    "format_of",
    "read_mesh",
    "read_mesh_file",
    "source_name",
]

#: The reader of each format, by file extension (lower case, without the dot).
READERS: dict[str, Reader] = {"stl": read_stl, "obj": read_obj, "tri": read_tri, **EXTRA_READERS}

#: Formats read with the optional extra ``hullslice[formats]`` (trimesh, meshio).
EXTRA_FORMATS = tuple(EXTRA_READERS)

#: File formats :func:`~hullslice.load_hull` reads (by file extension).
SUPPORTED_FORMATS = tuple(READERS)

#: What a mesh can be read from: a path, or a file object open for binary reading.
MeshSource = str | os.PathLike | IO[bytes]


def _is_file(source: Any) -> bool:
    return hasattr(source, "read")


def source_name(source: MeshSource) -> str | None:
    """The file name of a mesh source: the path, or an open file's ``name`` (None when it
    has none, as a ``BytesIO``)."""
    if not _is_file(source):
        return str(source)
    name = getattr(source, "name", None)
    return str(name) if isinstance(name, (str, os.PathLike)) else None


def format_of(source: MeshSource, format: str | None = None) -> str:
    """The format of a mesh source: ``format`` when given, else the file name's extension.

    Raises
    ------
    InputError
        A file object without a name and no ``format``: nothing says how to read it.
    """
    if format is not None:
        return str(format).strip().lower().lstrip(".")
    name = source_name(source)
    if name is None:
        raise InputError(
            "a mesh given as an open file without a name needs its format: give "
            f"format= one of {', '.join(SUPPORTED_FORMATS)} (for instance format='stl')"
        )
    return Path(name).suffix.lower().lstrip(".")


def read_mesh(source: MeshSource, format: str | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Read the vertices and faces of a mesh file as they are in the file.

    Parameters
    ----------
    source : str, path-like or binary file object
        The mesh file, or a file open for reading in binary mode (``open(path, "rb")``,
        ``io.BytesIO``), read from its current position.
    format : str, optional
        One of :data:`SUPPORTED_FORMATS` (``"stl"``, ``"obj"``, ``"tri"``, and with the
        extra ``hullslice[formats]`` ``"ply"``, ``"off"``, ``"glb"``, ``"gltf"``, ``"3mf"``,
        ``"msh"``); default: the file name's extension.

    Returns
    -------
    vertices : (n, 3) float
    faces : (m, 3) int
        Triangles; an OBJ's polygons are split into fans of triangles.

    Raises
    ------
    MeshError
        The file is missing, not a file, of another format, empty, too large, malformed,
        or holds no triangles; the message says which and, for text formats, on what line.
    InputError
        A file object without a name and no ``format``, or one open in text mode.
    MissingDependencyError
        A format of the extra ``hullslice[formats]`` without it installed: the message
        names what to install.
    """
    v, f, _ = read_mesh_file(source, format)
    return v, f


def read_mesh_file(
    source: MeshSource, format: str | None = None
) -> tuple[np.ndarray, np.ndarray, Conventions]:
    """Read the vertices and faces of a mesh file, and what the file declares about them.

    As :func:`read_mesh`, with a third item: the file's
    :class:`~hullslice.readers.base.Conventions` (a 3MF's unit, glTF's +Y up, the float32
    precision of a binary STL or GLB). The vertices are float32 where the file stores
    single precision (a binary STL), float64 otherwise.
    """
    if not _is_file(source) and not str(os.fspath(source)).strip():  # type: ignore[arg-type]
        raise MeshError("mesh path is empty: give the path of a mesh file")
    label = source_name(source) or "(file object)"
    if not _is_file(source):
        path = Path(source)  # type: ignore[arg-type]
        if not path.exists():
            raise MeshError(f"mesh file {label!r} does not exist")
        if not path.is_file():
            raise MeshError(f"mesh path {label!r} is not a file: give the path of a mesh file")
    ext = format_of(source, format)
    if ext not in READERS:
        raise MeshError(
            f"mesh file {label!r} has format {ext or '(no extension)'!r}; "
            f"hullslice reads {', '.join(SUPPORTED_FORMATS)}: export the hull as STL or OBJ, "
            "or give format="
        )
    try:
        if _is_file(source):
            fh, size = _sized(source, label)  # type: ignore[arg-type]
            v, f, conventions = _read(READERS[ext], fh, size, label)
        else:
            size = Path(source).stat().st_size  # type: ignore[arg-type]
            _check_size(size, label)
            with open(source, "rb") as fh:  # type: ignore[arg-type]
                v, f, conventions = _read(READERS[ext], fh, size, label)
    except FormatError as exc:
        raise MeshError(f"mesh file {label!r} is not a valid {ext.upper()} file: {exc}") from None
    except OSError as exc:
        raise MeshError(f"mesh file {label!r} cannot be read: {exc.strerror or exc}") from None
    except MemoryError:
        raise MeshError(
            f"mesh file {label!r} needs more memory than this machine has: decimate the mesh"
        ) from None
    if len(v) == 0 or len(f) == 0:
        raise MeshError(
            f"mesh file {label!r} holds no triangles: is it a valid {ext.upper()} file?"
        )
    return v, f, conventions


def _check_size(size: int, label: str) -> None:
    if size == 0:
        raise MeshError(f"mesh file {label!r} is empty")
    if size > MAX_FILE_BYTES:
        raise MeshError(
            f"mesh file {label!r} is {size / 1024**3:.1f} GiB, more than the "
            f"{MAX_FILE_BYTES / 1024**3:.0f} GiB hullslice reads: decimate the mesh"
        )


def _read(
    reader: Reader, fh: IO[bytes], size: int, label: str
) -> tuple[np.ndarray, np.ndarray, Conventions]:
    head = fh.read(0)
    if not isinstance(head, bytes):
        raise InputError(
            f"mesh file {label!r} is open in text mode: open it in binary mode, open(path, 'rb')"
        )
    out = reader(fh, size)
    conventions = out[2] if len(out) == 3 else NO_CONVENTIONS
    if out[0].dtype == np.float32:
        conventions = replace(conventions, float32=True)
    return out[0], out[1], conventions


def _sized(fh: IO[bytes], label: str) -> tuple[IO[bytes], int]:
    """A file object and its bytes from the current position to the end, checked against
    the size limit; a stream that cannot seek is read (up to the limit) into memory."""
    try:
        start = fh.tell()
        end = fh.seek(0, io.SEEK_END)
        fh.seek(start)
        size = end - start
    except (OSError, AttributeError, ValueError):
        data = fh.read(MAX_FILE_BYTES + 1)
        if not isinstance(data, bytes):
            raise InputError(
                f"mesh file {label!r} is open in text mode: open it in binary mode, "
                "open(path, 'rb')"
            ) from None
        fh, size = io.BytesIO(data), len(data)
    _check_size(size, label)
    return fh, size
