"""A free-pitch stage's one compiled call with its arguments kept in one object.

:func:`~hullslice.planecut_loops.stage_loops` reads 46 arguments, of which only six change
from one stage to the next: the pitch's cosine and sine, the centre of gravity's height and
the body's three velocities. numba unboxes every argument at each call and boxes every
array it returns (the contours, and the seven arrays of the memo that comes back to be
given again): about 4 us of a call, measured (40 arrays given: 2.1 us; 10 returned: 2.2
us). A :class:`StageKit` (a numba ``StructRef``) holds the others, the thread's memo and
the contours of the last call: :func:`kit_stage_loops` takes it and the six numbers, calls
the stage's loops inside the compiled code, keeps what they return on the kit and returns
their status alone; :func:`kit_rings_loops` gives the contours when a result needs them.
The same call, the same numbers.

This module needs numba: only the compiled path imports it (:mod:`hullslice.forces.fused`).
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np
from numba import types
from numba.experimental import structref

from . import planecut_loops

__all__ = ["StageKit", "kit_rings_loops", "kit_stage_loops", "new_kit"]

#: The digest of ``planecut_loops.py`` (its ``STAGE_HELPERS_DIGEST`` line covers the
#: stage's helpers): numba keeps this module's compiled functions by this file's time, and
#: does not see a change in the loops they call. A change there changes this digest
#: (``tests/test_stage_loops.py`` checks it), so this file, so the cache.
STAGE_DIGEST = "ed18986a2f7e2d8d"

#: How many of the stage's arguments come before the six numbers of a stage.
HULL_ARGS = 32
#: How many come after them but the memo (their last).
BUFFER_ARGS = 7


@structref.register
class StageKitType(types.StructRef):
    """numba's type of a :class:`StageKit`: fields ``hull`` (the stage's first
    :data:`HULL_ARGS` arguments, a tuple), ``buffers`` (its :data:`BUFFER_ARGS` after the
    six numbers of a stage),
    ``memo`` and ``rings`` (the last call's contours: points, ring starts, ring
    stations)."""

    def preprocess_fields(self, fields):
        return tuple((name, types.unliteral(t)) for name, t in fields)


class StageKit(structref.StructRefProxy):
    """A thread's arguments of :func:`~hullslice.planecut_loops.stage_loops` on one hull,
    kept in compiled memory (see the module)."""


structref.define_boxing(StageKitType, StageKit)

#: The stage's loops, compiled, as the functions below call them.
STAGE: Any = planecut_loops.compiled("stage")
if STAGE is None:  # numba is here, and switched off (HULLSLICE_NUMBA=0)
    raise ImportError("the stage's kit needs its loops compiled: numba is switched off")

_jit = numba.njit(cache=True, nogil=True, error_model="numpy")


@_jit
def _new_kit_loops(kit_type, hull, buffers, memo, rings):
    kit = structref.new(kit_type)
    kit.hull = hull
    kit.buffers = buffers
    kit.memo = memo
    kit.rings = rings
    return kit


@_jit
def kit_stage_loops(kit, c, s, z_cg, w, u, q):
    """:func:`~hullslice.planecut_loops.stage_loops` with the kit's arguments and the
    pitch's cosine ``c`` and sine ``s``, the centre of gravity's height ``z_cg`` (m) and
    the body's velocities ``w``, ``u`` and ``q``: its status; its memo and contours are
    kept on the kit (:func:`kit_rings_loops`)."""
    h, b = kit.hull, kit.buffers
    status, points, ring_start, ring_station, memo = STAGE(
        h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], h[8], h[9], h[10], h[11], h[12], h[13],
        h[14], h[15], h[16], h[17], h[18], h[19], h[20], h[21], h[22], h[23], h[24], h[25],
        h[26], h[27], h[28], h[29], h[30], h[31], c, s, z_cg, w, u, q, b[0], b[1], b[2], b[3],
        b[4], b[5], b[6], kit.memo,
    )  # fmt: skip
    kit.memo = memo
    kit.rings = (points, ring_start, ring_station)
    return status


@_jit
def kit_rings_loops(kit):
    """The contours of the kit's last call: ``(points, ring_start, ring_station)``."""
    return kit.rings


def new_kit(hull: tuple, buffers: tuple, memo: tuple) -> StageKit:
    """A kit of the stage's first :data:`HULL_ARGS` arguments ``hull``, its last but the
    memo ``buffers`` and the memo ``memo``. The fields' types are those numba gives these
    values and the stage's returns at them (the stage is compiled for them here, or read
    from numba's cache)."""
    if len(hull) != HULL_ARGS or len(buffers) != BUFFER_ARGS:
        raise ValueError(
            f"a stage kit takes {HULL_ARGS} and {BUFFER_ARGS} arguments, "
            f"not {len(hull)} and {len(buffers)}"
        )
    typeof = numba.typeof
    f8 = types.float64
    args = (*(typeof(v) for v in hull), f8, f8, f8, f8, f8, f8,
            *(typeof(v) for v in buffers), typeof(memo))  # fmt: skip
    STAGE.compile(args)
    _, points_t, start_t, station_t, memo_t = STAGE.overloads[args].signature.return_type
    kit_type = StageKitType([
        ("hull", typeof(hull)), ("buffers", typeof(buffers)), ("memo", memo_t),
        ("rings", types.Tuple((points_t, start_t, station_t))),
    ])  # fmt: skip
    rings = (np.empty((0, 2)), np.empty(1, dtype=np.int64), np.empty(1, dtype=np.int64))
    return _new_kit_loops(kit_type, hull, buffers, memo, rings)
