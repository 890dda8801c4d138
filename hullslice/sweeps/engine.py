"""Where a sweep's cases run: in this process, or on Dask, in groups that share a hull.

The cases are grouped into tasks (:func:`groups`): the same mass properties and pitch
together, since they share a hull with those properties and, with the fixed slicing, its
cuts. The hull and the files' contents go to the workers once, as tasks of their own, and
each task runs its cases with :func:`~hullslice.sweeps.run.run_batch`. A task whose worker
dies is rerun by Dask; a case that kills its worker each time is recorded as failed.
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager, nullcontext
from typing import Any

from ..errors import HullsliceWarning, InputError
from ..extras import need
from .plan import Plan
from .run import HullState, _mass_key, run_batch

#: Called with each finished case: ``finish(index, record)``.
Finish = Callable[[int, dict], None]

#: Seconds to wait for a scheduler given by its address, and then for its first worker.
CONNECT_TIMEOUT = 10.0

#: Most worker processes a local cluster starts per core: a case keeps its core busy, and
#: more processes only share the cores, each with its own memory.
MAX_WORKERS_PER_CORE = 4

#: Environment variables Dask sets in its workers that a sweep's own cluster leaves unset.
#: ``MALLOC_TRIM_THRESHOLD_`` (glibc) also fixes the threshold above which memory comes from
#: ``mmap``: every array of the cut is then mapped and unmapped afresh, and a free-pitch case
#: takes twice as long in a worker as in a plain process. (A cluster given to a sweep is
#: left as it is.)
UNSET_WORKER_ENVIRON = ("MALLOC_TRIM_THRESHOLD_",)

#: Tasks a sweep's cases are grouped into, at least, per worker: more balance the
#: workers' loads at the end, fewer share more cuts (see :func:`groups`).
MIN_TASKS_PER_WORKER = 4
#: The most cases in one task.
MAX_TASK_CASES = 16
#: Cases in each of the last, small tasks of a sweep (see :func:`groups`).
TAIL_TASK_CASES = 1


def require(*modules: str) -> None:
    """Import the libraries of the extra ``hullslice[sweep]`` a sweep will use, or raise
    the one-line hint naming what to install."""
    for m in modules:
        need("sweep", m, "a sweep")


def groups(plan: Plan, todo: list[int], n_workers: int) -> list[list[int]]:
    """The cases to run, grouped into tasks, largest first.

    Cases with the same mass properties and pitch share a hull and, with the fixed slicing,
    its cuts: they stay in one task, so that one worker makes those cuts, unless there are
    too few such groups to give every worker :data:`MIN_TASKS_PER_WORKER` tasks; then each
    group is split into tasks of equal size. No task holds more than :data:`MAX_TASK_CASES`
    cases (a task's cases are kept for ``resume`` when it ends). The last tasks, one per
    worker, are split into tasks of :data:`TAIL_TASK_CASES` cases, so that the workers end
    at about the same time.
    """
    keyed: dict[tuple[str, Any], list[int]] = {}
    for i in sorted(todo):
        case = plan.case(i)
        keyed.setdefault((repr(_mass_key(case)), case.get("pitch", 0.0)), []).append(i)
    wanted = MIN_TASKS_PER_WORKER * max(1, n_workers)
    parts = max(1, math.ceil(wanted / max(1, len(keyed))))
    out = []
    for _, cases in sorted(keyed.items(), key=lambda kv: (kv[0][0], kv[0][1])):
        n = max(min(parts, len(cases)), math.ceil(len(cases) / MAX_TASK_CASES))
        size = math.ceil(len(cases) / n)
        out += [cases[j : j + size] for j in range(0, len(cases), size)]
    out.sort(key=len, reverse=True)
    # the finish: the last tasks, one per worker, in small ones, so that the workers end
    # together (DaskRun hands them to Dask in this order, as priorities)
    w = max(1, n_workers)
    if len(out) > w:
        n = TAIL_TASK_CASES
        out = out[:-w] + [t[j : j + n] for t in out[-w:] for j in range(0, len(t), n)]
    return out


def capped_workers(workers: int) -> int:
    """``workers``, or :data:`MAX_WORKERS_PER_CORE` per core of this machine with a warning
    when it asks for more."""
    cores = os.cpu_count() or 1
    cap = MAX_WORKERS_PER_CORE * cores
    if workers <= cap:
        return workers
    warnings.warn(
        f"workers {workers} is more than {MAX_WORKERS_PER_CORE} per core ({cores} cores here): "
        f"the sweep starts {cap} (more would only share the cores, each with its own memory)",
        HullsliceWarning,
        stacklevel=3,
    )
    return cap


def _client(client, workers: int | None, timeout: float):
    """``(client, owned)``: the Dask client to use, and whether this sweep made it."""
    require("distributed")
    from distributed import Client

    if client is not None and not isinstance(client, str | os.PathLike):
        return client, False
    if client is not None:
        address = str(client)
        try:
            connected = Client(address, timeout=timeout)
        except Exception as exc:  # OSError, TimeoutError, ValueError for a bad address
            why = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
            raise InputError(
                f"no Dask scheduler answers at {address!r} within {timeout:g} s ({why}): "
                "start one ('dask scheduler'), check the address, or leave out --scheduler "
                "to run on this machine"
            ) from None
        try:
            connected.wait_for_workers(1, timeout=timeout)
        except BaseException as exc:
            connected.close()
            if not isinstance(exc, Exception):
                raise
            raise InputError(
                f"the Dask scheduler at {address!r} has no workers (none joined within "
                f"{timeout:g} s): start some ('dask worker {address}'), or leave out "
                "--scheduler to run on this machine"
            ) from None
        return connected, True
    return local_client(workers or os.cpu_count() or 1), True


#: Where a sweep's own cluster serves its HTTP routes (health and metrics; the dashboard is
#: off): this machine only, on a free port, so that a port already taken (Dask's 8787 by
#: another cluster) is no conflict and no warning.
HTTP_ADDRESS = "127.0.0.1:0"


#: Dask settings of a sweep's own cluster, passed to each worker by its nanny.
WORKER_CONFIG = {"distributed.worker.profile.enabled": False}


def local_client(workers: int):
    """A Dask client of a cluster of ``workers`` processes on this machine, one thread each,
    made as a sweep makes its own (:data:`UNSET_WORKER_ENVIRON` unset in the workers; a
    worker started again later, after a crash, inherits this process's environment: see
    :func:`worker_environ`, which a sweep holds for as long as its cluster runs).

    The cluster starts quietly: no dashboard, its HTTP server on a free port
    (:data:`HTTP_ADDRESS`), its logs silenced below CRITICAL, and the warnings Dask's own
    modules give while it starts (its notes on ports and start-up times, for a programmer
    running Dask, not for a sweep's user) are not shown; hullslice's are. Its workers run
    without Dask's statistical profiler (:data:`WORKER_CONFIG`, see :func:`worker_environ`),
    which reads every thread's stack every 10 ms for a dashboard the cluster does not have:
    a free-pitch case took a tenth longer in a worker with it.
    """
    require("distributed")
    from distributed import Client, LocalCluster

    with worker_environ(), warnings.catch_warnings():
        warnings.filterwarnings("ignore", module=r"(distributed|dask)(\.|$)")
        cluster = LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            scheduler_kwargs={"dashboard": False, "dashboard_address": HTTP_ADDRESS},
            silence_logs=50,
        )
        try:
            return Client(cluster)
        except BaseException:
            cluster.close()
            raise


@contextmanager
def worker_environ() -> Iterator[None]:
    """While inside, Dask workers started by this process go without
    :data:`UNSET_WORKER_ENVIRON`: unset in Dask's settings (read by each nanny as it is made)
    and in this process's environment (which every worker inherits, and where an earlier
    cluster of this process may have left it); both are as they were on leaving. They get
    :data:`WORKER_CONFIG` too (Dask's settings, which a nanny hands to each worker it
    starts)."""
    require("distributed")
    import dask

    unset = {f"distributed.nanny.pre-spawn-environ.{key}": None for key in UNSET_WORKER_ENVIRON}
    saved = {key: os.environ.pop(key) for key in UNSET_WORKER_ENVIRON if key in os.environ}
    try:
        with dask.config.set({**unset, **WORKER_CONFIG}):
            yield
    finally:
        os.environ.update(saved)


def _value(x):
    return x


class DaskRun:
    """The cases ``todo`` of ``plan`` submitted to a Dask ``client`` as tasks
    (:func:`groups`); :meth:`collect` gathers their records as they end.

    The hull goes to the workers as its state (``source``, a
    :class:`~hullslice.sweeps.run.HullState`), a task of its own (not scattered data: Dask
    computes it again if the workers holding it die): cheap to send and to receive, each
    worker builds the hull from it at its first task, all of them at the same time, and
    keeps it under ``token``.
    """

    def __init__(self, client, plan: Plan, todo, inputs, keep: bool, token: str, source):
        self.client = client
        self.plan = plan
        self.keep = keep
        self.token = token
        self.futures: dict = {}
        try:
            n_workers = max(1, len(client.scheduler_info().get("workers", {})))
            self.source = client.submit(_value, source, pure=False)
            self.inputs = client.submit(_value, inputs, pure=False)
            tasks = groups(plan, todo, n_workers)
            for k, group in enumerate(tasks):  # handed out in this order (Dask's priority)
                self.futures[self.submit(group, priority=len(tasks) - k)] = group
        except BaseException:
            self.cancel()
            raise

    def submit(self, group: list[int], priority: int = 0):
        """The task running the cases ``group``; of the tasks waiting, Dask hands out those
        of the highest ``priority`` first (without it, not in the order they came)."""
        items = [(i, self.plan.case(i)) for i in group]
        return self.client.submit(
            run_batch, self.source, items, self.inputs, self.keep, self.token, pure=False,
            retries=1, priority=priority,
        )  # fmt: skip

    def cancel(self) -> None:
        """Cancel the tasks that have not ended."""
        for fut in list(self.futures):
            fut.cancel()

    def collect(self, finish: Finish) -> None:
        """Call ``finish(index, record)`` for each case as its task ends."""
        from distributed import as_completed

        futures = self.futures
        try:
            queue = as_completed(list(futures))
            # Cases whose worker died under them (Dask gave up: KilledWorker): the case that
            # kills it, or one that was on the worker when another did. Each runs once
            # more, alone and one after the other, so that only the case that kills its
            # worker again is recorded as failed.
            suspects: list[int] = []
            alone: list = []  # the one suspect running, if any
            for fut in queue:
                group = futures.pop(fut)
                retried = bool(alone) and fut is alone[0]
                if retried:
                    alone.clear()
                try:
                    results = fut.result()
                except Exception as exc:
                    results = []
                    if not retried:
                        suspects.extend(group)
                    else:
                        why = str(exc).splitlines()[0] if str(exc) else ""
                        results = [
                            (
                                group[0],
                                {
                                    "error": f"the worker running this case stopped "
                                    f"({type(exc).__name__}: {why})",
                                    "runtime": math.nan,
                                    "lost": True,  # resuming runs it again
                                },
                            )
                        ]
                if suspects and not alone:
                    i = suspects.pop(0)
                    f = self.submit([i])
                    futures[f] = [i]
                    alone.append(f)
                    queue.add(f)
                for index, record in results:
                    finish(index, record)
        except BaseException:
            self.cancel()
            raise


@contextmanager
def session(client, workers: int | None, timeout: float, needed: bool) -> Iterator[Any]:
    """The Dask client a sweep runs on, or None to run in this process (``workers=1``
    without a client, or nothing to run); a cluster started here is stopped on leaving."""
    if not needed or (client is None and workers == 1):
        yield None
        return
    local = client is None  # a cluster of this machine, started here
    with worker_environ() if local else nullcontext():  # also for workers started again
        dask_client, owned = _client(client, workers, timeout)
        try:
            yield dask_client
        finally:
            if owned:
                cluster = getattr(dask_client, "cluster", None)
                dask_client.close()
                if cluster is not None:
                    cluster.close()


def run_cases(
    plan: Plan,
    hull,
    inputs: Mapping[str, Any],
    todo: list[int],
    keep: bool,
    finish: Finish,
    client=None,
    token: str = "",
) -> None:
    """Run the cases ``todo`` of ``plan`` on ``client`` (None: in this process, one case
    at a time), calling ``finish(index, record)`` as each one ends; on Dask the workers
    build the hull from its state (:class:`~hullslice.sweeps.run.HullState`), kept under
    ``token`` (see :func:`~hullslice.sweeps.run.run_batch`)."""
    if client is None:
        for i in todo:
            for index, record in run_batch(hull, [(i, plan.case(i))], inputs, keep):
                finish(index, record)
    elif todo:
        DaskRun(client, plan, todo, inputs, keep, token, HullState(hull)).collect(finish)
