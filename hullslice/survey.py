"""An open or welded mesh described shell by shell, without loading it as a hull.

``hullslice info`` on a mesh that is not one closed surface (:class:`~hullslice.errors.
OpenMeshError`: holes, or parts welded at an edge) lists its shells instead of refusing it,
so that the shells to keep can be chosen before ``--repair close``: for each shell its
faces, its box, its open edges, whether ``--repair close`` would close it and the volume
it would then enclose. The shells are what the repair works on
(:func:`hullslice.repair.close.shell_outcomes`: copies of a vertex that differ by rounding
stitched, a shell that does not close with the parts welded to it split), and those that
would close are numbered by that volume, largest first, as ``--repair close --keep N``
numbers the bodies.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO

import numpy as np

from .axes import axis_matrix
from .errors import InputError
from .limits import check_precision
from .prepare import check_scale
from .readers import read_mesh_file, source_name
from .readers.conventions import resolve_conventions
from .repair.close import shell_outcomes
from .topology import edge_use, unique_rows

__all__ = ["Shell", "Survey", "survey_mesh"]


@dataclass(frozen=True)
class Shell:
    """One shell of a mesh, in m and the body frame.

    Attributes
    ----------
    number : int or None
        The body number ``--repair close --keep N`` would give it (1 the largest volume
        once closed); None for a shell that would be dropped.
    faces : int
        Its triangles.
    open_edges : int
        Its edges with a single face.
    closes : bool or None
        ``--repair close`` would close it (True also for a shell closed already); None when
        that is unknown (pymeshfix not installed).
    volume : float or None
        The volume it encloses once closed, m^3 (None when it would not close).
    inside_out : bool
        It is wound inside out (the repair turns it outward).
    bounds_min, bounds_max : (3,) float
        Its box, m.
    """

    number: int | None
    faces: int
    open_edges: int
    closes: bool | None
    volume: float | None
    inside_out: bool
    bounds_min: tuple[float, float, float]
    bounds_max: tuple[float, float, float]

    @property
    def extents(self) -> tuple[float, float, float]:
        lo, hi = self.bounds_min, self.bounds_max
        return (hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2])

    def as_dict(self) -> dict:
        return {
            "number": self.number,
            "faces": self.faces,
            "open_edges": self.open_edges,
            "closes": self.closes,
            "volume": self.volume,
            "inside_out": self.inside_out,
            "bounds_min": list(self.bounds_min),
            "bounds_max": list(self.bounds_max),
            "extents": list(self.extents),
        }


@dataclass(frozen=True)
class Survey:
    """A mesh file that is not one closed surface, described shell by shell.

    ``vertices`` and ``faces`` are the whole mesh in m and the body frame (copies of a
    vertex merged), for the views; ``shells`` the shells, those that would close first.
    """

    name: str
    path: str | None
    units: str
    forward: str
    up: str
    scale: float
    reason: str
    vertices: np.ndarray
    faces: np.ndarray
    open_edges: int
    nonmanifold_edges: int
    stitched: int
    fill_known: bool
    shells: list[Shell] = field(default_factory=list)

    @property
    def bounds(self) -> np.ndarray:
        """(2, 3) float: the lowest and highest corners of the whole mesh, m."""
        used = self.vertices[np.unique(self.faces)]
        return np.array([used.min(axis=0), used.max(axis=0)])


def survey_mesh(
    path: str | os.PathLike | IO[bytes],
    *,
    units: str | None = None,
    forward: str | None = None,
    up: str | None = None,
    scale: float | None = None,
    length: float | None = None,
    format: str | None = None,
    reason: str = "",
) -> Survey:
    """Read a mesh file and describe its shells (see the module's documentation).

    Parameters
    ----------
    path, units, forward, up, scale, length, format
        As :func:`hullslice.load_hull` takes them (``length`` is the whole mesh's extent
        along ``forward``).
    reason : str
        Why the mesh was not loaded as a hull (the loader's message), kept on the survey.

    Raises
    ------
    MeshError
        The file cannot be read, or holds no triangle.
    InputError
        A bad unit, axis, scale or length.
    """
    file_name = source_name(path)
    name = Path(file_name).stem if file_name else "hull"
    v, f, declared = read_mesh_file(path, format)
    units, forward, up = resolve_conventions(declared, name, units=units, forward=forward,
                                             up=up, length=length)  # fmt: skip
    unit, scale, length = check_scale(units, scale, length)
    unit_text = units if scale is None and length is None else "file units"
    check_precision(v, f, name, float32=declared.float32, unit=unit_text)
    v, inverse = unique_rows(np.asarray(v, dtype=np.float64))
    f = inverse[np.asarray(f, dtype=np.int64)]
    rot = axis_matrix(forward, up)
    if length is not None:
        extent = float(np.ptp(v[np.unique(f)] @ rot[0]))
        if extent <= 0.0:
            raise InputError(f"mesh {name!r} has no extent along {forward!r}: check --forward")
        factor = length / extent
    else:
        factor = unit * (scale if scale is not None else 1.0)
    body = (v * factor) @ rot.T
    counts, _ = edge_use(f)
    outcomes, stitched, fill_known = shell_outcomes(body, f)
    closing = sorted((o for o in outcomes if o.closes), key=lambda o: -(o.volume or 0.0))
    rest = sorted(
        (o for o in outcomes if not o.closes), key=lambda o: -float(np.linalg.norm(o.extents))
    )
    shells = [_shell(o, i + 1, True) for i, o in enumerate(closing)]
    shells += [_shell(o, None, False if fill_known or not o.open_edges else None) for o in rest]
    return Survey(
        name=name,
        path=str(Path(file_name)) if file_name else None,
        units=str(units),
        forward=str(forward),
        up=str(up),
        scale=factor,
        reason=reason,
        vertices=body,
        faces=f,
        open_edges=int((counts == 1).sum()),
        nonmanifold_edges=int((counts > 2).sum()),
        stitched=stitched,
        fill_known=fill_known,
        shells=shells,
    )


def _shell(o, number: int | None, closes: bool | None) -> Shell:
    used = o.vertices[np.unique(o.faces)]
    lo, hi = used.min(axis=0), used.max(axis=0)
    return Shell(
        number=number,
        faces=len(o.faces),
        open_edges=o.open_edges,
        closes=closes,
        volume=o.volume,
        inside_out=o.flipped,
        bounds_min=(float(lo[0]), float(lo[1]), float(lo[2])),
        bounds_max=(float(hi[0]), float(hi[1]), float(hi[2])),
    )
