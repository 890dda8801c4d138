"""One case of a sweep, computed as a single run computes it: the case's hull, its mass
properties, the motion call, and the record of its results.

A checked ``simulate`` case (:func:`~hullslice.case.validate_case`) becomes a history in
three steps, each written once here and used by every path of a sweep (in this process or
on a Dask worker): :func:`read_mesh` and :func:`read_files` read the mesh and the case's
files, once per sweep (the mesh's hull kept for a later sweep of the same file);
:func:`hull_for` gives the hull the case's mass properties (kept for the next case with the
same ones); :func:`run_case` makes the case a :class:`~hullslice.Study` and runs it by
:func:`hullslice.study.simulation`, the call ``hullslice simulate`` makes for the same
case. :func:`run_batch` runs cases one after the other and records each
one's results (:func:`summarise`) or its one-line error.
"""

from __future__ import annotations

import math
import sys
import threading
import time
import traceback
import warnings
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import HullsliceError

#: The hull each process keeps, by token (see run_batch and read_mesh).
_SHARED: dict[str, Any] = {}
_SHARED_KEPT = 2
#: The warnings the reading of each hull kept by :func:`read_mesh` gave, by token.
_READ_WARNINGS: dict[str, list] = {}
_KEEP_LOCK = threading.Lock()

#: Hulls with their mass properties, kept by each worker process (key: mesh and mass).
_HULLS: dict[tuple, Any] = {}
_HULLS_KEPT = 8


def shaping(case: Mapping[str, Any]) -> dict[str, Any]:
    """How a checked case's mesh is read and shaped (units, axes, scale, repair, parts,
    fixes): the keyword arguments of :func:`~hullslice.load_hull` a single run passes
    (:func:`hullslice.study.mesh_options`)."""
    from ..study import mesh_options

    return mesh_options(case)


def read_mesh(case: Mapping[str, Any], token: str = ""):
    """The mesh of a checked case, without mass, read as a single run reads it.

    With a ``token`` (the mesh file's SHA-256, path and shaping, as :func:`run_batch`'s),
    the process keeps the hull under it, as the workers do: a later sweep of the same file,
    shaped the same way, does not read and check it again (0.5 s for a 128k-face mesh). The
    warnings its reading gave are recorded, all of them, and shown through the filters as
    they are, now and at each later sweep that takes the kept hull, each as from where it
    was given (its module's name and registry: a warning the filters show once is shown
    once, as reading the file again would show it)."""
    from ..mesh import load_hull

    if token and token in _SHARED:
        _show(_READ_WARNINGS.get(token, []))
        return _SHARED[token]
    caught: list = []
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")  # every one, to be shown through the filters
            hull = load_hull(Path(case["mesh"]), **shaping(case))
    finally:  # once recording has stopped (warnings before a failure too)
        _show(caught)
    if token:
        _keep(token, hull, caught)
    return hull


def _show(caught: list) -> None:
    """Show recorded warnings through the filters as :func:`warnings.warn` shows them: with
    the name and the registry of the module they were given from."""
    for w in caught:
        module, registry = _origin(w.filename)
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno, module=module,
                               registry=registry)  # fmt: skip


def _origin(filename: str) -> tuple[str | None, dict | None]:
    """The name and warnings registry of the module loaded from ``filename`` (None, None
    where none was)."""
    for mod in list(sys.modules.values()):
        if getattr(mod, "__file__", None) == filename:
            return mod.__name__, vars(mod).setdefault("__warningregistry__", {})
    return None, None


def _keep(token: str, hull, caught: list | None = None) -> None:
    """Keep ``hull`` under ``token`` (with the warnings its reading gave, ``caught``), the
    last :data:`_SHARED_KEPT` of them (a worker's threads may keep one at once)."""
    with _KEEP_LOCK:
        _SHARED[token] = hull
        _READ_WARNINGS[token] = list(caught or [])
        while len(_SHARED) > _SHARED_KEPT:
            gone = next(iter(_SHARED))
            _SHARED.pop(gone, None)
            _READ_WARNINGS.pop(gone, None)


def read_files(case: Mapping[str, Any]) -> dict[str, Any]:
    """The contents of a checked case's files besides its mesh: ``mass_distribution``
    (:class:`~hullslice.MassDistribution`) and ``kinematics``
    (:class:`~hullslice.Kinematics`), for the cases that name them."""
    from ..mass import read_mass_distribution
    from ..motion import read_kinematics

    inputs: dict[str, Any] = {}
    if "mass_distribution" in case:
        inputs["mass_distribution"] = read_mass_distribution(case["mass_distribution"])
    if "kinematics" in case:
        inputs["kinematics"] = read_kinematics(case["kinematics"])
    return inputs


def load_inputs(case: Mapping[str, Any], token: str = "") -> tuple[Any, dict[str, Any]]:
    """The mesh of a checked case without mass (:func:`read_mesh`, kept under ``token``
    if given) and its files' contents (:func:`read_files`)."""
    return read_mesh(case, token), read_files(case)


class HullState:
    """A hull as it travels to a worker: its pickled state (the arrays, name and mass
    properties), cheap to send and to receive; :meth:`build` makes the hull, and its
    ``Manifold``, where it is used (once per process under :func:`run_batch`'s token), so
    that the workers build theirs at the same time rather than one after the other."""

    def __init__(self, hull) -> None:
        self.kind = type(hull)
        self.state = hull.__getstate__()

    def build(self):
        """The hull, as unpickling it gives it."""
        hull = self.kind.__new__(self.kind)
        hull.__setstate__(self.state)
        return hull


def _mass_key(case: Mapping[str, Any]) -> tuple:
    cg = case.get("cg")
    return (
        case.get("mass"),
        str(case.get("mass_distribution")),
        None if cg is None else tuple(cg),
        case.get("inertia"),
    )


def with_case_mass(hull, case: Mapping[str, Any], inputs: Mapping[str, Any]):
    """The hull with the case's mass properties (``mass``, ``mass_distribution`` as read
    into ``inputs``, ``cg``, ``inertia``), checked and made afresh (with its warnings)."""
    return hull.with_mass(
        case.get("mass"),
        mass_distribution=inputs.get("mass_distribution"),
        cg=case.get("cg"),
        inertia=case.get("inertia"),
    )


def hull_for(hull, case: Mapping[str, Any], inputs: Mapping[str, Any]):
    """:func:`with_case_mass`, kept for the next case of the same hull, the same mass
    distribution as read (the same object: a sweep reads its files once, and a later
    sweep reads them again) and the same other mass properties."""
    md = inputs.get("mass_distribution")
    key = (id(hull), id(md), _mass_key(case))
    found = _HULLS.get(key)
    if found is not None and found[0] is hull and found[1] is md:
        return found[2]
    h = with_case_mass(hull, case, inputs)
    _HULLS[key] = (hull, md, h)
    while len(_HULLS) > _HULLS_KEPT:
        _HULLS.pop(next(iter(_HULLS)), None)
    return h


def study_of(case: Mapping[str, Any]):
    """The :class:`~hullslice.Study` of a checked ``simulate`` case: validated as any
    study is (a free fall without ``velocity`` or ``t_end`` is refused by name)."""
    from ..study import Study

    return Study.from_case(case, checked=True)


def run_case(hull, case: Mapping[str, Any], inputs: Mapping[str, Any] | None = None):
    """The :class:`~hullslice.motion.History` of one checked ``simulate`` case, computed by
    the same call as ``hullslice simulate`` and ``hullslice run`` make for it
    (:func:`hullslice.study.simulation`).

    ``hull`` is the mesh without mass (its mass properties come from the case); ``inputs``
    holds the case's files already read (``mass_distribution``, ``kinematics``).
    """
    from ..study import simulation

    inputs = inputs or {}
    study = study_of(case)
    return simulation(study, hull_for(hull, case, inputs), kinematics=inputs.get("kinematics"))


def summarise(history) -> dict[str, Any]:
    """A case's results from its history (see :data:`~hullslice.sweeps.dataset.RESULTS`),
    read from its columns generically: every column's final value, and the history's
    flagged share."""
    cols = history.columns()
    out: dict[str, Any] = {"steps": len(history), "stop_reason": str(history.stop_reason)}
    flagged = np.asarray(history.flagged_share, dtype=float)
    t = np.asarray(cols["t"], dtype=float)
    if len(history):
        i = int(np.argmax(cols["force"]))
        j = int(np.argmax(cols["acceleration"]))
        k = int(np.argmax(np.abs(cols["moment"])))
        out.update(
            peak_force=float(cols["force"][i]),
            peak_time=float(t[i]),
            peak_acceleration=float(cols["acceleration"][j]),
            peak_acceleration_time=float(t[j]),
            peak_moment=float(cols["moment"][k]),
            peak_moment_time=float(t[k]),
            flagged_share=float(flagged[i]),
            max_flagged_share=float(flagged.max()),
        )
    for name, values in cols.items():
        v = values[-1] if len(values) else math.nan
        out[f"final_{name}"] = str(v) if isinstance(v, str) else float(v)
    for rule, when in history.first_crossed.items():
        out[f"first_crossed_{rule}"] = math.nan if when is None else float(when)
    return out


def _history_record(history) -> dict[str, list]:
    return {
        name: [str(v) if isinstance(v, str) else float(v) for v in values]
        for name, values in history.columns().items()
    }


def run_batch(
    hull, items: Sequence[tuple[int, dict]], inputs: Mapping, keep: bool, token: str = ""
) -> list:
    """Run cases one after the other on one hull: ``[(index, record), ...]``. A case that
    fails gives a record with its one-line ``error``; the others are not affected.

    ``token`` names the hull (its mesh's SHA-256 and axes): a process keeps the first copy
    it gets under that name and uses it for every later task, with the cuts it has made,
    whichever copy Dask hands it. With a token, ``hull`` may also be a :class:`HullState`,
    built into the hull once; a hull that cannot be built fails every case of the batch
    with its message."""
    if token:
        found = _SHARED.get(token)
        if found is None:
            try:
                found = hull.build() if isinstance(hull, HullState) else hull
            except HullsliceError as exc:
                return [(index, {"error": str(exc), "runtime": 0.0}) for index, _ in items]
            _keep(token, found)
        hull = found
    out = []
    for index, case in items:
        start = time.perf_counter()
        try:
            history = run_case(hull, case, inputs)
            record = summarise(history)
            if keep:
                record["history"] = _history_record(history)
            record["error"] = ""
        except HullsliceError as exc:
            record = {"error": str(exc)}
        except Exception as exc:  # a bug must not lose the other cases: record it
            where = traceback.extract_tb(exc.__traceback__)[-1]
            record = {
                "error": f"internal error: {type(exc).__name__}: {exc} "
                f"({Path(where.filename).name}:{where.lineno})"
            }
        record["runtime"] = time.perf_counter() - start
        out.append((index, record))
    return out
