"""2D solvers: the interface, the registry and the default solver.

- :mod:`~hullslice.solvers.base`: what a solver is given and returns.
- :mod:`~hullslice.solvers.registry`: solvers by name, from entry points.
- :mod:`~hullslice.solvers.curves`: characteristic curves and their CSV tables.
- :mod:`~hullslice.solvers.peaks`: the peak values of a free-falling wedge (Eq. 2).
- :mod:`~hullslice.solvers.pileup`: the pile-up laws.
- :mod:`~hullslice.solvers.karman`: the curve solvers, the default among them.
- :mod:`~hullslice.solvers.momentum`: von Karman's momentum theory in closed form.
- :mod:`~hullslice.solvers.contour`: a section's wetted width from its own contour.

Solvers are found through the entry-point group ``hullslice.solvers``; see
:mod:`hullslice.solvers.registry`.
"""

from .base import (
    FREE_FALL,
    MOMENTUM,
    SOLVER_KINDS,
    AddedMass,
    MomentumFormSolver,
    SectionLoads,
    SectionPressures,
    Solver,
    SolverBase,
    join_reasons,
)
from .curves import CURVE_COLUMNS, PAPER_CURVES, CharacteristicCurves
from .karman import CurveSolver, ExtendedVonKarman
from .momentum import FreeFallMomentumSolver, MomentumSolver, chine_half_width, momentum_curves
from .peaks import peak_froude, peak_values
from .pileup import (
    PILE_UP_LAWS,
    dobrovolskaya_pile_up,
    pile_up_law,
    von_karman_pile_up,
    wagner_pile_up,
)
from .registry import (
    DEFAULT_SOLVER,
    ENTRY_POINT_GROUP,
    SolverInfo,
    get_solver,
    list_solvers,
    refresh,
    solver_names,
)

__all__ = [
    "CURVE_COLUMNS",
    "DEFAULT_SOLVER",
    "ENTRY_POINT_GROUP",
    "FREE_FALL",
    "MOMENTUM",
    "PAPER_CURVES",
    "PILE_UP_LAWS",
    "SOLVER_KINDS",
    "AddedMass",
    "CharacteristicCurves",
    "CurveSolver",
    "ExtendedVonKarman",
    "FreeFallMomentumSolver",
    "MomentumFormSolver",
    "MomentumSolver",
    "SectionLoads",
    "SectionPressures",
    "Solver",
    "SolverBase",
    "SolverInfo",
    "chine_half_width",
    "dobrovolskaya_pile_up",
    "get_solver",
    "join_reasons",
    "list_solvers",
    "momentum_curves",
    "peak_froude",
    "peak_values",
    "pile_up_law",
    "refresh",
    "solver_names",
    "von_karman_pile_up",
    "wagner_pile_up",
]
