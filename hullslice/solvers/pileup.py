"""Pile-up laws: how far the water rises along a wedge, ``c = gamma p / tan(beta)``.

``gamma(beta)`` multiplies the wetted half-width of a wedge of deadrise ``beta`` at keel
depth ``p``: 1 with no pile-up (von Karman), ``pi / 2`` by Wagner's small-deadrise theory,
``-0.0114 beta_deg + 1.5669`` by the paper's fit of Dobrovol'skaya's similarity solution.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from numbers import Real

import numpy as np

from ..errors import InputError

__all__ = [
    "PILE_UP_LAWS",
    "PileUp",
    "dobrovolskaya_pile_up",
    "pile_up_law",
    "von_karman_pile_up",
    "wagner_pile_up",
]

PileUp = Callable[[np.ndarray], np.ndarray]


def dobrovolskaya_pile_up(beta: np.ndarray) -> np.ndarray:
    """Pile-up coefficient ``gamma_D = -0.0114 beta_deg + 1.5669`` (paper, after Eq. 2).

    A linear fit of Dobrovol'skaya's similarity solution; ``beta`` in rad.
    """
    return -0.0114 * np.degrees(beta) + 1.5669


def von_karman_pile_up(deadrise: np.ndarray) -> np.ndarray:
    """Von Karman's pile-up coefficient: ``gamma = 1`` (no pile-up); ``deadrise`` in rad."""
    return np.ones_like(np.asarray(deadrise, dtype=np.float64))


def wagner_pile_up(deadrise: np.ndarray) -> np.ndarray:
    """Wagner's pile-up coefficient: ``gamma = pi / 2`` (small deadrise); ``deadrise`` in rad."""
    return np.full_like(np.asarray(deadrise, dtype=np.float64), np.pi / 2)


#: Pile-up laws by name: ``gamma(deadrise in rad)``.
PILE_UP_LAWS: Mapping[str, PileUp] = {
    "dobrovolskaya": dobrovolskaya_pile_up,
    "wagner": wagner_pile_up,
    "von-karman": von_karman_pile_up,
}


def pile_up_law(spec: str | float) -> PileUp:
    """A pile-up law from its name (a key of :data:`PILE_UP_LAWS`) or a constant ``gamma``.

    Parameters
    ----------
    spec : str or float
        ``"dobrovolskaya"`` (``-0.0114 beta_deg + 1.5669``), ``"wagner"`` (``pi / 2``),
        ``"von-karman"`` (1), or a positive number used for every deadrise.

    Returns
    -------
    callable
        ``gamma(deadrise)`` with ``deadrise`` in rad.

    Raises
    ------
    InputError
        An unknown name, or a number that is not positive and finite.
    """
    if isinstance(spec, str):
        law = PILE_UP_LAWS.get(spec.strip().lower())
        if law is None:
            raise InputError(
                f"pile-up law {spec!r} is unknown: give one of {', '.join(PILE_UP_LAWS)} or a "
                "positive number (the constant gamma)"
            )
        return law
    if isinstance(spec, bool) or not isinstance(spec, Real):
        raise InputError(
            f"pile-up {spec!r} is neither a law's name ({', '.join(PILE_UP_LAWS)}) nor a number"
        )
    gamma = float(spec)
    if not (math.isfinite(gamma) and gamma > 0.0):
        raise InputError(f"pile-up coefficient {spec!r} is not a positive number (e.g. 1.5708)")

    def constant(deadrise: np.ndarray) -> np.ndarray:
        return np.full_like(np.asarray(deadrise, dtype=np.float64), gamma)

    constant.__doc__ = f"Constant pile-up coefficient gamma = {gamma:g}."
    return constant
