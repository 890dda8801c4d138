"""The result of cutting a hull at a pose: :class:`Sections`, arrays over wetted pieces.

A section may have several wetted pieces (two floats, a catamaran): each piece is an
**entry** of :class:`Sections` with its own keel, penetration and deadrise, and its share of
the section's mass per metre. A section with one piece (the usual case) is one entry.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, fields
from typing import ClassVar

import numpy as np

from ..kernel.outline import ByStation, Polygons

__all__ = ["Sections", "ShiftedPolygons"]


class ShiftedPolygons(ByStation):
    """Station contours scaled and moved when they are read (no copy until then).

    Parameters
    ----------
    polygons : sequence of sequences of (k, 2) float
        Contours per station.
    shift : (float, float)
        Offset added to every point, m.
    scale : float
        Every point is divided by it before the shift.
    lift : (s,) float, optional
        A further height added to each station's points, m.
    index : (s,) int, optional
        Station ``i``'s contours are ``polygons[index[i]]`` (default: ``polygons[i]``), so
        that a slice's station is looked up when it is read.
    """

    def __init__(
        self,
        polygons: Sequence[Polygons],
        shift: tuple[float, float],
        scale: float = 1.0,
        lift: np.ndarray | None = None,
        index: np.ndarray | None = None,
    ) -> None:
        self._polygons = polygons
        self._index = None if index is None else np.asarray(index, dtype=np.int64)
        self._shift = np.asarray(shift, dtype=np.float64)
        self._scale = float(scale)
        self._lift = None if lift is None or not np.any(lift) else np.asarray(lift, dtype=float)

    def __len__(self) -> int:
        return len(self._polygons) if self._index is None else len(self._index)

    def _raw(self, i: int) -> Polygons:
        """Station ``i``'s contours as given (not moved)."""
        return self._polygons[i] if self._index is None else self._polygons[int(self._index[i])]

    def _station(self, i: int) -> Polygons:
        shift = self._shift
        if self._lift is not None:
            shift = shift + np.array([0.0, self._lift[i]])
        return tuple(np.asarray(c) / self._scale + shift for c in self._raw(i))

    def contour_counts(self) -> np.ndarray:
        """(s,) the number of contours of each station (none of them moved)."""
        return np.array([len(self._raw(i)) for i in range(len(self))], dtype=np.int64)

    def extent_below(self, stations: np.ndarray) -> np.ndarray:
        """(k,) the lateral extent (largest less smallest ``Y``, m) of the points at or
        below ``Z = 0`` of the first contour of each of ``stations``, the points moved by
        the same arithmetic as :meth:`__getitem__`'s, all stations at once; NaN where
        there are none."""
        k = np.asarray(stations, dtype=np.int64)
        out = np.full(len(k), np.nan)
        raw = [np.asarray(self._raw(int(i))[0]) for i in k]
        counts = np.array([len(c) for c in raw], dtype=np.int64)
        if not counts.any():
            return out
        pts = np.concatenate([c for c in raw if len(c)])
        shift_z = np.full(len(k), self._shift[1])
        if self._lift is not None:
            shift_z = self._shift[1] + self._lift[k]
        y = pts[:, 0] / self._scale + self._shift[0]
        z = pts[:, 1] / self._scale + np.repeat(shift_z, counts)
        below = z <= 0.0
        nz = counts[counts > 0]
        start = np.cumsum(nz) - nz  # each non-empty station's first point
        has = np.add.reduceat(below.astype(np.int64), start)
        hi = np.maximum.reduceat(np.where(below, y, -np.inf), start)
        lo = np.minimum.reduceat(np.where(below, y, np.inf), start)
        out[counts > 0] = np.where(has > 0, hi - lo, np.nan)
        return out


@dataclass(frozen=True, eq=False)
class Sections:
    """Cross-sections of a hull at one pose, as arrays over entries (wetted pieces).

    Every array has one value per entry; ``station`` says which station (slice) an entry
    belongs to. A dry station has one entry with zero penetration.

    Attributes
    ----------
    station : (n,) int
        Index of the entry's station, into ``polygons`` and the station arrays.
    x : (n,) float
        Station position along the earth's ``X`` in m (equal to the body's ``x`` when level).
    dx : (n,) float
        Thickness of the entry's slice in m.
    penetration : (n,) float
        Depth of the piece's lowest point below the water, m (``>= 0``).
    half_beam : (n,) float
        Half the width of the wetted piece at the waterline, m.
    half_beam_port, half_beam_stbd : (n,) float
        Horizontal distance from the keel to the waterline on each side, m.
    deadrise : (n,) float
        Local deadrise in rad (both sides combined; NaN for a dry entry).
    deadrise_port, deadrise_stbd : (n,) float
        Deadrise of each side in rad.
    area : (n,) float
        Area of the station's whole cross-section (not only its wetted part), m^2.
    mass_per_metre : (n,) float
        Mass per metre carried by the piece, kg/m (NaN without a hull mass).
    chine_wetted : (n,) bool
        The water has reached the station's widest point (chine or deck) on either side.
    keel_slope : (n,) float
        Slope ``dZ/dX`` of the body's keel line over the station's slice (earth frame):
        its chord over the slice (:meth:`~hullslice.kernel.keel.KeelLine.mean_slope`).
    keel_z : (n,) float
        Earth height of the station's lowest point, m (at the water where the station has
        no section: a gap between parts one behind the other).
    y_keel : (n,) float
        Lateral position ``y`` of the piece's keel, m.
    part_half_beam : (n,) float
        Half the largest width of the separate part of the section that the piece belongs
        to (its float, for a catamaran), m; NaN for a dry entry.
    polygons : sequence of tuples of (k, 2) float
        Contours of each **station** in the earth ``(Y, Z)`` plane, m; the waterline is
        ``Z = 0``; outer contours counter-clockwise.
    deadrise_method : str
        The estimator used, a key of :data:`DEADRISE_ESTIMATORS`.
    draft, pitch, wetted_length : float
        The pose (m; rad, :attr:`pitch_deg` in degrees) and the length of the wetted part
        along ``X`` (m).
    z_cg : float
        Earth height of the centre of gravity, m.
    keel_curvature : (n,) float
        The keel line's ``d^2 Z_k / dX^2`` averaged over the entry's slice, 1/m (zeros when
        not given).
    """

    station: np.ndarray
    x: np.ndarray
    dx: np.ndarray
    penetration: np.ndarray
    half_beam: np.ndarray
    half_beam_port: np.ndarray
    half_beam_stbd: np.ndarray
    deadrise: np.ndarray
    deadrise_port: np.ndarray
    deadrise_stbd: np.ndarray
    area: np.ndarray
    mass_per_metre: np.ndarray
    chine_wetted: np.ndarray
    keel_slope: np.ndarray
    keel_z: np.ndarray
    y_keel: np.ndarray
    part_half_beam: np.ndarray
    polygons: Sequence[Polygons] = field(repr=False, default=())
    deadrise_method: str = "wedge"
    draft: float = 0.0
    pitch: float = 0.0
    wetted_length: float = 0.0
    z_cg: float = 0.0
    keel_curvature: np.ndarray | None = field(repr=False, default=None)

    #: The per-entry arrays' names, in order (taken from the fields after the class).
    _ARRAYS: ClassVar[tuple[str, ...]] = ()

    def __post_init__(self) -> None:
        values = self.__dict__  # frozen: set once here, read-only arrays
        n = len(values["x"])
        if values["keel_curvature"] is None:
            values["keel_curvature"] = np.zeros(n)
        for name in self._ARRAYS:
            arr = values[name]
            if not (type(arr) is np.ndarray and arr.shape == (n,) and arr.flags.c_contiguous):
                arr = np.ascontiguousarray(arr)
                if arr.shape != (n,):
                    raise ValueError(f"Sections.{name} has shape {arr.shape}, expected ({n},)")
            arr.setflags(write=False)  # the method: cheaper than the flags' object
            values[name] = arr

    def __len__(self) -> int:
        return len(self.x)

    @property
    def n_stations(self) -> int:
        """Number of stations (slices)."""
        return len(self.polygons)

    @property
    def wetted(self) -> np.ndarray:
        """(n,) bool: entries with a positive penetration."""
        return self.penetration > 0.0

    @property
    def pitch_deg(self) -> float:
        """The pitch in degrees, nose up (:attr:`pitch` in rad)."""
        return math.degrees(self.pitch)

    @property
    def deadrise_deg(self) -> np.ndarray:
        """(n,) float: deadrise angles in degrees."""
        return np.degrees(self.deadrise)

    def subset(self, mask: np.ndarray) -> Sections:
        """The entries where ``mask`` is true, as a new :class:`Sections` (same stations)."""
        mask = np.asarray(mask, dtype=bool)
        kw = {name: getattr(self, name)[mask] for name in self._ARRAYS}
        return Sections(
            **kw,
            polygons=self.polygons,
            deadrise_method=self.deadrise_method,
            draft=self.draft,
            pitch=self.pitch,
            wetted_length=self.wetted_length,
            z_cg=self.z_cg,
        )

    def to_xarray(self):
        """The entries as an ``xarray.Dataset`` with units (needs xarray)."""
        from ..xarray_io import sections_to_xarray

        return sections_to_xarray(self)

    def to_dataframe(self):
        """The entries as a ``pandas.DataFrame``, units in ``attrs``."""
        from ..xarray_io import sections_to_dataframe

        return sections_to_dataframe(self)

    def as_dict(self) -> dict[str, np.ndarray]:
        """The per-entry arrays by name, deadrise also in degrees (``*_deg``)."""
        d = {name: getattr(self, name) for name in self._ARRAYS}
        d["deadrise_deg"] = self.deadrise_deg
        d["deadrise_port_deg"] = np.degrees(self.deadrise_port)
        d["deadrise_stbd_deg"] = np.degrees(self.deadrise_stbd)
        return d


Sections._ARRAYS = tuple(f.name for f in fields(Sections) if "np.ndarray" in str(f.type))
