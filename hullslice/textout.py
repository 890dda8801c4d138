"""Turning results into text: aligned tables, CSV and JSON."""

from __future__ import annotations

import csv
import io
import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ._version import __version__
from .atomic import write_atomic
from .constants import TOL

__all__ = [
    "Column",
    "coordinate_text",
    "csv_text",
    "json_text",
    "significant",
    "table_text",
    "write_atomic",
]


@dataclass(frozen=True)
class Column:
    """One column of a report table.

    Attributes
    ----------
    key : str
        Key of the data in the records / machine formats (CSV header, JSON field).
    label : str
        Heading in a terminal table.
    unit : str
        Unit shown under the heading (``""`` for none).
    fmt : str
        Format spec for numbers in a terminal table, e.g. ``".4f"``; ``"~N"`` prints the
        column in fixed point with N significant digits for its largest value (the same
        decimals on every row), so that rounding noise shows as 0.
    """

    key: str
    label: str
    unit: str = ""
    fmt: str = ".6g"


def _unsigned_zero(text: str) -> str:
    """``-0.000`` (a tiny negative number rounded) as ``0.000``."""
    if text.startswith("-") and not text.strip("-0.") and "e" not in text:
        return text[1:]
    return text


def _cell(value: Any, fmt: str) -> str:
    if isinstance(value, bool | np.bool_):
        return "yes" if value else "no"
    if isinstance(value, int | np.integer):
        return str(int(value))
    if isinstance(value, float | np.floating):
        v = float(value)
        if math.isnan(v):
            return "-"
        return _unsigned_zero(format(v, fmt)) if math.isfinite(v) else str(v)
    return str(value)


#: Most decimals a ``"~N"`` column prints.
_MAX_DECIMALS = 12


def _column_format(fmt: str, values: Sequence[Any]) -> str:
    """The format spec of a column: ``"~N"`` becomes fixed point with the decimals that give
    its largest finite value N significant digits; other specs are kept."""
    if not fmt.startswith("~"):
        return fmt
    digits = int(fmt[1:])
    finite = [abs(float(v)) for v in values if _is_number(v) and math.isfinite(float(v))]
    largest = max(finite, default=0.0)
    if largest == 0.0:
        return f".{digits - 1}f"
    decimals = digits - 1 - math.floor(math.log10(largest))
    return f".{min(max(decimals, 0), _MAX_DECIMALS)}f"


def significant(value: float, digits: int = 7) -> str:
    """A number with ``digits`` significant digits, for a line of text (``-`` for NaN).

    Parameters
    ----------
    value : float
        The number, in any unit.
    digits : int
        Significant digits (default 7: a force's precision, not its rounding noise).
    """
    v = float(value)
    if math.isnan(v):
        return "-"
    return _unsigned_zero(format(v, f".{digits}g"))


def coordinate_text(value: float, size: float, digits: int = 6) -> str:
    """A coordinate in m for a table or line: 0 when it is below the mesh's tolerance
    (:data:`hullslice.constants.TOL` ``.coordinate`` times ``size``), rounding noise rather
    than a position; else ``digits`` significant digits.

    Parameters
    ----------
    value : float
        The coordinate, m.
    size : float
        The body's size (bounding-box diagonal), m, which scales the tolerance.
    """
    v = float(value)
    if math.isfinite(v) and abs(v) < TOL.coordinate * size:
        return "0"
    return significant(v, digits)


def table_text(columns: Sequence[Column], rows: Sequence[Mapping[str, Any]]) -> str:
    """An aligned text table: a heading line, a unit line, then one line per row.

    Numbers are right-aligned, text left-aligned.
    """
    fmts = [_column_format(c.fmt, [r.get(c.key) for r in rows]) for c in columns]
    cells = [[_cell(r.get(c.key, ""), f) for c, f in zip(columns, fmts, strict=True)] for r in rows]
    heads = [c.label for c in columns]
    units = [f"[{c.unit}]" if c.unit else "" for c in columns]
    widths = [
        max([len(h), len(u), *(len(row[i]) for row in cells)])
        for i, (h, u) in enumerate(zip(heads, units, strict=True))
    ]
    numeric = [all(_is_number(r.get(c.key)) for r in rows) if rows else True for c in columns]

    def line(items: Sequence[str]) -> str:
        parts = [
            s.rjust(w) if num else s.ljust(w)
            for s, w, num in zip(items, widths, numeric, strict=True)
        ]
        return "  ".join(parts).rstrip()

    out = [line(heads)]
    if any(units):
        out.append(line(units))
    out += [line(row) for row in cells]
    return "\n".join(out)


def _is_number(v: Any) -> bool:
    return isinstance(v, int | float | np.integer | np.floating) and not isinstance(
        v, bool | np.bool_
    )


def _plain(value: Any) -> Any:
    """Numpy scalars and arrays to plain Python; NaN and infinities to None (valid JSON)."""
    if isinstance(value, Mapping):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()]
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, float | np.floating):
        v = float(value)
        return v if math.isfinite(v) else None
    return value


#: Version of the layout of hullslice's JSON outputs: raised when a key changes meaning
#: or goes away (new keys do not raise it).
JSON_SCHEMA_VERSION = 3


def json_text(data: Mapping[str, Any]) -> str:
    """JSON with plain types; NaN and infinite numbers become ``null``. Every document
    starts with ``hullslice_version`` and ``schema_version`` (:data:`JSON_SCHEMA_VERSION`)."""
    head = {"hullslice_version": __version__, "schema_version": JSON_SCHEMA_VERSION}
    return json.dumps(_plain({**head, **data}), indent=2, allow_nan=False) + "\n"


def csv_text(columns: Sequence[str], rows: Sequence[Mapping[str, Any]]) -> str:
    """CSV with a header line of column keys; numbers with full precision (``repr``)."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(columns)
    for r in rows:
        vals = []
        for c in columns:
            v = _plain(r.get(c, ""))
            vals.append("" if v is None else repr(v) if isinstance(v, float) else v)
        w.writerow(vals)
    return buf.getvalue()


# -- records of results -----------------------------------------------------------------------

#: Columns of the per-slice table of a force result (terminal view).
SLICE_COLUMNS = (
    Column("j", "j", ""),
    Column("x", "x", "m", ".5f"),
    Column("dx", "d", "m", ".5f"),
    Column("penetration", "p", "m", ".5f"),
    Column("velocity", "v", "m/s", ".4f"),
    Column("half_beam", "c", "m", ".5f"),
    Column("deadrise_deg", "beta", "deg", ".3f"),
    Column("mass_per_metre", "mass/m", "kg/m", ".4f"),
    Column("z_tilde", "z~", "m^1.5/kg^0.5", ".5f"),
    Column("force_per_metre", "f", "N/m", "~7"),
    Column("force", "F", "N", "~7"),
    Column("valid", "valid", ""),
    Column("reason", "reason", ""),
)

#: Columns of the section table at one pose (terminal view).
SECTION_COLUMNS = (
    Column("j", "j", ""),
    Column("x", "x", "m", ".5f"),
    Column("dx", "d", "m", ".5f"),
    Column("penetration", "p", "m", ".5f"),
    Column("half_beam", "c", "m", ".5f"),
    Column("deadrise_deg", "beta", "deg", ".3f"),
    Column("area", "A", "m^2", ".6g"),
    Column("mass_per_metre", "mass/m", "kg/m", ".4f"),
    Column("chine_wetted", "chine wet", ""),
)


def _records(columns: Mapping[str, np.ndarray]) -> list[dict[str, Any]]:
    n = len(next(iter(columns.values()))) if columns else 0
    return [{"j": j + 1, **{k: v[j] for k, v in columns.items()}} for j in range(n)]


def section_records(sections) -> list[dict[str, Any]]:
    """One dict per entry (wetted piece, or dry station) of a
    :class:`~hullslice.sections.Sections`, numbered ``j`` from 1 (SI, deadrise in deg)."""
    return _records(sections.as_dict())


def force_records(result) -> list[dict[str, Any]]:
    """One dict per slice of a :class:`~hullslice.forces.ForceResult` (SI, deadrise in deg)."""
    return _records(result.columns())


def convergence_summary(study) -> dict[str, Any]:
    """The totals of a :class:`~hullslice.forces.ConvergenceStudy` and its extrapolation.

    ``gci_fraction`` is the GCI error band as a fraction of the extrapolated force (0.01 is
    1 %); each entry of ``convergence`` holds one count's vertical force, horizontal force
    (N) and pitch moment about the centre of gravity (N m).
    """
    rich = study.richardson
    out: dict[str, Any] = {
        "force": study.finest.total,
        "slices": study.counts[-1],
        "convergence": [
            {
                "slices": n,
                "force": r.total,
                "force_x": r.total_x,
                "moment": r.moment,
                "valid": r.all_valid,
            }
            for n, r in zip(study.counts, study.results, strict=True)
        ],
        "extrapolated_force": None,
        "gci_fraction": None,
        "order": None,
        "convergence_behaviour": None,
    }
    if rich is not None:
        out.update(
            extrapolated_force=rich.extrapolated,
            gci_fraction=rich.gci,
            order=rich.order,
            convergence_behaviour=rich.behaviour,
        )
    return out


#: Leading columns of the force CSV: what a row is, and its slice count.
FORCE_CSV_HEAD = ("row", "slices", "j")

#: Trailing columns of the force CSV, filled on its ``extrapolated`` row.
FORCE_CSV_TAIL = ("moment", "order", "gci_fraction", "convergence_behaviour")


def force_csv(study) -> tuple[list[str], list[dict[str, Any]]]:
    """The columns and rows of the force CSV: every count's slices and totals, and the
    extrapolation, in one table.

    ``row`` says what a row is: ``slice`` (one slice of the count ``slices``, numbered
    ``j`` from 1, with the per-slice columns), ``total`` (the sums over that count's
    slices: ``force``, ``force_x``, ``moment`` and ``valid``, all slices inside the
    range), then ``extrapolated`` (the Richardson force with ``order``, ``gci_fraction``
    and ``convergence_behaviour``; present with three or more counts).

    Parameters
    ----------
    study : ConvergenceStudy
        The force at each slice count.
    """
    names: list[str] = list(FORCE_CSV_HEAD)
    for r in study.results:
        names += [k for k in r.columns() if k not in names]
    names += [k for k in FORCE_CSV_TAIL if k not in names]
    rows: list[dict[str, Any]] = []
    for n, r in zip(study.counts, study.results, strict=True):
        rows += [{"row": "slice", "slices": n, **rec} for rec in force_records(r)]
    for n, r in zip(study.counts, study.results, strict=True):
        rows.append(
            {
                "row": "total",
                "slices": n,
                "force": r.total,
                "force_x": r.total_x,
                "moment": r.moment,
                "valid": r.all_valid,
            }
        )
    rich = study.richardson
    if rich is not None:
        rows.append(
            {
                "row": "extrapolated",
                "force": rich.extrapolated,
                "order": rich.order,
                "gci_fraction": rich.gci,
                "convergence_behaviour": rich.behaviour,
            }
        )
    return names, rows


#: Columns of a time history (terminal view).
HISTORY_COLUMNS = (
    Column("t", "t", "s", ".5f"),
    Column("draft", "draft", "m", ".5f"),
    Column("velocity", "v", "m/s", ".4f"),
    Column("acceleration", "a", "m/s^2", ".3f"),
    Column("force", "F", "N", "~7"),
    Column("wetted_length", "wetted L", "m", ".4f"),
    Column("slices", "slices", ""),
    Column("valid", "valid", ""),
    Column("reason", "reason", ""),
)


#: Extra columns of a history with pitch or forward speed (terminal view).
HISTORY_PITCH_COLUMNS = (
    Column("pitch_deg", "pitch", "deg", ".3f"),
    Column("forward_speed", "u", "m/s", ".3f"),
    Column("force_x", "Fx", "N", "~7"),
    Column("moment", "My", "N m", "~7"),
)


def history_records(
    history, every: int = 1, indices: Sequence[int] | None = None
) -> list[dict[str, Any]]:
    """One dict per instant of a :class:`~hullslice.motion.History`: those at ``indices``
    when given, else every ``every``-th, always with the first and the last."""
    cols = history.columns()
    n = len(history)
    if indices is None:
        idx = list(range(0, n, max(1, every)))
        if n and idx[-1] != n - 1:
            idx.append(n - 1)
    else:
        idx = list(indices)
    return [{k: v[i] for k, v in cols.items()} for i in idx]


def history_summary(history) -> dict[str, Any]:
    """The run's inputs, its peak, why it ended and when each limit was first crossed."""
    return {
        "mode": history.mode,
        "settings": dict(history.settings),
        "steps": len(history),
        "peak": history.peak if len(history) else None,
        "horizontal": history.horizontal if len(history) else None,
        "step_change": history.step_change,
        "stop_reason": history.stop_reason,
        "first_crossed": dict(history.first_crossed),
        "valid": bool(np.all(history.valid)),
        "max_flagged_share": history.max_flagged_share,
    }


#: Columns of a pressure file (``hullslice force --pressures``), with their units.
PRESSURE_COLUMNS = (
    ("slice", ""), ("x", "m"), ("side", ""), ("y", "m"), ("z", "m"), ("weight", "m"),
    ("pressure", "Pa"), ("clipped", ""),
)  # fmt: skip


def pressure_records(result) -> list[dict[str, Any]]:
    """One record per point of every wetted section's pressure in a force result: the
    slice, its station ``x`` along the earth (m), the side (``port``: ``+y`` from the keel,
    ``starboard``), the point's distance ``y`` from the keel and height ``z`` above it (m),
    its weight ``dy`` (m, so that the weights times the pressures sum to the force per
    metre) and the gauge pressure (Pa); ``clipped`` when a point of the section was held
    at the suction limit (its pressures then sum to more than its force). Points with no
    weight (dry sections, the ends of a loaded region) are left out."""
    pr = result.pressures
    if pr is None:
        return []
    pts = pr.points
    x = np.asarray(result.sections.x, dtype=np.float64)
    out = []
    n, _, k = pr.pressure.shape
    clipped = np.zeros(n, dtype=bool) if pr.clipped is None else np.asarray(pr.clipped)
    for i in range(n):
        for side, name in ((0, "port"), (1, "starboard")):
            for j in range(k):
                w = float(pts.weight[i, side, j])
                if w <= 0.0:
                    continue
                out.append({
                    "slice": i, "x": float(x[i]), "side": name,
                    "y": float(pts.y[i, side, j]), "z": float(pts.z[i, side, j]),
                    "weight": w, "pressure": float(pr.pressure[i, side, j]),
                    "clipped": bool(clipped[i]),
                })  # fmt: skip
    return out


def pressure_text(result, path: str) -> str:
    """A force result's pressures as CSV, or as JSON when ``path`` ends in ``.json``."""
    records = pressure_records(result)
    if str(path).lower().endswith(".json"):
        units = {k: u for k, u in PRESSURE_COLUMNS if u}
        return json_text({"solver": result.solver, "units": units, "points": records})
    return csv_text([k for k, _ in PRESSURE_COLUMNS], records)
