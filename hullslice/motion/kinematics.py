"""Prescribed kinematics: the table a motion is read from, checked, and its derivatives.

A kinematics table maps the names ``t`` (s, increasing), ``draft`` (m, the draft of the
lowest point, >= 0) and ``velocity`` (m/s, vertical velocity of the centre of gravity,
negative down) to arrays; optionally ``acceleration`` (m/s^2, positive up), ``pitch_rad``
(rad, nose up), ``pitch_rate_rad_s`` (rad/s), ``pitch_acceleration_rad_s2`` (rad/s^2),
``forward_speed`` (m/s) and ``forward_acceleration`` (m/s^2). Each angle may be given in
degrees instead, under the name that says so (:data:`DEGREE_KEYS`: ``pitch_deg``,
``pitch_rate_deg_s``, ``pitch_acceleration_deg_s2``, the names of the files' columns),
converted to rad once. A pitch that changes without a pitch rate has its derivative as its
rate. The former names ``penetration``, ``pitch``, ``pitch_rate`` and
``pitch_acceleration`` (angles in rad) are still taken, with a :class:`DeprecationWarning`
(:data:`DEPRECATED_KEYS`).

A CSV file of kinematics (:func:`read_kinematics`) names its columns as the command line's
own history files do: ``t``, ``draft`` (formerly ``penetration``, still read), ``velocity``,
and the optional
``acceleration``, ``pitch_deg``, ``pitch_rate_deg_s``, ``pitch_acceleration_deg_s2``,
``forward_speed``, ``forward_acceleration`` (:data:`FILE_COLUMNS`): its angles are in
degrees, converted to rad once, as it is read.

A momentum-form solver needs the body's accelerations. Where the table gives no
``acceleration`` it is the derivative of ``velocity`` in time, and likewise the pitch and
forward accelerations of the pitch rate and forward speed: second-order central
differences inside the table and second-order one-sided ones at its ends
(``numpy.gradient(..., edge_order=2)``), so three rows at least. A given rate must agree
with its value (``acceleration`` with ``velocity``, ``pitch_rate_rad_s`` with ``pitch_rad``,
``pitch_acceleration_rad_s2`` with ``pitch_rate_rad_s``, ``forward_acceleration`` with
``forward_speed``): its trapezoidal integral from the first row may differ from the
value's change by at most :data:`ACCELERATION_TOLERANCE` of the value's largest size. The
draft is checked against the velocity by the same rule where the pitch is constant (the
lowest point then moves with the centre of gravity): ``-velocity`` integrated from the first
row must change the draft as the draft column does, within
:data:`ACCELERATION_TOLERANCE` of the largest draft.

A table has at most :data:`~hullslice.constants.MAX_STEPS` rows, the step limit of
:func:`~hullslice.motion.integrate.simulate`: each row is one cut of the body.
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Mapping, Sequence

import numpy as np

from ..constants import MAX_STEPS
from ..errors import CaseError
from ..limits import MAX_PITCH, MAX_PITCH_DEG
from ..mesh import Hull
from ..paths import printable
from ..sections import _height_at
from ..state import Acceleration
from ..tables import column_values, header_text, read_csv

__all__ = [
    "ACCELERATION_TOLERANCE",
    "DEGREE_KEYS",
    "DEPRECATED_KEYS",
    "FILE_COLUMNS",
    "KINEMATICS_COLUMNS",
    "KINEMATICS_OPTIONAL",
    "Kinematics",
    "check_kinematics",
    "kinematics_accelerations",
    "read_kinematics",
]

KINEMATICS_COLUMNS = ("t", "draft", "velocity")
#: Optional kinematics columns and their value when absent (NaN: derived when needed).
KINEMATICS_OPTIONAL = {
    "acceleration": math.nan,
    "pitch_rad": 0.0,
    "pitch_rate_rad_s": 0.0,
    "pitch_acceleration_rad_s2": math.nan,
    "forward_speed": 0.0,
    "forward_acceleration": math.nan,
}

#: Former names of kinematics keys: ``old -> new`` (the same values).
DEPRECATED_KEYS: dict[str, str] = {
    "penetration": "draft",
    "pitch": "pitch_rad",
    "pitch_rate": "pitch_rate_rad_s",
    "pitch_acceleration": "pitch_acceleration_rad_s2",
}

#: Kinematics keys of angles in degrees: ``key -> the key in rad`` they are converted to.
DEGREE_KEYS: dict[str, str] = {
    "pitch_deg": "pitch_rad",
    "pitch_rate_deg_s": "pitch_rate_rad_s",
    "pitch_acceleration_deg_s2": "pitch_acceleration_rad_s2",
}

#: The columns of a kinematics file -> the keys they are read into (angles converted from
#: degrees). ``penetration`` is the former name of ``draft``.
FILE_COLUMNS: dict[str, str] = {
    "t": "t",
    "draft": "draft",
    "penetration": "draft",
    "velocity": "velocity",
    "acceleration": "acceleration",
    "pitch_deg": "pitch_rad",
    "pitch_rate_deg_s": "pitch_rate_rad_s",
    "pitch_acceleration_deg_s2": "pitch_acceleration_rad_s2",
    "forward_speed": "forward_speed",
    "forward_acceleration": "forward_acceleration",
}

#: The columns of a kinematics file in degrees (or degrees per second, per second squared).
FILE_DEGREES = frozenset(DEGREE_KEYS)

#: Largest disagreement between a given ``acceleration`` column, integrated in time, and
#: the ``velocity`` column, as a share of the largest speed in the table.
ACCELERATION_TOLERANCE = 0.02


class Kinematics(dict[str, np.ndarray]):
    """A kinematics table (a dict of arrays by the keys of the module notes); its former keys
    (:data:`DEPRECATED_KEYS`) are still read, with a :class:`DeprecationWarning`."""

    def __missing__(self, key: str) -> np.ndarray:
        new = DEPRECATED_KEYS.get(key)
        if new is None or new not in self:
            raise KeyError(key)
        warnings.warn(
            f"the kinematics key {key!r} is deprecated: read {new!r} (the same values)",
            DeprecationWarning,
            stacklevel=2,
        )
        return self[new]


def _current(
    kin: Mapping[str, Sequence[float] | np.ndarray],
) -> dict[str, Sequence[float] | np.ndarray]:
    """``kin`` with its deprecated keys renamed, each warned about, and degrees in rad."""
    out = dict(kin)
    for key in [k for k in DEPRECATED_KEYS if k in kin]:
        new = DEPRECATED_KEYS[key]
        if new in kin:
            raise CaseError(f"kinematics give both {key!r} and {new!r}: give {new!r} only")
        warnings.warn(
            f"the kinematics key {key!r} is deprecated: give {new!r} (the same values)",
            DeprecationWarning,
            stacklevel=4,
        )
        out[new] = out.pop(key)
    for key in [k for k in DEGREE_KEYS if k in kin]:
        new = DEGREE_KEYS[key]
        if new in out:
            raise CaseError(
                f"kinematics give the angle twice, {key!r} (deg) and {new!r} (rad): give one"
            )
        out[new] = np.radians(np.asarray(out.pop(key), dtype=np.float64))
    return out


def check_kinematics(
    kin: Mapping[str, Sequence[float] | np.ndarray], hull: Hull
) -> dict[str, np.ndarray]:
    """Kinematics as float arrays of equal length, every optional key filled, checked.

    Parameters
    ----------
    kin : mapping
        The keys of the module notes (SI, angles in rad, or in degrees under the keys of
        :data:`DEGREE_KEYS`); the deprecated ones of :data:`DEPRECATED_KEYS` are renamed
        with a :class:`DeprecationWarning`.
    hull : Hull
        The body (its height limits the draft).

    Raises
    ------
    CaseError
        A key is missing, a value is not finite, the time does not increase, a rate
        disagrees with its value, the pitch is too steep or the draft negative or deeper
        than the body.
    """
    kin = _current(kin)
    missing = [c for c in KINEMATICS_COLUMNS if c not in kin]
    if missing:
        raise CaseError(
            f"kinematics lack the column(s) {', '.join(missing)}: give t (s), draft (m, "
            "positive down) and velocity (m/s, negative down)"
        )
    out = {c: np.asarray(kin[c], dtype=np.float64).ravel() for c in KINEMATICS_COLUMNS}
    n = len(out["t"])
    if n == 0:
        raise CaseError("the kinematics table has no rows")
    if n > MAX_STEPS:
        raise CaseError(
            f"the kinematics table has {n} rows, more than the {MAX_STEPS} hullslice allows "
            "(the step limit of simulate; each row is one cut of the body): give every k-th "
            "row (an impact is resolved with a few hundred)"
        )
    given = [c for c in KINEMATICS_OPTIONAL if c in kin]
    for c, default in KINEMATICS_OPTIONAL.items():
        out[c] = np.asarray(kin[c], dtype=np.float64).ravel() if c in kin else np.full(n, default)
    for c, a in out.items():
        if len(a) != n:
            raise CaseError(f"kinematics column {c!r} has {len(a)} values, t has {n}")
        if (c in KINEMATICS_COLUMNS or c in given) and not np.all(np.isfinite(a)):
            i = int(np.flatnonzero(~np.isfinite(a))[0])
            raise CaseError(f"kinematics column {c!r} row {i + 1} is not a finite number")
    back = np.flatnonzero(np.diff(out["t"]) <= 0)
    if len(back):
        i = int(back[0])
        raise CaseError(
            f"kinematics time goes backwards or repeats at row {i + 2} "
            f"(t = {out['t'][i]:g} s, then {out['t'][i + 1]:g} s): sort the table by time"
        )
    if n >= 2:
        t = out["t"]
        pitch = out["pitch_rad"]
        if "pitch_rate_rad_s" not in given and np.any(pitch != pitch[0]):
            # a pitch that changes without its rate: the rate is its derivative
            out["pitch_rate_rad_s"] = _derivative(pitch, t)
        for rate, value in RATES:
            if rate in given and (value in given or value in KINEMATICS_COLUMNS):
                _check_rate(t, out[value], out[rate], value, rate)
        if np.all(pitch == pitch[0]):
            _check_draft(t, out["draft"], out["velocity"])
    p = out["draft"]
    steep = np.flatnonzero(np.abs(out["pitch_rad"]) >= MAX_PITCH)
    if len(steep):
        i = int(steep[0])
        raise CaseError(
            f"kinematics pitch at row {i + 1} ({math.degrees(out['pitch_rad'][i]):g} deg) is too "
            f"steep for a 2D+t model: keep it between -{MAX_PITCH_DEG:g} and "
            f"{MAX_PITCH_DEG:g} deg"
        )
    if np.any(p < 0):
        i = int(np.flatnonzero(p < 0)[0])
        raise CaseError(
            f"kinematics draft at row {i + 1} is negative ({p[i]:g} m): the "
            "draft is the depth of the lowest point below the water, >= 0"
        )
    heights = np.array([_height_at(hull, float(th)) for th in out["pitch_rad"]])
    if np.any(p > heights):
        i = int(np.flatnonzero(p > heights)[0])
        raise CaseError(
            f"kinematics draft at row {i + 1} ({p[i]:g} m) is deeper than the "
            f"body's height {heights[i]:.6g} m"
        )
    return out


def read_kinematics(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """Read a kinematics table from CSV.

    The header names the columns (:data:`FILE_COLUMNS`); ``t`` (s), ``draft`` (m, the
    draft of the lowest point, positive; formerly ``penetration``) and ``velocity`` (m/s,
    negative down) are required; the optional columns are read when present, their angles
    in degrees; other columns are ignored. Lines starting with ``#`` are comments.

    Returns
    -------
    Kinematics (a dict) of (k,) float arrays
        ``t``, ``draft``, ``velocity`` and the optional columns present under the keys of
        the module notes, angles in rad (``pitch_rad``, ``pitch_rate_rad_s``,
        ``pitch_acceleration_rad_s2``); the former keys ``pitch``, ... are still read, with
        a :class:`DeprecationWarning`.
    """
    why = " (the step limit of simulate; each row is one cut of the body)"
    header, rows = read_csv(path, "kinematics", MAX_STEPS, why)  # hullslice/tables.py
    if "draft" in header and "penetration" in header:
        raise CaseError(
            f"kinematics file {printable(path)!r} has both a draft and a penetration column "
            "(the former name of the draft): keep draft"
        )
    columns = {c: key for c, key in FILE_COLUMNS.items() if c in header}
    missing = [c for c in KINEMATICS_COLUMNS if c not in columns.values()]
    if missing:
        raise CaseError(
            f"kinematics file {printable(path)!r} lacks the column(s) {', '.join(missing)} "
            f"({header_text(header)}); it needs t, draft, velocity"
        )
    names = list(columns)
    idx = [header.index(c) for c in names]
    arr = column_values(rows, idx, names, f"kinematics file {printable(path)!r}")
    out = {
        columns[c]: np.radians(arr[:, i]) if c in FILE_DEGREES else arr[:, i]
        for i, c in enumerate(names)
    }
    return Kinematics({k: out[k] for k in (*KINEMATICS_COLUMNS, *KINEMATICS_OPTIONAL) if k in out})


def _derivative(values: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Time derivative of a column: second-order differences inside the table and at its
    ends (``numpy.gradient``); first-order with two rows."""
    if len(t) > 2:
        return np.gradient(values, t, edge_order=2)
    return np.gradient(values, t)


#: Columns that are the time derivatives of others, with their units: ``(rate, value)``.
RATES = (
    ("acceleration", "velocity"),
    ("pitch_rate_rad_s", "pitch_rad"),
    ("pitch_acceleration_rad_s2", "pitch_rate_rad_s"),
    ("forward_acceleration", "forward_speed"),
)


def _against_integral(t: np.ndarray, x: np.ndarray, rate: np.ndarray):
    """``rate`` integrated in time (trapezoids) from the first row, how far it misses the
    change of ``x``, the largest size of ``x`` and the row where it misses most."""
    integral = np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(t))])
    miss = np.abs(integral - (x - x[0]))
    return integral, miss, float(np.abs(x).max()), int(np.argmax(miss))


def _check_rate(t: np.ndarray, x: np.ndarray, rate: np.ndarray, value: str, name: str) -> None:
    """A given rate must agree with its value: integrated in time (trapezoids) it changes the
    value as the table does, within :data:`ACCELERATION_TOLERANCE` of the value's largest
    size."""
    integral, miss, scale, worst = _against_integral(t, x, rate)
    unit = {"velocity": "m/s", "pitch_rad": "rad", "pitch_rate_rad_s": "rad/s"}.get(value, "m/s")
    if miss[worst] > ACCELERATION_TOLERANCE * scale + 1e-12:
        raise CaseError(
            f"kinematics {name} disagrees with {value}: integrated from t = {t[0]:g} s to "
            f"t = {t[worst]:g} s it changes the {value} by {integral[worst]:.6g} {unit}, the "
            f"{value} column by {x[worst] - x[0]:.6g} {unit} (more than "
            f"{100 * ACCELERATION_TOLERANCE:g} % of its largest size, {scale:.6g} {unit}); fix "
            f"the {name} column or leave it out to derive it"
        )


def _check_draft(t: np.ndarray, draft: np.ndarray, velocity: np.ndarray) -> None:
    """At a constant pitch the draft must follow the velocity: ``-velocity`` integrated in
    time (trapezoids) changes the draft as the table does, within
    :data:`ACCELERATION_TOLERANCE` of the largest draft."""
    integral, miss, scale, worst = _against_integral(t, draft, -velocity)
    if miss[worst] > ACCELERATION_TOLERANCE * scale + 1e-12:
        raise CaseError(
            f"kinematics draft disagrees with velocity: the velocity integrated from "
            f"t = {t[0]:g} s to t = {t[worst]:g} s moves the body {integral[worst]:.6g} m down, "
            f"the draft column by {draft[worst] - draft[0]:.6g} m (more than "
            f"{100 * ACCELERATION_TOLERANCE:g} % of the largest draft, {scale:.6g} m); the "
            "velocity is negative down and the draft positive down: fix the sign or the column"
        )


def kinematics_accelerations(kin: Mapping[str, np.ndarray]) -> list[Acceleration]:
    """The body's acceleration at each row of checked kinematics (:func:`check_kinematics`).

    Given columns are used as they are; missing ones are derived from the velocities (module
    notes).

    Raises
    ------
    CaseError
        A derivative is needed and the table has fewer than three rows.
    """
    t = kin["t"]
    cols = {}
    for acc, vel in (
        ("acceleration", "velocity"),
        ("pitch_acceleration_rad_s2", "pitch_rate_rad_s"),
        ("forward_acceleration", "forward_speed"),
    ):
        a = np.asarray(kin[acc], dtype=np.float64)
        if np.all(np.isfinite(a)):
            cols[acc] = a
            continue
        v = np.asarray(kin[vel], dtype=np.float64)
        if np.all(v == v[0]):
            cols[acc] = np.zeros_like(v)  # a constant: no derivative needed
            continue
        if len(t) < 3:
            raise CaseError(
                f"the kinematics table has {len(t)} row(s), too few to differentiate {vel} in "
                f"time (three at least): give more rows or an {acc} column"
            )
        cols[acc] = _derivative(v, t)
    pitch = cols["pitch_acceleration_rad_s2"]
    return [
        Acceleration(float(a), float(q), float(u))
        for a, q, u in zip(cols["acceleration"], pitch, cols["forward_acceleration"], strict=True)
    ]
