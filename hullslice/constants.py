"""Physical constants, unit factors and the numerical tolerances of hullslice, in one place.

All quantities inside hullslice are SI (m, kg, s, N, rad); units are converted at the edges.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = [
    "AXES",
    "LENGTH_UNITS",
    "MAX_SLICES",
    "MAX_SLICE_STEPS",
    "MAX_STEPS",
    "NU_SEA",
    "NU_WATER",
    "P_ATM",
    "P_VAPOUR",
    "RHO_SEA",
    "RHO_WATER",
    "TOL",
    "G",
    "Tolerances",
]

#: Standard gravity in m/s^2 (the paper's value, Eq. 12).
G = 9.81

#: Fresh-water density in kg/m^3 (the paper's characteristic curves were made with it).
RHO_WATER = 1000.0
#: Density of sea water, kg/m^3 (ITTC 2011, 15 deg C and 35 g/kg salinity: 1026; 1025 is
#: the value ditching rules and DNV-RP-C205 take).
RHO_SEA = 1025.0
#: Kinematic viscosity of fresh water at 20 deg C and of sea water at 15 deg C, m^2/s
#: (ITTC 2011 fresh and sea water tables).
NU_WATER = 1.0e-6
NU_SEA = 1.19e-6
#: Atmospheric pressure at sea level, Pa (ISO 2533 standard atmosphere).
P_ATM = 101325.0
#: Vapour pressure of water at 20 deg C, Pa (about 2.34 kPa; the IAPWS formulation).
P_VAPOUR = 2339.0
#: Speed of sound in fresh water at 20 deg C, m/s (1481 m/s; 1520 in sea water): a body's
#: speed past it is refused, the water of the method being incompressible.
SOUND_WATER = 1481.0

#: Length units a mesh may be given in, as metres per unit.
LENGTH_UNITS: dict[str, float] = {
    "m": 1.0,
    "cm": 1e-2,
    "mm": 1e-3,
    "in": 0.0254,
    "ft": 0.3048,
}

#: Most slices one cut may have: far finer than any mesh resolves (the paper converges with
#: 64), and a bound on the run time of a mistyped count (each slice is one manifold3d cut).
MAX_SLICES = 100_000

#: Most time steps one free-fall run may take (each step cuts the hull four times).
MAX_STEPS = 1_000_000

#: Most slices times steps (or kinematics rows) one run may compute: each is one section
#: cut and solved (20 to 80 us on the 1 m wedge prism, more on a fine mesh), so the bound is
#: minutes to hours of work for a mistyped count; a converged run needs far fewer (256
#: slices over 1500 steps is 4e5).
MAX_SLICE_STEPS = 10_000_000

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
    merge, merge_max : float
        Distances, relative to the mesh's own size (never to its distance from the origin),
        over which the vertices of an open mesh are merged on loading to close it (an STL
        is a triangle soup whose copies of one vertex may differ by rounding): ``merge``
        first, then ten times more up to ``merge_max``, until the surface closes. An ASCII
        STL written with 6 significant digits rounds two copies of a vertex up to 1e-5
        apart (relative).
    merge_edge : float
        A merge moves no vertex by more than this fraction of its shortest edge: farther,
        the two points are not copies that differ by rounding but different points.
    keel_merge : float
        Break points of a keel line closer than this are one point: vertices sharing a
        station at one pitch (a ring of a round body, port and starboard) part by their
        height difference times a pitch change, and at a pitch that differs from theirs by
        rounding (1e-12 rad) the facets between them are far thinner than the mesh resolves.
        Only ties of that size: a real pitch's thin facets are left as they are.
    volume : float
        Relative difference of volumes treated as equal (overlapping-shell detection).
    flat : float
        A closed mesh enclosing less than this times the cube of its size is flat (a
        zero-thickness surface), not a body.
    """

    coordinate: float = 1e-6
    merge: float = 1e-9
    merge_max: float = 1e-4
    merge_edge: float = 0.05
    keel_merge: float = 1e-12
    volume: float = 1e-6
    flat: float = 1e-12


#: The tolerances in use.
TOL = Tolerances()
