"""Characteristic curves of a free-falling wedge, ``v~(z~)`` and ``a~(z~)``, and their tables.

The curves are polynomials in the scaled penetration ``z~`` (the paper's Eqs. 5 and 6,
:data:`PAPER_CURVES`) or a table of ``z~, a~, v~`` read from a CSV file
(:meth:`CharacteristicCurves.from_csv`). :class:`~hullslice.solvers.karman.CurveSolver`
uses them in inverse form.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, cast

import numpy as np

from ..errors import CaseError, InputError
from ..paths import printable
from ..tables import column_values, header_text, read_csv

__all__ = ["CURVE_COLUMNS", "PAPER_CURVES", "CharacteristicCurves"]


@dataclass(frozen=True)
class CharacteristicCurves:
    """Scaled velocity ``v~(z~)`` and acceleration ``a~(z~)`` of a free-falling wedge.

    Either polynomials (coefficients in ascending powers of ``z~``) or a table.

    Parameters
    ----------
    a_coeffs, v_coeffs : sequence of float
        Polynomial coefficients of ``a~`` and ``v~``, constant term first.
    table : (k, 3) float, optional
        Rows of ``z~, a~, v~`` (``z~ <= 0``), used instead of polynomials (linear
        interpolation).
    rho : float
        Water density the curves were made for, kg/m^3 (default 1000).
    z_range : (float, float), optional
        Range of ``z~`` where the curves are valid. Default for polynomials: from the first
        local minimum of ``a~`` below its peak (where the fit turns upward again) to 0;
        for a table, its first and last ``z~``.
    source : str
        Where the curves come from.
    """

    a_coeffs: Sequence[float] = ()
    v_coeffs: Sequence[float] = ()
    table: np.ndarray | None = None
    rho: float = 1000.0
    z_range: tuple[float, float] | None = None
    source: str = ""
    _a: Callable[[np.ndarray], np.ndarray] = field(init=False, repr=False, compare=False)
    _v: Callable[[np.ndarray], np.ndarray] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        rho = _number(self.rho, "curve density rho", "kg/m^3")
        if rho <= 0.0:
            raise InputError(f"curve density {self.rho!r} kg/m^3 is not positive (try 1000)")
        object.__setattr__(self, "rho", rho)
        if self.table is not None:
            if _given(self.a_coeffs) or _given(self.v_coeffs):
                raise InputError(
                    "characteristic curves take either a table or polynomial coefficients, not both"
                )
            t = _float_array(self.table, "curve table")
            if t.ndim != 2 or t.shape[1] != 3 or len(t) < 2 or not np.all(np.isfinite(t)):
                raise InputError(
                    f"a curve table needs at least two rows of three finite numbers "
                    f"(z~, a~, v~); got an array of shape {t.shape}"
                )
            t = t[np.argsort(t[:, 0], kind="stable")]
            if np.any(np.diff(t[:, 0]) <= 0):
                raise InputError("a curve table has repeated z~ values: give each z~ once")
            if t[-1, 0] > 0.0:
                raise InputError(
                    f"a curve table has z~ = {t[-1, 0]:g} > 0: the scaled penetration "
                    "z~ = -p gamma / (sqrt(M) tan(beta)) is negative or zero"
                )
            t.flags.writeable = False
            object.__setattr__(self, "table", t)
            z, a, v = t.T
            object.__setattr__(self, "_a", lambda zt: np.interp(zt, z, a))
            object.__setattr__(self, "_v", lambda zt: np.interp(zt, z, v))
            default_range = (float(z[0]), float(z[-1]))
        else:
            if not (_given(self.a_coeffs) and _given(self.v_coeffs)):
                raise InputError(
                    "characteristic curves need the coefficients of both a~ and v~ "
                    "(ascending powers of z~), or a table of z~, a~, v~"
                )
            ca = _coefficients(self.a_coeffs, "a~")
            cv = _coefficients(self.v_coeffs, "v~")
            pa, pv = np.polynomial.Polynomial(ca), np.polynomial.Polynomial(cv)
            object.__setattr__(self, "a_coeffs", tuple(float(c) for c in pa.coef))
            object.__setattr__(self, "v_coeffs", tuple(float(c) for c in pv.coef))
            ka, kv = tuple(pa.coef.tolist()), tuple(pv.coef.tolist())
            object.__setattr__(self, "_a", lambda zt: _horner(zt, ka))
            object.__setattr__(self, "_v", lambda zt: _horner(zt, kv))
            default_range = None
        if self.z_range is None:
            rng = default_range if default_range is not None else (_fit_floor(pa), 0.0)
            object.__setattr__(self, "z_range", rng)
        else:
            zr = _float_array(self.z_range, "curve range z_range")
            if zr.shape != (2,) or not np.all(np.isfinite(zr)) or not zr[0] < zr[1]:
                raise InputError(
                    f"curve range {self.z_range!r} is not a range of z~: give (low, high) "
                    "with low < high, e.g. (-0.0387, 0)"
                )
            object.__setattr__(self, "z_range", (float(zr[0]), float(zr[1])))

    @classmethod
    def from_csv(
        cls,
        path: str | os.PathLike,
        *,
        rho: float = 1000.0,
        z_range: tuple[float, float] | None = None,
    ) -> CharacteristicCurves:
        """Curves from a CSV table with the columns ``z_tilde``, ``a_tilde``, ``v_tilde``.

        The header names the columns (any order; other columns are ignored); lines starting
        with ``#`` are comments. Between rows the curves are interpolated linearly.

        Parameters
        ----------
        path : str or path
            The CSV file.
        rho : float
            Water density the curves were made for, kg/m^3 (default 1000).
        z_range : (float, float), optional
            Range of ``z~`` where the curves are valid (default: the table's first and last
            ``z~``).

        Raises
        ------
        CaseError
            The file is missing, or lacks a column, or a row is not three numbers.
        """
        p = Path(path)
        header, numbered = read_csv(p, "curve table")  # hullslice/tables.py
        missing = [c for c in CURVE_COLUMNS if c not in header]
        if missing:
            raise CaseError(
                f"curve table {printable(p)!r} lacks the column(s) {', '.join(missing)} "
                f"({header_text(header)}); it needs z_tilde, a_tilde, v_tilde"
            )
        idx = [header.index(c) for c in CURVE_COLUMNS]
        rows = column_values(numbered, idx, CURVE_COLUMNS, f"curve table {printable(p)!r}")
        try:
            return cls(table=np.array(rows).reshape(-1, 3), rho=rho, z_range=z_range, source=str(p))
        except InputError as exc:
            raise CaseError(f"curve table {str(p)!r}: {exc}") from None

    def a(self, zt: np.ndarray) -> np.ndarray:
        """Scaled acceleration ``a~`` at scaled penetration ``zt``."""
        return np.asarray(self._a(np.asarray(zt, dtype=np.float64)), dtype=np.float64)

    def v(self, zt: np.ndarray) -> np.ndarray:
        """Scaled velocity ``v~`` at scaled penetration ``zt``."""
        return np.asarray(self._v(np.asarray(zt, dtype=np.float64)), dtype=np.float64)

    @property
    def peak(self) -> tuple[float, float]:
        """``(z~, a~)`` at the peak of ``a~`` inside the range."""
        lo, hi = cast(tuple[float, float], self.z_range)  # set in __post_init__
        z = np.linspace(lo, hi, 20001)
        a = self.a(z)
        i = int(np.argmax(a))
        return float(z[i]), float(a[i])


def _fit_floor(pa: np.polynomial.Polynomial) -> float:
    """Lower end of a fitted ``a~`` polynomial: its first local minimum below its peak."""
    roots = pa.deriv().roots()
    real = np.sort(roots[np.abs(roots.imag) < 1e-12].real)
    real = real[real <= 0.0]
    # the peak is the local maximum closest below zero; the floor the next minimum below it
    maxima = [r for r in real if pa.deriv(2)(r) < 0]
    if not maxima:
        raise InputError("the a~ polynomial has no peak below z~ = 0; give z_range explicitly")
    peak = max(maxima)
    minima = [r for r in real if r < peak and pa.deriv(2)(r) > 0]
    if not minima:
        raise InputError("the a~ polynomial has no minimum below its peak; give z_range")
    return float(max(minima))


def _given(value: Any) -> bool:
    """True unless ``value`` is None or an empty sequence."""
    return value is not None and (not hasattr(value, "__len__") or len(value) > 0)


def _number(value: Any, what: str, unit: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what} {value!r} is not a number (in {unit})") from None
    if not np.isfinite(v):
        raise InputError(f"{what} {value!r} is not finite (in {unit})")
    return v


def _float_array(value: Any, what: str) -> np.ndarray:
    try:
        return np.array(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError(f"{what} {value!r} is not made of numbers") from None


def _coefficients(value: Any, what: str) -> np.ndarray:
    c = _float_array(value, f"coefficients of {what}")
    if c.ndim != 1 or not np.all(np.isfinite(c)):
        raise InputError(
            f"coefficients of {what} {value!r} are not a list of finite numbers (ascending "
            "powers of z~, constant term first)"
        )
    return c


#: The columns of a curve table (CSV), in the order of a table's rows.
CURVE_COLUMNS = ("z_tilde", "a_tilde", "v_tilde")

#: The characteristic curves of the paper, Eqs. 5 and 6: a free-falling wedge with
#: beta = 45 deg, M = 4.6842 kg/m, v_z0 = 5.5 m/s in water of 1000 kg/m^3.
PAPER_CURVES = CharacteristicCurves(
    a_coeffs=(
        -0.35026,
        -3093.66877,
        11743.57797,
        2.26181e7,
        1.28322e9,
        2.8479e10,
        2.29482e11,
    ),
    v_coeffs=(1.00131, -0.36998, -1852.65292, -56703.97435, -531047.33189),
    rho=1000.0,
    source="2D+t method based on extended von Karman's momentum theory, Eqs. 5-6",
)


def _horner(x: np.ndarray, c: tuple[float, ...]) -> np.ndarray:
    """The polynomial of ascending coefficients ``c`` at ``x``: numpy's ``polyval`` without
    its checks (the same operations, the same numbers)."""
    y = c[-1] + x * 0.0
    for ci in c[-2::-1]:
        y = ci + y * x
    return y
