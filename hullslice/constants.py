"""Physical constants, unit factors and the numerical tolerances of hullslice, in one place.

All quantities inside hullslice are SI (m, kg, s, N, rad); units are converted at the edges.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = [
    "AXES",
    "LENGTH_UNITS",
    "RHO_WATER",
    "TOL",
    "G",
    "Tolerances",
]

#: Standard gravity in m/s^2 (the paper's value, Eq. 12).
G = 9.81

#: Fresh-water density in kg/m^3 (the paper's characteristic curves were made with it).
RHO_WATER = 1000.0

#: Length units a mesh may be given in, as metres per unit.
LENGTH_UNITS: dict[str, float] = {
    "m": 1.0,
    "cm": 1e-2,
    "mm": 1e-3,
    "in": 0.0254,
    "ft": 0.3048,
}

#: Axis names accepted for the forward and up directions of a mesh, as unit vectors.
AXES: dict[str, tuple[float, float, float]] = {
    "+x": (1.0, 0.0, 0.0),
    "-x": (-1.0, 0.0, 0.0),
    "+y": (0.0, 1.0, 0.0),
    "-y": (0.0, -1.0, 0.0),
    "+z": (0.0, 0.0, 1.0),
    "-z": (0.0, 0.0, -1.0),
}


@dataclass(frozen=True)
class Tolerances:
    """Numerical tolerances, each relative to the size of the hull (its bounding-box diagonal).

    Attributes
    ----------
    coordinate : float
        Two coordinates closer than this are the same point. manifold3d returns its cross
        sections in single precision (about 1.2e-7 relative), so this must be larger.
    merge : float
        Distance below which vertices of a mesh file are merged on loading (STL triangle soup).
    volume : float
        Relative difference of volumes treated as equal (overlapping-shell detection).
    """

    coordinate: float = 1e-6
    merge: float = 1e-9
    volume: float = 1e-6


#: The tolerances in use.
TOL = Tolerances()
