"""Loading a hull mesh: a mesh file to an immutable :class:`Hull` in SI units and the body frame.

The body frame (:mod:`hullslice.axes`): ``x`` forward, ``y`` to port, ``z`` up, metres.
Files are read by :mod:`hullslice.readers` and prepared by :mod:`hullslice.prepare`; every
hull is checked, safely repaired (``fix=False`` refuses instead) and converted to a
manifold3d ``Manifold`` by :mod:`hullslice.repair.passes`.
"""

from __future__ import annotations

import functools
import os
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import IO

import numpy as np

from .axes import axis_matrix, unit_scale
from .caching import Cache
from .errors import MeshError, MeshRepairWarning
from .limits import check_cg_near_body, check_density, check_precision, no_mass
from .mass import MassDistribution, MassProperties, fit_to_body
from .paths import printable
from .prepare import prepare_arrays
from .readers import MAX_FILE_BYTES as MAX_FILE_BYTES
from .readers import SUPPORTED_FORMATS, read_mesh, read_mesh_file, source_name
from .readers.conventions import resolve_conventions
from .repair.passes import check_and_repair
from .topology import (
    check_finite,
    merge_exact_copies,
    second_moment,
    to_manifold,
    unique_edges,
    volume_centroid,
)

__all__ = ["SUPPORTED_FORMATS", "Hull", "axis_matrix", "load_hull", "read_mesh"]

_to_manifold = to_manifold


def _readonly(a: np.ndarray) -> np.ndarray:
    a.flags.writeable = False
    return a


class Hull:
    """An immutable closed body in SI units and in the body frame.

    Use :func:`load_hull` to read one from a file, or :meth:`Hull.from_arrays` for arrays.

    Parameters
    ----------
    vertices : (n, 3) float
        Vertex coordinates in metres, body frame (x forward, y port, z up).
    faces : (m, 3) int
        Triangles as indices into ``vertices``, counter-clockwise seen from outside.
    mass : float, optional
        Mass of the body in kg. Needed for mass per metre and forces.
    name : str
        A name for reports (the file name when loaded from a file).
    source : dict, optional
        How the mesh was read: path, units, forward and up axes, repairs made.
    mass_distribution, cg, inertia
        The other mass properties, see :class:`~hullslice.MassProperties` (``cg`` is
        ``(x, z)`` or ``(x, y, z)``, m).
    mass_properties : MassProperties, optional
        All of them in one, instead of the four keywords (giving both is an ``InputError``).
    fix : bool
        False: make none of the safe repairs (:mod:`hullslice.repair.passes`); a mesh that
        needs one raises a ``MeshError`` naming the repair. Default True.

    Notes
    -----
    The constructor checks the mesh and repairs what can be repaired safely (see the
    module's documentation); the arrays it stores are float64/int64 and read-only.
    """

    def __init__(
        self,
        vertices: np.ndarray,
        faces: np.ndarray,
        *,
        mass: float | None = None,
        name: str = "hull",
        source: dict | None = None,
        mass_distribution: MassDistribution | None = None,
        cg: Sequence[float] | None = None,
        inertia: float | None = None,
        mass_properties: MassProperties | None = None,
        fix: bool = True,
    ) -> None:
        v, f, manifold, repairs = check_and_repair(vertices, faces, name, fix=fix)
        self._vertices = _readonly(v)
        self._faces = _readonly(f)
        self._manifold = manifold
        self.name = printable(name)  # one line of visible text, whatever the file was called
        src = dict(source or {})
        src["repairs"] = tuple(src.get("repairs", ())) + tuple(repairs)
        self.source = src
        self.cache = Cache()  # what the layers above compute about this body
        self._set_mass(MassProperties.from_keywords(
            mass_properties, mass=mass, mass_distribution=mass_distribution, cg=cg,
            inertia=inertia))  # fmt: skip

    def _set_mass(self, props: MassProperties) -> None:
        self.mass_properties = props
        self.mass = props.mass
        dist = props.distribution  # checked against the body, and spread along it
        self.mass_distribution = dist and fit_to_body(dist, self.bounds, self.centroid[2],
                                                      self.name)  # fmt: skip
        if props.cg is not None:
            check_cg_near_body(props.cg, self.bounds, self.name)
        self._cg_given = props.cg
        self._inertia_given = props.inertia
        if self.mass is not None and props.distribution is None:
            check_density(self.mass, self.volume, self.source.get("units", "m"), self.name)

    @functools.cached_property
    def mass_properties(self) -> MassProperties:
        """The mass properties as given (set on construction; rebuilt after a pickle)."""
        return MassProperties(
            self.mass, self.mass_distribution, self._cg_given, self._inertia_given
        )

    # -- construction -------------------------------------------------------------------

    @classmethod
    def from_arrays(
        cls,
        vertices: np.ndarray,
        faces: np.ndarray,
        *,
        units: str = "m",
        forward: str = "+x",
        up: str = "+z",
        mass: float | None = None,
        name: str = "hull",
        mass_distribution: MassDistribution | None = None,
        cg: Sequence[float] | None = None,
        inertia: float | None = None,
        mass_properties: MassProperties | None = None,
        fix: bool = True,
        source: dict | None = None,
    ) -> Hull:
        """Build a hull from mesh arrays given in any length unit and axis orientation.

        Parameters
        ----------
        vertices : (n, 3) float
            Vertex coordinates in ``units``, mesh axes.
        faces : (m, 3) int
            Triangle vertex indices.
        units : str
            Length unit of the coordinates: ``m, cm, mm, in, ft`` (default ``m``).
        forward, up : str
            Mesh axes pointing forward and up (defaults ``+x`` and ``+z``).
        mass : float, optional
            Body mass in kg.
        name : str
            Name for reports.
        mass_distribution, cg, inertia, mass_properties
            Mass properties, see :meth:`Hull.with_mass` (SI, body frame).
        fix : bool
            False: make no safe repair, refuse a mesh that needs one (see :class:`Hull`).
        source : dict, optional
            More entries for the hull's ``source``, after the units and axes.
        """
        scale = unit_scale(units)
        rot = axis_matrix(forward, up)
        v = np.asarray(vertices, dtype=np.float64)
        if v.ndim != 2 or v.shape[1] != 3:
            raise MeshError(f"mesh {name!r}: vertices have shape {v.shape}, expected (n, 3)")
        check_finite(v, name)  # before the transform spreads a NaN to a vertex's 3 values
        # exact duplicates first (every STL is a triangle soup): fewer rows to transform
        v, faces = merge_exact_copies(v, faces)
        v = (v * scale) @ rot.T
        src = {"units": str(units), "forward": str(forward), "up": str(up), **(source or {})}
        return cls(
            v, faces, mass=mass, name=name, source=src, mass_distribution=mass_distribution,
            cg=cg, inertia=inertia, mass_properties=mass_properties, fix=fix,
        )  # fmt: skip

    @classmethod
    def from_trimesh(cls, mesh, **kwargs) -> Hull:
        """Build a hull from a ``trimesh.Trimesh`` (or a ``trimesh.Scene``, its meshes placed
        and joined), checked and repaired as a file is.

        ``mesh`` is in ``units`` and mesh axes; ``kwargs`` are those of
        :meth:`Hull.from_arrays` (``units``, ``forward``, ``up``, ``mass``, ``name``, ...).
        """
        from .readers.extra import trimesh_arrays

        return cls.from_arrays(*trimesh_arrays(mesh), **kwargs)

    def to_trimesh(self):
        """The checked and repaired body as a ``trimesh.Trimesh`` in m, body frame (copies
        of :attr:`vertices` and :attr:`faces`, in their order). Needs trimesh (``pip
        install 'hullslice[formats]'``)."""
        from .readers.extra import to_trimesh

        return to_trimesh(self._vertices, self._faces)

    def save(self, path: str | os.PathLike, format: str | None = None, units: str = "m") -> Path:
        """Write the checked and repaired mesh, completely or not at all, in the body frame.

        Parameters
        ----------
        path : str or path-like
            The file; its extension gives the format: ``.stl`` (binary), ``.obj``, ``.tri``
            (Cart3D), and with ``hullslice[formats]`` ``.ply``, ``.off``, ``.glb``, ``.3mf``.
        format : str, optional
            The format, instead of the extension.
        units : str
            Length unit of the coordinates written: ``m, cm, mm, in, ft`` (default ``m``).
        """
        from .readers.write import write_mesh

        return write_mesh(self._vertices, self._faces, path, format, name=self.name, units=units)

    def with_mass(
        self,
        mass: float | None = None,
        *,
        mass_distribution: MassDistribution | None = None,
        cg: Sequence[float] | None = None,
        inertia: float | None = None,
        mass_properties: MassProperties | None = None,
    ) -> Hull:
        """The same body with other mass properties (a new hull; this one is unchanged).

        Parameters
        ----------
        mass : float, optional
            Mass in kg (default: the distribution's total).
        mass_distribution : MassDistribution, optional
            Mass along the body (default: uniform over the volume).
        cg : (float, float) or (float, float, float), optional
            Centre of gravity ``x, z`` (``y = 0``) or ``x, y, z`` in m, body frame
            (default: from the distribution, or the centre of volume).
        inertia : float, optional
            Pitch moment of inertia about the centre of gravity, kg m^2 (default: from the
            distribution, or the mesh with uniform density).
        mass_properties : MassProperties, optional
            All of these in one (not with the keywords).
        """
        new = object.__new__(Hull)
        new.__dict__.update({k: self.__dict__[k] for k in _GEOMETRY if k in self.__dict__})
        new.cache = self.cache.geometry()  # the same geometry: its caches are shared
        new._set_mass(
            MassProperties.from_keywords(
                mass_properties, mass=mass, mass_distribution=mass_distribution, cg=cg,
                inertia=inertia,
            )
        )  # fmt: skip
        return new

    # -- geometry -------------------------------------------------------------------------

    @property
    def vertices(self) -> np.ndarray:
        """(n, 3) float: vertex coordinates in m, body frame (read-only)."""
        return self._vertices

    @property
    def faces(self) -> np.ndarray:
        """(m, 3) int: triangle vertex indices (read-only)."""
        return self._faces

    @property
    def manifold(self):
        """The hull as a ``manifold3d.Manifold`` in the body frame."""
        return self._manifold

    @functools.cached_property
    def bounds(self) -> np.ndarray:
        """(2, 3) float: lowest and highest corner of the bounding box, in m."""
        return _readonly(np.array([self._vertices.min(axis=0), self._vertices.max(axis=0)]))

    @property
    def extents(self) -> np.ndarray:
        """(3,) float: length, beam and height of the bounding box, in m."""
        return self.bounds[1] - self.bounds[0]

    @functools.cached_property
    def size(self) -> float:
        """Diagonal of the bounding box in m: the length scale of the tolerances."""
        return float(np.linalg.norm(self.extents))

    @functools.cached_property
    def edges(self) -> np.ndarray:
        """(e, 2) int: the unique undirected edges as vertex index pairs (low, high)."""
        return _readonly(unique_edges(self._faces, len(self._vertices)))

    @functools.cached_property
    def volume(self) -> float:
        """Enclosed volume in m^3."""
        return float(self._manifold.volume())

    @functools.cached_property
    def centroid(self) -> np.ndarray:
        """(3,) float: centre of volume in m, body frame."""
        return _readonly(volume_centroid(self._vertices, self._faces))

    @functools.cached_property
    def cg(self) -> np.ndarray:
        """(3,) float: centre of gravity in m, body frame.

        Given, or from the mass distribution (its line density at the height of the centre
        of volume unless it says otherwise), or the centre of volume (uniform density).
        """
        c = self.centroid.copy()
        if self._cg_given is not None:
            c = self._cg_given.copy()
        elif self.mass_distribution is not None:
            c[[0, 2]] = self.mass_distribution.cg(line_z=self.centroid[2])
        return _readonly(c)

    @functools.cached_property
    def pitch_inertia(self) -> float:
        """Moment of inertia about the pitch axis (``y``) through the centre of gravity, kg m^2.

        Given, or from the mass distribution, or from the mesh with uniform density.
        """
        if self._inertia_given is not None:
            return self._inertia_given
        if self.mass is None:
            raise no_mass(self.name)
        if self.mass_distribution is not None:
            return self.mass_distribution.pitch_inertia(self.cg[[0, 2]], self.centroid[2])
        second = self._second_moment(self.cg)
        return float(self.mass / self.volume * (second[0, 0] + second[2, 2]))

    def _second_moment(self, origin: np.ndarray) -> np.ndarray:
        """(3, 3) float: the volume integrals of ``r_i r_j`` with ``r = v - origin``, m^5."""
        return second_moment(self._vertices, self._faces, origin)

    def mass_per_metre_at(self, x: np.ndarray) -> np.ndarray | None:
        """Mass per metre of body length at body stations ``x`` (m) from the mass
        distribution, kg/m; None when the mass is spread uniformly over the volume."""
        if self.mass_distribution is None:
            return None
        return self.mass_distribution.at(x)

    @property
    def density(self) -> float | None:
        """Mean density in kg/m^3 (mass / volume), or None without a mass."""
        return None if self.mass is None else self.mass / self.volume

    def __getstate__(self) -> dict:
        """Pickled: the arrays, name, source and mass properties; the ``Manifold`` (which
        cannot be pickled) is rebuilt from the arrays, and the caches refill on use."""
        return {k: self.__dict__[k] for k in _PICKLED if k in self.__dict__}

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)
        self.cache = Cache()
        self._manifold = _to_manifold(self._vertices.copy(), self._faces.copy(), self.name)
        self._vertices, self._faces = _readonly(self._vertices), _readonly(self._faces)

    def __repr__(self) -> str:
        mass = "no mass" if self.mass is None else f"{self.mass:g} kg"
        L, B, H = self.extents
        return (
            f"<Hull {self.name!r}: {len(self._faces)} faces, "
            f"{L:.4g} x {B:.4g} x {H:.4g} m, {self.volume:.6g} m^3, {mass}>"
        )


#: Cached attributes that depend on the geometry only (kept by Hull.with_mass); and what
#: a pickled hull holds (see Hull.__getstate__).
_GEOMETRY = ("_vertices", "_faces", "_manifold", "name", "source", "bounds", "size", "volume",
             "centroid", "edges")  # fmt: skip
_PICKLED = ("_vertices", "_faces", "name", "source", "mass", "mass_distribution", "_cg_given",
            "_inertia_given")  # fmt: skip


def load_hull(
    path: str | os.PathLike | IO[bytes],
    *,
    units: str | None = None,
    forward: str | None = None,
    up: str | None = None,
    mass: float | None = None,
    mass_distribution: MassDistribution | None = None,
    cg: Sequence[float] | None = None,
    inertia: float | None = None,
    scale: float | None = None,
    length: float | None = None,
    repair: str | None = None,
    keep: str | int | Sequence[int] | None = None,
    keep_box: Sequence[float] | str | None = None,
    format: str | None = None,
    mass_properties: MassProperties | None = None,
    fix: bool = True,
) -> Hull:
    """Read a mesh file into a :class:`Hull` (the formats of :data:`SUPPORTED_FORMATS`).

    Parameters
    ----------
    path : str, path-like or binary file object
        The mesh file, or a file open in binary mode; the extension of its name (``.stl``,
        ``.obj``, ``.tri``; ``.ply``, ``.off``, ``.glb``, ``.gltf``, ``.3mf``, ``.msh`` with
        the extra ``hullslice[formats]``) gives the format unless ``format`` does.
    units, forward, up : str, optional
        Length unit of the file's coordinates (``m, cm, mm, in, ft``), mesh axes pointing
        forward and up. Default: what the file declares, with a warning naming it (a 3MF's
        ``unit``, glTF's ``+y`` up), else ``m``, ``+x``, ``+z``.
    mass : float, optional
        Body mass in kg.
    mass_distribution : MassDistribution, optional
        Mass along the body in the body frame (SI), instead of a uniform density.
    cg : (float, float) or (float, float, float), optional
        Centre of gravity ``x, z`` (``y = 0``) or ``x, y, z`` in m, body frame.
    inertia : float, optional
        Pitch moment of inertia about the centre of gravity in kg m^2.
    scale : float, optional
        Metres per file unit (times the unit's when ``units`` is given too): 0.0254 for
        inches, 2.56 for a model whose 14.7 units are 37.6 m. Not with ``length``.
    length : float, optional
        The body's extent along ``forward`` in m (after ``keep``); the scale follows from
        it. Not with ``scale``, nor with ``units`` other than ``m``.
    repair : str, optional
        ``"close"``: fill the holes of an open mesh and drop the shells that cannot be
        closed, with a :class:`MeshRepairWarning` giving the figures (needs ``pymeshfix``,
        the extra ``hullslice[repair]``). Default ``None``: an open mesh is refused.
    keep : str, int or sequence of int, optional
        The bodies (shells) to keep: ``"largest"``, or numbers from 1, largest first
        (``hullslice info`` lists them; ``hull.source["bodies"]`` too). Default: all.
    keep_box : six floats or str, optional
        ``xmin, xmax, ymin, ymax, zmin, zmax`` in m, body frame after scaling: only the
        part of the body inside this box is kept (cut by manifold3d).
    format : str, optional
        The format (``"stl"``, ``"obj"``, ...): needed for a file object without a name.
    mass_properties : MassProperties, optional
        All four mass properties in one (not with their keywords).
    fix : bool
        False (``--no-fix``): make no safe repair, refuse a mesh that needs one (see
        :class:`Hull`).

    Returns
    -------
    Hull
        Its ``source`` records the scale (``"scale"``, m per file unit), the bodies
        (``"bodies"``), those kept (``"kept"``) and every repair (``"repairs"``).

    Raises
    ------
    MeshError
        The file is missing, empty, not a mesh, not a closed 2-manifold body, or float32 too
        far from the origin for its size (:func:`~hullslice.limits.check_precision`).
    InputError
        A bad option (unknown unit or axis, non-positive mass, scale or length, a body number
        the mesh does not have, a box that keeps nothing), or a file object without a format.
    """
    file_name = source_name(path)
    name = Path(file_name).stem if file_name else "hull"
    v, f, declared = read_mesh_file(path, format)
    units, forward, up = resolve_conventions(declared, name, units=units, forward=forward,
                                             up=up, length=length)  # fmt: skip
    unit = units if scale is None and length is None else "file units"
    check_precision(v, f, name, float32=declared.float32, unit=unit)
    prep = prepare_arrays(
        v, f, name, units=units, scale=scale, length=length, forward=forward, up=up,
        repair=repair, keep=keep,
    )  # fmt: skip
    box = None
    if keep_box is not None:
        from .parts import parse_box

        box = parse_box(keep_box)
    props = MassProperties.from_keywords(
        mass_properties, mass=mass, mass_distribution=mass_distribution, cg=cg, inertia=inertia
    )
    source = {
        "repairs": tuple(prep.notes), "scale": prep.scale, "bodies": prep.bodies,
        "kept": prep.kept, "path": str(Path(file_name)) if file_name else None,
    }  # fmt: skip
    hull = Hull.from_arrays(
        prep.vertices, prep.faces, units=units, forward=forward, up=up, name=name,
        mass_properties=props if box is None else None, fix=fix, source=source,
    )  # fmt: skip
    if box is not None:
        hull = _cut_to_box(hull, box, props, fix)
    return hull


def _cut_to_box(hull: Hull, box: np.ndarray, props: MassProperties, fix: bool) -> Hull:
    """The part of ``hull`` inside ``box`` (m, body frame), with the mass properties."""
    from .parts import box_note, cut_to_box

    v, f, inside, whole = cut_to_box(hull.vertices, hull.faces, hull.manifold, box, hull.name)
    note = box_note(box, inside, whole)
    warnings.warn(f"mesh {hull.name!r}: {note}", MeshRepairWarning, stacklevel=3)
    source = dict(hull.source)
    source["repairs"] = (*source.get("repairs", ()), note)
    return Hull(v, f, name=hull.name, source=source, mass_properties=props, fix=fix)
