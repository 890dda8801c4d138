"""hullslice: water-impact loads on hulls and fuselages by the 2D+t method.

The hull is cut into cross-sections at each instant; each section is treated as a 2D wedge
entering the water (the paper's extended von Karman momentum theory by default, other 2D
solvers through plugins), and the 2D forces are summed along the body.

    >>> import hullslice as hs
    >>> hull = hs.load_hull("meshes/paper_prism.stl", mass=1.0)
    >>> study = hs.convergence(hull, 0.0383, -3.4943, slices=(16, 32, 64))  # draft, velocity
    >>> history = hs.simulate(hull, -4.0, 0.03, dt=1e-4)  # free fall from -4 m/s

All quantities are SI: m, kg, s, N; angles in rad inside the library, under parameter
names that say so (``Pose(draft, pitch_rad)``, ``simulate(..., pitch_rad=)`` or
``pitch_deg=``); the command line, case files and :class:`Study` take degrees.
"""

from . import loads
from ._version import __version__
from .aero import AERO_MODELS, Aerodynamics, Coefficients, WeightLift
from .case import load_case, validate_case
from .constants import RHO_WATER, TOL, G
from .convergence import Richardson, richardson
from .errors import (
    CaseError,
    HullsliceError,
    HullsliceWarning,
    InputError,
    MeshError,
    MeshRepairWarning,
    MissingDependencyError,
    OpenMeshError,
    OrientationWarning,
    PluginError,
    PluginWarning,
    SolverError,
    UnitsWarning,
    UnknownSolverError,
)
from .forces import ConvergenceStudy, ForceResult, compute_force, convergence
from .loads import FacePressures, FrameLoads, face_pressures
from .mass import MassDistribution, MassProperties, read_mass_distribution
from .mesh import Hull, load_hull
from .motion import STOP_RULES, ForceModel, History, prescribed, read_kinematics, simulate
from .sections import DEADRISE_ESTIMATORS, Sections, cut
from .solvers import (
    AddedMass,
    CharacteristicCurves,
    CurveSolver,
    FreeFallMomentumSolver,
    MomentumFormSolver,
    MomentumSolver,
    SectionLoads,
    SectionPressures,
    Solver,
    SolverBase,
    get_solver,
    list_solvers,
)
from .state import Acceleration, Fluid, Motion, Pose
from .study import Study, execute
from .sweeps import sweep

__all__ = [
    "AERO_MODELS",
    "DEADRISE_ESTIMATORS",
    "RHO_WATER",
    "STOP_RULES",
    "TOL",
    "Acceleration",
    "AddedMass",
    "Aerodynamics",
    "CaseError",
    "CharacteristicCurves",
    "Coefficients",
    "ConvergenceStudy",
    "CurveSolver",
    "FacePressures",
    "Fluid",
    "ForceModel",
    "ForceResult",
    "FrameLoads",
    "FreeFallMomentumSolver",
    "G",
    "History",
    "Hull",
    "HullsliceError",
    "HullsliceWarning",
    "InputError",
    "MassDistribution",
    "MassProperties",
    "MeshError",
    "MeshRepairWarning",
    "MissingDependencyError",
    "MomentumFormSolver",
    "MomentumSolver",
    "Motion",
    "OpenMeshError",
    "OrientationWarning",
    "PluginError",
    "PluginWarning",
    "Pose",
    "Richardson",
    "SectionLoads",
    "SectionPressures",
    "Sections",
    "Solver",
    "SolverBase",
    "SolverError",
    "Study",
    "UnitsWarning",
    "UnknownSolverError",
    "WeightLift",
    "__version__",
    "compute_force",
    "convergence",
    "cut",
    "execute",
    "face_pressures",
    "get_solver",
    "list_solvers",
    "load_case",
    "load_hull",
    "loads",
    "prescribed",
    "read_kinematics",
    "read_mass_distribution",
    "richardson",
    "simulate",
    "sweep",
    "validate_case",
]
