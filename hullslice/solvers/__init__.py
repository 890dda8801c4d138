"""2D solvers: the interface, the registry and the default solver.

Solvers are found through the entry-point group ``hullslice.solvers``; see
:mod:`hullslice.solvers.registry`.
"""

from .base import SectionLoads, Solver
from .karman import (
    PAPER_CURVES,
    CharacteristicCurves,
    CurveSolver,
    ExtendedVonKarman,
    dobrovolskaya_pile_up,
    peak_values,
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
    "DEFAULT_SOLVER",
    "ENTRY_POINT_GROUP",
    "PAPER_CURVES",
    "CharacteristicCurves",
    "CurveSolver",
    "ExtendedVonKarman",
    "SectionLoads",
    "Solver",
    "SolverInfo",
    "dobrovolskaya_pile_up",
    "get_solver",
    "list_solvers",
    "peak_values",
    "refresh",
    "solver_names",
]
