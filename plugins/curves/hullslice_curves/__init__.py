"""Characteristic curves supplied by the user, for hullslice.

The paper's method in its general form: a free-falling wedge described by its scaled
velocity ``v~(z~)`` and acceleration ``a~(z~)`` (paper, Eq. 3), used in inverse form for
every slice (the free fall the slice is in, ``F = M (a + g) d``) by
:class:`hullslice.CurveSolver`. This plugin takes the curves from its options instead of
the paper's Eqs. 5-6: polynomials fitted to one's own CFD or drop tests, a table, or
curves made for another water density (seawater).

Options (keyword arguments, or ``--solver-option KEY=VALUE`` on the command line):

``a_coeffs``, ``v_coeffs``
    Polynomial coefficients of ``a~(z~)`` and ``v~(z~)``, constant term first.
``table``
    Instead of polynomials: a CSV file with the columns ``z_tilde, a_tilde, v_tilde``
    (header line; ``#`` comments), or a ``(k, 3)`` array of such rows; linear
    interpolation between rows.
``rho``
    Water density the curves were made for, kg/m^3 (default 1000). For water of another
    density the curves are used with the equivalent mass ``M rho_curves / rho``.
``z_range``
    ``(low, high)``: the range of ``z~`` where the curves are valid (default: a table's
    first and last ``z~``; for polynomials, from the first minimum of ``a~`` below its peak
    to 0).
``pile_up``
    The pile-up law the curves were scaled with: ``"dobrovolskaya"`` (default, as in the
    paper), ``"wagner"``, ``"von-karman"``, or a number (a constant ``gamma``).
``froude_min``
    Smallest peak Froude number ``Fr*`` inside the range (default 6.5).
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any, ClassVar

import numpy as np

from hullslice import CharacteristicCurves, CurveSolver, InputError
from hullslice.solvers import pile_up_law

__all__ = ["UserCurves"]
__version__ = "0.1.0"

#: How far v~ may be from 1 at z~ = 0 (by definition v~ = v / v_z0 = 1 at first contact);
#: the paper's fit has 1.00131.
V_TILDE_AT_CONTACT_TOL = 0.05


class UserCurves(CurveSolver):
    """Characteristic curves supplied by the user, in the paper's inverse form.

    Parameters
    ----------
    a_coeffs, v_coeffs : sequence of float, optional
        Polynomial coefficients of ``a~`` and ``v~`` in ascending powers of ``z~``.
    table : str, path or (k, 3) float, optional
        A CSV file of ``z_tilde, a_tilde, v_tilde``, or an array of such rows.
    rho : float, optional
        Water density the curves were made for, kg/m^3 (default 1000).
    z_range : (float, float), optional
        Range of ``z~`` where the curves are valid.
    pile_up : str or float, optional
        Pile-up law: ``"dobrovolskaya"`` (default), ``"wagner"``, ``"von-karman"`` or a
        constant ``gamma``.
    froude_min : float, optional
        Smallest peak Froude number ``Fr*`` inside the range (default 6.5).

    Raises
    ------
    InputError
        No curves, both a table and coefficients, a missing or malformed table, an unknown
        pile-up law, or curves whose ``v~`` at ``z~ = 0`` is not 1.
    """

    name = "curves"
    description = (
        "Characteristic curves supplied by the user (polynomials or a z~, a~, v~ table), "
        "e.g. fitted to CFD or made for seawater"
    )
    options: ClassVar[Mapping[str, Any]] = {
        "a_coeffs": None,
        "v_coeffs": None,
        "table": None,
        "rho": 1000.0,
        "z_range": None,
        "pile_up": "dobrovolskaya",
        "froude_min": 6.5,
    }

    def __init__(self, **options: Any) -> None:
        super().__init__(**options)
        s = self.settings
        self._pile_up = pile_up_law(s["pile_up"])
        self.curves = _curves(s["a_coeffs"], s["v_coeffs"], s["table"], s["rho"], s["z_range"])
        if self.curves.z_range[1] == 0.0:
            v0 = float(self.curves.v(0.0))
            if not abs(v0 - 1.0) <= V_TILDE_AT_CONTACT_TOL:
                raise InputError(
                    f"the curves give v~ = {v0:g} at z~ = 0, where v~ = v / v_z0 is 1 by "
                    "definition: check the curves (a table's columns are z_tilde, a_tilde, "
                    "v_tilde)"
                )

    def pile_up(self, deadrise: np.ndarray) -> np.ndarray:
        """Pile-up coefficient of the chosen law, for deadrise angles in rad."""
        return self._pile_up(deadrise)


def _curves(a_coeffs, v_coeffs, table, rho, z_range) -> CharacteristicCurves:
    has_poly = a_coeffs is not None or v_coeffs is not None
    if table is None and not has_poly:
        raise InputError(
            "solver 'curves' needs characteristic curves: give the options a_coeffs and "
            "v_coeffs (ascending powers of z~) or table (a CSV of z_tilde,a_tilde,v_tilde), "
            "e.g. --solver-option table=curves.csv"
        )
    if table is not None and has_poly:
        raise InputError(
            "solver 'curves' takes either table or a_coeffs and v_coeffs, not both: leave one out"
        )
    if table is None and (a_coeffs is None or v_coeffs is None):
        missing = "a_coeffs" if a_coeffs is None else "v_coeffs"
        raise InputError(f"solver 'curves' needs {missing} too: give a~ and v~ polynomials")
    if isinstance(table, str | os.PathLike):
        return CharacteristicCurves.from_csv(table, rho=rho, z_range=z_range)
    if table is not None:
        return CharacteristicCurves(table=table, rho=rho, z_range=z_range, source="table")
    return CharacteristicCurves(
        a_coeffs=a_coeffs, v_coeffs=v_coeffs, rho=rho, z_range=z_range, source="polynomials"
    )
