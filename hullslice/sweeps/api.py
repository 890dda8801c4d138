"""The sweep's entry point: :func:`sweep` runs a plan and returns its Dataset."""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from ..errors import InputError
from .dataset import build, provenance
from .engine import CONNECT_TIMEOUT, capped_workers, require, run_cases, session
from .plan import Plan, load_sweep, make_plan
from .run import load_inputs, shaping, with_case_mass
from .store import Partial, sha256, spec


def sweep(
    case_or_study: str | os.PathLike | Mapping[str, Any] | Plan,
    grid: Mapping[str, Any] | None = None,
    client=None,
    *,
    workers: int | None = None,
    keep_histories: bool = False,
    partial: str | os.PathLike | None = None,
    resume: bool = False,
    progress: Callable[[int, int, int], None] | None = None,
    timeout: float = CONNECT_TIMEOUT,
):
    """Run a parameter sweep and return its results as an ``xarray.Dataset``.

    Parameters
    ----------
    case_or_study : path, mapping or Plan
        A case file (TOML; its ``[sweep]`` table is the grid unless ``grid`` is given), a
        case as a mapping (paths relative to the working folder), or a :class:`Plan`.
    grid : mapping, optional
        Swept key -> list of values (case-file units: SI, angles in degrees), and/or
        ``cases`` (a CSV of one case per row, or a list of mappings); see :func:`make_plan`.
    client : dask.distributed.Client or str, optional
        The Dask client, or a scheduler's address (``"tcp://host:8786"``). Without it, a
        local cluster of ``workers`` processes (default: one per core) is started and
        stopped; ``workers=1`` runs in this process, without Dask. More workers than
        :data:`~hullslice.sweeps.engine.MAX_WORKERS_PER_CORE` per core are that many, with
        a warning. A scheduler given by address must have a worker within ``timeout``.
    keep_histories : bool
        Keep every case's history along a ``t`` dimension (variables ``history_<column>``).
    partial : path, optional
        Folder that keeps each finished case as it arrives (one small JSON file per case);
        an interrupted sweep run again with ``resume=True`` skips the cases found there.
    resume : bool
        Continue the sweep kept in ``partial`` (it must be of the same case and grid).
    progress : callable, optional
        Called as ``progress(done, total, failed)`` after each case.
    timeout : float
        Seconds to wait for a scheduler given by address, and then for its first worker
        (default 10).

    Returns
    -------
    xarray.Dataset
        See the module's documentation; a case that failed has NaN results and its
        message in ``error``.
    """
    require("xarray")
    from .._version import __version__
    from ..solvers.registry import DEFAULT_SOLVER, describe, get_solver

    if isinstance(case_or_study, Plan):
        plan = case_or_study
    elif isinstance(case_or_study, Mapping):
        plan = make_plan(case_or_study, grid or {})
    else:
        plan = load_sweep(case_or_study)
        if grid is not None:
            plan = make_plan({k: v for k, v in plan.base.items()}, grid, source=str(case_or_study))
    base = plan.base
    if workers is not None and (
        isinstance(workers, bool) or int(workers) != workers or workers < 1
    ):
        raise InputError(f"workers {workers!r} is not a positive whole number: give 1 or more")
    if workers is not None and client is None:
        workers = capped_workers(int(workers))
    mesh_path = Path(base["mesh"])
    try:
        mesh_sha = sha256(mesh_path)
    except OSError:  # reading the mesh says what is wrong, in its own words
        mesh_sha = ""
    token = f"{mesh_sha}:{mesh_path.resolve()}:{shaping(base)!r}" if mesh_sha else ""
    hull, inputs = load_inputs(base, token)  # kept under the token for the next sweep
    # the base case's own mass properties are checked here, at each sweep (its warnings
    # shown once, whatever hull the process kept)
    with_case_mass(hull, base, inputs)
    solver = get_solver(base.get("solver", DEFAULT_SOLVER), **base.get("solver_options", {}))
    kept = (
        Partial(
            Path(partial),
            spec(base, plan.grid, len(plan.cases), mesh_sha, keep_histories),
            resume,
            {"hullslice": __version__, "solver": describe(solver)},
        )
        if partial is not None
        else None
    )
    records: dict[int, dict] = dict(kept.done) if kept else {}
    total = len(plan.cases)
    todo = [i for i in range(total) if i not in records]
    failed = sum(1 for r in records.values() if r.get("error"))

    def finish(index: int, record: dict) -> None:
        nonlocal failed
        records[index] = record
        failed += bool(record.get("error"))
        if kept is not None:
            kept.add(index, record)
        if progress is not None:
            progress(len(records), total, failed)

    with session(client, workers, timeout, needed=bool(todo)) as dask_client:
        if kept is not None:
            kept.create()
        if progress is not None:
            progress(len(records), total, failed)
        run_cases(plan, hull, inputs, todo, keep_histories, finish, dask_client, token)
    ds = build(plan, records, keep_histories)
    ds.attrs.update(provenance(plan, mesh_path.name, mesh_sha, solver, records))
    if kept is not None:
        ds.attrs["partial"] = str(kept.folder)
    return ds
