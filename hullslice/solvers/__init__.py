"""2D solvers: the interface, the registry and the default solver.

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
    Solver,
    SolverBase,
    join_reasons,
)
from .karman import (
    CURVE_COLUMNS,
    PAPER_CURVES,
    CharacteristicCurves,
    CurveSolver,
    ExtendedVonKarman,
    dobrovolskaya_pile_up,
    peak_froude,
    peak_values,
)
from .momentum import (
    PILE_UP_LAWS,
    FreeFallMomentumSolver,
    MomentumSolver,
    chine_half_width,
    momentum_curves,
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
