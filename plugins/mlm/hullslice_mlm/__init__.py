"""The Modified Logvinovich Model (MLM) for hullslice: pressures on the real body.

Korobkin (2004), "Analytical models of water impact", Eur. J. Appl. Math. 15, 821-838,
as the momentum-form solver ``mlm``. Wagner's theory finds the wetted width of a section
well and its force badly at moderate deadrise (its flat plate gives a 30-degree wedge
about 1.5 times the nonlinear force). The MLM keeps Wagner's contact and evaluates the
pressure on the real body.

Per side of a section with its bottom at height ``f(y)`` above the keel, ``y`` the
distance from the keel, penetration ``h`` and penetration speed ``V = dh/dt`` (down):

- **Contact.** Wagner's condition on the side's own contour,
  ``integral_0^{pi/2} f(c sin t) dt = (pi / 2) h``, gives the wetted half-width ``c`` and
  ``c' = dc/dh`` (:mod:`hullslice.solvers.contour`).
- **Pressure.** Logvinovich's potential on the body, ``phi = -V (sqrt(c^2 - y^2) + f - h)``,
  in Bernoulli's equation with the exact body condition:

      p / rho = dV/dt (sqrt(c^2 - y^2) + f - h)
              + V^2 [c c' / sqrt(c^2 - y^2) - 1/2 - y^2 / (2 (c^2 - y^2) (1 + f'^2))].

  The bracket is negative near the spray root (it falls to minus infinity there); the
  force per metre is the integral, over ``dy``, from the keel to the point ``y*`` where
  the bracket changes sign (Korobkin 2004: the positive part of the pressure).
- **Momentum form.** The ``dV/dt`` term is an added mass,
  ``m_a = rho integral_0^{y*} (sqrt(c^2 - y^2) + f - h) dy`` both sides, on the left of the
  body's equations of motion; the bracket's integral times ``rho`` is the coefficient of
  ``v^2`` (hullslice's ``rate``): ``f = rate v^2 - m_a a`` per metre (``a`` up, ``v < 0``
  down), the ``v^2`` term dropped on a section leaving the water. At constant speed a
  wedge of deadrise ``beta`` (``k = tan(beta)``, ``c = pi h / (2 k)``) gets, with
  ``s = sin(t*)`` at the sign change,

      f = 2 rho V^2 c [c' t* - s / 2 - (atanh(s) - s) / (2 (1 + k^2))],   c' = pi / (2 k),

  (:func:`wedge_force`), which tends to Wagner's ``rho pi c c' V^2`` as ``beta -> 0``.
- **A sharp edge** (a chine or a knuckle: the bottom meets the section's widest point at
  a deadrise below ``smooth_edge_deg``): once ``c`` passes the edge the flow separates.
  The contact goes on along a fictitious body continuing the bottom from the edge
  (Tassin, Korobkin & Cooker 2014, Appl. Ocean Res. 48, 33-41: the fictitious body
  continuation), a straight line at the deadrise ``continuation`` (``"tangent"``: the
  bottom's own slope at the edge), and the pressure is integrated over the real body
  only (``y`` up to the edge).
- **A smooth widest point** (a round section, whose side is steeper than
  ``smooth_edge_deg`` there): the flow does not separate. The contact goes on along the
  contour reflected through its widest point, ``f(E + d) = 2 f(E) - f(E - d)`` (for a
  circle, the circle's own upper half unrolled outwards: the wetted girth keeps growing
  with the same slope), and the pressure is integrated over the real body's lower half.
  Once the contact has passed the reflection (a circle under water to its top), ``c`` and
  the added mass stay at their values there.
- **Gravity** (option ``gravity``): the hydrostatic pressure ``rho g`` times the depth
  below the calm water on the wetted contour, integrated as the section's area below the
  calm water (a vertical force, buoyancy).
- **Gravity's correction of the contact** (option ``gravity_contact``, after the approach of
  Hulin et al. 2022; derived in :mod:`hullslice_mlm.gravity`): gravity pulls the raised
  free surface down, so the contact is Wagner's at the penetration ``h (1 - delta)``,
  to first order exactly for a section ``f = A y^n`` at constant speed:
  ``delta = lambda(m) g h^2 / (m V^2 c)``, ``m = c' h / c = 1/n`` (a wedge's
  ``delta = kappa / Fr*^2``, ``Fr*^2 = V^2 / (g h tan(beta))``, ``kappa = 0.00894``), any
  other section by the power law of its own ``m``; ``c'`` times ``1 - (3 - m) delta``
  (quasi-steady, at the current speed).
  ``delta`` is held at 0.2, and such sections flagged. With ``gravity`` both are in.

Sections are flagged (``reason``) where the bottom turns back down (a re-entrant
contour: the MLM takes the contour's running maximum) and where the section Froude number
``|v| / sqrt(g h)`` is below ``froude_min``; a separation or a continuation is modelled,
not flagged (diagnostics ``separated``, ``continued``, ``submerged``).
"""

from __future__ import annotations

import math
from numbers import Real
from typing import Any, ClassVar

import numpy as np

from hullslice import AddedMass, InputError
from hullslice.solvers import join_reasons
from hullslice.solvers.base import MomentumFormSolver, SectionPressures
from hullslice.solvers.contour import contour_heights, submerged_parts, wagner_root

from .gravity import DELTA_MAX, contact_shift

__all__ = [
    "CONTINUATION",
    "CROSS_FLOW_DRAG",
    "MLM",
    "SMOOTH_EDGE_DEG",
    "continuation_for_drag",
    "wedge_force",
]
__version__ = "0.1.0"

#: The separated section's drag coefficient that sets the default continuation:
#: Zarnick's (1978) cross-flow drag after the chine, ``C_D,c rho b v^2`` per metre with
#: ``b`` the half-beam (Keuning 1994 gives 1.33 for the same drag).
CROSS_FLOW_DRAG = 1.0


def continuation_for_drag(drag: float) -> float:
    """The continuation's deadrise (deg) whose separated section, entering deep at constant
    speed, carries the cross-flow drag ``drag rho b V^2`` per metre (``b`` the half-beam).

    Far past the edge the contact on a straight continuation of deadrise ``beta_c`` grows
    as a wedge's, ``c' -> pi / (2 tan(beta_c))``, and ``c >> b``: the velocity term's
    pressure tends to ``rho V^2 (c' - 1/2)`` over the whole real width ``2 b``, a force of
    ``rho V^2 b (pi / tan(beta_c) - 1)``. So ``tan(beta_c) = pi / (1 + drag)``.
    """
    return math.degrees(math.atan(math.pi / (1.0 + drag)))


#: Default deadrise of the fictitious body past a sharp edge, deg: the continuation whose
#: late drag is Zarnick's cross-flow drag (57.52 deg; Keuning's 1.33 gives 53.4 deg).
CONTINUATION: str | float = continuation_for_drag(CROSS_FLOW_DRAG)

#: A side meeting its widest point steeper than this (deg) is smooth there.
SMOOTH_EDGE_DEG = 75.0
#: Gauss-Legendre nodes over ``t`` in ``(0, t*)`` per side (the pressure's points).
NODES = 32
#: Points of the scan for the pressure's change of sign.
SCAN = 64
#: Samples of each side's contour as cut, and of its continued contour.
RAW, GRID = 129, 257
#: How far the continuation runs past a sharp edge, in edge half-widths.
SHARP_REACH = 4.0
_X, _WX = np.polynomial.legendre.leggauss(NODES)
_U = 0.5 * (_X + 1.0)  # (0, 1)
_WU = 0.5 * _WX


def wedge_force(deadrise: float, penetration: float, speed: float, rho: float = 1000.0) -> float:
    """The MLM force per metre on a wedge at constant speed (Korobkin 2004), N/m.

    Parameters
    ----------
    deadrise : float
        Deadrise angle, rad, in (0, pi/2).
    penetration : float
        Depth of the keel below the calm water, m.
    speed : float
        Entry speed, m/s (down, positive).
    rho : float
        Water density, kg/m^3.
    """
    k = math.tan(deadrise)
    cp = math.pi / (2.0 * k)
    c = cp * penetration

    def bracket(t: float) -> float:  # the velocity term's pressure times cos(t)
        return cp - 0.5 * math.cos(t) - math.sin(t) ** 2 / (2.0 * math.cos(t) * (1.0 + k * k))

    if bracket(0.0) <= 0.0:
        return 0.0
    lo, hi = 0.0, 0.5 * math.pi * (1.0 - 1e-15)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if bracket(mid) > 0.0 else (lo, mid)
    t = 0.5 * (lo + hi)
    s = math.sin(t)
    return (
        2.0 * rho * speed**2 * c * (cp * t - 0.5 * s - (math.atanh(s) - s) / (2.0 * (1.0 + k * k)))
    )


def _number(solver: MLM, key: str, lo: float, hi: float, *, open_lo: bool = False) -> float:
    value = solver.settings[key]
    ok = isinstance(value, Real) and not isinstance(value, bool)
    v = float(value) if ok else math.nan
    inside = math.isfinite(v) and (v > lo if open_lo else v >= lo) and v <= hi
    if not inside:
        span = f"in ({lo:g}, {hi:g}]" if open_lo else f"in [{lo:g}, {hi:g}]"
        raise InputError(
            f"solver 'mlm': option {key}={value!r} is not a number {span} "
            f"(default {solver.options[key]!r})"
        )
    return v


class MLM(MomentumFormSolver):
    """The Modified Logvinovich Model (Korobkin 2004) with flow separation.

    Parameters
    ----------
    section_method : str, optional
        ``"auto"`` (default: each section's own contour, the equivalent wedge on a flat
        bottom), ``"contour"`` or ``"wedge"`` (the equivalent wedge of every section, its
        chine at the section's widest point).
    continuation : str or float, optional
        The fictitious body past a sharp edge: ``"tangent"`` (the bottom's slope at the
        edge) or its deadrise in degrees, in (0, 90), steeper than the bottom at every
        sharp edge met (default :data:`CONTINUATION`).
    smooth_edge_deg : float, optional
        A side meeting its widest point at a deadrise above this (deg, in (0, 90]) is
        smooth there (no separation); default 75.
    gravity : bool, optional
        Add the hydrostatic pressure (default False).
    gravity_contact : bool, optional
        Correct Wagner's contact for gravity, to first order in ``1 / Fr*^2``
        (:mod:`hullslice_mlm.gravity`; default False).
    froude_min : float, optional
        Smallest section Froude number ``|v| / sqrt(g h)`` inside the range (default 2),
        where ``gravity`` is off (with it the hydrostatic force is in the load).
    """

    name = "mlm"
    description = (
        "Modified Logvinovich Model (Korobkin 2004): Wagner's contact, the pressure on the "
        "real body, separation at sharp edges on a fictitious body, pressures returned"
    )
    models_separation = True
    positive_pressure = True
    gives_pressures = True
    own_checks = ("continuation", "smooth_edge_deg", "gravity", "gravity_contact", "froude_min")
    options: ClassVar[dict[str, Any]] = {
        "section_method": "auto",
        "continuation": CONTINUATION,
        "smooth_edge_deg": SMOOTH_EDGE_DEG,
        "gravity": False,
        "gravity_contact": False,
        "froude_min": 2.0,
    }

    def __init__(self, **options: Any) -> None:
        super().__init__(**options)
        s = self.settings
        if s["section_method"] not in ("auto", "contour", "wedge"):
            raise InputError(
                f"solver 'mlm': option section_method={s['section_method']!r} is unknown; "
                "choose auto, contour or wedge"
            )
        cont = s["continuation"]
        self._cont_given = "continuation" in options
        if isinstance(cont, str):
            if cont.strip().lower() != "tangent":
                raise InputError(
                    f"solver 'mlm': option continuation={cont!r} is neither 'tangent' nor a "
                    "deadrise in degrees (e.g. 57.5)"
                )
            s["continuation"] = "tangent"
            self._cont_tan = None
        else:
            deg = _number(self, "continuation", 0.0, 90.0, open_lo=True)
            if deg >= 90.0:
                raise InputError(
                    f"solver 'mlm': option continuation={cont!r} deg is vertical: the contact "
                    "would stop at the edge; give a deadrise below 90 deg, e.g. 60"
                )
            s["continuation"] = deg
            self._cont_tan = math.tan(math.radians(deg))
        s["smooth_edge_deg"] = _number(self, "smooth_edge_deg", 0.0, 90.0, open_lo=True)
        s["froude_min"] = _number(self, "froude_min", 0.0, math.inf)
        if not isinstance(s["gravity"], bool):
            raise InputError(f"solver 'mlm': option gravity={s['gravity']!r} is not true or false")
        if not isinstance(s["gravity_contact"], bool):
            raise InputError(
                f"solver 'mlm': option gravity_contact={s['gravity_contact']!r} is not true or "
                "false (true: gravity's correction of the contact)"
            )

    # -- the sides' contours ---------------------------------------------------------------

    def _contours(self, sections):
        """Each side's bottom as cut: heights ``f`` on an even grid from the keel (rising),
        the side's extent ``E`` to its widest point (the sampled reach where the grid ends
        before it),
        the grid's step, and the sides whose contour turns back down."""
        n = len(sections)
        p = np.asarray(sections.penetration, dtype=np.float64)
        calm = np.maximum(np.stack([sections.half_beam_port, sections.half_beam_stbd]), 0.0)
        chine = np.asarray(sections.part_half_beam, dtype=np.float64)
        extent = _extents(sections)  # (2, n) from the polygons
        method = self.settings["section_method"]
        tb = np.tan(np.stack([sections.deadrise_port, sections.deadrise_stbd]))
        wedge = np.full(n, method == "wedge")
        if method != "wedge":
            reach = np.where(2.5 * calm < extent, 2.5 * calm, 1.02 * extent)
            reach = np.where(reach > 0, reach, 2.5 * np.maximum(calm, 1e-9))
            raw = contour_heights(sections, reach, RAW)
            ds = reach / (RAW - 1)
            finite = np.isfinite(raw)
            near = raw[:, :, : max(2, RAW // 10)]
            flat = np.any(np.all(np.abs(near) <= 1e-9 * p[None, :, None] + 1e-12, axis=2), axis=0)
            flat |= ~finite[:, :, 1].all(axis=0)
            wedge |= flat
            last = np.where(finite.all(axis=-1), RAW - 1, np.argmin(finite, axis=-1) - 1)
            last = np.maximum(last, 1)
            gap = (last < RAW - 1) & ((last + 1) * ds < extent)
            extent = np.where(gap, (last + 1) * ds, extent)  # a side that ends before
            edge_in = extent <= reach * (1.0 + 1e-12)
            filled = np.where(finite, raw, -np.inf)
            rising = np.maximum.accumulate(filled, axis=-1)
            drop = rising - np.where(finite, raw, rising)
            reentrant = np.any(drop > 1e-6 * p[None, :, None] + 1e-9, axis=-1)
            raw = np.where(np.isfinite(rising), rising, 0.0)
        else:
            reach = np.maximum(extent, 1e-12)
            ds = reach / (RAW - 1)
            raw = np.zeros((2, n, RAW))
            last = np.full((2, n), RAW - 1)
            edge_in = np.ones((2, n), dtype=bool)
            reentrant = np.zeros((2, n), dtype=bool)
        if wedge.any():  # the equivalent wedge, its chine at the section's widest point
            ext_w = np.broadcast_to(chine[wedge], (2, int(wedge.sum())))
            extent[:, wedge] = ext_w
            ds[:, wedge] = np.maximum(ext_w, 1e-12) / (RAW - 1)
            raw[:, wedge] = tb[:, wedge, None] * ds[:, wedge, None] * np.arange(RAW)
            last[:, wedge] = RAW - 1
            edge_in[:, wedge] = True
            reentrant[:, wedge] = False
        return raw, ds, last, extent, edge_in, reentrant

    def _continued(self, sections, raw, ds, last, extent, edge_in):
        """The sides' contours for the contact, on an even grid of GRID points: the real
        bottom up to the departure point, a straight fictitious line past it (at a sharp
        edge, the edge; on a smooth side, where it becomes as steep as the continuation).

        Returns the heights (2, n, GRID) and their step, the edge ``e`` (the side's
        widest point), the line's ``(offset, slope)`` (``f = offset + slope y`` past the
        departure), which sides are sharp and smooth there, and the last sample of the real
        bottom with its slope ``(y_last, s_edge)`` (:func:`_real` goes on with it)."""
        k_raw = raw.shape[-1]
        slope_raw = np.diff(raw, axis=-1) / ds[..., None]
        i_last = np.clip(last, 1, k_raw - 1)
        s_edge = np.take_along_axis(slope_raw, (i_last - 1)[..., None], axis=-1)[..., 0]
        y_last = i_last * ds
        e = np.where(edge_in, extent, y_last)
        f_edge = _real(raw, ds, y_last, s_edge, e[..., None])[0][..., 0]
        sharp = edge_in & (np.degrees(np.arctan(s_edge)) < self.settings["smooth_edge_deg"])
        smooth = edge_in & ~sharp
        if self._cont_tan is None:
            s_cont = s_edge
            tan_dep = math.tan(math.radians(self.settings["smooth_edge_deg"]))
        else:
            s_cont = np.maximum(s_edge, self._cont_tan)  # the default: at least the tangent
            tan_dep = self._cont_tan
            steep = sharp & (s_edge > self._cont_tan * (1.0 + 1e-9))
            if self._cont_given and steep.any():
                side, i = (int(a[0]) for a in np.nonzero(steep))
                raise InputError(
                    f"solver 'mlm': continuation={self.settings['continuation']:g} deg is not "
                    f"steeper than the bottom at the sharp edge of the section at x = "
                    f"{float(sections.x[i]):.6g} m ({math.degrees(math.atan(s_edge[side, i])):.4g}"
                    " deg there): give a steeper continuation or continuation=tangent"
                )
        # a smooth side leaves its contour where it is first as steep as the continuation
        index = np.arange(k_raw - 1)
        steep_at = (slope_raw >= tan_dep) & (index <= (i_last - 1)[..., None])
        found = steep_at.any(axis=-1)
        i_dep = np.argmax(steep_at, axis=-1)
        d_smooth = np.where(found, i_dep * ds, e)
        f_smooth = np.where(
            found, np.take_along_axis(raw, i_dep[..., None], axis=-1)[..., 0], f_edge
        )
        s_smooth = np.where(found, tan_dep, np.maximum(s_edge, tan_dep))
        dep = np.where(smooth, d_smooth, e)
        f_dep = np.where(smooth, f_smooth, f_edge)
        slope = np.where(smooth, s_smooth, s_cont)
        end = np.where(edge_in, SHARP_REACH * e, e)
        step = end / (GRID - 1)
        y = step[..., None] * np.arange(GRID)
        inside = _real(raw, ds, y_last, s_edge, np.minimum(y, e[..., None]))[0]
        line = f_dep[..., None] + (y - dep[..., None]) * slope[..., None]
        g = np.where(edge_in[..., None] & (y > dep[..., None]), line, inside)
        g = np.maximum.accumulate(g, axis=-1)
        return g, step, e, (f_dep - slope * dep, slope), sharp, smooth, (y_last, s_edge)

    # -- the solver ------------------------------------------------------------------------

    def added_mass(self, sections, velocity, fluid) -> AddedMass:
        n = len(sections)
        p = np.asarray(sections.penetration, dtype=np.float64)
        v = np.asarray(velocity, dtype=np.float64)
        raw, ds, last, extent, edge_in, reentrant = self._contours(sections)
        g, step, e, line, sharp, smooth, (y_last, s_last) = self._continued(
            sections, raw, ds, last, extent, edge_in
        )
        pen = np.broadcast_to(p, (2, n))
        c, cp, capped, i_end = _contact(g, step, pen, edge_in, line)
        shift = held = np.zeros((2, n))
        if self.settings["gravity_contact"]:  # Wagner's contact at h (1 - delta)
            shift, held, factor = contact_shift(pen, v, fluid.g, c, cp)
            if shift.any():
                c, cp, capped, i_end = _contact(g, step, pen * (1.0 - shift), edge_in, line)
                cp = cp * factor  # quasi-steady: V and the growth exponent held
        # past the end of the continuation the contact and the added mass stay
        h_cap = i_end / (0.5 * np.pi) / (1.0 - shift)
        h = np.where(capped, np.minimum(h_cap, p), p)
        # the pressure: on the real body only, up to the velocity term's change of sign
        y_lim = np.where(edge_in, np.minimum(e, c), c)
        t_lim = np.arcsin(np.clip(y_lim / np.where(c > 0, c, 1.0), 0.0, 1.0))
        t_lim = np.minimum(t_lim, 0.5 * np.pi * (1.0 - 1e-12))

        def body(y):  # the real bottom's height and slope at y (up to its widest point)
            return _real(raw, ds, y_last, s_last, y)

        t_star = _sign_change(c, cp, body, t_lim)
        tk = t_star[..., None] * _U
        wk = t_star[..., None] * _WU
        yk = c[..., None] * np.sin(tk)
        fk, fpk = body(yk)
        cos = np.cos(tk)
        pv = cp[..., None] / cos - 0.5 - np.tan(tk) ** 2 / (2.0 * (1.0 + fpk**2))
        pa = c[..., None] * cos + fk - h[..., None]
        dy = c[..., None] * cos * wk
        rho = fluid.rho
        phi = (pv * dy).sum(axis=-1)  # (2, n), m
        ma = np.maximum((pa * dy).sum(axis=-1), 0.0)
        # the bound on suction is the pressure's, point by point: over the loaded width
        girth = dy.sum(axis=-1)
        added = rho * ma.sum(axis=0)
        rate = rho * np.maximum(phi, 0.0).sum(axis=0)
        vertical = np.zeros(n)
        if self.settings["gravity"]:
            area, _ = submerged_parts(sections)
            vertical = rho * fluid.g * area
        with np.errstate(divide="ignore", invalid="ignore"):
            froude = np.abs(v) / np.sqrt(fluid.g * p) if fluid.g > 0 else np.full(n, np.inf)
        fr_min = self.settings["froude_min"]
        separated = np.any(sharp & (c > e), axis=0)
        continued = np.any(smooth & (c > e), axis=0)
        submerged = np.any(capped & edge_in, axis=0)
        re_in = np.any(reentrant, axis=0)
        slow = (froude <= fr_min) & (not self.settings["gravity"])  # else buoyancy is in
        reason = join_reasons(
            n,
            [
                (slow, f"Fr = |v| / sqrt(g p) <= {fr_min:g} (gravity not negligible)"),
                (
                    re_in,
                    "re-entrant contour (the bottom turns back down): its running maximum used",
                ),
                (
                    np.any(held, axis=0),
                    f"kappa / Fr*^2 > {DELTA_MAX:g}: gravity's contact correction held there",
                ),
            ],
        )
        if self.settings["gravity_contact"]:
            extra = {"gravity_shift": 0.5 * (shift[0] + shift[1])}
        else:
            extra = {}
        pressure = SectionPressures(
            y=np.moveaxis(yk, 0, 1),
            z=np.moveaxis(fk, 0, 1),
            weight=np.moveaxis(dy, 0, 1),
            velocity_coefficient=rho * np.moveaxis(pv, 0, 1),
            acceleration_coefficient=rho * np.moveaxis(pa, 0, 1),
        )
        return AddedMass(
            added_mass=added,
            rate=rate,
            valid=reason == "",
            reason=reason,
            vertical=vertical,
            diagnostics={
                "wetted_half_width": 0.5 * (c[0] + c[1]),
                "pressure_half_width": 0.5 * (c * np.sin(t_star)).sum(axis=0),
                "edge_half_width": 0.5 * (e[0] + e[1]),
                "separated": separated.astype(np.float64),
                "continued": continued.astype(np.float64),
                "submerged": submerged.astype(np.float64),
                "froude": froude,
                "buoyancy": vertical,
                "contour": np.ones(n),
                **extra,
            },
            girth=girth.sum(axis=0),
            pressure=pressure,
        )


def _contact(g, step, pen, edge_in, line):
    """Wagner's contact ``c`` of the penetrations ``pen`` (2, n) on the continued contours
    ``g`` (step ``step``), ``c' = dc/dh``, where it is held at the grid's end, and Wagner's
    integral there."""
    target = 0.5 * np.pi * pen
    c = wagner_root(g, step, target)
    end = step * (GRID - 1)
    capped = ~np.isfinite(c)
    c = np.where(capped, end, c)
    # c' = (pi / 2) / integral_0^{pi/2} f'(c sin t) sin t dt
    t = 0.5 * np.pi * _U
    wt = 0.5 * np.pi * _WU
    slope = np.diff(g, axis=-1) / step[..., None]
    fp_c = _slope_at(slope, step, c[..., None] * np.sin(t))
    denom = (fp_c * np.sin(t)) @ wt
    with np.errstate(divide="ignore", invalid="ignore"):
        cp = np.where(denom > 0, 0.5 * np.pi / denom, 0.0)
    cp = np.where(capped, 0.0, cp)
    i_end = _interp_rows(g, step, end[..., None] * np.sin(t)) @ wt  # Wagner's, at the end
    far = capped & edge_in
    if far.any():  # past the grid the continuation is straight: c grows as a wedge's
        offset, k_c = line
        rest = i_end - k_c * end - 0.5 * np.pi * offset  # decays as 1 / c
        with np.errstate(divide="ignore", invalid="ignore"):
            c_far = (0.5 * np.pi * (pen - offset) - rest) / k_c
        ok = far & (k_c > 0) & (c_far >= end)
        c = np.where(ok, c_far, c)
        cp = np.where(ok, 0.5 * np.pi / np.where(k_c > 0, k_c, 1.0), cp)
        capped = capped & ~ok
    return c, cp, capped, i_end


def _sign_change(c, cp, body, t_lim):
    """The first ``t`` in ``(0, t_lim)`` where the velocity term's pressure changes sign
    (``t_lim`` where it does not; 0 where it is not positive at the keel); ``body(y)``
    gives the real bottom's height and slope."""

    def bracket(t):
        fp = body(c[..., None] * np.sin(t))[1]
        return cp[..., None] - 0.5 * np.cos(t) - np.sin(t) ** 2 / (2.0 * np.cos(t) * (1.0 + fp**2))

    grid = t_lim[..., None] * np.linspace(0.0, 1.0, SCAN + 1)
    b = bracket(grid)
    neg = b <= 0.0
    first = np.where(neg.any(axis=-1), np.argmax(neg, axis=-1), SCAN + 1)
    none = first > SCAN
    at_keel = first == 0
    j = np.clip(first, 1, SCAN)
    lo = np.take_along_axis(grid, (j - 1)[..., None], axis=-1)[..., 0]
    hi = np.take_along_axis(grid, j[..., None], axis=-1)[..., 0]
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        pos = bracket(mid[..., None])[..., 0] > 0.0
        lo, hi = np.where(pos, mid, lo), np.where(pos, hi, mid)
    t = 0.5 * (lo + hi)
    return np.where(none, t_lim, np.where(at_keel, 0.0, t))


def _real(raw, ds, y_last, s_last, y):
    """The real bottom's height and slope at ``y`` ((2, n, m)): the samples up to the last
    one, the last interval's slope on to the widest point."""
    k = raw.shape[-1]
    yc = np.minimum(y, y_last[..., None])
    f = _interp_rows(raw, ds, yc) + np.maximum(y - y_last[..., None], 0.0) * s_last[..., None]
    slope = np.diff(raw, axis=-1) / np.where(ds > 0, ds, 1.0)[..., None]
    fp = _slope_at(slope, ds, np.minimum(y, (k - 1.5) * ds[..., None]))
    fp = np.where(y >= y_last[..., None], s_last[..., None], fp)
    return f, fp


def _extents(sections) -> np.ndarray:
    """(2, n): how far each side of each entry reaches from its keel (port: +y), m, from
    its station's polygons."""
    n = len(sections)
    station = np.asarray(sections.station, dtype=np.int64)
    stations, index = np.unique(station, return_inverse=True)
    lo = np.full(len(stations), np.inf)
    hi = np.full(len(stations), -np.inf)
    for j, st in enumerate(stations):
        for poly in sections.polygons[int(st)]:
            a = np.asarray(poly, dtype=np.float64)
            if len(a):
                lo[j] = min(lo[j], float(a[:, 0].min()))
                hi[j] = max(hi[j], float(a[:, 0].max()))
    yk = np.asarray(sections.y_keel, dtype=np.float64)
    out = np.stack([hi[index] - yk, yk - lo[index]]) if n else np.zeros((2, 0))
    chine = 2.0 * np.asarray(sections.part_half_beam, dtype=np.float64)
    out = np.where(np.isfinite(out), out, chine)
    return np.minimum(np.maximum(out, 0.0), np.maximum(chine, 1e-300))


def _interp_rows(f: np.ndarray, ds: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Rows of ``f`` ((2, n, K), sampled every ``ds`` (2, n) from 0), linearly at ``y``
    ((2, n, m)); held at the ends."""
    k = f.shape[-1]
    with np.errstate(invalid="ignore", divide="ignore"):
        x = np.where(ds[..., None] > 0, y / ds[..., None], 0.0)
    x = np.clip(x, 0.0, k - 1)
    i0 = np.clip(np.floor(x).astype(np.int64), 0, k - 2)
    frac = x - i0
    a = np.take_along_axis(f, i0, axis=-1)
    b = np.take_along_axis(f, i0 + 1, axis=-1)
    return a * (1.0 - frac) + b * frac


def _slope_at(slope: np.ndarray, ds: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The piecewise-constant slope ((2, n, K-1)) of rows sampled every ``ds`` at ``y``."""
    k = slope.shape[-1]
    with np.errstate(invalid="ignore", divide="ignore"):
        x = np.where(ds[..., None] > 0, y / ds[..., None], 0.0)
    i = np.clip(np.floor(x).astype(np.int64), 0, k - 1)
    return np.take_along_axis(slope, i, axis=-1)
