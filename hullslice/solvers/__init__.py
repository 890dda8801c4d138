"""2D solvers: the interface, the registry and the default solver.

Solvers are found through the entry-point group ``hullslice.solvers``; see
:mod:`hullslice.solvers.registry`.
"""

from .base import SectionLoads, Solver, join_reasons
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
    "PAPER_CURVES",
    "PILE_UP_LAWS",
    "CharacteristicCurves",
    "CurveSolver",
    "ExtendedVonKarman",
    "MomentumSolver",
    "SectionLoads",
    "Solver",
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
