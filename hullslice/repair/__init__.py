"""Checking and repairing a mesh: the passes every hull goes through, and closing holes.

- :mod:`hullslice.repair.passes`: the checks and safe fixes run on every hull, in order
  (:data:`~hullslice.repair.passes.PASSES`); ``fix=False`` (``--no-fix``) turns the fixes
  off.
- :mod:`hullslice.repair.close`: ``repair="close"`` (``--repair close``), filling the holes
  of an open mesh; never done unasked.
"""

from __future__ import annotations

from .close import CloseReport, close_mesh
from .passes import PASSES, Pass, check_and_repair

__all__ = ["PASSES", "CloseReport", "Pass", "check_and_repair", "close_mesh"]
