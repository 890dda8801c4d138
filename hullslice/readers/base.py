"""What every mesh reader shares: the error a reader raises and the size limit.

A reader is a function ``read(fh, size) -> (vertices, faces)`` of an open binary file
positioned at the start of the mesh and the number of bytes from there to its end; it
raises :class:`FormatError` with the reason (without the file's name) when the file does
not follow its format. :func:`hullslice.readers.read_mesh` adds the name and turns the
reason into a :class:`~hullslice.errors.MeshError`.
"""

from __future__ import annotations

from typing import IO, Protocol

import numpy as np

__all__ = ["MAX_FILE_BYTES", "MAX_UNPACKED_BYTES", "FormatError", "Reader"]

#: Largest file :func:`~hullslice.load_hull` reads, in bytes (about 4 GiB holds a 80M-face
#: binary STL).
MAX_FILE_BYTES = 4 * 1024**3

#: Largest total a compressed mesh file (a 3MF zip archive) may unpack to, in bytes.
MAX_UNPACKED_BYTES = MAX_FILE_BYTES


class FormatError(ValueError):
    """A mesh file does not follow its format (the reason, without the file name)."""


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
    """

    def __call__(self, fh: IO[bytes], size: int) -> tuple[np.ndarray, np.ndarray]: ...
