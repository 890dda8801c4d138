"""The unit and axes a mesh is read in: the file's own declared convention, unless an option
says otherwise.

One rule for every format: ``units``, ``forward`` and ``up`` given (``--units``,
``--forward``, ``--up``) win; left out (None), the file's declaration is taken where its
format makes one (:class:`~hullslice.readers.base.Conventions`: a 3MF's ``unit``, glTF's
+Y up), else metres, ``+x`` forward and ``+z`` up. What a file declared and was taken is
said in one warning line (:class:`~hullslice.errors.UnitsWarning` for a unit,
:class:`~hullslice.errors.OrientationWarning` for axes).
"""

from __future__ import annotations

import warnings

from ..errors import InputError, OrientationWarning, UnitsWarning
from .base import Conventions

__all__ = ["DEFAULT_FORWARD", "DEFAULT_UNITS", "DEFAULT_UP", "resolve_conventions"]

#: What a file read without options and declaring nothing is taken to be in.
DEFAULT_UNITS = "m"
DEFAULT_FORWARD = "+x"
DEFAULT_UP = "+z"


def _axis_key(axis: str) -> str:
    return str(axis).strip().lower().lstrip("+-")


def resolve_conventions(
    declared: Conventions,
    name: str,
    *,
    units: str | None = None,
    forward: str | None = None,
    up: str | None = None,
    length: float | None = None,
    stacklevel: int = 3,
) -> tuple[str, str, str]:
    """The unit, forward and up axes a file is read in, warning what its declaration set.

    Parameters
    ----------
    declared : Conventions
        What the file declares.
    name : str
        The mesh's name, for messages.
    units, forward, up : str, optional
        As given by the user (None: not given).
    length : float, optional
        The body's length in m, when given: it sets the size, so a declared unit is not
        taken (metres, which ``length`` requires).

    Returns
    -------
    units, forward, up : str

    Raises
    ------
    InputError
        ``forward`` given along the axis the file declares up, without ``up``.
    """
    if units is None:
        units = DEFAULT_UNITS
        if declared.units is not None and length is None:
            units = declared.units
            warnings.warn(
                f"mesh {name!r}: the file declares its unit {declared.unit_name or units!r}: "
                f"read in {units} (give --units to override)",
                UnitsWarning,
                stacklevel=stacklevel,
            )
    elif declared.units is not None and str(units).strip().lower() != declared.units:
        warnings.warn(
            f"mesh {name!r}: the file declares its unit {declared.unit_name or declared.units!r}"
            f"; read in {units} as given",
            UnitsWarning,
            stacklevel=stacklevel,
        )
    taken = []
    if up is None:
        up = declared.up or DEFAULT_UP
        if declared.up is not None:
            if forward is not None and _axis_key(forward) == _axis_key(up):
                raise InputError(
                    f"forward axis {forward!r} is the axis the file declares up ({up}): give "
                    "--up too (e.g. --up z)"
                )
            taken.append(f"up {up}")
    if forward is None:
        forward = declared.forward or DEFAULT_FORWARD
        if declared.forward is not None:
            taken.append(f"forward {forward}")
    if taken:
        warnings.warn(
            f"mesh {name!r}: its format declares {' and '.join(taken)} (glTF is +Y up): read "
            f"with forward {forward}, up {up} (give --forward, --up to override)",
            OrientationWarning,
            stacklevel=stacklevel,
        )
    return str(units), str(forward), str(up)
