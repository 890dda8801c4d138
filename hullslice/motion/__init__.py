"""Time histories: the body's free motion, or a prescribed motion, with the 2D+t force.

- :mod:`~hullslice.motion.integrate`: the equations of motion (with the added mass of a
  momentum-form solver on the left) and their integration, :func:`simulate` and
  :func:`prescribed`, and :class:`ForceModel`.
- :mod:`~hullslice.motion.history`: :class:`History`, the stop rules.
- :mod:`~hullslice.motion.kinematics`: reading and checking prescribed kinematics, and
  their derivatives.
"""

from .history import DEFAULT_STOP_ON, MAX_FLAGGED_SHARE, MAX_PITCH, STOP_RULES, History
from .integrate import ForceModel, prescribed, simulate
from .kinematics import KINEMATICS_COLUMNS, KINEMATICS_OPTIONAL, read_kinematics

__all__ = [
    "DEFAULT_STOP_ON",
    "KINEMATICS_COLUMNS",
    "KINEMATICS_OPTIONAL",
    "MAX_FLAGGED_SHARE",
    "MAX_PITCH",
    "STOP_RULES",
    "ForceModel",
    "History",
    "prescribed",
    "read_kinematics",
    "simulate",
]
