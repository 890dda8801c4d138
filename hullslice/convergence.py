"""Richardson extrapolation and the grid convergence index (GCI) over slice counts.

The procedure of Roache (1998) as written out by Celik et al., "Procedure for estimation and
reporting of uncertainty due to discretization in CFD applications", J. Fluids Eng. 130
(2008) 078001: three solutions ``f1, f2, f3`` on fine, medium and coarse discretisations with
refinement ratios ``r21 = n1 / n2`` and ``r32 = n2 / n3`` (``n`` slices, so the slice
thickness ``h`` is proportional to ``1 / n``). The observed order ``p`` solves

    p = | ln|e32 / e21| + q(p) | / ln r21,    q(p) = ln((r21^p - s) / (r32^p - s)),

with ``e32 = f3 - f2``, ``e21 = f2 - f1`` and ``s = sign(e32 / e21)``; then

    f_ext = (r21^p f1 - f2) / (r21^p - 1),    GCI_fine = 1.25 |(f1 - f2) / f1| / (r21^p - 1).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from .errors import InputError

__all__ = ["Richardson", "richardson"]

#: Safety factor of the GCI for three or more solutions (Roache).
SAFETY_FACTOR = 1.25
#: An observed order below this is no convergence: the extrapolated limit would lie
#: ``1 / (r^p - 1)`` times the last difference beyond the finest solution, 2.4 times at
#: p = 0.5 and r = 2, 48 times at p = 0.03.
MIN_ORDER = 0.5
#: Differences between solutions up to this fraction of their size are rounding: a body
#: the method computes exactly at any slice count (a prism of constant section) converged.
ROUNDING = 1e-10


@dataclass(frozen=True)
class Richardson:
    """A Richardson extrapolation over three discretisations.

    Attributes
    ----------
    extrapolated : float
        The extrapolated value (``n`` to infinity).
    order : float
        Observed order of convergence ``p``.
    gci : float
        Grid convergence index of the finest solution, as a fraction (0.001 = 0.1 %).
    counts : (int, int, int)
        Slice counts used, fine to coarse.
    values : (float, float, float)
        Solutions used, fine to coarse.
    behaviour : str
        ``"monotonic"``, ``"oscillatory"`` (the differences change sign), ``"converged"``
        (the two finest solutions are equal to rounding, :data:`ROUNDING`) or
        ``"divergent"`` (the differences do not shrink, or so slowly that the observed order
        is below :data:`MIN_ORDER`; ``extrapolated`` is NaN, ``order`` NaN or the observed
        one, and ``gci`` is infinite).
    """

    extrapolated: float
    order: float
    gci: float
    counts: tuple[int, int, int]
    values: tuple[float, float, float]
    behaviour: str

    @property
    def band(self) -> tuple[float, float]:
        """The error band of the finest solution: ``f1 (1 -+ GCI)``."""
        f1 = self.values[0]
        return (f1 - abs(f1) * self.gci, f1 + abs(f1) * self.gci)


def richardson(counts: Sequence[int], values: Sequence[float]) -> Richardson:
    """Richardson extrapolation over the three finest of several slice counts.

    Parameters
    ----------
    counts : sequence of int
        Slice counts (at least three, all different).
    values : sequence of float
        The solution for each count.

    Returns
    -------
    Richardson
    """
    if len(counts) != len(values):
        raise InputError("counts and values differ in length")
    pairs = sorted(zip(counts, values, strict=True), key=lambda cv: -cv[0])
    if len({c for c, _ in pairs}) != len(pairs):
        raise InputError(f"slice counts {list(counts)} repeat a value: give distinct counts")
    if len(pairs) < 3:
        raise InputError(
            f"Richardson extrapolation needs three slice counts, got {len(pairs)}: "
            "give for instance 16, 32, 64"
        )
    (n1, f1), (n2, f2), (n3, f3) = pairs[:3]
    r21, r32 = n1 / n2, n2 / n3
    e21, e32 = f2 - f1, f3 - f2
    noise = ROUNDING * max(abs(f1), abs(f2), abs(f3))
    if abs(e21) <= noise:
        return Richardson(f1, math.inf, 0.0, (n1, n2, n3), (f1, f2, f3), "converged")
    if abs(e32) <= noise:
        raise InputError(
            f"the solutions for {n2} and {n3} slices are equal but the one for {n1} differs: "
            "no convergence order can be observed; use finer slice counts"
        )
    ratio = e32 / e21
    if abs(ratio) <= 1.0:
        # the differences do not shrink under refinement: nothing to extrapolate
        return Richardson(math.nan, math.nan, math.inf, (n1, n2, n3), (f1, f2, f3), "divergent")
    s = 1.0 if ratio > 0 else -1.0
    p = abs(math.log(abs(ratio))) / math.log(r21)
    settled = r21 == r32  # q = 0: no iteration needed
    for _ in range(200):
        q = math.log((r21**p - s) / (r32**p - s)) if p > 0 else 0.0
        p_new = abs(math.log(abs(ratio)) + q) / math.log(r21)
        if abs(p_new - p) < 1e-12 * max(1.0, p):
            p, settled = p_new, True
            break
        p = p_new
    if not settled:
        raise InputError(
            f"the observed order of convergence over {n1}, {n2}, {n3} slices does not settle "
            "(uneven refinement ratios): give slice counts in a constant ratio, e.g. 16, 32, 64"
        )
    if p < MIN_ORDER:  # the differences barely shrink: no limit to extrapolate to
        return Richardson(math.nan, p, math.inf, (n1, n2, n3), (f1, f2, f3), "divergent")
    rp = r21**p
    ext = (rp * f1 - f2) / (rp - 1.0)
    gci = SAFETY_FACTOR * abs((f1 - f2) / f1) / (rp - 1.0) if f1 != 0 else math.inf
    kind = "monotonic" if s > 0 else "oscillatory"
    return Richardson(ext, p, gci, (n1, n2, n3), (f1, f2, f3), kind)
