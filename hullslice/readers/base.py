"""What every mesh reader shares: the error a reader raises and the size limit.

A reader is a function ``read(fh, size) -> (vertices, faces)`` of an open binary file
positioned at the start of the mesh and the number of bytes from there to its end; it
raises :class:`FormatError` with the reason (without the file's name) when the file does
not follow its format. :func:`hullslice.readers.read_mesh` adds the name and turns the
reason into a :class:`~hullslice.errors.MeshError`. A reader of a format that declares its
conventions (a 3MF its unit, glTF its up axis, a binary file its precision) returns them as
a third item, :class:`Conventions`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import IO, Protocol

import numpy as np

__all__ = [
    "MAX_3MF_MODEL_BYTES",
    "MAX_FILE_BYTES",
    "MAX_UNPACKED_BYTES",
    "NO_CONVENTIONS",
    "Conventions",
    "FormatError",
    "Reader",
]

#: Largest file :func:`~hullslice.load_hull` reads, in bytes (about 4 GiB holds a 80M-face
#: binary STL).
MAX_FILE_BYTES = 4 * 1024**3

#: Largest total a compressed mesh file (a 3MF zip archive) may unpack to, in bytes.
MAX_UNPACKED_BYTES = MAX_FILE_BYTES

#: Largest total of a 3MF's model XML (its ``.model`` parts), in bytes: parsed, each object's
#: XML takes about 17 times its size in memory (trimesh and lxml: 0.5 GB for the 28 MB of
#: 330 thousand triangles), so this bounds the parse at about 2 GB; it holds about 1.5
#: million triangles. A larger mesh is read as binary STL (50 bytes a triangle, no parse).
MAX_3MF_MODEL_BYTES = 128 * 1024**2


class FormatError(ValueError):
    """A mesh file does not follow its format (the reason, without the file name)."""


@dataclass(frozen=True)
class Conventions:
    """What a mesh file declares about its coordinates (None: the format says nothing).

    Attributes
    ----------
    units : str, optional
        The length unit the file declares, a name of
        :data:`~hullslice.constants.LENGTH_UNITS` (a 3MF's ``unit``; glTF is in metres).
    unit_name : str, optional
        The unit as the file names it, for messages (``"millimeter"``).
    up, forward : str, optional
        The axes the format declares up and forward (glTF: ``+y`` up).
    float32 : bool
        The file stores its coordinates in single precision (binary STL, GLB).
    """

    units: str | None = None
    unit_name: str | None = None
    up: str | None = None
    forward: str | None = None
    float32: bool = False


#: Nothing declared.
NO_CONVENTIONS = Conventions()


class Reader(Protocol):
    """Reads one mesh format.

    Parameters
    ----------
    fh : binary file
        Open for reading, at the start of the mesh.
    size : int
        Bytes from there to the end of the file (at most :data:`MAX_FILE_BYTES`).

    Returns
    -------
    vertices : (n, 3) float
        As in the file (its units and axes).
    faces : (m, 3) int
        Triangles as indices into ``vertices`` (any index may be out of range: the hull's
        checks report it).
    conventions : Conventions, optional
        A third item, from a format that declares its unit, axes or precision.
    """

    def __call__(
        self, fh: IO[bytes], size: int
    ) -> tuple[np.ndarray, np.ndarray] | tuple[np.ndarray, np.ndarray, Conventions]: ...
