"""A sweep's results as an ``xarray.Dataset``: one dimension per swept key (``case`` for the
rows of a table), one variable per result with CF ``units`` and ``long_name``, and the
provenance of the computation in its attributes."""

from __future__ import annotations

import datetime
import json
import math
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from ..xarray_io import attrs_for
from .plan import Plan, key_spec
from .store import jsonable

#: Per-case results: name -> (units, long name). Besides these, every history column ``c``
#: gives ``final_c`` (its value at the end of the run) and every stop rule ``r`` gives
#: ``first_crossed_r`` (s).
RESULTS: dict[str, tuple[str, str]] = {
    "peak_force": ("N", "largest vertical force"),
    "peak_time": ("s", "time of the largest vertical force"),
    "peak_acceleration": ("m s-2", "largest vertical acceleration, positive up"),
    "peak_acceleration_time": ("s", "time of the largest vertical acceleration"),
    "peak_moment": ("N m", "pitch moment of largest magnitude, positive nose up"),
    "peak_moment_time": ("s", "time of the pitch moment of largest magnitude"),
    "flagged_share": ("1", "share of the force carried by flagged slices at the peak force"),
    "max_flagged_share": ("1", "largest share of the force carried by flagged slices"),
    "steps": ("1", "instants recorded"),
    "runtime": ("s", "computing time of the case on its worker"),
    "stop_reason": ("", "what ended the run (t_end or a stop rule)"),
    "error": ("", "why the case failed, empty when it ran"),
}

_TEXT = {name for name, (units, _) in RESULTS.items() if not units}


def build(plan: Plan, records: Mapping[int, dict], keep: bool):
    """The Dataset of a sweep's records (index of the case in ``plan.cases`` -> record):
    one variable per result along the plan's dimensions (NaN or empty text for a case
    without a record), the swept keys as coordinates, and with ``keep`` the histories
    along ``t`` (s)."""
    import xarray as xr

    shape = plan.shape
    names: list[str] = [n for n in RESULTS]
    skip = {*RESULTS, "history", "lost"}
    extra = sorted({k for r in records.values() for k in r if k not in skip})
    names += [n for n in extra if n.startswith("final_")] + [
        n for n in extra if not n.startswith("final_")
    ]
    data = {}
    for name in names:
        values = [records.get(i, {}).get(name) for i in range(len(plan.cases))]
        text = name in _TEXT or any(isinstance(v, str) for v in values)
        if text:
            arr = np.array(["" if v is None else str(v) for v in values], dtype=object)
        else:
            arr = np.array([math.nan if v is None else float(v) for v in values], dtype=float)
        data[name] = (plan.dims, arr.reshape(shape), _result_attrs(name))
    coords: dict[str, Any] = {}
    for d in plan.dims:
        attrs = {} if d == "case" else _key_attrs(d)
        coords[d] = (d, plan.coords[d], attrs)
    for k, v in plan.table.items():
        coords[k] = ("case", v, _key_attrs(k))
    if keep:
        histories = {i: r["history"] for i, r in records.items() if r.get("history")}
        t = np.unique(np.concatenate([np.asarray(h["t"], float) for h in histories.values()]))
        coords["t"] = ("t", t, {"units": "s", "long_name": "time since the start of the run"})
        columns = [c for h in histories.values() for c in h if c != "t"]
        for col in dict.fromkeys(columns):
            text = any(isinstance(v, str) for h in histories.values() for v in h.get(col, [])[:1])
            fill = "" if text else math.nan
            arr = np.full((len(plan.cases), len(t)), fill, dtype=object if text else float)
            for i, h in histories.items():
                if col in h:
                    arr[i, np.searchsorted(t, np.asarray(h["t"], float))] = h[col]
            data[f"history_{col}"] = (
                (*plan.dims, "t"),
                arr.reshape((*shape, len(t))),
                attrs_for(col),
            )
    return xr.Dataset(data, coords=coords)


def _result_attrs(name: str) -> dict[str, str]:
    from ..motion import STOP_RULES

    if name in RESULTS:
        units, long_name = RESULTS[name]
        return {"units": units, "long_name": long_name} if units else {"long_name": long_name}
    if name.startswith("final_"):
        a = attrs_for(name.removeprefix("final_"))
        a["long_name"] = "at the end of the run: " + a.get("long_name", "")
        return a
    if name.startswith("first_crossed_"):
        rule = name.removeprefix("first_crossed_")
        return {"units": "s", "long_name": f"first time: {STOP_RULES.get(rule, rule)}"}
    return {"long_name": name.replace("_", " ")}


def _key_attrs(key: str) -> dict[str, str]:
    k = key_spec(key)
    units = {"deg": "degree", "deg/s": "degree s-1", "m/s": "m s-1", "m/s^2": "m s-2",
             "kg/m^3": "kg m-3", "kg*m^2": "kg m2", "": "1"}.get(k.unit, k.unit)  # fmt: skip
    return {"units": units, "long_name": k.help}


def iter_failures(ds) -> Iterable[tuple[str, str]]:
    """``(case label, error)`` of each failed case of a sweep's Dataset."""
    err = ds["error"]
    for idx in zip(*np.nonzero(err.values != ""), strict=False):
        point = {d: ds[d].values[i] for d, i in zip(err.dims, idx, strict=True)}
        label = ", ".join(f"{d}={v:g}" for d, v in point.items())
        yield label, str(err.values[idx])


def provenance(
    plan: Plan, mesh_name: str, mesh_sha256: str, solver, records: Mapping[int, dict]
) -> dict[str, Any]:
    """The attributes of a sweep's Dataset: CF conventions, the hullslice version, the mesh
    and its SHA-256, the solver and its options, the base case, the grid, the date, the
    number of cases and of failed ones."""
    from .._version import __version__

    created = datetime.datetime.now(datetime.UTC).replace(microsecond=0).isoformat()
    base = plan.base
    return {
        "title": str(base.get("title", f"sweep of {mesh_name}")),
        "Conventions": "CF-1.8",
        "source": f"hullslice {__version__}, 2D+t method",
        "history": f"{created} hullslice sweep of {len(plan.cases)} cases",
        "hullslice_version": __version__,
        "created": created,
        "mesh": mesh_name,
        "mesh_sha256": mesh_sha256,
        "solver": solver.name,
        "solver_options": json.dumps(jsonable(dict(solver.settings)), sort_keys=True),
        "base_case": json.dumps(jsonable(base)),
        "sweep": json.dumps(jsonable(plan.grid)),
        "cases": len(plan.cases),
        "failed": int(sum(1 for r in records.values() if r.get("error"))),
    }
