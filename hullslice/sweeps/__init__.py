"""Parameter sweeps: many cases of one time history, run on Dask, as a labelled Dataset.

A sweep is a base case (a ``simulate`` case, see :mod:`hullslice.case`) and a grid: case
keys mapped to lists of values, run as a full factorial (``velocity = [-1.0, -1.5]`` and
``pitch = [4, 6, 8]`` are six cases), and/or ``cases``, a table with one case per row (a CSV
file whose columns are case keys, e.g. a ``scipy.stats.qmc`` design). In a case file the grid
is the ``[sweep]`` table. Besides the number keys of a case and ``slices``, a sweep varies
``cg_x`` and ``cg_z`` (m), the components of the case's centre of gravity ``cg``.

How a case flows, module by module:

1. **plan** (:mod:`.plan`): the base case is checked as a case file
   (:func:`~hullslice.case.validate_case`), the grid expanded, and every case checked as the
   case file it amounts to; a :class:`Plan` lists each case's keys, its place in the result
   (C order over the swept keys) and the whole case (:meth:`Plan.case`).
2. **inputs** (:mod:`.run`): the mesh is read and checked once, here, with the base case's
   units, axes, scale, repair and parts, and its files (mass distribution, kinematics) read.
3. **groups** (:mod:`.engine`): the cases are grouped into tasks, the same mass properties
   and pitch together (they share a hull with those properties and, with the fixed
   slicing, its cuts).
4. **workers** (:mod:`.engine`, :mod:`.run`): the hull travels to the workers once, as its
   state (the arrays and mass properties, cheap to send); each worker builds it (its
   ``Manifold``) at its first task, all of them at the same time, and keeps it under a
   token of the mesh (its SHA-256, path and shaping), so a worker keeps its cuts from one
   case to the next; the sweep's own process keeps the hull it read under the same token,
   so a later sweep of the same file does not read it again. The tasks go to Dask with
   priorities in their order, the largest first and single cases last. Each case is
   computed as a single run computes it: :func:`~hullslice.sweeps.run.hull_for` gives the
   hull the case's mass properties, and the case, made a :class:`~hullslice.Study`, runs
   by :func:`hullslice.study.simulation`, the call ``hullslice simulate`` makes for it.
   Dask runs the tasks: a local cluster of worker processes by default, any scheduler by
   its address, or in this process with ``workers=1``.
5. **records** (:mod:`.run`, :mod:`.store`): each case gives a record, its results
   (:func:`summarise`) or its one-line error (the others go on); a task whose worker dies
   is rerun by Dask, and a case that kills its worker each time is recorded as failed.
   Each record can be kept in a folder (``partial``) as it arrives, so that an interrupted
   sweep resumes where it stopped.
6. **dataset** (:mod:`.dataset`): an ``xarray.Dataset`` with one dimension per swept key
   (named as the key; ``case`` for the rows of a table), per-case variables with CF
   ``units`` and ``long_name`` (:data:`RESULTS`, the final value of every history column,
   the first time each limit was crossed) and provenance attributes (hullslice version,
   mesh and its SHA-256, solver and its options, the base case, the grid, the date).
"""

from __future__ import annotations

from .api import sweep
from .dataset import RESULTS, build, iter_failures, provenance  # noqa: F401
from .engine import (  # noqa: F401
    CONNECT_TIMEOUT,
    MAX_TASK_CASES,
    MIN_TASKS_PER_WORKER,
    TAIL_TASK_CASES,
    DaskRun,
    groups,
    require,
    run_cases,
    session,
)
from .plan import (  # noqa: F401
    COMPONENTS,
    MESH_KEYS,
    OUTPUT_KEYS,
    SWEEP_KEYS,
    Plan,
    apply,
    key_spec,
    load_sweep,
    make_plan,
)
from .run import (  # noqa: F401
    _HULLS,
    _SHARED,
    HullState,
    hull_for,
    load_inputs,
    run_batch,
    run_case,
    shaping,
    study_of,
    summarise,
)
from .store import PARTIAL_SPEC, Partial, jsonable, remove_partial, sha256, spec  # noqa: F401

__all__ = ["RESULTS", "SWEEP_KEYS", "Plan", "load_sweep", "make_plan", "sweep"]
