"""Parameter sweeps: many cases of one time history, run on Dask, as a labelled Dataset.

A sweep is a base case (a ``simulate`` case, see :mod:`hullslice.case`) and a grid: case
keys mapped to lists of values, run as a full factorial (``velocity = [-1.0, -1.5]`` and
``pitch = [4, 6, 8]`` are six cases), and/or ``cases``, a table with one case per row (a CSV
file whose columns are case keys, e.g. a ``scipy.stats.qmc`` design). In a case file the grid
is the ``[sweep]`` table.

Execution: the hull is read and checked once, here; it travels to the workers pickled (its
``Manifold`` is rebuilt there) and stays in their memory, so a worker keeps its cuts from one
case to the next. Cases with the same mass properties and pitch are grouped into one task
(the fixed slicing's cuts are per pitch), a few tasks per worker. Dask runs the tasks: a local
cluster of worker processes by default, any scheduler by its address, or in this process with
``workers=1``. A case that fails records its one-line error and the others go on; a task
whose worker dies is rerun by Dask, and a case that kills its worker each time is recorded
as failed. Each finished case can be kept in a folder (``partial``) as it arrives, so that a
sweep that is interrupted resumes where it stopped.

Results: an ``xarray.Dataset`` with one dimension per swept key (named as the key; ``case``
for the rows of a table), per-case variables with CF ``units`` and ``long_name``
(:data:`RESULTS`, the final value of every history column, the first time each limit was
crossed) and provenance attributes (hullslice version, mesh and its SHA-256, solver and its
options, the base case, the grid, the date).
"""

from __future__ import annotations

import datetime
import difflib
import hashlib
import itertools
import json
import math
import os
import shutil
import time
import tomllib
import traceback
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .case import COMMAND_KEYS, MAX_CASE_BYTES, SCHEMA, case_command, validate_case
from .errors import CaseError, HullsliceError, InputError, MissingDependencyError
from .paths import printable

__all__ = ["RESULTS", "SWEEP_KEYS", "Plan", "load_sweep", "make_plan", "sweep"]

#: Keys that shape the mesh: one mesh per sweep, so a sweep does not vary them.
MESH_KEYS = ("scale", "length")
#: Keys of a case that a sweep does not take: it writes one dataset (``-o``), not a file
#: per case.
OUTPUT_KEYS = ("output", "plot", "format")

#: Keys a sweep can vary: the number keys of a ``simulate`` case, and the slice count.
SWEEP_KEYS: tuple[str, ...] = tuple(
    name
    for name, key in SCHEMA.items()
    if name in COMMAND_KEYS["simulate"]
    and (key.kind == "number" or name == "slices")
    and name not in MESH_KEYS
)

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

#: Seconds to wait for a scheduler given by its address.
CONNECT_TIMEOUT = 10.0

#: Tasks a sweep's cases are grouped into, per worker: more balance the workers' loads at
#: the end, fewer share more cuts.
TASKS_PER_WORKER = 8

#: File of a partial sweep's description, in its folder.
PARTIAL_SPEC = "sweep.json"


# -- the plan ------------------------------------------------------------------------------


@dataclass(frozen=True)
class Plan:
    """A checked sweep: the base case and every case to run, with where it goes.

    Attributes
    ----------
    base : dict
        The base case, checked (:func:`~hullslice.case.validate_case`).
    dims : tuple of str
        The result's dimensions: the table's ``case`` first when there is one, then the
        swept keys in the order given.
    coords : dict of str to array
        Each dimension's values (``case``: the row numbers 0, 1, ...).
    table : dict of str to array
        The table's columns, along ``case`` (empty without a table).
    cases : list of dict
        The keys each case changes, in the order of the dataset's points (C order).
    grid : dict
        The grid as given (JSON-able), for provenance.
    """

    base: dict[str, Any]
    dims: tuple[str, ...]
    coords: dict[str, np.ndarray]
    table: dict[str, np.ndarray]
    cases: list[dict[str, Any]]
    grid: dict[str, Any] = field(default_factory=dict)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(self.coords[d]) for d in self.dims)

    def label(self, i: int) -> str:
        """A case's keys as ``key=value, ...`` for messages."""
        return ", ".join(f"{k}={v:g}" for k, v in self.cases[i].items())

    def case(self, i: int) -> dict[str, Any]:
        """The checked case ``i``: the base case with its keys."""
        return {**self.base, **self.cases[i]}


def _number_list(key: str, values: Any, where: str) -> list:
    if not isinstance(values, list):
        raise CaseError(
            f"{where}[sweep] key {key!r} must be a list of values, e.g. {key} = [1.0, 2.0], "
            f"not {values!r}"
        )
    if not values:
        raise CaseError(f"{where}[sweep] key {key!r} is an empty list: give at least one value")
    whole = SCHEMA[key].kind != "number"
    for v in values:
        ok = isinstance(v, int) if whole else isinstance(v, int | float)
        if isinstance(v, bool) or not ok or (not whole and not math.isfinite(v)):
            what = "a whole number" if whole else "a finite number"
            unit = f" in {SCHEMA[key].unit}" if SCHEMA[key].unit else ""
            raise CaseError(
                f"{where}[sweep] key {key!r}: every value must be {what}{unit}, not {v!r}"
                + (" (write the number without quotes)" if isinstance(v, str) else "")
            )
    if len(set(values)) != len(values):
        raise CaseError(f"{where}[sweep] key {key!r} repeats a value: {values!r}")
    return [int(v) for v in values] if whole else [float(v) for v in values]


def _sweep_key(key: Any, where: str) -> str:
    if key in SWEEP_KEYS:
        return key
    keys = ", ".join(SWEEP_KEYS)
    if key in SCHEMA:
        raise CaseError(
            f"{where}[sweep] key {key!r} is not a number key of a simulate case: a sweep varies "
            f"{keys}"
        )
    close = difflib.get_close_matches(str(key), [*SWEEP_KEYS, "cases"], n=1)
    hint = f"did you mean {close[0]!r}? " if close else ""
    raise CaseError(f"{where}[sweep] unknown key {key!r}; {hint}a sweep varies {keys} or cases")


def _read_table(path: Path, where: str) -> dict[str, list]:
    """The columns of a cases table (CSV, header of case keys, one case per row), read as
    every table hullslice reads (:func:`hullslice.tables.read_csv`: UTF-8 or UTF-16, true
    line numbers, no content of a file that is not a table quoted)."""
    from .tables import header_text, read_csv

    name = printable(path)
    try:
        header, rows = read_csv(path, f"{where}[sweep] cases")
    except CaseError as exc:
        raise CaseError(str(exc)) from None
    if not rows:
        raise CaseError(
            f"{where}[sweep] cases file {name!r} has no rows: give a header of case keys and "
            "one case per row"
        )
    if header_text(header) != f"its header: {', '.join(header)}":
        raise CaseError(
            f"{where}[sweep] cases file {name!r}: {header_text(header)}; give a header of "
            "case keys and one case per row"
        )
    for h in header:
        if h not in SWEEP_KEYS:
            _sweep_key(h, f"{where}[sweep] cases file {name!r}: column {h!r}: ")
    if len(set(header)) != len(header):
        raise CaseError(f"{where}[sweep] cases file {name!r} repeats a column: {header!r}")
    columns: dict[str, list] = {h: [] for h in header}
    for lineno, row in rows:
        if len(row) != len(header):
            raise CaseError(
                f"{where}[sweep] cases file {name!r} line {lineno} has {len(row)} values for "
                f"{len(header)} columns"
            )
        for h, cell in zip(header, row, strict=True):
            try:
                value = float(cell)
            except ValueError:
                value = math.nan
            whole = SCHEMA[h].kind != "number"
            if not math.isfinite(value) or (whole and value != round(value)):
                what = "a whole number" if whole else "a finite number"
                raise CaseError(
                    f"{where}[sweep] cases file {name!r} line {lineno} column {h!r}: "
                    f"{printable(cell.strip())!r} is not {what}"
                )
            columns[h].append(int(value) if whole else value)
    return columns


def make_plan(
    case: Mapping[str, Any],
    grid: Mapping[str, Any],
    *,
    base: str | os.PathLike | None = None,
    source: str = "",
) -> Plan:
    """Check a base case and a grid and list the cases of the sweep.

    Parameters
    ----------
    case : mapping
        The base case, as a case file holds it (``tomllib``'s dict) or already checked.
    grid : mapping
        Swept key -> list of values (in the case file's units: SI, angles in degrees), and
        optionally ``cases``: a CSV path (relative to ``base``) or a list of mappings, one
        case per row.
    base : path, optional
        Folder of the case file (for relative paths).
    source : str
        The case file's name, for messages.

    Raises
    ------
    CaseError
        The base case is not a ``simulate`` case, the grid is empty, a key is unknown or
        not a number key, a list is empty or holds a value that is not a number, a table
        has a column that is not a case key; or a case of the grid is not a valid case (the
        message names the case).
    """
    where = f"case file {source!r}: " if source else "case: "
    given = [k for k in OUTPUT_KEYS if k in case]
    if given:
        raise CaseError(
            f"{where}a sweep writes one dataset, given by -o OUT (.nc, .zarr or .parquet); "
            f"leave out the key {given[0]!r}"
        )
    checked = validate_case(_raw(case), base=base, source=source)
    command = case_command(checked)
    if command != "simulate":
        raise CaseError(
            f"{where}a sweep runs time histories: the case's command is {command!r}; give "
            'command = "simulate" with velocity and t_end (or kinematics)'
        )
    if not isinstance(grid, Mapping) or not grid:
        raise CaseError(
            f"{where}[sweep] is empty: give at least one case key with a list of values, e.g. "
            'pitch = [4.0, 6.0, 8.0], or cases = "design.csv"'
        )
    table: dict[str, list] = {}
    axes: dict[str, list] = {}
    for key, values in grid.items():
        if key == "cases":
            if isinstance(values, str | os.PathLike):
                p = Path(values)
                table = _read_table(p if base is None else Path(base, p), where)
            elif (
                isinstance(values, Sequence)
                and values
                and all(isinstance(r, Mapping) for r in values)
            ):
                names = list(values[0])
                for n in names:
                    _sweep_key(n, where)
                table = {n: _number_list(n, [r.get(n) for r in values], where) for n in names}
            else:
                raise CaseError(
                    f"{where}[sweep] key 'cases' must name a CSV file of cases (a header of "
                    f"case keys, one case per row), not {values!r}"
                )
            continue
        name = _sweep_key(key, where)
        axes[name] = _number_list(name, values, where)
    both = sorted(set(table) & set(axes))
    if both:
        raise CaseError(
            f"{where}[sweep] key {both[0]!r} is both a list and a column of the cases table: "
            "give it in one of them"
        )
    dims = (("case",) if table else ()) + tuple(axes)
    coords = {k: np.asarray(v) for k, v in axes.items()}
    n_rows = len(next(iter(table.values()))) if table else 0
    if table:
        coords["case"] = np.arange(n_rows)
    cases = []
    rows = range(n_rows) if table else [None]
    for row in rows:
        fixed = {k: v[row] for k, v in table.items()} if row is not None else {}
        for combo in itertools.product(*axes.values()):
            cases.append({**fixed, **dict(zip(axes, combo, strict=True))})
    plan = Plan(
        base=checked,
        dims=dims,
        coords=coords,
        table={k: np.asarray(v) for k, v in table.items()},
        cases=cases,
        grid={k: (str(v) if isinstance(v, str | os.PathLike) else v) for k, v in grid.items()},
    )
    for i, over in enumerate(cases):  # every case is a valid case file
        merged = _raw(checked)
        merged.update({k: ([v] if k == "slices" else v) for k, v in over.items()})
        try:
            validate_case(merged)
        except CaseError as exc:
            msg = str(exc).removeprefix("case: ")
            raise CaseError(f"{where}[sweep] case {plan.label(i)}: {msg}") from None
    return plan


def _raw(case: Mapping[str, Any]) -> dict[str, Any]:
    """A case as a case file holds it (paths as text, pairs as lists), to check again."""
    return {
        k: str(v) if isinstance(v, Path) else list(v) if isinstance(v, tuple) else v
        for k, v in case.items()
    }


def load_sweep(path: str | os.PathLike) -> Plan:
    """Read a case file with a ``[sweep]`` table and check it (see :func:`make_plan`)."""
    p = Path(path)
    name = str(p)
    if not p.exists():
        raise CaseError(f"case file {name!r} does not exist")
    if not p.is_file():
        raise CaseError(f"case path {name!r} is not a file: give a TOML case file")
    if p.stat().st_size > MAX_CASE_BYTES:
        raise CaseError(f"case file {name!r} is larger than {MAX_CASE_BYTES // 1024} KiB")
    try:
        data = tomllib.loads(p.read_bytes().decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise CaseError(f"case file {name!r} is not UTF-8 text (byte {exc.start})") from None
    except tomllib.TOMLDecodeError as exc:
        raise CaseError(f"case file {name!r} is not valid TOML: {exc}") from None
    grid = data.pop("sweep", None)
    if grid is None:
        raise CaseError(
            f"case file {name!r} has no [sweep] table: add one with the keys to vary, e.g. "
            "[sweep] pitch = [4.0, 6.0, 8.0]"
        )
    if not isinstance(grid, dict):
        raise CaseError(f"case file {name!r}: 'sweep' must be a table ([sweep]), not {grid!r}")
    return make_plan(data, grid, base=p.parent, source=name)


# -- running one case ----------------------------------------------------------------------

#: The hull each worker process keeps, by token (see run_batch).
_SHARED: dict[str, Any] = {}
_SHARED_KEPT = 2

#: Hulls with their mass properties, kept by each worker process (key: mesh and mass).
_HULLS: dict[tuple, Any] = {}
_HULLS_KEPT = 8


def _mass_key(case: Mapping[str, Any]) -> tuple:
    cg = case.get("cg")
    return (
        case.get("mass"),
        str(case.get("mass_distribution")),
        None if cg is None else tuple(cg),
        case.get("inertia"),
    )


def _hull_for(hull, case: Mapping[str, Any], inputs: Mapping[str, Any]):
    """The hull with the case's mass properties, kept for the next case that has them."""
    key = (id(hull), _mass_key(case))
    found = _HULLS.get(key)
    if found is not None and found[0] is hull:
        return found[1]
    h = hull.with_mass(
        case.get("mass"),
        mass_distribution=inputs.get("mass_distribution"),
        cg=case.get("cg"),
        inertia=case.get("inertia"),
    )
    _HULLS[key] = (hull, h)
    while len(_HULLS) > _HULLS_KEPT:
        _HULLS.pop(next(iter(_HULLS)))
    return h


def run_case(hull, case: Mapping[str, Any], inputs: Mapping[str, Any] | None = None):
    """The :class:`~hullslice.motion.History` of one checked ``simulate`` case, computed as
    ``hullslice simulate`` computes it from the case's command line.

    ``hull`` is the mesh without mass (its mass properties come from the case); ``inputs``
    holds the case's files already read (``mass_distribution``, ``kinematics``).
    """
    from .motion import DEFAULT_STOP_ON, prescribed, simulate
    from .solvers.registry import DEFAULT_SOLVER, get_solver
    from .state import Fluid

    inputs = inputs or {}
    h = _hull_for(hull, case, inputs)
    slices = case.get("slices", [32])
    slices = slices if isinstance(slices, int) else slices[0]
    common = {
        "slices": slices,
        "solver": get_solver(case.get("solver", DEFAULT_SOLVER), **case.get("solver_options", {})),
        "fluid": Fluid(rho=case["rho"], g=case["g"]),
        "deadrise": case["deadrise"],
        "slicing": case["slicing"],
        "max_flagged_share": case["max_flagged_share"],
    }
    if "kinematics" in case:
        return prescribed(h, inputs["kinematics"], **common)
    missing = [k for k in ("velocity", "t_end") if k not in case]
    if missing:
        raise InputError(
            f"a free fall needs {' and '.join(missing)} in the case (or kinematics for a "
            "prescribed motion)"
        )
    return simulate(
        h,
        case["velocity"],
        case["t_end"],
        dt=case.get("dt"),
        draft=case.get("draft", 0.0),
        pitch=math.radians(case.get("pitch", 0.0)),
        forward_speed=case.get("forward_speed", 0.0),
        pitch_rate=math.radians(case.get("pitch_rate", 0.0)),
        free_pitch=case.get("free_pitch", False),
        free_surge=case.get("free_surge", False),
        stop_on=() if case.get("continue_invalid", False) else DEFAULT_STOP_ON,
        **common,
    )


def summarise(history) -> dict[str, Any]:
    """A case's results from its history (see :data:`RESULTS`), read from its columns
    generically: every column's final value; the flagged share is the history's own
    ``flagged_share`` when it has one, else ``1 - valid_share``."""
    cols = history.output_columns()
    out: dict[str, Any] = {"steps": len(history), "stop_reason": str(history.stop_reason)}
    flagged = getattr(history, "flagged_share", None)  # an attribute, a column, or derived
    if flagged is None:
        flagged = cols.get("flagged_share", 1.0 - np.asarray(cols["valid_share"], dtype=float))
    flagged = np.asarray(flagged, dtype=float)
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
        for name, values in history.output_columns().items()
    }


def run_batch(
    hull, items: Sequence[tuple[int, dict]], inputs: Mapping, keep: bool, token: str = ""
) -> list:
    """Run cases one after the other on one hull: ``[(index, record), ...]``. A case that
    fails gives a record with its one-line ``error``; the others are not affected.

    ``token`` names the hull (its mesh's SHA-256 and axes): a process keeps the first copy
    it gets under that name and uses it for every later task, with the cuts it has made,
    whichever copy Dask hands it."""
    if token:
        hull = _SHARED.setdefault(token, hull)
        while len(_SHARED) > _SHARED_KEPT:
            _SHARED.pop(next(iter(_SHARED)))
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


# -- partial results -----------------------------------------------------------------------


def _dump(path: Path, data: Any) -> None:
    from .atomic import write_atomic

    write_atomic(path, json.dumps(data, allow_nan=True, default=str))


class _Partial:
    """A folder with one small file per finished case, for resuming a sweep."""

    def __init__(self, folder: Path, spec: dict, resume: bool) -> None:
        self.folder = folder
        self.done: dict[int, dict] = {}
        spec_file = folder / PARTIAL_SPEC
        if folder.exists():
            if not resume:
                raise InputError(
                    f"a partial sweep is in {str(folder)!r}: give --resume (resume=True) to "
                    "continue it, or remove the folder to start again"
                )
            try:
                found = json.loads(spec_file.read_text(encoding="utf-8"))
            except (OSError, ValueError):
                found = None
            if found != json.loads(json.dumps(spec, default=str)):
                raise InputError(
                    f"the partial results in {str(folder)!r} are of another sweep (another "
                    "case, grid or mesh): remove the folder, or resume with the same case file"
                )
            for f in folder.glob("case-*.json"):
                try:
                    index = int(f.stem.removeprefix("case-"))
                    record = json.loads(f.read_text(encoding="utf-8"))
                except (OSError, ValueError):
                    continue  # a file cut short by the kill: the case runs again
                if not record.pop("lost", False):
                    self.done[index] = record
        self.spec = spec

    def create(self) -> None:
        """Make the folder (once the sweep is about to run)."""
        if not self.folder.exists():
            self.folder.mkdir()
            _dump(self.folder / PARTIAL_SPEC, self.spec)

    def add(self, index: int, record: dict) -> None:
        _dump(self.folder / f"case-{index}.json", record)


def remove_partial(folder: str | os.PathLike) -> None:
    """Remove a sweep's partial results (once its output is complete)."""
    folder = Path(folder)
    if (folder / PARTIAL_SPEC).is_file():
        shutil.rmtree(folder, ignore_errors=True)


# -- the sweep -----------------------------------------------------------------------------


def _require(*modules: str) -> None:
    import importlib

    for m in modules:
        try:
            importlib.import_module(m)
        except ImportError:
            raise MissingDependencyError(
                f"sweeps need {m}, which is not installed: pip install 'hullslice[sweep]'"
            ) from None


def sha256(path: str | os.PathLike) -> str:
    """The SHA-256 of a file, hex."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _jsonable(value: Any) -> Any:
    if isinstance(value, Path):
        return str(value)
    if isinstance(value, Mapping):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    return value


def _groups(plan: Plan, todo: list[int], n_workers: int) -> list[list[int]]:
    """The cases to run, grouped: same mass properties and pitch together (they share a
    hull and its cuts), in tasks of a size that gives each worker a few."""
    order = sorted(
        todo,
        key=lambda i: (
            repr(_mass_key(plan.case(i))),
            plan.case(i).get("pitch", 0.0),
            i,
        ),
    )
    size = max(1, min(16, math.ceil(len(order) / (TASKS_PER_WORKER * max(1, n_workers)))))
    groups: list[list[tuple[tuple[str, Any], int]]] = []
    for i in order:
        key = (repr(_mass_key(plan.case(i))), plan.case(i).get("pitch", 0.0))
        if groups and len(groups[-1]) < size and groups[-1][0][0] == key:
            groups[-1].append((key, i))
        else:
            groups.append([(key, i)])
    return [[i for _, i in g] for g in groups]


def _client(client, workers: int | None, timeout: float):
    """``(client, owned)``: the Dask client to use, and whether this sweep made it."""
    _require("distributed")
    from distributed import Client, LocalCluster

    if client is not None and not isinstance(client, str | os.PathLike):
        return client, False
    if client is not None:
        address = str(client)
        try:
            return Client(address, timeout=timeout), True
        except Exception as exc:  # OSError, TimeoutError, ValueError for a bad address
            why = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
            raise InputError(
                f"no Dask scheduler answers at {address!r} within {timeout:g} s ({why}): "
                "start one ('dask scheduler'), check the address, or leave out --scheduler "
                "to run on this machine"
            ) from None
    n = workers or os.cpu_count() or 1
    cluster = LocalCluster(
        n_workers=n,
        threads_per_worker=1,
        processes=True,
        dashboard_address=None,
        silence_logs=50,
    )
    return Client(cluster), True


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
        stopped; ``workers=1`` runs in this process, without Dask.
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
        Seconds to wait for a scheduler given by address (default 10).

    Returns
    -------
    xarray.Dataset
        See the module's documentation; a case that failed has NaN results and its
        message in ``error``.
    """
    _require("xarray")
    from ._version import __version__
    from .mass import read_mass_distribution
    from .mesh import load_hull
    from .motion import read_kinematics
    from .solvers.registry import DEFAULT_SOLVER, get_solver

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
    mesh_path = Path(base["mesh"])
    shaping = {k: base[k] for k in ("scale", "length", "repair", "keep", "keep_box") if k in base}
    hull = load_hull(
        mesh_path, units=base["units"], forward=base["forward"], up=base["up"], **shaping
    )
    inputs: dict[str, Any] = {}
    if "mass_distribution" in base:
        inputs["mass_distribution"] = read_mass_distribution(base["mass_distribution"])
    if "kinematics" in base:
        inputs["kinematics"] = read_kinematics(base["kinematics"])
    # the base case's own mass properties are checked here, once (warnings shown once)
    _hull_for(hull, base, inputs)
    solver = get_solver(base.get("solver", DEFAULT_SOLVER), **base.get("solver_options", {}))
    mesh_sha = sha256(mesh_path)
    spec = {  # what a partial folder must match to be resumed (paths absolute: any cwd)
        "base": _jsonable(
            {k: Path(v).resolve() if isinstance(v, Path) else v for k, v in base.items()}
        ),
        "grid": _jsonable(plan.grid),
        "cases": len(plan.cases),
        "mesh_sha256": mesh_sha,
        "keep_histories": bool(keep_histories),
    }
    store = _Partial(Path(partial), spec, resume) if partial is not None else None
    records: dict[int, dict] = dict(store.done) if store else {}
    total = len(plan.cases)
    todo = [i for i in range(total) if i not in records]
    failed = sum(1 for r in records.values() if r.get("error"))

    def finish(index: int, record: dict) -> None:
        nonlocal failed
        records[index] = record
        failed += bool(record.get("error"))
        if store is not None:
            store.add(index, record)
        if progress is not None:
            progress(len(records), total, failed)

    in_process = client is None and workers == 1
    dask_client, owned = (
        (None, False) if in_process or not todo else _client(client, workers, timeout)
    )
    try:
        if store is not None:
            store.create()
        if progress is not None:
            progress(len(records), total, failed)
        if todo and in_process:
            for i in todo:
                for index, record in run_batch(hull, [(i, plan.case(i))], inputs, keep_histories):
                    finish(index, record)
        elif todo:
            token = f"{mesh_sha}:{base['units']}:{base['forward']}:{base['up']}:{shaping!r}"
            _run_on_dask(plan, hull, inputs, todo, keep_histories, dask_client, finish, token)
    finally:
        if owned and dask_client is not None:
            cluster = getattr(dask_client, "cluster", None)
            dask_client.close()
            if cluster is not None:
                cluster.close()
    ds = _dataset(plan, records, keep_histories)
    created = datetime.datetime.now(datetime.UTC).replace(microsecond=0).isoformat()
    ds.attrs.update(
        {
            "title": str(base.get("title", f"sweep of {mesh_path.name}")),
            "Conventions": "CF-1.8",
            "source": f"hullslice {__version__}, 2D+t method",
            "history": f"{created} hullslice sweep of {len(plan.cases)} cases",
            "hullslice_version": __version__,
            "created": created,
            "mesh": mesh_path.name,
            "mesh_sha256": mesh_sha,
            "solver": solver.name,
            "solver_options": json.dumps(_jsonable(dict(solver.settings)), sort_keys=True),
            "base_case": json.dumps(_jsonable(base)),
            "sweep": json.dumps(_jsonable(plan.grid)),
            "cases": len(plan.cases),
            "failed": int(sum(1 for r in records.values() if r.get("error"))),
        }
    )
    if store is not None:
        ds.attrs["partial"] = str(store.folder)
    return ds


def _value(x):
    return x


def _run_on_dask(plan, hull, inputs, todo, keep, client, finish, token) -> None:
    from distributed import as_completed

    futures: dict = {}
    try:
        n_workers = max(1, len(client.scheduler_info().get("workers", {})))
        # the hull and the files' contents as tasks of their own, not scattered data: Dask
        # computes them again if the workers holding them die
        hull_f = client.submit(_value, hull, pure=False)
        inputs_f = client.submit(_value, inputs, pure=False)

        def submit(group: list[int]):
            items = [(i, plan.case(i)) for i in group]
            return client.submit(
                run_batch, hull_f, items, inputs_f, keep, token, pure=False, retries=1
            )

        for group in _groups(plan, todo, n_workers):
            futures[submit(group)] = group
        queue = as_completed(list(futures))
        # Cases whose worker died under them (Dask gave up: KilledWorker): the case that
        # kills it, or one that was on the worker when another did. Each runs once more,
        # alone and one after the other, so that only the case that kills its worker
        # again is recorded as failed.
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
                f = submit([i])
                futures[f] = [i]
                alone.append(f)
                queue.add(f)
            for index, record in results:
                finish(index, record)
    except BaseException:
        for fut in list(futures):
            fut.cancel()
        raise


def _dataset(plan: Plan, records: Mapping[int, dict], keep: bool):
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
            from .xarray_io import attrs_for

            data[f"history_{col}"] = (
                (*plan.dims, "t"),
                arr.reshape((*shape, len(t))),
                attrs_for(col),
            )
    return xr.Dataset(data, coords=coords)


def _result_attrs(name: str) -> dict[str, str]:
    from .motion import STOP_RULES
    from .xarray_io import attrs_for

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
    k = SCHEMA[key]
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
