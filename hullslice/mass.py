"""The body's mass properties, and how its mass is spread: uniformly over its volume
(default) or along its length.

:class:`MassProperties` holds what is given of the mass (total, distribution, centre of
gravity, pitch inertia), checked once; the hull fills in the rest from its volume.

A :class:`MassDistribution` describes the mass as line densities along the body's ``x`` axis
and point masses. It gives the total mass, the centre of gravity, the pitch moment of inertia,
and the mass per metre at any station, which the sections use in place of the uniform
``M = m A / V``. A hull checks its distribution against its body (:meth:`MassDistribution.
on_body`): the mass must lie along the body's length and its centre of gravity in the body's
bounding box, and point masses without a length are spread over a tenth of the body's length.

The body frame is the hull's: ``x`` forward, ``z`` up, metres, after the mesh's units and axes
are applied.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import cast

import numpy as np

from .errors import CaseError, InputError
from .limits import (
    MASS_OFF_BODY_TOLERANCE,
    check_cg_in_body,
    check_density,
    check_mass_on_body,
)
from .paths import printable
from .renamed import renamed_keywords
from .tables import column_values, header_text, read_csv

__all__ = [
    "POINT_SPREAD",
    "MassDistribution",
    "MassProperties",
    "check_density",
    "fit_to_body",
    "read_mass_distribution",
]

#: Length over which a point mass given without one is spread, as a fraction of the body's
#: length (centred on the mass, narrowed near the body's ends so that it stays on the body).
POINT_SPREAD = 0.1


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
    points : (j, 4) or (j, 3) float
        Point masses as rows ``x, z, mass, length``: ``mass`` (kg) at ``(x, z)`` (m), spread
        evenly over ``length`` m along ``x`` for the sections (a mass at one point would give a
        section an infinite mass per metre). Without a length (three columns, or NaN) the
        mass follows the body: it is spread over :data:`POINT_SPREAD` of the body's length
        centred on ``x``, narrowed where ``x`` is nearer an end of the body than half of
        that (at least 1/4000 of the body's length on each side, cut at the body's end).
    body : (float, float), optional
        The body's range of ``x``, m, set by :meth:`on_body` when a hull takes the
        distribution; needed by point masses without a length.

    Notes
    -----
    The sections carry each point mass exactly: a slice takes the part of the mass's
    spread that lies between its two planes, whatever its thickness.
    """

    x: np.ndarray = field(default_factory=lambda: np.empty(0))
    mass_per_metre: np.ndarray = field(default_factory=lambda: np.empty(0))
    line_z: float | None = None
    points: np.ndarray = field(default_factory=lambda: np.empty((0, 4)))
    body: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        x = np.asarray(self.x, dtype=np.float64).ravel()
        m = np.asarray(self.mass_per_metre, dtype=np.float64).ravel()
        pts = np.asarray(self.points, dtype=np.float64)
        if pts.ndim == 2 and pts.shape[1] == 3:  # no lengths: they follow the body
            pts = np.column_stack([pts, np.full(len(pts), np.nan)])
        if pts.size % 4:
            raise InputError(
                f"mass distribution: point masses have shape {pts.shape}: give rows of "
                "x, z, mass (m, m, kg) and optionally length (m)"
            )
        pts = pts.reshape(-1, 4)
        if len(x) != len(m):
            raise InputError(f"mass distribution: {len(x)} stations but {len(m)} values")
        if len(x) == 1:
            raise InputError("a line density needs at least two stations (x, mass_per_metre)")
        for name, arr in (("x", x), ("mass per metre", m), ("point masses", pts[:, :3])):
            if not np.all(np.isfinite(arr)):
                raise InputError(f"mass distribution: {name} has NaN or infinite values")
        if np.any(np.diff(x) <= 0):
            raise InputError("mass distribution: stations x must be strictly increasing (m)")
        if np.any(m < 0):
            raise InputError("mass distribution: a mass per metre is negative (kg/m)")
        if np.any(pts[:, 2] <= 0) or np.any(pts[:, 3] <= 0) or np.any(np.isinf(pts[:, 3])):
            raise InputError("mass distribution: point masses and their lengths must be > 0")
        if self.body is not None:
            lo, hi = (float(b) for b in self.body)
            if not (np.isfinite(lo) and np.isfinite(hi) and hi > lo):
                raise InputError(f"mass distribution: body range {self.body!r} m is not x0 < x1")
            object.__setattr__(self, "body", (lo, hi))
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
        return MassDistribution(self.x, self.mass_per_metre, float(z), self.points, self.body)

    def on_body(self, x0: float, x1: float) -> MassDistribution:
        """The same distribution on a body that spans ``x0 <= x <= x1`` (m): point masses
        without a length are spread over :data:`POINT_SPREAD` of ``x1 - x0``.

        Use :func:`fit_to_body` to check the distribution against the body too.
        """
        return MassDistribution(self.x, self.mass_per_metre, self.line_z, self.points, (x0, x1))

    def spreads(self) -> tuple[np.ndarray, np.ndarray]:
        """Where each point mass is spread along ``x``: ``(start, end)``, m, each ``(j,)``.

        Raises
        ------
        InputError
            A point mass without a length on a distribution not yet on a body.
        """
        px, length = self.points[:, 0], self.points[:, 3]
        lo, hi = px - length / 2, px + length / 2
        free = np.isnan(length)
        if free.any():
            if self.body is None:
                raise InputError(
                    "mass distribution: point masses without a length are spread along the "
                    "body: give the distribution to a hull (Hull.with_mass(mass_distribution="
                    "...)), or give each point mass a length in m"
                )
            x0, x1 = self.body
            span = x1 - x0
            d = np.clip(np.minimum(px - x0, x1 - px), 0.0, None)
            half = np.maximum(np.minimum(POINT_SPREAD * span / 2, d), span / 4000)
            lo = np.where(free, np.maximum(px - half, x0), lo)
            hi = np.where(free, np.minimum(px + half, x1), hi)
        return lo, hi

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
        along ``x`` over its spread (:meth:`spreads`), its centre of mass at the point.
        """
        zl = self.line_z if self.line_z is not None else line_z
        xg, zg = float(cg[0]), float(cg[1])
        i_line = _moment2(self.x - xg, self.mass_per_metre) if len(self.x) else 0.0
        i_line += self.line_mass * (zl - zg) ** 2
        p = self.points
        lo, hi = self.spreads()
        # a rod from lo to hi about the point x: its length^2 / 12 plus its offset^2
        rod = (hi - lo) ** 2 / 12 + ((lo + hi) / 2 - p[:, 0]) ** 2
        i_pts = (p[:, 2] * ((p[:, 0] - xg) ** 2 + (p[:, 1] - zg) ** 2 + rod)).sum()
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
        for pm, lo, hi in zip(self.points[:, 2], *self.spreads(), strict=True):
            out = out + np.where((x >= lo) & (x <= hi), pm / (hi - lo), 0.0)
        return out

    @renamed_keywords(pitch="pitch_rad")
    def on_planes(
        self, x_rel, pitch_rad: float, cg, line_z: float, dx: np.ndarray | None = None
    ) -> np.ndarray:
        """Mass per metre of earth ``X`` on the planes ``X - X_g = x_rel`` (m) of a body pitched
        by ``pitch_rad`` (rad, nose up) about ``cg = (x, z)`` (m), kg/m.

        Each part of the distribution lies at its own height ``z``: a plane meets it at body
        ``x = x_g + (x_rel + (z - z_g) sin(pitch)) / cos(pitch)``, and a density of ``m`` per
        metre of body counts ``m / cos(pitch)`` per metre of earth. Given the slices'
        thicknesses ``dx`` (m, along ``X``), a point mass counts on each slice the part of
        it between the slice's planes, divided by ``dx``: the slices carry it whole however
        thick they are.
        """
        x_rel = np.asarray(x_rel, dtype=np.float64)
        pitch = pitch_rad
        c, s = np.cos(pitch), np.sin(pitch)
        xg, zg = float(cg[0]), float(cg[1])
        zl = self.line_z if self.line_z is not None else line_z
        out = np.zeros_like(x_rel)
        if len(self.x):
            x = xg + (x_rel + (zl - zg) * s) / c
            out += np.interp(x, self.x, self.mass_per_metre, left=0.0, right=0.0)
        if dx is not None:
            half = np.asarray(dx, dtype=np.float64) / 2
        for (pz, pm), lo, hi in zip(self.points[:, 1:3], *self.spreads(), strict=True):
            x = xg + (x_rel + (pz - zg) * s) / c
            if dx is None:
                out += np.where((x >= lo) & (x <= hi), pm / (hi - lo), 0.0)
            else:  # the share of [lo, hi] between the slice's planes, per metre of earth
                a, b = x - half / c, x + half / c
                overlap = np.clip(np.minimum(b, hi) - np.maximum(a, lo), 0.0, None)
                out += pm * overlap / (hi - lo) * c / np.where(half > 0, 2 * half, 1.0)
        return out / c


def fit_to_body(
    dist: MassDistribution, bounds: np.ndarray, line_z: float, name: str
) -> MassDistribution:
    """``dist`` on the body whose bounding box is ``bounds`` ((2, 3), m), checked.

    Parameters
    ----------
    dist : MassDistribution
        The distribution, body frame.
    bounds : (2, 3) float
        The body's bounding box, m.
    line_z : float
        Height of the line density when it has none of its own, m.
    name : str
        The hull's name, for messages.

    Raises
    ------
    InputError
        More than :data:`~hullslice.limits.MASS_OFF_BODY_SHARE` of the mass beyond the
        body's ends (the rows named), or the centre of gravity outside the bounding box.
        A smaller share beyond the ends is warned of.
    """
    x0, x1 = float(bounds[0][0]), float(bounds[1][0])
    tol = MASS_OFF_BODY_TOLERANCE * (x1 - x0)
    lo, hi = x0 - tol, x1 + tol
    on = dist.on_body(x0, x1)
    outside, rows = 0.0, []
    if len(dist.x):
        xs, m = dist.x, dist.mass_per_metre
        cut = np.unique(np.clip(np.concatenate([xs, [x0, x1]]), x0, x1))
        outside += dist.line_mass - float(
            np.trapezoid(np.interp(cut, xs, m, left=0.0, right=0.0), cut)
        )
        rows += [float(x) for x in xs if not lo <= x <= hi]
    p_lo, p_hi = on.spreads()
    for (px, _, pm, _), a, b in zip(dist.points, p_lo, p_hi, strict=True):
        beyond = pm * (max(x0 - a, 0.0) + max(b - x1, 0.0)) / (b - a)
        if not lo <= px <= hi:
            beyond = pm
        outside += min(beyond, pm)
        if not lo <= a <= b <= hi:
            rows.append(float(px))
    check_mass_on_body(max(outside, 0.0), dist.total, sorted(rows), (x0, x1), name)
    check_cg_in_body(dist.cg(line_z), bounds, name)
    return on


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
      along x (default: :data:`POINT_SPREAD` of the length of the body that takes it).

    A header with both ``mass_per_metre`` and ``mass`` is refused: its rows would be read
    as one form and the other column ignored.

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
    if "mass_per_metre" in col and "mass" in col:
        raise CaseError(
            f"{where} has both a mass_per_metre column (a line density) and a mass column "
            "(point masses): a table holds one form; give x,mass_per_metre or "
            "x,z,mass[,length], or both forms together through the library "
            "(MassDistribution(x=..., mass_per_metre=..., points=...))"
        )
    try:
        if "mass_per_metre" in col and "x" in col:
            return MassDistribution(x=col["x"], mass_per_metre=col["mass_per_metre"])
        if {"x", "z", "mass"} <= set(col):
            length = col.get("length", np.full(len(data), np.nan))
            pts = np.stack([col["x"], col["z"], col["mass"], length], axis=1)
            return MassDistribution(points=pts)
    except InputError as exc:
        raise CaseError(f"{where}: {exc}") from None
    raise CaseError(
        f"{where} has no columns it can use ({header_text(header)}); it needs "
        "x,mass_per_metre (a line density) or x,z,mass[,length] (point masses)"
    )


@dataclass(frozen=True, eq=False)
class MassProperties:
    """What is given of a body's mass, each part optional (SI units, body frame).

    Parameters
    ----------
    mass : float, optional
        Total mass in kg (``> 0``). Default: the distribution's total, if one is given.
    distribution : MassDistribution, optional
        Mass along the body. Default: the mass spread uniformly over the volume. Its total
        must agree with ``mass`` within 0.5 %.
    cg : sequence of 2 or 3 float, optional
        Centre of gravity in m, body frame. Held as the point ``(x, y, z)``; two numbers
        are taken as ``(x, z)`` in the plane of symmetry (``y = 0``), as the ``cg=``
        keyword of :func:`~hullslice.load_hull` and ``--cg X,Z`` take it. Default: from the
        distribution, or the centre of volume.
    inertia : float, optional
        Pitch moment of inertia about the centre of gravity, kg m^2 (``> 0``). Default:
        from the distribution, or the mesh with uniform density.

    Raises
    ------
    InputError
        A value that is not a number, not positive or not finite, a ``cg`` of another
        length, or a mass that disagrees with the distribution.
    """

    mass: float | None = None
    distribution: MassDistribution | None = None
    cg: np.ndarray | None = None
    inertia: float | None = None

    def __post_init__(self) -> None:
        mass = _checked_mass(self.mass)
        distribution = self.distribution
        if distribution is not None:
            if not isinstance(distribution, MassDistribution):
                raise InputError("mass_distribution must be a hullslice.MassDistribution")
            total = distribution.total
            if mass is None:
                mass = total
            elif abs(total - mass) > 0.005 * mass:
                raise InputError(
                    f"the mass distribution adds up to {total:.6g} kg but the mass is given as "
                    f"{mass:.6g} kg: give one of them, or make them agree within 0.5 %"
                )
        cg = self.cg
        if cg is not None:
            c = np.asarray(cg, dtype=np.float64).ravel()
            if c.shape not in ((2,), (3,)) or not np.all(np.isfinite(c)):
                raise InputError(
                    f"cg {cg!r} is not two numbers x, z or three x, y, z (m, body frame)"
                )
            cg = _ro(c if len(c) == 3 else [c[0], 0.0, c[1]])
        inertia = self.inertia
        if inertia is not None:
            i = float(inertia)
            if not (np.isfinite(i) and i > 0):
                raise InputError(f"pitch inertia {inertia!r} kg m^2 is not positive")
            inertia = i
        object.__setattr__(self, "mass", mass)
        object.__setattr__(self, "cg", cg)
        object.__setattr__(self, "inertia", inertia)

    @classmethod
    def from_keywords(
        cls,
        mass_properties: MassProperties | None = None,
        *,
        mass: float | None = None,
        mass_distribution: MassDistribution | None = None,
        cg: Sequence[float] | None = None,
        inertia: float | None = None,
    ) -> MassProperties:
        """The mass properties given either as one ``mass_properties`` or as the keywords
        ``mass``, ``mass_distribution``, ``cg`` and ``inertia`` (not both)."""
        given = [k for k, v in (("mass", mass), ("mass_distribution", mass_distribution),
                                ("cg", cg), ("inertia", inertia)) if v is not None]  # fmt: skip
        if mass_properties is None:
            # the field holds the array __post_init__ makes of the sequence given
            return cls(mass, mass_distribution, cast("np.ndarray | None", cg), inertia)
        if given:
            raise InputError(
                f"mass_properties and {', '.join(given)} both give the mass properties: give "
                "mass_properties=MassProperties(...) alone, or the keywords alone"
            )
        if not isinstance(mass_properties, MassProperties):
            raise InputError(
                f"mass_properties {mass_properties!r} is not a hullslice.MassProperties"
            )
        return mass_properties


def _checked_mass(mass: float | None) -> float | None:
    if mass is None:
        return None
    try:
        m = float(mass)
    except (TypeError, ValueError):
        raise InputError(f"mass {mass!r} is not a number: give the body's mass in kg") from None
    if not np.isfinite(m) or m <= 0.0:
        raise InputError(f"mass {mass!r} kg is not positive: give the body's mass in kg")
    return m
