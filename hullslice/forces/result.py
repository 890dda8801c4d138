"""The force on a body at one state, per slice and in total: :class:`ForceResult`.

How the slice forces add up to the body's force and moment is in the notes of
:mod:`hullslice.forces`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..sections import Sections
from ..solvers.base import FREE_FALL, MOMENTUM, SectionLoads, SectionPressures
from ..state import Acceleration, Fluid, Motion, Pose

__all__ = ["MIN_SLENDERNESS", "ForceResult", "SectionPressureResult"]

#: Smallest wetted length over wetted beam of a slender body (2D+t's assumption).
MIN_SLENDERNESS = 2.0


@dataclass(frozen=True, eq=False)
class SectionPressureResult:
    """The pressure along each section's wetted contour at one state.

    Attributes
    ----------
    points : SectionPressures
        The solver's points (``y`` from the keel and ``z`` above it, m, per section, side
        and point) and their weights ``dy`` (m).
    pressure : (n, 2, k) float
        Gauge pressure at each point, Pa, bounded below by the fluid's suction limit.
    clipped : (n,) bool
        Sections with a point whose pressure fell below the suction limit and is shown at
        it (the section's force keeps its own total, bounded as a whole): on them the
        pressures' integral is above the force per metre. Elsewhere they agree to
        rounding.
    """

    points: SectionPressures
    pressure: np.ndarray
    clipped: np.ndarray | None = None

    def force_per_metre(self) -> np.ndarray:
        """(n,) the pressure's integral over both sides, N/m (``sum(weight p)``)."""
        return (self.points.weight * self.pressure).sum(axis=(1, 2))

    def peak(self) -> np.ndarray:
        """(n,) the largest pressure on each section, Pa."""
        return self.pressure.max(axis=(1, 2)) if self.pressure.size else np.zeros(0)


@dataclass(frozen=True, eq=False)
class ForceResult:
    """The 2D+t force on a body at one state, per slice and in total.

    Attributes
    ----------
    sections : Sections
        The slices.
    velocity : (n,) float
        Penetration velocity of each slice in m/s (negative down).
    loads : SectionLoads
        The solver's output for every slice (zero force on dry slices); ``valid`` and
        ``reason`` include the geometric checks (chine wetted).
    solver : str
        Name of the solver used.
    fluid : Fluid
    pose : Pose
    motion : Motion
    x_cg : float
        Earth ``X`` of the centre of gravity, m.
    kind : str
        The solver's kind, ``"free-fall"`` or ``"momentum"``.
    acceleration : Acceleration or None
        The body's acceleration the force was formed with (momentum form), else None.
    section_acceleration : (n,) float or None
        Each section's penetration acceleration, m/s^2, positive up (momentum form).
    pressures : SectionPressureResult or None
        The pressure along each section's wetted contour, where the solver gives it.
    """

    sections: Sections
    velocity: np.ndarray
    loads: SectionLoads
    solver: str
    fluid: Fluid
    pose: Pose
    motion: Motion
    x_cg: float = 0.0
    kind: str = FREE_FALL
    acceleration: Acceleration | None = None
    section_acceleration: np.ndarray | None = None
    pressures: SectionPressureResult | None = None

    @property
    def force(self) -> np.ndarray:
        """(n,) float: vertical force on each slice (entry) in N, positive up."""
        return self.loads.force_per_metre * self.sections.dx

    @property
    def force_x(self) -> np.ndarray:
        """(n,) float: horizontal force on each slice in N, positive forward: the force
        normal to the keel line has a horizontal part, a vertical (hydrostatic) force of a
        momentum-form solver has none."""
        normal = self.force
        vertical = self.loads.diagnostics.get("vertical_force")
        if vertical is not None:
            normal = normal - np.nan_to_num(vertical) * self.sections.dx
        return -normal * self.sections.keel_slope

    @cached_property
    def total(self) -> float:
        """Total vertical force in N, positive up (Eq. 12)."""
        return float(self.force.sum())

    @cached_property
    def total_x(self) -> float:
        """Total horizontal force in N, positive forward."""
        return float(self.force_x.sum())

    @cached_property
    def moment(self) -> float:
        """Pitch moment about the centre of gravity in N m, positive nose up.

        A free-fall force is applied halfway between its keel and the waterline, a
        momentum-form force at its keel point (see the module notes).
        """
        s = self.sections
        arm_x = s.x - self.x_cg
        keel = s.keel_z if self.kind == MOMENTUM else 0.5 * s.keel_z
        arm_z = keel - s.z_cg
        return float((arm_x * self.force - arm_z * self.force_x).sum())

    @property
    def added_mass(self) -> float:
        """Heave added mass ``sum m_a dx`` in kg (momentum form; NaN for free-fall)."""
        if self.kind != MOMENTUM:
            return float("nan")
        return float((self.loads.diagnostics["added_mass"] * self.sections.dx).sum())

    @property
    def slenderness(self) -> float:
        """Wetted length over wetted beam (the widest wetted piece at the waterline);
        ``inf`` when nothing is wetted. See :data:`MIN_SLENDERNESS`."""
        s = self.sections
        wet = s.penetration > 0
        if not wet.any():
            return float("inf")
        beam = float((s.half_beam_port + s.half_beam_stbd)[wet].max())
        return s.wetted_length / beam if beam > 0 else float("inf")

    @property
    def station_force(self) -> np.ndarray:
        """(s,) float: vertical force on each station (its pieces added), N."""
        s = self.sections
        return np.bincount(s.station, weights=self.force, minlength=s.n_stations)

    @property
    def valid(self) -> np.ndarray:
        """(n,) bool: slices inside the method's validity range."""
        return self.loads.valid

    @property
    def all_valid(self) -> bool:
        """True when every slice is inside the validity range."""
        return bool(self.loads.valid.all())

    def __len__(self) -> int:
        return len(self.sections)

    def to_xarray(self):
        """The per-slice results as an ``xarray.Dataset`` with units (needs xarray)."""
        from ..xarray_io import force_to_xarray

        return force_to_xarray(self)

    def to_dataframe(self):
        """The per-slice results as a ``pandas.DataFrame``, units in ``attrs``."""
        from ..xarray_io import force_to_dataframe

        return force_to_dataframe(self)

    def columns(self) -> dict[str, np.ndarray]:
        """Per-slice columns by name, SI units (deadrise in degrees)."""
        s = self.sections
        cols = {
            "station": s.station,
            "x": s.x,
            "dx": s.dx,
            "penetration": s.penetration,
            "velocity": self.velocity,
            "half_beam": s.half_beam,
            "deadrise_deg": s.deadrise_deg,
            "deadrise_port_deg": np.degrees(s.deadrise_port),
            "deadrise_stbd_deg": np.degrees(s.deadrise_stbd),
            "keel_slope": s.keel_slope,
            "area": s.area,
            "mass_per_metre": s.mass_per_metre,
            "force_per_metre": self.loads.force_per_metre,
            "force": self.force,
            "force_x": self.force_x,
        }
        if self.section_acceleration is not None:
            cols["section_acceleration"] = self.section_acceleration
        cols.update(self.loads.diagnostics)
        cols["valid"] = self.loads.valid
        cols["reason"] = self.loads.reason
        return cols
