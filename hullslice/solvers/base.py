"""The interfaces of the 2D solvers, and what they return.

There are two kinds of solver (:data:`SOLVER_KINDS`):

``free-fall`` (:class:`Solver`)
    The paper's form. Each slice is a 2D section of its own mass per metre in a free fall
    of its own, and the solver returns the force per metre inferred from that fall,
    ``f = M (a + g)`` (paper, Eq. 12). It needs the mass per metre of every section.
``momentum`` (:class:`MomentumFormSolver`)
    The fluid's momentum (see :mod:`hullslice.forces`). The
    solver returns, per section and from the sections alone (no body mass), the added mass
    per metre ``m_a`` (kg/m), its rate ``dm_a/dp`` (kg/m^2) and any force per metre that
    does not depend on an acceleration (N/m: drag, buoyancy). hullslice forms the force

        f = m_a' v^2 - m_a a + extra          (N/m, positive up)

    with each section's own penetration velocity ``v`` (m/s, negative down) and
    acceleration ``a`` (m/s^2, positive up), drops the flux term ``m_a' v^2`` on sections
    leaving the water (``v >= 0``), and puts ``m_a`` on the left of the body's equations
    of motion.
"""

from __future__ import annotations

import abc
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..errors import InputError
from ..safety import check_options
from ..sections import Sections
from ..state import Fluid

__all__ = [
    "FREE_FALL",
    "MOMENTUM",
    "SOLVER_KINDS",
    "AddedMass",
    "MomentumFormSolver",
    "SectionLoads",
    "SectionPressures",
    "Solver",
    "SolverBase",
    "join_reasons",
]

#: The paper's form: a force per metre inferred from each slice's own free fall.
FREE_FALL = "free-fall"
#: The momentum form: added mass per metre and its rate, forces formed by hullslice.
MOMENTUM = "momentum"
#: Solver kinds by name, with a one-line description.
SOLVER_KINDS: dict[str, str] = {
    FREE_FALL: "force per metre from each slice's own free fall, M (a + g) (the paper's form)",
    MOMENTUM: "added mass per metre and its rate; f = m_a' v^2 - m_a a + extra (a rigid body)",
}


def _freeze(fields: dict, arrays: Sequence[tuple[str, Any]]) -> None:
    """Make a frozen record's fields read-only arrays of their dtypes (no copy when they are
    already), and its ``diagnostics`` a dict of read-only float arrays."""
    for name, dtype in arrays:
        a = np.asarray(fields[name], dtype=dtype)
        a.setflags(write=False)
        fields[name] = a
    diags = {}
    for k, a in dict(fields["diagnostics"]).items():
        arr = np.asarray(a, dtype=np.float64)  # no copy: the solver's own arrays
        arr.setflags(write=False)
        diags[str(k)] = arr
    fields["diagnostics"] = diags


@dataclass(frozen=True, eq=False)
class SectionLoads:
    """What a 2D solver returns for a set of sections.

    Attributes
    ----------
    force_per_metre : (n,) float
        Vertical hydrodynamic force per metre of body length on each section, in N/m,
        positive upward.
    valid : (n,) bool
        True where the section is inside the solver's range of validity.
    reason : (n,) str
        Why a section is not valid (``""`` where it is).
    diagnostics : mapping of str to (n,) float
        Named intermediate arrays, for reports and checks.
    """

    force_per_metre: np.ndarray
    valid: np.ndarray
    reason: np.ndarray
    diagnostics: Mapping[str, np.ndarray] = field(default_factory=dict)

    def __post_init__(self) -> None:
        fields = self.__dict__  # frozen: set once here, read-only arrays
        valid = np.asarray(fields["valid"])
        if valid.dtype != bool:  # NaN or "no" cast to bool is True: a check switched off
            raise TypeError(
                f"SectionLoads.valid must be a boolean array (True inside the solver's range), "
                f"not {valid.dtype} values such as {valid.ravel()[:1].tolist()}"
            )
        _freeze(fields, (("force_per_metre", np.float64), ("valid", bool), ("reason", object)))

    def __len__(self) -> int:
        return len(self.force_per_metre)


class SolverBase(abc.ABC):  # noqa: B024 (its two subclasses each add the abstract method)
    """What every 2D solver has: a name, a description, options and a kind.

    Subclass :class:`Solver` (the free-fall form) or :class:`MomentumFormSolver` (the
    momentum form), not this class. Subclasses set the class variables :attr:`name` (the
    registry key, as in the entry point) and :attr:`description` (one line for
    ``hullslice solvers``). Options are keyword arguments of the constructor; the base
    constructor refuses any it does not know (list them in :attr:`options`).

    A solver is registered in the entry-point group ``hullslice.solvers`` of its
    distribution::

        [project.entry-points."hullslice.solvers"]
        my-solver = "my_package.module:MySolver"
    """

    #: Registry name, e.g. ``"extended-von-karman"``.
    name: ClassVar[str] = ""
    #: One-line description for listings.
    description: ClassVar[str] = ""
    #: Accepted options with their defaults (keyword arguments of the constructor).
    options: ClassVar[Mapping[str, Any]] = {}
    #: The solver's kind, a key of :data:`SOLVER_KINDS` (set by the two base classes).
    kind: ClassVar[str] = ""
    #: True when the solver returns the pressure along each section's wetted contour
    #: (:class:`SectionPressures`, in :class:`AddedMass`).
    gives_pressures: ClassVar[bool] = False
    #: Options whose range the solver checks itself in ``__init__`` (hullslice then refuses
    #: only NaN and infinities in them; otherwise an option with a positive default must be
    #: a positive number).
    own_checks: ClassVar[tuple[str, ...]] = ()

    def __init__(self, **options: Any) -> None:
        unknown = sorted(set(options) - set(self.options))
        if unknown:
            known = ", ".join(self.options) or "none"
            close = did_you_mean(unknown[0], self.options)
            raise InputError(
                f"solver {self.name!r} has no option {', '.join(map(repr, unknown))}; "
                f"{close}its options: {known}"
            )
        check_options(  # no NaN, no threshold switched off
            self.name or type(self).__name__, self.options, options, frozenset(self.own_checks)
        )
        self.settings = {**self.options, **options}

    def __repr__(self) -> str:
        opts = ", ".join(f"{k}={v!r}" for k, v in self.settings.items())
        return f"{type(self).__name__}({opts})"


class Solver(SolverBase):
    """A free-fall-form 2D solver (the paper's): sections and velocities in, force out.

    Implement :meth:`section_loads`. Each slice is taken as a 2D section of its own mass
    per metre in a free fall of its own; the force per metre is inferred from that fall.
    See :class:`SolverBase` for the name, description and options.
    """

    kind: ClassVar[str] = FREE_FALL

    @abc.abstractmethod
    def section_loads(self, sections: Sections, velocity: np.ndarray, fluid: Fluid) -> SectionLoads:
        """Loads on wetted sections.

        Parameters
        ----------
        sections : Sections
            The wetted sections (every penetration is positive).
        velocity : (n,) float
            Penetration velocity of each section in m/s, negative downward.
        fluid : Fluid
            Water density (kg/m^3) and gravity (m/s^2).

        Returns
        -------
        SectionLoads
            Arrays of the same length as ``sections``.
        """


@dataclass(frozen=True, eq=False)
class SectionPressures:
    """The pressure along each section's wetted contour, as a momentum-form solver gives it
    before the body's accelerations are known.

    Every array is (n, 2, k): per section, per side (0: port, ``+y`` from the keel; 1:
    starboard) and per point. The pressure at a point is

        p = velocity_coefficient v^2 [v < 0] - acceleration_coefficient a      (Pa, gauge)

    with the section's penetration velocity ``v`` (m/s, negative down) and acceleration
    ``a`` (m/s^2, positive up), and ``sum(weight * p)`` over both sides is the force per
    metre that the two coefficients give (``rate v^2 - m_a a``).

    Attributes
    ----------
    y : distance of the point from the keel, m (outwards on its side).
    z : height of the point above the keel, m.
    weight : the point's share of the width ``dy``, m (quadrature weights).
    velocity_coefficient : Pa per (m/s)^2.
    acceleration_coefficient : Pa per m/s^2.
    """

    y: np.ndarray
    z: np.ndarray
    weight: np.ndarray
    velocity_coefficient: np.ndarray
    acceleration_coefficient: np.ndarray

    FIELDS: ClassVar[tuple[str, ...]] = (
        "y", "z", "weight", "velocity_coefficient", "acceleration_coefficient",
    )  # fmt: skip

    def __post_init__(self) -> None:
        shape = np.shape(self.y)
        for name in self.FIELDS:
            a = np.asarray(getattr(self, name), dtype=np.float64)
            if a.shape != shape or a.ndim != 3 or shape[1:2] != (2,):
                raise TypeError(
                    f"SectionPressures.{name} has shape {a.shape}; every field must be "
                    f"(n, 2, k) like y's {shape}"
                )
            a.flags.writeable = False
            object.__setattr__(self, name, a)

    def __len__(self) -> int:
        return int(np.shape(self.y)[0])

    def spread(self, wet: np.ndarray) -> SectionPressures:
        """The same over every section, zero on those not in ``wet`` ((N,) bool)."""
        n = len(wet)
        k = np.shape(self.y)[2]
        out = {}
        for name in self.FIELDS:
            full = np.zeros((n, 2, k))
            full[wet] = getattr(self, name)
            out[name] = full
        return SectionPressures(**out)

    def pressure(self, velocity: np.ndarray, acceleration: np.ndarray) -> np.ndarray:
        """(n, 2, k) pressures in Pa at the sections' penetration velocities (m/s) and
        accelerations (m/s^2, up)."""
        v = np.asarray(velocity, dtype=np.float64)[:, None, None]
        a = np.asarray(acceleration, dtype=np.float64)[:, None, None]
        vv = np.where(v < 0.0, v * v, 0.0)
        return self.velocity_coefficient * vv - self.acceleration_coefficient * a


@dataclass(frozen=True, eq=False)
class AddedMass:
    """What a momentum-form solver returns for a set of sections.

    Attributes
    ----------
    added_mass : (n,) float
        Added mass per metre of each section, kg/m (``>= 0``).
    rate : (n,) float
        Its rate with the penetration, ``dm_a/dp``, kg/m^2. Zero once the flow has
        separated (the spray root past the chine). In general the coefficient of ``v^2``
        in the force per metre: a solver whose force is not the flux of its added mass
        (the MLM, whose ``v^2`` term is its pressure's integral) gives that here.
    extra : (n,) float
        Force per metre normal to the keel line that does not depend on an acceleration
        (a cross-flow drag), N/m, positive up. Zeros by default.
    valid : (n,) bool
        True where the section is inside the solver's range of validity.
    reason : (n,) str
        Why a section is not valid (``""`` where it is).
    diagnostics : mapping of str to (n,) float
        Named intermediate arrays, for reports and checks.
    vertical : (n,) float
        Vertical force per metre that does not depend on an acceleration (a hydrostatic
        force: buoyancy), N/m, positive up; unlike ``extra`` it has no horizontal part
        along a sloping keel. Zeros by default.
    girth : (n,) float or None
        The horizontal breadth of each section's wetted bottom that carries the pressure,
        m (both sides), for the bound on suction (a pressure no lower than ``-p_lim``
        pulls the section down by at most ``p_lim`` times it); None: hullslice takes the
        breadth of the section's bottom under the calm water
        (:func:`hullslice.solvers.section_parts.submerged_widths`).
    pressure : SectionPressures or None
        The pressure along each section's wetted contour, where the solver models it.
    """

    added_mass: np.ndarray
    rate: np.ndarray
    valid: np.ndarray
    reason: np.ndarray
    extra: np.ndarray | None = None
    diagnostics: Mapping[str, np.ndarray] = field(default_factory=dict)
    vertical: np.ndarray | None = None
    girth: np.ndarray | None = None
    pressure: SectionPressures | None = None

    def __post_init__(self) -> None:
        fields = self.__dict__  # frozen: set once here, read-only arrays
        for name in ("extra", "vertical"):
            if fields[name] is None:
                fields[name] = np.zeros(np.shape(fields["added_mass"]))
        if fields["girth"] is not None:
            g = np.asarray(fields["girth"], dtype=np.float64)
            g.flags.writeable = False
            fields["girth"] = g
        fields["valid"] = np.asarray(fields["valid"])  # kept as given: checked by hullslice
        _freeze(
            fields,
            (("added_mass", np.float64), ("rate", np.float64), ("extra", np.float64),
             ("vertical", np.float64), ("valid", None), ("reason", object)),
        )  # fmt: skip

    def __len__(self) -> int:
        return len(self.added_mass)


class MomentumFormSolver(SolverBase):
    """A momentum-form 2D solver: the added mass of each section, from its shape alone.

    Implement :meth:`added_mass`. hullslice forms the force per metre of each section,

        f = m_a' v^2 - m_a a + extra          (N/m, positive up)

    with the section's penetration velocity ``v`` (m/s, negative down) and acceleration
    ``a`` (m/s^2, positive up), dropping ``m_a' v^2`` where ``v >= 0`` (a section leaving
    the water: the flow separates, no suction). The inertia term ``- m_a a`` moves to the
    left of the body's equations of motion, so the force does not depend on the body's
    mass or its distribution, and gravity acts on the body, never in ``extra`` unless the
    solver models a hydrostatic force (buoyancy). See :class:`SolverBase` for the name,
    description and options.
    """

    kind: ClassVar[str] = MOMENTUM
    #: True when the solver models the flow's separation at the chine (a cross-flow drag
    #: after it): hullslice then does not flag sections whose water reaches their chine,
    #: and the ``chine`` stop rule does not apply.
    models_separation: ClassVar[bool] = False
    #: True when only the part of each section's wetted contour where the pressure is
    #: positive carries load (the MLM's rule: water does not pull, it ventilates): with
    #: the solver's :class:`SectionPressures`, hullslice then keeps the points whose
    #: pressure at the body's rest in acceleration (the section's own motion: its velocity
    #: and the acceleration of a curved keel line passing by) is positive, and forms the
    #: force and the added mass from those points alone.
    positive_pressure: ClassVar[bool] = False

    @abc.abstractmethod
    def added_mass(self, sections: Sections, velocity: np.ndarray, fluid: Fluid) -> AddedMass:
        """Added mass per metre and its rate on wetted sections.

        Parameters
        ----------
        sections : Sections
            The wetted sections (every penetration is positive). ``mass_per_metre`` may be
            NaN (a body without mass under a prescribed motion): do not use it.
        velocity : (n,) float
            Penetration velocity of each section in m/s, negative downward (for velocity-
            dependent terms such as drag, and for validity checks).
        fluid : Fluid
            Water density (kg/m^3) and gravity (m/s^2).

        Returns
        -------
        AddedMass
            Arrays of the same length as ``sections``.
        """


def did_you_mean(name: str, choices: Sequence[str] | Mapping[str, Any]) -> str:
    """``"did you mean 'x'? "`` for the choice closest to ``name`` (case, ``-`` and ``_``
    ignored), or ``""`` when none is close."""
    import difflib

    def norm(s: str) -> str:
        return str(s).strip().lower().replace("-", "_")

    by_norm = {norm(c): c for c in choices}
    found = by_norm.get(norm(name))
    if found is None:
        close = difflib.get_close_matches(norm(name), list(by_norm), n=1, cutoff=0.7)
        found = by_norm[close[0]] if close else None
    return f"did you mean {found!r}? " if found is not None and found != name else ""


def join_reasons(n: int, checks: Sequence[tuple[np.ndarray, str]]) -> np.ndarray:
    """The ``reason`` array of :class:`SectionLoads` from a list of validity checks.

    Parameters
    ----------
    n : int
        Number of sections.
    checks : sequence of ((n,) bool, str)
        For each check, the sections that fail it and the message that says why.

    Returns
    -------
    (n,) object array of str
        Per section, the messages of the checks it fails joined by ``"; "``; ``""`` where
        it passes them all (so ``reason == ""`` is the ``valid`` array).
    """
    reason = np.full(n, "", dtype=object)
    for mask, msg in checks:
        mask = np.asarray(mask, dtype=bool)
        if mask.shape != (n,):
            mask = np.broadcast_to(mask, (n,))
        if mask.any():
            reason[mask] = [f"{r}; {msg}" if r else msg for r in reason[mask]]
    return reason
