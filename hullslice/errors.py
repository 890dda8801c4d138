"""The exceptions and warnings of hullslice.

Every error the package raises on purpose derives from :class:`HullsliceError`, so a caller
can catch them all at once; each one also derives from the built-in class that fits it
(``ValueError`` for a bad value, ``LookupError`` for an unknown name, ...), so code that
catches the built-in keeps working. Messages quote the offending value and say what to do.
"""

from __future__ import annotations

__all__ = [
    "CaseError",
    "HullsliceError",
    "HullsliceWarning",
    "InputError",
    "MeshError",
    "MeshRepairWarning",
    "MissingDependencyError",
    "OpenMeshError",
    "OrientationWarning",
    "PluginError",
    "PluginWarning",
    "SolverError",
    "UnitsWarning",
    "UnknownSolverError",
]


class HullsliceError(Exception):
    """Base class of every error raised by hullslice."""


class InputError(ValueError, HullsliceError):
    """A parameter has a value hullslice cannot work with (negative mass, no slices, ...)."""


class MeshError(ValueError, HullsliceError):
    """A mesh file cannot be read or does not describe a closed body."""


class OpenMeshError(MeshError):
    """A mesh is not one closed surface: edges with a single face (holes) or with more than
    two (parts welded together). ``hullslice info`` then lists its shells."""


class CaseError(InputError):
    """A case file or kinematics table is malformed (unknown key, wrong type, bad column)."""


class SolverError(RuntimeError, HullsliceError):
    """A 2D solver failed or returned results that cannot be used (NaN, wrong shape)."""


class PluginError(ImportError, HullsliceError):
    """A solver plugin cannot be loaded (import error, not a Solver subclass)."""


class UnknownSolverError(LookupError, HullsliceError):
    """No installed solver has the requested name."""


class HullsliceWarning(UserWarning):
    """Base class of the warnings hullslice emits."""


class MeshRepairWarning(HullsliceWarning):
    """A mesh was repaired on loading (vertices merged, faces re-oriented, shells united)."""


class UnitsWarning(HullsliceWarning):
    """A value looks like it is in the wrong unit (a mesh in mm read as metres, ...)."""


class OrientationWarning(HullsliceWarning):
    """A mesh may be turned the wrong way (its longest axis is not the forward one, ...)."""


class PluginWarning(HullsliceWarning):
    """A solver plugin is broken or shadowed by another with the same name."""


class MissingDependencyError(ImportError, HullsliceError):
    """An optional dependency is needed and not installed."""
