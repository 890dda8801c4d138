"""Where the body is (:class:`Pose`), how it moves (:class:`Motion`) and the water (:class:`Fluid`).

Signs follow the earth frame: ``z`` up, calm water at ``z = 0``; a vertical velocity is
negative when the body moves down into the water; forces and accelerations are positive up.

Angles are in rad, and every angle field says so in its name: ``Pose.pitch_rad``,
``Motion.pitch_rate_rad_s``, ``Acceleration.pitch_rad_s2``. The former keywords ``pitch=``
and ``pitch_rate=`` are still taken for one release, with a :class:`DeprecationWarning`
(:func:`~hullslice.renamed.renamed_keywords`); the attributes ``pitch`` and ``pitch_rate``
read the same values in rad, ``pitch_deg`` and ``pitch_rate_deg_s`` in degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .constants import NU_SEA, NU_WATER, P_ATM, P_VAPOUR, RHO_SEA, RHO_WATER, SOUND_WATER, G
from .errors import InputError
from .limits import check_pitch
from .renamed import renamed_keywords

__all__ = ["Acceleration", "Fluid", "Motion", "Pose"]


def _finite(value, what: str, unit: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what} {value!r} is not a number (in {unit})") from None
    if not math.isfinite(v):
        raise InputError(f"{what} {value!r} is not a finite number: give one in {unit}")
    return v


@renamed_keywords(pitch="pitch_rad")
@dataclass(frozen=True)
class Pose:
    """The position of the body relative to the calm water.

    Parameters
    ----------
    draft : float
        Depth of the body's lowest point below the calm water, in m (``>= 0``; ``0`` is
        first contact).
    pitch_rad : float
        Pitch angle in rad, positive nose up (the body's forward ``x`` axis raised above
        the horizontal); the body turns about its centre of gravity. Default 0 (level).
        Formerly ``pitch=`` (deprecated).
    """

    draft: float
    pitch_rad: float = 0.0

    @property
    def pitch(self) -> float:
        """The pitch angle in rad (:attr:`pitch_rad`)."""
        return self.pitch_rad

    @property
    def pitch_deg(self) -> float:
        """The pitch angle in degrees."""
        return math.degrees(self.pitch_rad)

    def __post_init__(self) -> None:
        d = _finite(self.draft, "draft", "m")
        if d < 0.0:
            raise InputError(
                f"draft {self.draft!r} m is negative: the draft is the depth of the body's "
                "lowest point below the water, 0 at first contact"
            )
        pitch = check_pitch(_finite(self.pitch_rad, "pitch", "rad"))
        object.__setattr__(self, "draft", d)
        object.__setattr__(self, "pitch_rad", pitch)


@renamed_keywords(pitch_rate="pitch_rate_rad_s")
@dataclass(frozen=True)
class Motion:
    """The velocity of the body (of its centre of gravity, and its pitch rate).

    Parameters
    ----------
    velocity : float
        Vertical velocity in m/s, negative downward (into the water).
    forward_speed : float
        Horizontal velocity along the body's forward direction in m/s (default 0).
    pitch_rate_rad_s : float
        Rate of change of the pitch in rad/s, positive nose up (default 0). Formerly
        ``pitch_rate=`` (deprecated).
    """

    velocity: float
    forward_speed: float = 0.0
    pitch_rate_rad_s: float = 0.0

    @property
    def pitch_rate(self) -> float:
        """The pitch rate in rad/s (:attr:`pitch_rate_rad_s`)."""
        return self.pitch_rate_rad_s

    @property
    def pitch_rate_deg_s(self) -> float:
        """The pitch rate in degrees per second."""
        return math.degrees(self.pitch_rate_rad_s)

    def __post_init__(self) -> None:
        for name, what in (("velocity", "velocity"), ("forward_speed", "forward speed")):
            v = _finite(getattr(self, name), what, "m/s")
            if abs(v) >= SOUND_WATER:
                raise InputError(
                    f"{what} {v:g} m/s is past the speed of sound in water "
                    f"({SOUND_WATER:g} m/s), where water is not the incompressible fluid "
                    "of the method: give a speed in m/s (a ditching touches down at 50 to "
                    "80 m/s forward, a drop test enters at a few m/s)"
                )
            object.__setattr__(self, name, v)
        object.__setattr__(
            self, "pitch_rate_rad_s", _finite(self.pitch_rate_rad_s, "pitch rate", "rad/s")
        )


@renamed_keywords(pitch="pitch_rad_s2")
@dataclass(frozen=True)
class Acceleration:
    """The acceleration of the body (of its centre of gravity, and its pitch).

    Only momentum-form solvers use it: their force has an added-inertia part ``- m_a a``.

    Parameters
    ----------
    vertical : float
        Vertical acceleration ``dw/dt`` in m/s^2, positive upward (default 0).
    pitch_rad_s2 : float
        Pitch acceleration ``dq/dt`` in rad/s^2, positive nose up (default 0). Formerly
        ``pitch=`` (deprecated).
    forward : float
        Forward acceleration ``du/dt`` in m/s^2 (default 0).
    """

    vertical: float = 0.0
    pitch_rad_s2: float = 0.0
    forward: float = 0.0

    @property
    def pitch(self) -> float:
        """The pitch acceleration in rad/s^2 (:attr:`pitch_rad_s2`)."""
        return self.pitch_rad_s2

    def __post_init__(self) -> None:
        for name, what, unit in (
            ("vertical", "vertical", "m/s^2"),
            ("pitch_rad_s2", "pitch", "rad/s^2"),
            ("forward", "forward", "m/s^2"),
        ):
            object.__setattr__(
                self, name, _finite(getattr(self, name), f"{what} acceleration", unit)
            )

    def as_array(self) -> tuple[float, float, float]:
        """``(dw/dt, dq/dt, du/dt)``: the order of the equations of motion."""
        return (self.vertical, self.pitch_rad_s2, self.forward)


@dataclass(frozen=True)
class Fluid:
    """The water and gravity.

    Parameters
    ----------
    rho : float
        Water density in kg/m^3 (default 1000.0, fresh water as in the paper).
    g : float
        Gravitational acceleration in m/s^2 (default 9.81, the paper's value).
    p_atm : float
        Atmospheric pressure on the free surface in Pa (default 101325, sea level).
    p_vapour : float
        The water's vapour pressure in Pa (default 2339, at 20 deg C). No gauge pressure
        on the body falls below ``p_vapour - p_atm`` (:attr:`suction_limit`): the water
        cavitates first.
    nu : float
        The water's kinematic viscosity in m^2/s, for the friction drag (default 1.0e-6,
        fresh water at 20 deg C; :meth:`sea` gives 1.19e-6, sea water at 15 deg C).
    """

    rho: float = RHO_WATER
    g: float = G
    p_atm: float = P_ATM
    p_vapour: float = P_VAPOUR
    nu: float = NU_WATER

    @classmethod
    def sea(cls, **kw) -> Fluid:
        """Sea water: 1025 kg/m^3 and 1.19e-6 m^2/s (ITTC, 15 deg C), the other fields as
        given."""
        return cls(**{"rho": RHO_SEA, "nu": NU_SEA, **kw})

    @property
    def suction_limit(self) -> float:
        """The largest suction (gauge pressure below zero) the water sustains, Pa:
        ``p_atm - p_vapour``."""
        return self.p_atm - self.p_vapour

    def __post_init__(self) -> None:
        rho = _finite(self.rho, "water density", "kg/m^3")
        g = _finite(self.g, "gravity", "m/s^2")
        if rho <= 0.0:
            raise InputError(f"water density {self.rho!r} kg/m^3 is not positive (try 1000)")
        if g < 0.0:
            raise InputError(f"gravity {self.g!r} m/s^2 is negative (try 9.81)")
        p_atm = _finite(self.p_atm, "atmospheric pressure", "Pa")
        p_vap = _finite(self.p_vapour, "vapour pressure", "Pa")
        if p_atm <= 0.0:
            raise InputError(f"atmospheric pressure {self.p_atm!r} Pa is not positive (try 101325)")
        if not 0.0 <= p_vap < p_atm:
            raise InputError(
                f"vapour pressure {self.p_vapour!r} Pa is not in [0, the atmospheric pressure "
                f"{p_atm:g} Pa) (try 2339, water at 20 deg C)"
            )
        object.__setattr__(self, "rho", rho)
        object.__setattr__(self, "g", g)
        object.__setattr__(self, "p_atm", p_atm)
        object.__setattr__(self, "p_vapour", p_vap)
        nu = _finite(self.nu, "kinematic viscosity", "m^2/s")
        if nu <= 0.0:
            raise InputError(f"kinematic viscosity {self.nu!r} m^2/s is not positive (try 1e-6)")
        object.__setattr__(self, "nu", nu)
