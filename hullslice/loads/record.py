"""What a structural load needs of one instant of a run: :class:`SectionRecord`.

A run that keeps its sections (``simulate(..., sections_every=N)``) stores one record per
kept instant: the pose that places the mesh, each slice's station, keel and force, and,
from a solver that gives them, the pressures along each section's wetted contour. A
record is small (a few arrays over the slices), so a run keeps its records and maps them
onto the mesh's faces afterwards, one instant at a time (:mod:`hullslice.loads.faces`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..forces import ForceResult
from ..solvers.base import MOMENTUM

__all__ = ["SectionRecord"]


@dataclass(frozen=True, eq=False)
class SectionRecord:
    """One instant's slices, as the structural loads need them.

    Attributes
    ----------
    t : float
        Time, s.
    kind : str
        The solver's kind (``"momentum"`` or ``"free-fall"``): where a slice's force acts
        (at its keel, or halfway between its keel and the water).
    pitch : float
        Pitch, rad, nose up.
    z_cg : float
        Earth height of the centre of gravity, m.
    x_cg : float
        Earth ``X`` of the centre of gravity, m.
    x, dx : (n,) float
        Each entry's station (earth ``X``, m) and slice thickness (m).
    station : (n,) int
        The station of each entry (a section with two wetted pieces has two entries).
    y_keel, keel_z : (n,) float
        Each entry's keel: lateral position ``y`` and earth height ``Z``, m.
    force, force_x : (n,) float
        Each entry's vertical and horizontal force, N (positive up and forward).
    y, z, weight, pressure : (n, 2, k) float or None
        The solver's pressure points per entry, side (0 port, 1 starboard) and point:
        distance from the keel (m), height above it (m), width share (m) and gauge
        pressure (Pa); None from a solver that gives no pressures.
    hydrostatic : float
        ``rho g`` (Pa/m) when the slices' forces hold the calm water's hydrostatic
        pressure (a solver's gravity option), else 0.
    """

    t: float
    kind: str
    pitch: float
    z_cg: float
    x_cg: float
    x: np.ndarray
    dx: np.ndarray
    station: np.ndarray
    y_keel: np.ndarray
    keel_z: np.ndarray
    force: np.ndarray
    force_x: np.ndarray
    y: np.ndarray | None = None
    z: np.ndarray | None = None
    weight: np.ndarray | None = None
    pressure: np.ndarray | None = None
    hydrostatic: float = 0.0

    @classmethod
    def of(cls, t: float, result: ForceResult) -> SectionRecord:
        """The record of a force result at time ``t`` (s)."""
        s = result.sections
        vertical = result.loads.diagnostics.get("vertical_force")
        holds_gravity = vertical is not None and bool(np.any(np.nan_to_num(vertical) != 0.0))
        pts = result.pressures
        arrays: dict[str, np.ndarray | None] = dict.fromkeys(("y", "z", "weight", "pressure"))
        if pts is not None:
            arrays = {
                "y": np.array(pts.points.y, dtype=np.float64),
                "z": np.array(pts.points.z, dtype=np.float64),
                "weight": np.array(pts.points.weight, dtype=np.float64),
                "pressure": np.array(pts.pressure, dtype=np.float64),
            }
        return cls(
            t=float(t),
            kind=result.kind,
            pitch=float(result.pose.pitch),
            z_cg=float(s.z_cg),
            x_cg=float(result.x_cg),
            x=np.array(s.x, dtype=np.float64),
            dx=np.array(s.dx, dtype=np.float64),
            station=np.array(s.station, dtype=np.int64),
            y_keel=np.array(s.y_keel, dtype=np.float64),
            keel_z=np.array(s.keel_z, dtype=np.float64),
            force=np.array(result.force, dtype=np.float64),
            force_x=np.array(result.force_x, dtype=np.float64),
            hydrostatic=result.fluid.rho * result.fluid.g if holds_gravity else 0.0,
            **arrays,
        )

    @property
    def has_pressures(self) -> bool:
        """Whether the record holds the sections' pressures."""
        return self.pressure is not None

    @property
    def total(self) -> float:
        """The vertical force on the body, N."""
        return float(self.force.sum())

    @property
    def total_x(self) -> float:
        """The horizontal force on the body, N."""
        return float(self.force_x.sum())

    @property
    def force_height(self) -> np.ndarray:
        """(n,) earth height at which each entry's force acts, m: its keel (momentum form)
        or halfway between its keel and the water (free fall), as in
        :attr:`~hullslice.ForceResult.moment`."""
        return self.keel_z if self.kind == MOMENTUM else 0.5 * self.keel_z

    @property
    def moment(self) -> float:
        """Pitch moment of the slices' forces about the centre of gravity, N m, nose up."""
        arm_z = self.force_height - self.z_cg
        return float(((self.x - self.x_cg) * self.force - arm_z * self.force_x).sum())
