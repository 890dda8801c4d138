"""The interface every 2D solver implements, and the loads it returns."""

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

__all__ = ["SectionLoads", "Solver", "join_reasons"]


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
        for name, dtype in (("force_per_metre", np.float64), ("valid", bool), ("reason", object)):
            a = np.asarray(fields[name], dtype=dtype)  # no copy when it is one already
            a.flags.writeable = False
            fields[name] = a
        diags = {}
        for k, a in dict(self.diagnostics).items():
            arr = np.asarray(a, dtype=np.float64)  # no copy: the solver's own arrays
            arr.flags.writeable = False
            diags[str(k)] = arr
        fields["diagnostics"] = diags

    def __len__(self) -> int:
        return len(self.force_per_metre)


class Solver(abc.ABC):
    """A 2D water-entry solver: sections and their velocities in, force per metre out.

    Subclasses set the class variables :attr:`name` (the registry key, as in the entry
    point) and :attr:`description` (one line for ``hullslice solvers``), and implement
    :meth:`section_loads`. Options are keyword arguments of the constructor; the base
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

    def __init__(self, **options: Any) -> None:
        unknown = sorted(set(options) - set(self.options))
        if unknown:
            known = ", ".join(self.options) or "none"
            raise InputError(
                f"solver {self.name!r} has no option {', '.join(map(repr, unknown))}; "
                f"its options: {known}"
            )
        check_options(self.name or type(self).__name__, self.options, options)  # no NaN, ...
        self.settings = {**self.options, **options}

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

    def __repr__(self) -> str:
        opts = ", ".join(f"{k}={v!r}" for k, v in self.settings.items())
        return f"{type(self).__name__}({opts})"


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
