"""How the body's mass is spread: uniformly over its volume (default) or along its length.

A :class:`MassDistribution` describes the mass as line densities along the body's ``x`` axis
and point masses. It gives the total mass, the centre of gravity, the pitch moment of inertia,
and the mass per metre at any station, which the sections use in place of the uniform
``M = m A / V``.

The body frame is the hull's: ``x`` forward, ``z`` up, metres, after the mesh's units and axes
are applied.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np

from .errors import CaseError, InputError
from .paths import printable
from .tables import column_values, header_text, read_csv

__all__ = ["MassDistribution", "read_mass_distribution"]


def _ro(a) -> np.ndarray:
    a = np.array(a, dtype=np.float64)
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class MassDistribution:
    """Mass along the body: a line density and point masses.

    Parameters
    ----------
    x : (k,) float
        Stations of the line density along the body, m, increasing (may be empty).
    mass_per_metre : (k,) float
        Line density at those stations, kg/m (``>= 0``), linear between them and zero
        outside.
    line_z : float, optional
        Height of the line density in the body frame, m (default: given by the hull, its
        centre of volume's height).
    points : (j, 4) float
        Point masses as rows ``x, z, mass, length``: ``mass`` (kg) at ``(x, z)`` (m), spread
        evenly over ``length`` m along ``x`` for the sections (a mass at one point would give a
        section an infinite mass per metre).
    """

    x: np.ndarray = field(default_factory=lambda: np.empty(0))
    mass_per_metre: np.ndarray = field(default_factory=lambda: np.empty(0))
    line_z: float | None = None
    points: np.ndarray = field(default_factory=lambda: np.empty((0, 4)))

    def __post_init__(self) -> None:
        x = np.asarray(self.x, dtype=np.float64).ravel()
        m = np.asarray(self.mass_per_metre, dtype=np.float64).ravel()
        pts = np.asarray(self.points, dtype=np.float64).reshape(-1, 4)
        if len(x) != len(m):
            raise InputError(f"mass distribution: {len(x)} stations but {len(m)} values")
        if len(x) == 1:
            raise InputError("a line density needs at least two stations (x, mass_per_metre)")
        for name, arr in (("x", x), ("mass per metre", m), ("point masses", pts)):
            if not np.all(np.isfinite(arr)):
                raise InputError(f"mass distribution: {name} has NaN or infinite values")
        if np.any(np.diff(x) <= 0):
            raise InputError("mass distribution: stations x must be strictly increasing (m)")
        if np.any(m < 0):
            raise InputError("mass distribution: a mass per metre is negative (kg/m)")
        if np.any(pts[:, 2] <= 0) or np.any(pts[:, 3] <= 0):
            raise InputError("mass distribution: point masses and their lengths must be > 0")
        if self.line_z is not None and not np.isfinite(self.line_z):
            raise InputError("mass distribution: line height is not finite")
        object.__setattr__(self, "x", _ro(x))
        object.__setattr__(self, "mass_per_metre", _ro(m))
        object.__setattr__(self, "points", _ro(pts))
        with np.errstate(over="ignore", invalid="ignore"):
            total, moment = self.total, _moment1(x, m) if len(x) else 0.0
            moment += float((pts[:, 0] * pts[:, 2]).sum())
        if not (np.isfinite(total) and np.isfinite(moment)):
            raise InputError(
                f"mass distribution: its total mass or moment overflows ({total:.3g} kg): "
                "values near 1e308 are not masses in kg and stations in m"
            )
        if total <= 0:
            raise InputError("mass distribution: the total mass is zero")

    @property
    def line_mass(self) -> float:
        """Mass of the line density in kg (trapezoid rule, exact for a linear density)."""
        return float(np.trapezoid(self.mass_per_metre, self.x)) if len(self.x) else 0.0

    @property
    def total(self) -> float:
        """Total mass in kg."""
        return self.line_mass + float(self.points[:, 2].sum())

    def with_line_z(self, z: float) -> MassDistribution:
        """The same distribution with the line density at height ``z`` (m)."""
        return MassDistribution(self.x, self.mass_per_metre, float(z), self.points)

    def cg(self, line_z: float) -> np.ndarray:
        """Centre of gravity ``(x, z)`` in m; ``line_z`` is used when the line has no height."""
        zl = self.line_z if self.line_z is not None else line_z
        x, m = self.x, self.mass_per_metre
        mx = _moment1(x, m) if len(x) else 0.0
        p = self.points
        mass = self.total
        xg = (mx + float((p[:, 2] * p[:, 0]).sum())) / mass
        zg = (self.line_mass * zl + float((p[:, 2] * p[:, 1]).sum())) / mass
        return np.array([xg, zg])

    def pitch_inertia(self, cg: np.ndarray, line_z: float) -> float:
        """Moment of inertia about the pitch axis through ``cg`` = (x, z), kg m^2.

        The line density is taken as a thin line at its height; each point mass as a thin rod
        of its length along ``x``.
        """
        zl = self.line_z if self.line_z is not None else line_z
        xg, zg = float(cg[0]), float(cg[1])
        i_line = _moment2(self.x - xg, self.mass_per_metre) if len(self.x) else 0.0
        i_line += self.line_mass * (zl - zg) ** 2
        p = self.points
        i_pts = (p[:, 2] * ((p[:, 0] - xg) ** 2 + (p[:, 1] - zg) ** 2 + p[:, 3] ** 2 / 12)).sum()
        return float(i_line + i_pts)

    def at(self, x: np.ndarray) -> np.ndarray:
        """Mass per metre at body stations ``x`` (m), kg/m: the line density plus the point
        masses spread over their lengths."""
        x = np.asarray(x, dtype=np.float64)
        out = (
            np.interp(x, self.x, self.mass_per_metre, left=0.0, right=0.0)
            if len(self.x)
            else np.zeros_like(x)
        )
        for px, _, pm, length in self.points:
            inside = np.abs(x - px) <= length / 2
            out = out + np.where(inside, pm / length, 0.0)
        return out

    def on_planes(self, x_rel, pitch: float, cg, line_z: float) -> np.ndarray:
        """Mass per metre of earth ``X`` on the planes ``X - X_g = x_rel`` (m) of a body pitched
        by ``pitch`` (rad, nose up) about ``cg = (x, z)`` (m), kg/m.

        Each part of the distribution lies at its own height ``z``: a plane meets it at body
        ``x = x_g + (x_rel + (z - z_g) sin(pitch)) / cos(pitch)``, and a density of ``m`` per
        metre of body counts ``m / cos(pitch)`` per metre of earth.
        """
        x_rel = np.asarray(x_rel, dtype=np.float64)
        c, s = np.cos(pitch), np.sin(pitch)
        xg, zg = float(cg[0]), float(cg[1])
        zl = self.line_z if self.line_z is not None else line_z
        out = np.zeros_like(x_rel)
        if len(self.x):
            x = xg + (x_rel + (zl - zg) * s) / c
            out += np.interp(x, self.x, self.mass_per_metre, left=0.0, right=0.0)
        for px, pz, pm, length in self.points:
            x = xg + (x_rel + (pz - zg) * s) / c
            out += np.where(np.abs(x - px) <= length / 2, pm / length, 0.0)
        return out / c


def _moment1(x: np.ndarray, m: np.ndarray) -> float:
    """Integral of x m(x) dx for m linear between stations (exact)."""
    x0, x1, m0, m1 = x[:-1], x[1:], m[:-1], m[1:]
    h = x1 - x0
    return float((h * (m0 * (2 * x0 + x1) + m1 * (x0 + 2 * x1)) / 6).sum())


def _moment2(x: np.ndarray, m: np.ndarray) -> float:
    """Integral of x^2 m(x) dx for m linear between stations (exact)."""
    x0, x1, m0, m1 = x[:-1], x[1:], m[:-1], m[1:]
    h = x1 - x0
    a = m0 * (3 * x0**2 + 2 * x0 * x1 + x1**2)
    b = m1 * (x0**2 + 2 * x0 * x1 + 3 * x1**2)
    return float((h * (a + b) / 12).sum())


def read_mass_distribution(path: str | os.PathLike) -> MassDistribution:
    """Read a mass distribution from CSV (SI units, body frame after units and axes).

    Two forms, told apart by the header (lines starting with ``#`` are comments):

    - ``x,mass_per_metre``: a line density, kg/m at stations x (m);
    - ``x,z,mass[,length]``: point masses (kg) at (x, z) (m), each spread over ``length`` m
      along x (default 1 m).

    Returns
    -------
    MassDistribution
    """
    header, rows = read_csv(path, "mass distribution")
    where = f"mass distribution file {printable(path)!r}"
    for lineno, row in rows:
        if len(row) != len(header):
            raise CaseError(
                f"{where} line {lineno} has {len(row)} values for {len(header)} columns"
            )
    data = column_values(rows, range(len(header)), header, where)
    col = {h: data[:, i] for i, h in enumerate(header)}
    try:
        if "mass_per_metre" in col and "x" in col:
            return MassDistribution(x=col["x"], mass_per_metre=col["mass_per_metre"])
        if {"x", "z", "mass"} <= set(col):
            length = col.get("length", np.ones(len(data)))
            pts = np.stack([col["x"], col["z"], col["mass"], length], axis=1)
            return MassDistribution(points=pts)
    except InputError as exc:
        raise CaseError(f"{where}: {exc}") from None
    raise CaseError(
        f"{where} has no columns it can use ({header_text(header)}); it needs "
        "x,mass_per_metre (a line density) or x,z,mass[,length] (point masses)"
    )
