"""The plan of a sweep: a base case and a ``[sweep]`` table (or a ``cases`` table) checked
and listed as the cases to run.

A grid maps case keys to lists of values, run as a full factorial; ``cases`` is a table with
one case per row (a CSV file whose columns are case keys, or a list of mappings). The keys
a sweep varies are the number keys of a ``simulate`` case, the slice count, and ``cg_x`` and
``cg_z`` (m), which set one component of the case's centre of gravity ``cg``. Every case of
the plan is checked as a case file would be, before anything runs.
"""

from __future__ import annotations

import difflib
import itertools
import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from ..case import COMMAND_KEYS, SCHEMA, case_command, read_case_file, validate_case
from ..errors import CaseError, InputError
from ..paths import printable

#: Keys that shape the mesh: one mesh per sweep, so a sweep does not vary them.
MESH_KEYS = ("scale", "length")
#: Keys of a case that a sweep does not take: it writes one dataset (``-o``), not a file
#: per case.
OUTPUT_KEYS = ("output", "plot", "format")
#: Most cases one sweep may have, counted before any is listed: each case is a time history
#: (a tenth of a second to minutes), so more is weeks of work, and a typing slip (a list of
#: 1000 values among others) would fill the memory while the cases are listed and checked.
MAX_SWEEP_CASES = 100_000


class Component(NamedTuple):
    """A sweep key that sets one component of a pair key of the case (``cg_x``: the x of
    ``cg``); ``kind``, ``unit`` and ``help`` read as those of a case key."""

    name: str
    key: str
    part: int
    kind: str
    unit: str
    help: str


#: Sweep keys that set one component of a pair of the case, by name.
COMPONENTS: dict[str, Component] = {
    c.name: c
    for c in (
        Component("cg_x", "cg", 0, "number", "m", "centre of gravity x in the body frame"),
        Component("cg_z", "cg", 1, "number", "m", "centre of gravity z in the body frame"),
    )
}

#: Keys a sweep can vary: the number keys of a ``simulate`` case, the slice count, and the
#: components of the centre of gravity (:data:`COMPONENTS`).
SWEEP_KEYS: tuple[str, ...] = (
    *(
        name
        for name, key in SCHEMA.items()
        if name in COMMAND_KEYS["simulate"]
        and (key.kind == "number" or name == "slices")
        and name not in MESH_KEYS
    ),
    *COMPONENTS,
)


def key_spec(name: str) -> Any:
    """What a sweep key is: its ``kind``, ``unit`` and ``help`` (the case key's, or the
    component's)."""
    return COMPONENTS[name] if name in COMPONENTS else SCHEMA[name]


def apply(base: Mapping[str, Any], over: Mapping[str, Any]) -> dict[str, Any]:
    """The case ``base`` with the keys of one case of a sweep: a component key replaces its
    part of the pair (``cg_x`` the x of ``cg``, kept as a tuple like a checked pair); any
    other key replaces the key (a slice count as the one-count list a checked case holds)."""
    case = dict(base)
    for name, value in over.items():
        c = COMPONENTS.get(name)
        if c is None:
            case[name] = [value] if name == "slices" else value
            continue
        pair = list(case.get(c.key, (math.nan, math.nan)))
        pair[c.part] = value
        case[c.key] = tuple(pair)
    return case


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
        """The checked case ``i``: the base case with its keys (see :func:`apply`)."""
        return apply(self.base, self.cases[i])


def _number_list(key: str, values: Any, where: str) -> list:
    if not isinstance(values, list):
        raise CaseError(
            f"{where}[sweep] key {key!r} must be a list of values, e.g. {key} = [1.0, 2.0], "
            f"not {values!r}"
        )
    if not values:
        raise CaseError(f"{where}[sweep] key {key!r} is an empty list: give at least one value")
    spec = key_spec(key)
    whole = spec.kind != "number"
    for v in values:
        ok = isinstance(v, int) if whole else isinstance(v, int | float)
        if isinstance(v, bool) or not ok or (not whole and not math.isfinite(v)):
            what = "a whole number" if whole else "a finite number"
            unit = f" in {spec.unit}" if spec.unit else ""
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
        parts = [c.name for c in COMPONENTS.values() if c.key == key]
        hint = f" (its parts: {' and '.join(parts)})" if parts else ""
        raise CaseError(
            f"{where}[sweep] key {key!r} is not a number key of a simulate case: a sweep varies "
            f"{keys}{hint}"
        )
    close = difflib.get_close_matches(str(key), [*SWEEP_KEYS, "cases"], n=1)
    hint = f"did you mean {close[0]!r}? " if close else ""
    raise CaseError(f"{where}[sweep] unknown key {key!r}; {hint}a sweep varies {keys} or cases")


def _read_table(path: Path, where: str) -> dict[str, list]:
    """The columns of a cases table (CSV, header of case keys, one case per row), read as
    every table hullslice reads (:func:`hullslice.tables.read_csv`: UTF-8 or UTF-16, true
    line numbers, no content of a file that is not a table quoted)."""
    from ..tables import header_text, read_csv

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
            whole = key_spec(h).kind != "number"
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
        has a column that is not a case key, the sweep has more than
        :data:`MAX_SWEEP_CASES` cases (counted before any is listed); or a case of the grid
        is not a valid case (the message names the case).
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
    n_cases = (len(next(iter(table.values()))) if table else 1) * math.prod(
        len(v) for v in axes.values()
    )
    if n_cases > MAX_SWEEP_CASES:
        sizes = " x ".join(
            [*([f"{len(next(iter(table.values())))} rows"] if table else []),
             *(f"{len(v)} {k}" for k, v in axes.items())]
        )  # fmt: skip
        raise CaseError(
            f"{where}[sweep] has {n_cases} cases ({sizes}), more than the {MAX_SWEEP_CASES} "
            "hullslice runs in one sweep: give fewer values, or split it into sweeps"
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
    swept = [*table, *axes]
    for c in COMPONENTS.values():
        others = [o.name for o in COMPONENTS.values() if o.key == c.key and o.name not in swept]
        if c.name in swept and c.key not in checked and others:
            raise CaseError(
                f"{where}[sweep] key {c.name!r} sets a part of the case's {c.key!r}, which the "
                f"case does not give: add {c.key} = [x, z] to the case (the part not swept is "
                f"kept), or sweep {' and '.join(others)} as well"
            )
    from .run import study_of

    for i, over in enumerate(cases):  # every case is a valid case file, and a valid study
        merged = _raw(apply(checked, over))
        try:
            # the limits a single run enforces (the pitch, ...), before anything runs
            study_of(validate_case(merged))
        except InputError as exc:
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
    data, p, name = read_case_file(path)
    grid = data.pop("sweep", None)
    if grid is None:
        raise CaseError(
            f"case file {name!r} has no [sweep] table: add one with the keys to vary, e.g. "
            "[sweep] pitch = [4.0, 6.0, 8.0]"
        )
    if not isinstance(grid, dict):
        raise CaseError(f"case file {name!r}: 'sweep' must be a table ([sweep]), not {grid!r}")
    return make_plan(data, grid, base=p.parent, source=name)
