"""Loading a hull mesh: STL/OBJ to an immutable :class:`Hull` in SI units and the body frame.

The body frame is the mesh's own coordinates after the axis mapping and unit scale:
``x`` forward along the body, ``y`` to port, ``z`` up (right-handed). Every hull is checked
and converted to a manifold3d ``Manifold`` on loading; what manifold3d refuses becomes a
:class:`~hullslice.errors.MeshError` that says what is wrong, and what can be repaired
without guessing is repaired with a :class:`~hullslice.errors.MeshRepairWarning`.
"""

from __future__ import annotations

import functools
import os
import re
import warnings
from array import array
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .caching import Cache
from .constants import AXES, LENGTH_UNITS, TOL
from .errors import InputError, MeshError, MeshRepairWarning, UnitsWarning
from .integrity import check_sections_match_volume
from .limits import no_mass
from .mass import MassDistribution
from .paths import printable

__all__ = ["SUPPORTED_FORMATS", "Hull", "axis_matrix", "load_hull"]

#: File formats :func:`load_hull` reads (by file extension).
SUPPORTED_FORMATS = ("stl", "obj")

#: Largest file :func:`load_hull` reads, in bytes (about 4 GiB holds a 80M-face binary STL).
MAX_FILE_BYTES = 4 * 1024**3

# Densities outside this range (kg/m^3) are not a plausible body for a water-impact study:
# lighter than air means a mesh in mm read as metres, denser than osmium the reverse.
_PLAUSIBLE_DENSITY = (1.0, 25000.0)

# the length units by name, the most common in hull and CAD files first
_UNIT_NAMES = {
    "m": "metres",
    "mm": "millimetres",
    "cm": "centimetres",
    "in": "inches",
    "ft": "feet",
}


def _readonly(a: np.ndarray) -> np.ndarray:
    a.flags.writeable = False
    return a


def axis_matrix(forward: str = "+x", up: str = "+z") -> np.ndarray:
    """Rotation taking mesh coordinates to the body frame.

    Parameters
    ----------
    forward, up : str
        Which mesh axis points forward along the body and which points up, each one of
        ``+x, -x, +y, -y, +z, -z`` (a bare ``x`` means ``+x``).

    Returns
    -------
    (3, 3) float
        Matrix ``R`` with ``body = R @ mesh``; its rows are the body's x (forward),
        y (port = up x forward) and z (up) axes in mesh coordinates. ``det(R) = +1``.
    """
    f = _axis(forward, "forward")
    u = _axis(up, "up")
    if abs(float(np.dot(f, u))) > 0.5:
        raise InputError(
            f"forward axis {forward!r} and up axis {up!r} are not perpendicular: "
            "choose two different mesh axes (for instance forward='+x', up='+z')"
        )
    return np.array([f, np.cross(u, f), u])


def _axis(name: str, role: str) -> np.ndarray:
    key = str(name).strip().lower()
    if key in ("x", "y", "z"):
        key = "+" + key
    if key not in AXES:
        raise InputError(f"{role} axis {name!r} is not one of {', '.join(AXES)}")
    return np.array(AXES[key])


def _unit_scale(units: str) -> float:
    try:
        return LENGTH_UNITS[str(units).strip().lower()]
    except KeyError:
        raise InputError(f"length unit {units!r} is not one of {', '.join(LENGTH_UNITS)}") from None


def _check_mass(mass: float | None) -> float | None:
    if mass is None:
        return None
    try:
        m = float(mass)
    except (TypeError, ValueError):
        raise InputError(f"mass {mass!r} is not a number: give the body's mass in kg") from None
    if not np.isfinite(m) or m <= 0.0:
        raise InputError(f"mass {mass!r} kg is not positive: give the body's mass in kg")
    return m


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
    ) -> None:
        v, f, manifold, repairs = _checked_mesh(vertices, faces, name)
        self._vertices = _readonly(v)
        self._faces = _readonly(f)
        self._manifold = manifold
        self.name = printable(name)  # one line of visible text, whatever the file was called
        src = dict(source or {})
        src["repairs"] = tuple(src.get("repairs", ())) + tuple(repairs)
        self.source = src
        self.cache = Cache()  # what the layers above compute about this body
        self._set_mass(mass, mass_distribution, cg, inertia)

    def _set_mass(self, mass, distribution, cg, inertia) -> None:
        mass = _check_mass(mass)
        if distribution is not None:
            if not isinstance(distribution, MassDistribution):
                raise InputError("mass_distribution must be a hullslice.MassDistribution")
            total = distribution.total
            if mass is None:
                mass = total
            elif abs(total - mass) > 0.005 * mass:
                raise InputError(
                    f"the mass distribution adds up to {total:.6g} kg but the mass is given as "
                    f"{mass:.6g} kg: give one of them, or make them agree within 0.5 %"
                )
        self.mass = mass
        self.mass_distribution = distribution
        if cg is not None:
            c = np.asarray(cg, dtype=np.float64).ravel()
            if c.shape != (2,) or not np.all(np.isfinite(c)):
                raise InputError(f"cg {cg!r} is not two numbers x, z (m, body frame)")
            cg = c
        self._cg_given = cg
        if inertia is not None:
            i = float(inertia)
            if not (np.isfinite(i) and i > 0):
                raise InputError(f"pitch inertia {inertia!r} kg m^2 is not positive")
            inertia = i
        self._inertia_given = inertia
        if self.mass is not None and distribution is None:
            _check_density(self)

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
        mass_distribution, cg, inertia
            Mass properties, see :meth:`Hull.with_mass` (SI, body frame).
        """
        scale = _unit_scale(units)
        rot = axis_matrix(forward, up)
        v = np.asarray(vertices, dtype=np.float64)
        if v.ndim != 2 or v.shape[1] != 3:
            raise MeshError(f"mesh {name!r}: vertices have shape {v.shape}, expected (n, 3)")
        _check_finite(v, name)  # before the transform spreads a NaN to a vertex's 3 values
        f = np.asarray(faces)
        if len(v) and np.isfinite(v).all() and f.ndim == 2 and np.issubdtype(f.dtype, np.integer):
            # exact duplicates first (every STL is a triangle soup): fewer rows to transform
            v, inverse = _unique_rows(v)
            if f.size and f.min() >= 0 and f.max() < len(inverse):
                faces = inverse[f]
            else:  # leave the bad indices for the checks to report
                v = np.asarray(vertices, dtype=np.float64)
        v = (v * scale) @ rot.T
        src = {"units": str(units), "forward": str(forward), "up": str(up)}
        return cls(
            v,
            faces,
            mass=mass,
            name=name,
            source=src,
            mass_distribution=mass_distribution,
            cg=cg,
            inertia=inertia,
        )

    def with_mass(
        self,
        mass: float | None = None,
        *,
        mass_distribution: MassDistribution | None = None,
        cg: Sequence[float] | None = None,
        inertia: float | None = None,
    ) -> Hull:
        """The same body with other mass properties (a new hull; this one is unchanged).

        Parameters
        ----------
        mass : float, optional
            Mass in kg (default: the distribution's total).
        mass_distribution : MassDistribution, optional
            Mass along the body (default: uniform over the volume).
        cg : (float, float), optional
            Centre of gravity ``x, z`` in m, body frame (default: from the distribution,
            or the centre of volume).
        inertia : float, optional
            Pitch moment of inertia about the centre of gravity, kg m^2 (default: from the
            distribution, or the mesh with uniform density).
        """
        new = object.__new__(Hull)
        new.__dict__.update({k: self.__dict__[k] for k in _GEOMETRY if k in self.__dict__})
        new.cache = self.cache.geometry()  # the same geometry: its caches are shared
        new._set_mass(mass, mass_distribution, cg, inertia)
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
        n = len(self._vertices)
        e = np.sort(self._faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
        key = np.unique(e[:, 0] * n + e[:, 1])
        return _readonly(np.stack([key // n, key % n], axis=1))

    @functools.cached_property
    def volume(self) -> float:
        """Enclosed volume in m^3."""
        return float(self._manifold.volume())

    @functools.cached_property
    def centroid(self) -> np.ndarray:
        """(3,) float: centre of volume in m, body frame."""
        tri = self._vertices[self._faces]
        # signed volumes of the tetrahedra (origin, triangle), shifted for accuracy
        o = self._vertices.mean(axis=0)
        a, b, c = tri[:, 0] - o, tri[:, 1] - o, tri[:, 2] - o
        vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
        cen = (a + b + c) / 4.0
        return _readonly(o + (vol[:, None] * cen).sum(axis=0) / vol.sum())

    @functools.cached_property
    def cg(self) -> np.ndarray:
        """(3,) float: centre of gravity in m, body frame.

        Given, or from the mass distribution (its line density at the height of the centre
        of volume unless it says otherwise), or the centre of volume (uniform density).
        """
        c = self.centroid.copy()
        if self._cg_given is not None:
            c[[0, 2]] = self._cg_given
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
        tri = self._vertices[self._faces] - origin
        a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
        vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
        # tetrahedron (0, a, b, c): integral of r r^T = V/20 (sum v v^T + s s^T), s = a + b + c
        s = a + b + c
        outer = (
            np.einsum("i,ij,ik->jk", vol, a, a)
            + np.einsum("i,ij,ik->jk", vol, b, b)
            + np.einsum("i,ij,ik->jk", vol, c, c)
            + np.einsum("i,ij,ik->jk", vol, s, s)
        )
        return outer / 20.0

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


#: Cached attributes that depend on the geometry only (kept by Hull.with_mass).
_GEOMETRY = (
    "_vertices",
    "_faces",
    "_manifold",
    "name",
    "source",
    "bounds",
    "size",
    "volume",
    "centroid",
    "edges",
)


#: What a pickled hull holds (see Hull.__getstate__).
_PICKLED = (
    "_vertices",
    "_faces",
    "name",
    "source",
    "mass",
    "mass_distribution",
    "_cg_given",
    "_inertia_given",
)


def _check_density(hull: Hull) -> None:
    rho = hull.density
    lo, hi = _PLAUSIBLE_DENSITY
    if rho is None or lo <= rho <= hi:
        return
    units = str(hull.source.get("units", "m")).strip().lower()
    scale = LENGTH_UNITS.get(units, 1.0)
    # the density the same mass would have if the file were in each of the other units;
    # the plausible ones are named, the most common unit first
    plausible = {
        u: rho * (scale / LENGTH_UNITS[u]) ** 3
        for u in _UNIT_NAMES
        if u != units and lo <= rho * (scale / LENGTH_UNITS[u]) ** 3 <= hi
    }
    if plausible:
        u, *others = plausible
        hint = (
            f"if the mesh is in {_UNIT_NAMES[u]}, give its units (units={u!r}, --units {u}): "
            f"the density is then {plausible[u]:.4g} kg/m^3"
        )
        if others:
            hint += (
                " (in "
                + ", ".join(f"{_UNIT_NAMES[o]} {plausible[o]:.4g} kg/m^3" for o in others)
                + ")"
            )
    else:
        hint = "check the mass and the mesh's units"
    warnings.warn(
        f"hull {hull.name!r}: mass {hull.mass:g} kg in a volume of {hull.volume:.6g} m^3 "
        f"(units {units!r}) is a density of {rho:.4g} kg/m^3, implausible for a body; "
        f"{hint}",
        UnitsWarning,
        stacklevel=3,
    )


# -- reading files ---------------------------------------------------------------------------


def load_hull(
    path: str | os.PathLike,
    *,
    units: str = "m",
    forward: str = "+x",
    up: str = "+z",
    mass: float | None = None,
    mass_distribution: MassDistribution | None = None,
    cg: Sequence[float] | None = None,
    inertia: float | None = None,
    scale: float | None = None,
    length: float | None = None,
    repair: str | None = None,
    keep: str | int | Sequence[int] | None = None,
    keep_box: Sequence[float] | str | None = None,
) -> Hull:
    """Read an STL or OBJ file into a :class:`Hull`.

    Parameters
    ----------
    path : str or path-like
        The mesh file; its extension (``.stl`` or ``.obj``) gives the format.
    units : str
        Length unit of the file's coordinates: ``m, cm, mm, in, ft`` (default ``m``).
    forward : str
        Mesh axis pointing forward along the body (default ``+x``).
    up : str
        Mesh axis pointing up (default ``+z``).
    mass : float, optional
        Body mass in kg.
    mass_distribution : MassDistribution, optional
        Mass along the body in the body frame (SI), instead of a uniform density.
    cg : (float, float), optional
        Centre of gravity ``x, z`` in m, body frame.
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

    Returns
    -------
    Hull
        Its ``source`` records the scale (``"scale"``, m per file unit), the bodies
        (``"bodies"``), those kept (``"kept"``) and every repair (``"repairs"``).

    Raises
    ------
    MeshError
        The file is missing, empty, not a mesh, or not a closed 2-manifold body.
    InputError
        A bad option (unknown unit or axis, non-positive mass, scale or length, a body
        number the mesh does not have, a box that keeps nothing).
    """
    from .prepare import prepare_arrays

    p = Path(path)
    v, f = read_mesh(p)
    prep = prepare_arrays(
        v, f, p.stem, units=units, scale=scale, length=length, forward=forward, up=up,
        repair=repair, keep=keep,
    )  # fmt: skip
    box = None
    if keep_box is not None:
        from .parts import parse_box

        box = parse_box(keep_box)
    mass_options: dict[str, Any] = {
        "mass": mass, "mass_distribution": mass_distribution, "cg": cg, "inertia": inertia
    }  # fmt: skip
    hull = Hull.from_arrays(
        prep.vertices,
        prep.faces,
        units=units,
        forward=forward,
        up=up,
        name=p.stem,
        **({} if box is not None else mass_options),
    )
    if box is not None:
        hull = _cut_to_box(hull, box, mass_options)
    hull.source.update(
        units=str(units), scale=prep.scale, bodies=prep.bodies, kept=prep.kept, path=str(p)
    )
    hull.source["repairs"] = tuple(prep.notes) + tuple(hull.source["repairs"])
    return hull


def _cut_to_box(hull: Hull, box: np.ndarray, mass_options: dict) -> Hull:
    """The part of ``hull`` inside ``box`` (m, body frame), with the mass options."""
    from .parts import cut_to_box

    v, f, inside, whole = cut_to_box(hull.vertices, hull.faces, hull.manifold, box, hull.name)
    lo, hi = box
    note = (
        f"kept the part inside the box x {lo[0]:g} to {hi[0]:g}, y {lo[1]:g} to {hi[1]:g}, "
        f"z {lo[2]:g} to {hi[2]:g} m: {inside:.6g} of {whole:.6g} m^3"
    )
    warnings.warn(f"mesh {hull.name!r}: {note}", MeshRepairWarning, stacklevel=3)
    source = dict(hull.source)
    source["repairs"] = (*source.get("repairs", ()), note)
    return Hull(v, f, name=hull.name, source=source, **mass_options)


def read_mesh(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """Read the vertices and faces of a mesh file as they are in the file.

    Only the geometry of the two mesh formats is read, by hullslice's own parsers: nothing
    in a file is executed, no other file is opened (an OBJ's ``mtllib`` materials and
    textures are ignored), and memory stays in proportion to the file's size, which is
    bounded by :data:`MAX_FILE_BYTES` (a binary STL whose header claims more triangles than
    the file holds is refused before anything is allocated).

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
    """
    if not path.exists():
        raise MeshError(f"mesh file {str(path)!r} does not exist")
    if not path.is_file():
        raise MeshError(f"mesh path {str(path)!r} is not a file: give the path of an STL or OBJ")
    ext = path.suffix.lower().lstrip(".")
    if ext not in SUPPORTED_FORMATS:
        raise MeshError(
            f"mesh file {str(path)!r} has format {ext or '(no extension)'!r}; "
            f"hullslice reads {', '.join(SUPPORTED_FORMATS)}: export the hull as STL or OBJ"
        )
    size = path.stat().st_size
    if size == 0:
        raise MeshError(f"mesh file {str(path)!r} is empty")
    if size > MAX_FILE_BYTES:
        raise MeshError(
            f"mesh file {str(path)!r} is {size / 1024**3:.1f} GiB, more than the "
            f"{MAX_FILE_BYTES / 1024**3:.0f} GiB hullslice reads: decimate the mesh"
        )
    try:
        with open(path, "rb") as fh:
            v, f = _READERS[ext](fh, size)
    except _FormatError as exc:
        raise MeshError(
            f"mesh file {str(path)!r} is not a valid {ext.upper()} file: {exc}"
        ) from None
    except OSError as exc:
        raise MeshError(f"mesh file {str(path)!r} cannot be read: {exc.strerror or exc}") from None
    except MemoryError:
        raise MeshError(
            f"mesh file {str(path)!r} needs more memory than this machine has: decimate the mesh"
        ) from None
    if len(v) == 0 or len(f) == 0:
        raise MeshError(
            f"mesh file {str(path)!r} holds no triangles: is it a valid {ext.upper()} file?"
        )
    return v, f


class _FormatError(ValueError):
    """A mesh file does not follow its format (the reason, without the file name)."""


#: Binary STL: an 80-byte header, a little-endian uint32 triangle count, then 50 bytes per
#: triangle (normal, three corners as float32, a 2-byte attribute).
_STL_HEAD = 84
_STL_RECORD = np.dtype([("normal", "<f4", (3,)), ("corners", "<f4", (3, 3)), ("attr", "<u2")])

#: Longest OBJ statement read, in bytes (with its continuation lines): a vertex or a face
#: of a few thousand corners is far shorter; a longer one is not geometry, and reading it
#: whole would cost memory out of proportion.
_MAX_OBJ_LINE = 1024**2

#: Largest vertex index an OBJ face may hold (more vertices than any file can hold).
_MAX_INDEX = 2**40

_STL_VERTEX = re.compile(rb"\bvertex\s+(\S+)\s+(\S+)\s+(\S+)")


def _read_stl(fh, size: int) -> tuple[np.ndarray, np.ndarray]:
    """Binary or ASCII STL: a binary file's size must be exactly 84 + 50 n bytes."""
    head = fh.read(_STL_HEAD)
    claimed = int.from_bytes(head[80:84], "little") if len(head) == _STL_HEAD else None
    if claimed is not None and size == _STL_HEAD + _STL_RECORD.itemsize * claimed:
        data = np.frombuffer(fh.read(), dtype=_STL_RECORD, count=claimed)
        v = data["corners"].reshape(-1, 3).astype(np.float64)
        return v, np.arange(len(v), dtype=np.int64).reshape(-1, 3)
    binary = (
        f"as a binary STL its header claims {claimed} triangles "
        f"({_STL_HEAD + _STL_RECORD.itemsize * claimed} bytes) but the file has {size} bytes"
        if claimed is not None
        else f"at {size} bytes it is shorter than a binary STL's 84-byte header"
    )
    if not head.lstrip()[:5].lower() == b"solid":
        raise _FormatError(
            f"{binary}, and it does not start with 'solid' as an ASCII STL does "
            "(a truncated file, or another format)"
        )
    return _parse_ascii_stl(fh, head, binary)


#: Bytes of an ASCII STL parsed at a time (cut at a line end): memory stays bounded.
_STL_CHUNK = 16 * 1024**2


def _parse_ascii_stl(fh, head: bytes, binary: str) -> tuple[np.ndarray, np.ndarray]:
    coords = array("d")
    loops = 0
    rest = head
    while True:
        block = fh.read(_STL_CHUNK)
        data = rest + block
        if block:  # keep the last, perhaps partial, line for the next chunk
            cut = data.rfind(b"\n") + 1
            data, rest = data[:cut], data[cut:]
        if b"\0" in data:
            raise _FormatError(
                f"it starts with 'solid' but holds binary data; {binary} (a truncated file?)"
            )
        data = data.lower()
        corners = _STL_VERTEX.findall(data)
        loops += data.count(b"endloop")
        try:
            coords.extend(np.array(corners, dtype=np.float64).ravel())
        except ValueError:
            bad = next(t for c in corners for t in c if not _is_float(t))
            raise _FormatError(
                f"vertex coordinate {bad.decode('latin-1')!r} is not a number"
            ) from None
        if not block:
            break
    v = np.frombuffer(coords, dtype=np.float64).reshape(-1, 3).copy()
    if len(v) != 3 * loops:
        raise _FormatError(
            f"ASCII STL with {len(v)} vertex lines in {loops} facets: every facet needs "
            "exactly three (a truncated or hand-edited file?)"
        )
    return v, np.arange(len(v), dtype=np.int64).reshape(-1, 3)


def _is_float(token: bytes) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def _read_obj(fh, size: int) -> tuple[np.ndarray, np.ndarray]:
    """Wavefront OBJ: the ``v`` and ``f`` statements; everything else is ignored.

    Polygons are split into fans of triangles; indices count from 1, negative ones back
    from the last vertex read so far (the OBJ rules). ``mtllib``, ``usemtl``, normals,
    texture coordinates, groups and objects are skipped: all faces form the one body. The
    file is read line by line into typed arrays (24 bytes a vertex or a triangle, less
    than their text).
    """
    verts = array("d")
    tris = array("q")
    tri_lines = array("q")
    pending: list[str] = []  # the pieces of a statement continued over several lines
    pending_bytes = 0
    lines = iter(lambda: fh.readline(_MAX_OBJ_LINE + 1), b"")
    for lineno, raw in enumerate(lines, start=1):
        if b"\0" in raw:
            raise _FormatError(f"line {lineno} holds binary data; an OBJ is a text file")
        pending_bytes += len(raw)
        if pending_bytes > _MAX_OBJ_LINE:
            raise _FormatError(
                f"line {lineno}: a statement longer than {_MAX_OBJ_LINE // 1024**2} MiB (with "
                "its continuation lines); an OBJ statement is a vertex or a face"
            )
        if lineno == 1 and raw.startswith(b"\xef\xbb\xbf"):  # a UTF-8 byte-order mark
            raw = raw[3:]
        line = raw.decode("utf-8", errors="replace").rstrip("\r\n")
        if line.endswith("\\"):  # continued on the next line
            pending.append(line[:-1])
            continue
        if pending:
            line = " ".join([*pending, line])  # joined once: linear in the statement's length
            pending.clear()
        pending_bytes = 0
        parts = line.split("#", 1)[0].split()
        if not parts:
            continue
        key = parts[0]
        if key == "v":
            try:
                verts.extend([float(t) for t in parts[1:4]] if len(parts) >= 4 else ())
            except ValueError:
                raise _FormatError(
                    f"line {lineno}: {line.strip()[:60]!r} is not a vertex 'v x y z'"
                ) from None
            if len(parts) < 4:
                raise _FormatError(
                    f"line {lineno}: {line.strip()[:60]!r} is not a vertex 'v x y z'"
                )
        elif key == "f":
            if len(parts) < 4:
                raise _FormatError(
                    f"line {lineno}: {line.strip()[:60]!r} has fewer than three corners"
                )
            idx = []
            n_verts = len(verts) // 3
            for token in parts[1:]:
                try:
                    i = int(token.split("/", 1)[0])
                except ValueError:
                    raise _FormatError(
                        f"line {lineno}: face corner {token[:30]!r} is not a vertex index"
                    ) from None
                if i == 0 or abs(i) > _MAX_INDEX:
                    raise _FormatError(
                        f"line {lineno}: face index {i} does not exist (OBJ counts vertices "
                        "from 1); the file is corrupt"
                    )
                idx.append(i - 1 if i > 0 else n_verts + i)
            for k in range(1, len(idx) - 1):
                tris.extend((idx[0], idx[k], idx[k + 1]))
                tri_lines.append(lineno)
    v = np.frombuffer(verts, dtype=np.float64).reshape(-1, 3)
    f = np.frombuffer(tris, dtype=np.int64).reshape(-1, 3)
    bad = (f < 0) | (f >= len(v))
    if bad.any():
        k = int(np.flatnonzero(bad.any(axis=1))[0])
        raise _FormatError(
            f"line {tri_lines[k]}: a face refers to a vertex that does not exist (the file "
            f"has {len(v)} vertices); the file is corrupt"
        )
    return v.copy(), f.copy()


_READERS = {"stl": _read_stl, "obj": _read_obj}


# -- checking and repairing a mesh ----------------------------------------------------------


def _group(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Group equal keys: one index of each group, the group of every key, the group sizes.

    Like ``np.unique(..., return_index, return_inverse, return_counts)`` but with an
    unstable sort, several times faster on millions of keys.
    """
    order = np.argsort(keys)
    sk = keys[order]
    start = np.empty(len(sk), dtype=bool)
    start[:1] = True
    np.not_equal(sk[1:], sk[:-1], out=start[1:])
    group = np.cumsum(start) - 1
    inverse = np.empty(len(keys), dtype=np.int64)
    inverse[order] = group
    bounds = np.append(np.flatnonzero(start), len(sk))
    return order[start], inverse, np.diff(bounds)


def _edge_use(faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """How many faces use each undirected edge, and how many of them run from low to high index.

    In a closed, consistently oriented surface every edge is used twice, once each way.
    """
    directed = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    lo = directed.min(axis=1)
    hi = directed.max(axis=1)
    _, inverse, counts = _group(lo * (int(faces.max()) + 1) + hi)
    n_forward = np.bincount(inverse, weights=directed[:, 0] < directed[:, 1])
    return counts, n_forward


def _unique_rows(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Exactly equal rows of an (n, 3) float array merged: unique rows and the inverse index.

    Rows are hashed to one 64-bit integer each (a 1D sort is much faster than a sort of
    rows); a hash collision, checked for, falls back to sorting the rows themselves.
    """
    v = np.ascontiguousarray(v + 0.0)  # -0.0 and 0.0 are the same point
    bits = v.view(np.uint64)
    h = np.zeros(len(v), dtype=np.uint64)
    with np.errstate(over="ignore"):
        for k in range(v.shape[1]):  # splitmix64 finaliser over the three coordinates
            h ^= bits[:, k]
            h ^= h >> np.uint64(30)
            h *= np.uint64(0xBF58476D1CE4E5B9)
            h ^= h >> np.uint64(27)
            h *= np.uint64(0x94D049BB133111EB)
            h ^= h >> np.uint64(31)
    first, inverse, _ = _group(h)
    if not np.array_equal(v[first][inverse], v):
        raw = v.view(np.dtype((np.void, v.dtype.itemsize * v.shape[1]))).ravel()
        _, first, inverse = np.unique(raw, return_index=True, return_inverse=True)
    return v[first], inverse.reshape(-1)


#: Farthest a mesh may lie from the origin, in multiples of its size: beyond, its coordinates
#: keep fewer than 10 significant digits of the body in double precision, and manifold3d's
#: tolerances, relative to the coordinates, merge its features.
_MAX_OFFSET = 1e6

#: Most pairs of vertices closer than the merge distance, per vertex, for the merge to be of
#: copies of vertices (a cone's tip written once per face makes many): more, and the
#: distance is not rounding but the mesh's own spacing (and the pairs would fill memory).
_MAX_MERGE_PAIRS = 8


def _merge_close(
    v: np.ndarray, f: np.ndarray, tol: float
) -> tuple[np.ndarray, np.ndarray, int] | None:
    """Merge vertices closer than ``tol``; returns new arrays and the number merged, or
    None when the vertices within ``tol`` of one another are not copies of a vertex: more
    pairs than :data:`_MAX_MERGE_PAIRS` per vertex (counted before any is listed, so that
    memory stays in proportion to the mesh), or a face with two corners among them."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    tree = cKDTree(v)
    n_pairs = (int(tree.count_neighbors(tree, tol)) - len(v)) // 2
    if n_pairs > _MAX_MERGE_PAIRS * len(v):
        return None
    pairs = tree.query_pairs(tol, output_type="ndarray")
    if len(pairs) == 0:
        return v, f, 0
    n = len(v)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    ncomp, labels = connected_components(graph, directed=False)
    # representative: the first vertex of each group
    first = np.full(ncomp, n, dtype=np.int64)
    np.minimum.at(first, labels, np.arange(n))
    g = labels[f]
    if np.any((g[:, 0] == g[:, 1]) | (g[:, 1] == g[:, 2]) | (g[:, 2] == g[:, 0])):
        return None  # a face would collapse: the distance is larger than some edge
    return v[first], g, n - ncomp


def _checked_mesh(vertices, faces, name: str):
    """Validate a mesh, repair what is safe, and build its manifold3d ``Manifold``."""
    import manifold3d

    repairs: list[str] = []

    def repaired(msg: str) -> None:
        repairs.append(msg)
        warnings.warn(f"mesh {name!r}: {msg}", MeshRepairWarning, stacklevel=4)

    v = np.array(vertices, dtype=np.float64)
    if v.ndim != 2 or v.shape[1] != 3:
        raise MeshError(f"mesh {name!r}: vertices have shape {v.shape}, expected (n, 3)")
    try:
        f = np.array(faces)
    except (TypeError, ValueError) as exc:
        raise MeshError(f"mesh {name!r}: faces are not an (m, 3) integer array") from exc
    if f.ndim != 2 or f.shape[1] != 3:
        raise MeshError(f"mesh {name!r}: faces have shape {f.shape}, expected (m, 3) triangles")
    if len(v) == 0 or len(f) == 0:
        raise MeshError(f"mesh {name!r} is empty ({len(v)} vertices, {len(f)} faces)")
    if not np.issubdtype(f.dtype, np.integer):
        if not np.all(np.isfinite(f)) or np.any(f != np.round(f)):
            raise MeshError(f"mesh {name!r}: face indices are not whole numbers")
    f = f.astype(np.int64)
    _check_finite(v, name)
    if f.min() < 0 or f.max() >= len(v):
        badf = np.flatnonzero((f < 0).any(axis=1) | (f >= len(v)).any(axis=1))
        raise MeshError(
            f"mesh {name!r}: face {badf[0]} refers to vertex {f[badf[0]].tolist()} but the "
            f"mesh has only {len(v)} vertices (indices 0 to {len(v) - 1}); the file is corrupt"
        )
    # drop unused vertices (they carry no geometry) so later counts mean something
    used = np.zeros(len(v), dtype=bool)
    used[f.ravel()] = True
    if not used.all():
        remap = np.cumsum(used) - 1
        v, f = v[used], remap[f]
    size = float(np.linalg.norm(v.max(axis=0) - v.min(axis=0)))
    if size == 0.0:
        raise MeshError(f"mesh {name!r}: all vertices are at one point")
    reach = float(np.abs(v).max())
    if reach > _MAX_OFFSET * size:
        raise MeshError(
            f"mesh {name!r} lies {reach:.3g} m from the origin, {reach / size:.3g} times its "
            f"size ({size:.3g} m): coordinates that far out do not resolve the body (a binary "
            "STL keeps 7 digits, a double 16); move the body near the origin in your CAD tool"
        )

    # exact duplicates (every STL is a triangle soup on disk): merging them changes nothing
    uniq, inverse = _unique_rows(v)
    if len(uniq) < len(v):
        v, f = uniq, inverse[f]

    # faces that repeat a vertex have no area and no orientation
    degenerate = (f[:, 0] == f[:, 1]) | (f[:, 1] == f[:, 2]) | (f[:, 2] == f[:, 0])
    if degenerate.any():
        f = f[~degenerate]
        repaired(f"removed {int(degenerate.sum())} degenerate faces (a repeated vertex)")
        if len(f) == 0:
            raise MeshError(f"mesh {name!r} has only degenerate faces")

    # the same triangle written twice with the same winding: the copies add nothing
    f, n_copies = _drop_repeated_faces(f)
    if n_copies:
        repaired(f"removed {n_copies} repeated faces (the same triangle written again)")

    counts, n_forward = _edge_use(f)
    if (counts == 1).any():
        # perhaps vertices that should be shared differ by rounding: merge them, over the
        # smallest distance that closes the surface
        scale = max(size, float(np.abs(v).max()))
        tol = TOL.merge * scale
        while tol <= TOL.merge_max * scale * (1.0 + 1e-9):
            merged = _merge_close(v, f, tol)
            if merged is None:  # past rounding: a larger distance would only merge more
                break
            v2, f2, n_merged = merged
            if n_merged:
                f2, _ = _drop_repeated_faces(f2)
                if len(f2):
                    counts2, n_forward2 = _edge_use(f2)
                    if np.all(counts2 == 2):
                        v, f, counts, n_forward = v2, f2, counts2, n_forward2
                        repaired(
                            f"merged {n_merged} vertices closer than {tol:.3g} m to close the "
                            "surface (copies of one vertex that differ by rounding)"
                        )
                        break
            tol *= 10.0
    open_edges = int((counts == 1).sum())
    if open_edges:
        raise MeshError(
            f"mesh {name!r} is open: {open_edges} edges belong to a single face (holes in "
            "the surface); load it with --repair close (repair='close') to fill them and "
            "drop what cannot be closed, or close them in your CAD tool"
        )
    nonmanifold = int((counts > 2).sum())
    if nonmanifold:
        raise MeshError(
            f"mesh {name!r} is not manifold: {nonmanifold} edges are shared by more than two "
            "faces; separate the touching bodies or remesh"
        )
    # each edge used by two faces must be used once in each direction
    misoriented = int((n_forward != 1).sum())
    if misoriented:
        f, flipped = _orient_consistently(f, name)
        repaired(f"re-oriented {flipped} faces whose winding disagreed with their neighbours")

    vol = _signed_volume(v, f)
    if abs(vol) <= TOL.flat * size**3:
        raise MeshError(
            f"mesh {name!r} encloses no volume ({vol:.3g} m^3 in a box of diagonal "
            f"{size:.6g} m): it is a flat or zero-thickness surface, not a body"
        )
    manifold = _to_manifold(v, f, name)
    if manifold.volume() < 0.0:
        f = f[:, ::-1].copy()
        manifold = _to_manifold(v, f, name)
        repaired("the mesh was inside out (negative volume); all faces were flipped")

    parts = manifold.decompose()
    if len(parts) > 1:
        vols = np.array([p.volume() for p in parts])
        shells = [p for p, vol in zip(parts, vols, strict=True) if vol > 0]
        total = float(vols[vols > 0].sum())
        union = manifold3d.Manifold.batch_boolean(shells, manifold3d.OpType.Add)
        if len(shells) > 1 and union.volume() < total * (1.0 - TOL.volume):
            cavities = [_flipped(p) for p, vol in zip(parts, vols, strict=True) if vol < 0]
            body = union
            if cavities:
                body = manifold3d.Manifold.batch_boolean(
                    [union, *cavities], manifold3d.OpType.Subtract
                )
            mesh = body.to_mesh64()
            v = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3].copy()
            f = np.asarray(mesh.tri_verts, dtype=np.int64).copy()
            manifold = _to_manifold(v, f, name)
            repaired(
                f"{len(shells)} shells overlap (their volumes add to {total:.6g} m^3, "
                f"their union is {union.volume():.6g} m^3); the body is taken as their union"
            )
    if manifold.volume() <= 0.0:
        raise MeshError(f"mesh {name!r} encloses no volume")
    check_sections_match_volume(v, f, manifold, name)  # not passing through itself
    return v, f, manifold, repairs


def _drop_repeated_faces(f: np.ndarray) -> tuple[np.ndarray, int]:
    """Faces without repeats of the same triangle with the same winding, and how many went."""
    # rotate each triangle so that its smallest index comes first: the winding is kept
    r = np.argmin(f, axis=1)
    rolled = f[np.arange(len(f))[:, None], (r[:, None] + np.arange(3)) % 3]
    unique, inverse = _unique_rows(rolled.astype(np.float64))  # exact below 2^53 vertices
    if len(unique) == len(f):
        return f, 0
    first = np.full(len(unique), len(f))
    np.minimum.at(first, inverse, np.arange(len(f)))
    return f[np.sort(first)], len(f) - len(unique)


def _signed_volume(v: np.ndarray, f: np.ndarray) -> float:
    """Volume enclosed by an oriented closed surface (divergence theorem), m^3."""
    o = v.mean(axis=0)
    a, b, c = v[f[:, 0]] - o, v[f[:, 1]] - o, v[f[:, 2]] - o
    return float(np.einsum("ij,ij->", a, np.cross(b, c)) / 6.0)


def _check_finite(v: np.ndarray, name: str) -> None:
    bad = ~np.isfinite(v)
    if bad.any():
        rows = np.flatnonzero(bad.any(axis=1))
        raise MeshError(
            f"mesh {name!r}: {len(rows)} vertices have NaN or infinite coordinates "
            f"(first: vertex {rows[0]} = {v[rows[0]].tolist()}); fix the export"
        )


def _to_manifold(v: np.ndarray, f: np.ndarray, name: str):
    import manifold3d

    mesh = manifold3d.Mesh64(
        vert_properties=np.ascontiguousarray(v, dtype=np.float64),
        tri_verts=np.ascontiguousarray(f, dtype=np.uint64),
    )
    man = manifold3d.Manifold(mesh)
    status = man.status()
    if status != manifold3d.Error.NoError:
        raise MeshError(
            f"mesh {name!r} was refused by manifold3d ({status.name}): it is not a closed, "
            "consistently oriented 2-manifold; repair it in your CAD tool"
        )
    return man


def _orient_consistently(faces: np.ndarray, name: str) -> tuple[np.ndarray, int]:
    """Flip the fewest faces so that neighbours traverse every shared edge in opposite ways.

    Faces are the nodes of a graph whose edges are the mesh's edges (each shared by two
    faces, checked before); an edge says whether its two faces agree. A breadth-first tree
    of each connected part gives every face its parity to the root, found for all faces at
    once by pointer jumping. In each part, the parity seen by fewer faces is flipped.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import breadth_first_order, connected_components

    m = len(faces)
    directed = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    owner = np.repeat(np.arange(m), 3)
    lo, hi = directed.min(axis=1), directed.max(axis=1)
    order = np.argsort(lo * (int(faces.max()) + 1) + hi, kind="stable")
    a, b = order[0::2], order[1::2]  # the two uses of each edge, side by side
    fa, fb = owner[a], owner[b]
    disagree = (directed[a, 0] == directed[b, 0]).astype(np.int8)  # same direction
    # weights 1 (agree) and 3 (disagree) stay apart when two faces share two edges
    graph = coo_matrix((1 + 2 * disagree, (fa, fb)), shape=(m, m)).tocsr()
    graph = (graph + graph.T).tocsr()
    ncomp, labels = connected_components(graph, directed=False)
    pred = np.arange(m)
    for c in range(ncomp):
        root = int(np.flatnonzero(labels == c)[0])
        _, p = breadth_first_order(graph, root, directed=False, return_predecessors=True)
        members = p >= 0
        pred[members] = p[members]
    # parity of each face relative to its tree parent
    parity = (np.asarray(graph[np.arange(m), pred]).ravel() % 3 == 0).astype(np.int8)
    parity[pred == np.arange(m)] = 0
    jump = pred.copy()
    while np.any(jump != jump[jump]):  # pointer jumping: XOR of parities up to the root
        parity ^= parity[jump]
        jump = jump[jump]
    parity ^= parity[jump]
    flip = parity.astype(bool)
    if np.any(disagree.astype(bool) ^ flip[fa] ^ flip[fb]):
        raise MeshError(
            f"mesh {name!r}: the faces cannot be oriented consistently "
            "(a non-orientable surface); remesh the hull"
        )
    counts = np.bincount(labels, minlength=ncomp)
    flipped_per = np.bincount(labels, weights=flip, minlength=ncomp)
    swap = flipped_per > counts / 2  # flip the other set in this part: fewer faces
    flip ^= swap[labels]
    out = faces.copy()
    out[flip] = out[flip][:, ::-1]
    return out, int(flip.sum())


def _flipped(manifold):
    """The same surface with every face reversed (a cavity turned into a solid)."""
    mesh = manifold.to_mesh64()
    v = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
    f = np.asarray(mesh.tri_verts, dtype=np.int64)[:, ::-1]
    return _to_manifold(v, f, "cavity")
