"""The default 2D solver: the paper's extended von Karman wedge curves, used in inverse form.

Each wetted section is treated as a 2D wedge (deadrise ``beta``, mass per metre ``M``) in a
free fall of its own. Its scaled penetration ``z~`` (Eq. 9) picks a point on the
characteristic curves ``v~(z~)`` and ``a~(z~)`` (Eqs. 5-6); the velocity of the section,
``v = v~ v_z0``, gives the initial velocity ``v_z0`` of that free fall, and Eq. 4 its
acceleration ``a``. The section's force per metre is ``M (a + g)`` (Eq. 12).

The curves were made for water of density 1000 kg/m^3. von Karman's momentum balance
``(M + m_added) v = M v_z0`` with ``m_added`` proportional to ``rho`` depends on ``M`` and
``rho`` only through ``M / rho``, so for another density the scaled quantities use the
equivalent mass ``M' = M rho_curves / rho``; the force still uses the real ``M``.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar, cast

import numpy as np

from ..errors import CaseError, InputError
from ..paths import printable
from ..sections import Sections
from ..state import Fluid
from ..tables import column_values, header_text, read_csv
from .base import SectionLoads, Solver, join_reasons

__all__ = [
    "CURVE_COLUMNS",
    "PAPER_CURVES",
    "CharacteristicCurves",
    "CurveSolver",
    "ExtendedVonKarman",
    "dobrovolskaya_pile_up",
    "peak_froude",
    "peak_values",
]


def dobrovolskaya_pile_up(beta: np.ndarray) -> np.ndarray:
    """Pile-up coefficient ``gamma_D = -0.0114 beta_deg + 1.5669`` (paper, after Eq. 2).

    A linear fit of Dobrovol'skaya's similarity solution; ``beta`` in rad.
    """
    return -0.0114 * np.degrees(beta) + 1.5669


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


def peak_values(
    v_z0: np.ndarray,
    mass_per_metre: np.ndarray,
    deadrise: np.ndarray,
    gamma: np.ndarray,
    rho: float,
) -> dict[str, np.ndarray]:
    """Peak values of a free-falling wedge by momentum theory (paper, Eq. 2).

    Parameters
    ----------
    v_z0 : float or array
        Initial velocity in m/s (negative down).
    mass_per_metre : float or array
        Wedge mass per metre in kg/m.
    deadrise : float or array
        Deadrise in rad.
    gamma : float or array
        Pile-up coefficient.
    rho : float
        Water density in kg/m^3.

    Returns
    -------
    dict
        ``a_max`` (m/s^2, upward), ``z_star`` (m, penetration at the peak, positive),
        ``v_star`` (m/s), ``t_star`` (s).
    """
    tb = np.tan(deadrise)
    root = np.sqrt(2.0 * mass_per_metre / (5.0 * np.pi * rho * gamma**2))
    return {
        "a_max": v_z0**2
        * (5.0 / 6.0) ** 3
        * gamma
        / tb
        * np.sqrt(2.0 * np.pi * rho / (5.0 * mass_per_metre)),
        "z_star": root * tb,
        "v_star": 5.0 / 6.0 * v_z0,
        "t_star": np.abs(16.0 / 15.0 * root * tb / v_z0),
    }


def peak_froude(
    v_z0: np.ndarray,
    mass_per_metre: np.ndarray,
    deadrise: np.ndarray,
    gamma: np.ndarray,
    rho: float,
    g: float,
) -> np.ndarray:
    """Froude number at the peak of a free-falling wedge, ``Fr* = |v_z*| / sqrt(g z*)``.

    ``v_z*`` and ``z*`` are the velocity and penetration at the peak of the free fall
    (Eq. 2, :func:`peak_values`); the paper asks for ``Fr* > 6.5`` (gravity negligible during
    the impact). Parameters as for :func:`peak_values`, with ``g`` the gravitational
    acceleration in m/s^2; infinite for ``g = 0``.
    """
    # v_z* and z* as peak_values gives them, without its other peak values
    z_star = np.sqrt(2.0 * mass_per_metre / (5.0 * np.pi * rho * gamma**2)) * np.tan(deadrise)
    with np.errstate(divide="ignore"):
        return np.abs(5.0 / 6.0 * v_z0) / np.sqrt(g * z_star)


class CurveSolver(Solver):
    """Inverse use of characteristic curves, for any curves and pile-up law.

    Subclasses set :attr:`curves` and may override :meth:`pile_up`.
    """

    curves: ClassVar[CharacteristicCurves] = PAPER_CURVES
    options: ClassVar[dict[str, Any]] = {"froude_min": 6.5}

    def pile_up(self, deadrise: np.ndarray) -> np.ndarray:
        """Pile-up coefficient for deadrise angles in rad."""
        return dobrovolskaya_pile_up(deadrise)

    def section_loads(self, sections: Sections, velocity: np.ndarray, fluid: Fluid) -> SectionLoads:
        curves = self.curves
        M = sections.mass_per_metre
        beta = sections.deadrise
        tb = np.tan(beta)
        gam = self.pile_up(beta)
        m_eq = M * curves.rho / fluid.rho  # same M/rho as the section
        root_m = np.sqrt(m_eq)
        zt = -sections.penetration * gam / (root_m * tb)  # Eq. 9
        vt = curves.v(zt)  # Eq. 6
        at = curves.a(zt)  # Eq. 5
        with np.errstate(divide="ignore", invalid="ignore"):
            v0 = velocity / vt
        a = at * v0**2 / root_m * gam / tb  # Eq. 4
        force = M * (a + fluid.g)  # Eq. 12, per metre
        # a section moving up is leaving the water (behind a transom or the lowest point of a
        # hull moving forward): it is in no free fall, the flow separates, and it gets no force
        force = np.where(velocity < 0.0, force, 0.0)
        froude = peak_froude(v0, m_eq, beta, gam, curves.rho, fluid.g)

        lo, hi = cast(tuple[float, float], curves.z_range)
        fr_min = float(self.settings["froude_min"])
        checks = [
            ((zt < lo) | (zt > hi), f"z~ outside the curves' range [{lo:.4g}, {hi:.4g}]"),
            (vt <= 0.0, "v~ <= 0 (past the end of the curves)"),
            (velocity >= 0.0, "section not moving down into the water (no force)"),
            (froude <= fr_min, f"Fr* <= {fr_min:g} (gravity not negligible)"),
        ]
        reason = join_reasons(len(M), checks)
        return SectionLoads(
            force_per_metre=force,
            valid=reason == "",
            reason=reason,
            diagnostics={
                "gamma": gam,
                "z_tilde": zt,
                "v_tilde": vt,
                "a_tilde": at,
                "v_z0": v0,
                "acceleration": a,
                "froude": froude,
            },
        )


class ExtendedVonKarman(CurveSolver):
    """The paper's 2D solver: extended von Karman momentum theory, free-falling wedge."""

    name = "extended-von-karman"
    description = (
        "Extended von Karman momentum theory: the paper's characteristic curves of a "
        "free-falling wedge, with Dobrovol'skaya's pile-up (default)"
    )
    curves = PAPER_CURVES
