"""The air's forces on a ditching body: lift, drag and pitch moment.

A ditching aircraft touches the water with its wing carrying about its weight; the lift,
the drag and the aerodynamic pitch moment act in the equations of motion beside the
water's force (METHOD section 9). An :class:`Aerodynamics` model gives them in the earth's
axes at the body's state, from the flight path it is on:

- the speed ``V = sqrt(u^2 + w^2)`` (``u`` forward, ``w`` vertical, negative down) and the
  path angle ``gamma = atan2(w, u)`` (negative descending);
- the angle of attack ``alpha = theta - gamma`` (``theta`` the pitch, nose up);
- lift ``L`` normal to the path (up when flying forward), drag ``D`` along it (against the
  motion), and a pitch moment ``M`` about the centre of gravity (nose up):

      F_x = -D cos(gamma) - L sin(gamma),    F_z = L cos(gamma) - D sin(gamma).

Three models, by name (:data:`AERO_MODELS`):

``none``
    No air forces (the default: the whole weight is on the water).
``weight``
    Lift equal to a share of the weight at touchdown (``fraction``, 1 by default), the
    shortcut of ditching studies: ``L = fraction m g (V / V_0)^2 alpha / alpha_0``, the
    lift coefficient linear in the angle of attack through zero lift at ``alpha = 0`` and
    the dynamic pressure that of the speed, up to the wing's stall: beyond ``stall_deg``
    (15 degrees by default; a transport wing with its flaps down stalls at about 12 to 16
    degrees) the lift coefficient stays at its value there. No drag and no moment.
``coefficients``
    The lift, drag and moment of given coefficients on a reference area ``S`` and chord
    ``c``, at the air's dynamic pressure ``q = rho_air V^2 / 2``: ``L = q S (C_L0 +
    C_La alpha)`` (held within ``+-C_L,max`` where that is given: the stall),
    ``D = q S C_D``, ``M = q S c (C_m0 + C_ma alpha + C_mq q_b c / (2 V))``
    with the pitch rate ``q_b`` (rad/s), and an optional thrust ``T`` along the body's axis.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from numbers import Real

from .errors import HullsliceWarning, InputError

__all__ = [
    "AERO_MODELS",
    "AERO_NUMBERS",
    "AIR_DENSITY",
    "COEFFICIENTS",
    "FLAT_TOUCHDOWN_DEG",
    "STALL_DEG",
    "AeroForces",
    "Aerodynamics",
    "Coefficients",
    "NoAerodynamics",
    "WeightLift",
    "aero_model",
    "model_of",
]

#: Density of air at sea level, kg/m^3 (ISO 2533 standard atmosphere, 15 deg C).
AIR_DENSITY = 1.225

#: The aerodynamic models by name, with a one-line description.
AERO_MODELS: dict[str, str] = {
    "none": "no air forces: the whole weight is on the water",
    "weight": "lift equal to the weight at touchdown (or a share of it), scaled with the "
    "speed squared and the angle of attack",
    "coefficients": "lift, drag and pitch moment of given coefficients on a reference area "
    "and chord",
}


#: The numbers of the models, as case-file keys and command-line options: (name, unit,
#: what it is).
AERO_NUMBERS: tuple[tuple[str, str, str], ...] = (
    ("lift_fraction", "", "share of the weight the lift carries at touchdown, 0 to 2"),
    ("stall_deg", "deg", "angle of attack beyond which the lift coefficient stays at its "
     "value there (the wing's stall), 0 to 90"),
    ("wing_area", "m^2", "reference (wing) area"),
    ("wing_chord", "m", "reference (mean aerodynamic) chord"),
    ("cl0", "", "lift coefficient at zero angle of attack"),
    ("cl_alpha", "1/rad", "lift-curve slope"),
    ("cl_max", "", "largest lift coefficient, held beyond it (the stall)"),
    ("cd", "", "drag coefficient"),
    ("cm0", "", "pitch-moment coefficient about the centre of gravity at zero angle of "
     "attack, nose up"),
    ("cm_alpha", "1/rad", "pitch-moment slope in the angle of attack"),
    ("cm_q", "1/rad", "pitch damping dC_m / d(q c / 2V), negative damps"),
    ("thrust", "N", "thrust along the body's axis"),
)  # fmt: skip


@dataclass(frozen=True)
class AeroForces:
    """The air's forces at one state: earth axes, N and N m (nose up)."""

    force_x: float = 0.0
    force_z: float = 0.0
    moment: float = 0.0
    lift: float = 0.0
    drag: float = 0.0
    alpha: float = 0.0


def _number(value, what: str, unit: str, *, low: float | None = None, fix: str = "") -> float:
    ok = isinstance(value, Real) and not isinstance(value, bool)
    v = float(value) if ok else math.nan
    if not math.isfinite(v) or (low is not None and v <= low):
        need = "a finite number" if low is None else f"a finite number above {low:g}"
        raise InputError(f"{what} {value!r}{unit} is not {need}{fix}")
    return v


def path(u: float, w: float, theta: float) -> tuple[float, float, float]:
    """The speed (m/s), path angle and angle of attack (rad) of a body moving at ``u``
    forward and ``w`` up (m/s), pitched ``theta`` (rad, nose up)."""
    speed = math.hypot(u, w)
    gamma = math.atan2(w, u) if speed > 0 else 0.0
    return speed, gamma, theta - gamma


def _earth(lift: float, drag: float, gamma: float) -> tuple[float, float]:
    c, s = math.cos(gamma), math.sin(gamma)
    return -drag * c - lift * s, lift * c - drag * s


class Aerodynamics:
    """The air's forces on the body (subclass and give :meth:`forces`)."""

    #: The model's name, as ``--lift`` and the results give it.
    name = ""

    def start(self, mass: float, g: float, theta: float, u: float, w: float) -> Aerodynamics:
        """The model for a run that starts at this state (mass in kg, gravity m/s^2, pitch
        rad, speeds m/s): itself, unless it is set by the touchdown."""
        return self

    def forces(self, theta: float, u: float, w: float, q: float) -> AeroForces:
        raise NotImplementedError

    def settings(self) -> dict[str, object]:
        """The model's inputs, for a history's settings."""
        return {"aero": self.name}


class NoAerodynamics(Aerodynamics):
    """No air forces."""

    name = "none"

    def forces(self, theta: float, u: float, w: float, q: float) -> AeroForces:
        return AeroForces()


#: The weight model's default stall: the angle of attack, deg, beyond which its lift
#: coefficient stays at its value there (a transport wing with its flaps down stalls at
#: about 12 to 16 degrees).
STALL_DEG = 15.0


#: The weight model's touchdown angle of attack, deg, below which its lift's growth with
#: the angle (``1 / alpha_0``: 50 % of itself per degree here) is far steeper than a wing's
#: and is warned of.
FLAT_TOUCHDOWN_DEG = 2.0


class WeightLift(Aerodynamics):
    """Lift equal to ``fraction`` of the weight at touchdown, scaled with the speed squared
    and the angle of attack (zero lift at zero angle) from then on, up to the stall.

    Parameters
    ----------
    fraction : float
        Share of the weight the lift carries at touchdown, in [0, 2] (default 1).
    stall_deg : float
        Angle of attack, deg, in (0, 90], beyond which (either way) the lift coefficient
        stays at its value there (default :data:`STALL_DEG`).
    """

    name = "weight"

    def __init__(self, fraction: float = 1.0, stall_deg: float = STALL_DEG) -> None:
        f = _number(fraction, "lift fraction", "", fix=" in [0, 2] (1: the weight)")
        if not 0.0 <= f <= 2.0:
            raise InputError(
                f"lift fraction {fraction!r} is not in [0, 2]: give the share of the weight "
                "the wing carries at touchdown (1: the weight)"
            )
        stall = _number(stall_deg, "stall angle", " deg", low=0.0, fix=" up to 90 (15: a "
                        "transport wing with its flaps down)")  # fmt: skip
        if stall > 90.0:
            raise InputError(
                f"stall angle {stall_deg!r} deg is above 90: give the angle of attack at "
                "which the wing's lift stops growing (15: a transport wing with its flaps down)"
            )
        self.fraction = f
        self.stall_deg = stall
        self._lift0 = math.nan
        self._speed0 = math.nan
        self._alpha0 = math.nan

    def start(self, mass: float, g: float, theta: float, u: float, w: float) -> Aerodynamics:
        speed, _, alpha = path(u, w, theta)
        if self.fraction > 0.0 and not (speed > 0.0 and alpha > 0.0):
            raise InputError(
                f"lift equal to the weight needs a positive angle of attack at touchdown: the "
                f"pitch {math.degrees(theta):.4g} deg is {math.degrees(alpha):.4g} deg above the "
                "flight path; pitch the body up, or give the lift's coefficients"
            )
        stall = math.radians(self.stall_deg)
        if self.fraction > 0.0 and alpha > stall:
            raise InputError(
                f"lift equal to the weight at touchdown at an angle of attack of "
                f"{math.degrees(alpha):.4g} deg, above the stall at {self.stall_deg:.4g} deg: "
                "pitch the body down, or give the stall angle (--stall-deg)"
            )
        if self.fraction > 0.0 and alpha < math.radians(FLAT_TOUCHDOWN_DEG):
            deg = math.degrees(alpha)
            warnings.warn(
                f"lift equal to the weight at an angle of attack of {deg:.3g} deg: it then "
                f"grows by {100 / deg:.3g} % of itself per degree, where a transport wing's "
                "grows by about 9 % (C_L,alpha about 5 per rad at C_L about 1); for a touchdown "
                "this flat give the wing's coefficients (--lift coefficients)",
                HullsliceWarning,
                stacklevel=2,
            )
        out = WeightLift(self.fraction, self.stall_deg)
        out._lift0, out._speed0, out._alpha0 = self.fraction * mass * g, speed, alpha
        return out

    def forces(self, theta: float, u: float, w: float, q: float) -> AeroForces:
        speed, gamma, alpha = path(u, w, theta)
        if self.fraction == 0.0 or not math.isfinite(self._lift0):
            return AeroForces(alpha=alpha)
        stall = math.radians(self.stall_deg)
        held = min(max(alpha, -stall), stall)  # the stalled wing's coefficient stays
        lift = self._lift0 * (speed / self._speed0) ** 2 * held / self._alpha0
        fx, fz = _earth(lift, 0.0, gamma)
        return AeroForces(fx, fz, 0.0, lift, 0.0, alpha)

    def settings(self) -> dict[str, object]:
        return {"aero": self.name, "lift_fraction": self.fraction, "stall_deg": self.stall_deg}


class Coefficients(Aerodynamics):
    """Lift, drag and pitch moment from coefficients on a reference area and chord.

    Parameters
    ----------
    area : float
        Reference (wing) area ``S``, m^2, positive.
    chord : float
        Reference (mean aerodynamic) chord ``c``, m, positive.
    cl0, cl_alpha : float
        Lift coefficient at zero angle of attack, and its slope per rad.
    cl_max : float, optional
        Largest lift coefficient, positive: the lift coefficient is held within
        ``+-cl_max`` (the stall). Default: none.
    cd : float
        Drag coefficient, >= 0.
    cm0, cm_alpha : float
        Pitch-moment coefficient about the centre of gravity at zero angle of attack
        (nose up), and its slope per rad.
    cm_q : float
        Pitch damping ``dC_m / d(q c / (2 V))``, per rad, <= 0 damps.
    thrust : float
        Thrust along the body's axis, N, >= 0 (default 0).
    rho_air : float
        Air density, kg/m^3 (default :data:`AIR_DENSITY`).
    """

    name = "coefficients"

    def __init__(
        self,
        area: float,
        chord: float,
        *,
        cl0: float = 0.0,
        cl_alpha: float = 0.0,
        cd: float = 0.0,
        cm0: float = 0.0,
        cm_alpha: float = 0.0,
        cm_q: float = 0.0,
        thrust: float = 0.0,
        rho_air: float = AIR_DENSITY,
        cl_max: float | None = None,
    ) -> None:
        self.area = _number(area, "reference area", " m^2", low=0.0, fix=" (the wing's, e.g. 122)")
        self.chord = _number(chord, "reference chord", " m", low=0.0, fix=" (e.g. 4.2)")
        self.cl0 = _number(cl0, "C_L0", "")
        self.cl_alpha = _number(cl_alpha, "C_L,alpha", " per rad")
        self.cd = _number(cd, "C_D", "")
        if self.cd < 0.0:
            raise InputError(f"C_D {cd!r} is negative: a drag coefficient is zero or positive")
        self.cm0 = _number(cm0, "C_m0", "")
        self.cm_alpha = _number(cm_alpha, "C_m,alpha", " per rad")
        self.cm_q = _number(cm_q, "C_m,q", " per rad")
        self.thrust = _number(thrust, "thrust", " N")
        if self.thrust < 0.0:
            raise InputError(f"thrust {thrust!r} N is negative: give zero or a forward thrust")
        self.rho_air = _number(rho_air, "air density", " kg/m^3", low=0.0, fix=" (1.225)")
        self.cl_max = (
            None
            if cl_max is None
            else _number(
                cl_max, "C_L,max", "", low=0.0, fix=" (the wing's largest lift coefficient)"
            )
        )

    def forces(self, theta: float, u: float, w: float, q: float) -> AeroForces:
        speed, gamma, alpha = path(u, w, theta)
        qs = 0.5 * self.rho_air * speed * speed * self.area
        cl = self.cl0 + self.cl_alpha * alpha
        if self.cl_max is not None:  # the stalled wing's coefficient stays
            cl = min(max(cl, -self.cl_max), self.cl_max)
        lift = qs * cl
        drag = qs * self.cd
        rate = q * self.chord / (2.0 * speed) if speed > 0 else 0.0
        moment = qs * self.chord * (self.cm0 + self.cm_alpha * alpha + self.cm_q * rate)
        fx, fz = _earth(lift, drag, gamma)
        fx += self.thrust * math.cos(theta)
        fz += self.thrust * math.sin(theta)
        return AeroForces(fx, fz, moment, lift, drag, alpha)

    def settings(self) -> dict[str, object]:
        keys = ("area", "chord", "cl0", "cl_alpha", "cd", "cm0", "cm_alpha", "cm_q", "thrust",
                "rho_air")  # fmt: skip
        out = {"aero": self.name, **{k: getattr(self, k) for k in keys}}
        if self.cl_max is not None:
            out["cl_max"] = self.cl_max
        return out


def aero_model(spec: Aerodynamics | str | None = None, **options) -> Aerodynamics:
    """An aerodynamic model: one given, or one by name of :data:`AERO_MODELS` with its
    options (``weight``: ``fraction``, ``stall_deg``; ``coefficients``: those of
    :class:`Coefficients`)."""
    if isinstance(spec, Aerodynamics):
        return spec
    name = "none" if spec is None else str(spec).strip().lower()
    if name == "none":
        if options:
            raise InputError(f"the aerodynamic model 'none' takes no options ({sorted(options)})")
        return NoAerodynamics()
    if name == "weight":
        if set(options) - {"fraction", "stall_deg"}:
            raise InputError(
                f"the aerodynamic model 'weight' takes only a fraction and a stall_deg ({options})"
            )
        return WeightLift(**options)
    if name == "coefficients":
        if "area" not in options or "chord" not in options:
            raise InputError(
                "the aerodynamic model 'coefficients' needs the reference area (m^2) and chord "
                "(m): --wing-area and --wing-chord"
            )
        unknown = sorted(set(options) - set(COEFFICIENTS.values()))
        if unknown:
            raise InputError(f"the aerodynamic model 'coefficients' has no option {unknown[0]!r}")
        return Coefficients(**options)
    raise InputError(f"unknown aerodynamic model {spec!r}: choose one of {', '.join(AERO_MODELS)}")


#: The fields of the coefficients (case keys and ``--`` options with ``-``) by keyword of
#: :class:`Coefficients`.
COEFFICIENTS = {
    "wing_area": "area", "wing_chord": "chord", "cl0": "cl0", "cl_alpha": "cl_alpha",
    "cl_max": "cl_max", "cd": "cd", "cm0": "cm0", "cm_alpha": "cm_alpha", "cm_q": "cm_q",
    "thrust": "thrust",
}  # fmt: skip


def model_of(
    lift: str | None,
    fraction: float | None,
    coefficients: dict[str, float | None],
    stall_deg: float | None = None,
) -> Aerodynamics:
    """The model of a case's or a command line's ``lift``, ``lift_fraction``,
    ``stall_deg`` and coefficients (by the keys of :data:`COEFFICIENTS`; None where not
    given).

    Raises
    ------
    InputError
        Coefficients without ``lift = coefficients``, a fraction or a stall angle without
        ``lift = weight``, or a value the model refuses.
    """
    name = (lift or "none").strip().lower()
    given = {k: v for k, v in coefficients.items() if v is not None}
    if given and name != "coefficients":
        keys = ", ".join("--" + k.replace("_", "-") for k in given)
        raise InputError(f"{keys}: coefficients of --lift coefficients; give that too")
    if fraction is not None and name != "weight":
        raise InputError(
            "--lift-fraction is the share of the weight of --lift weight; give that too"
        )
    if stall_deg is not None and name != "weight":
        raise InputError(
            "--stall-deg is the stall of --lift weight; give that too (with --lift "
            "coefficients, --cl-max)"
        )
    if name == "weight":
        options = {k: v for k, v in (("fraction", fraction), ("stall_deg", stall_deg))
                   if v is not None}  # fmt: skip
        return aero_model(name, **options)
    if name == "coefficients":
        return aero_model(name, **{COEFFICIENTS[k]: v for k, v in given.items()})
    return aero_model(name)
