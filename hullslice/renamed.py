"""Former keyword names, still taken for one release with a :class:`DeprecationWarning`.

An angle parameter of the Python API says its unit in its name (``pitch_rad``,
``pitch_rate_rad_s``, ``pitch_acceleration_rad_s2``); the former bare names (``pitch``,
``pitch_rate``, ...) meant the same values in rad. :func:`renamed_keywords` wraps a function
or a class so that a former name is taken as its new one, with a warning that names the new
one. The wrapped callable's signature (:func:`inspect.signature`) shows the new names only;
positional calls are untouched.
"""

from __future__ import annotations

import functools
import warnings
from collections.abc import Callable
from typing import Any, TypeVar, cast

from .errors import InputError

__all__ = ["former_attribute", "renamed_keywords"]

T = TypeVar("T")


def _unit(name: str) -> str:
    """The unit a name's suffix says: ``pitch_rate_rad_s`` -> ``rad/s``."""
    for suffix, unit in (("_rad_s2", "rad/s^2"), ("_rad_s", "rad/s"), ("_rad", "rad")):
        if name.endswith(suffix):
            return unit
    return "the same unit"


def renamed_keywords(**former: str) -> Callable[[T], T]:
    """Take each keyword ``old=`` of ``former`` (``old="new"``) as ``new=`` with a warning.

    Decorates a function or a class (its ``__init__``). Giving both names is an
    :class:`~hullslice.errors.InputError`.
    """

    def decorate(obj: T) -> T:
        is_class = isinstance(obj, type)
        subject = cast(Any, obj)
        target: Callable[..., Any] = subject.__init__ if is_class else subject
        where: str = getattr(obj, "__qualname__", "")

        @functools.wraps(target)
        def wrapper(*args: Any, **kw: Any) -> Any:
            for old in [k for k in former if k in kw]:
                new = former[old]
                if new in kw:
                    raise InputError(f"{where} got both {old}= and {new}=: give {new}= only")
                warnings.warn(
                    f"{where}: the keyword {old}= is deprecated: give {new}= (the same "
                    f"value, in {_unit(new)})",
                    DeprecationWarning,
                    stacklevel=2,
                )
                kw[new] = kw.pop(old)
            return target(*args, **kw)

        if is_class:
            subject.__init__ = wrapper
            return obj
        return wrapper  # type: ignore[return-value]

    return decorate


def former_attribute(where: str, new: str) -> property:
    """A read-only attribute under its former name ``where`` (``"Class.old"``): the value of
    ``new``, with a :class:`DeprecationWarning` naming it."""

    def get(self: Any) -> Any:
        warnings.warn(
            f"{where} is deprecated: read {new} (the same value, in {_unit(new)})",
            DeprecationWarning,
            stacklevel=2,
        )
        return getattr(self, new)

    return property(get, doc=f"Deprecated: :attr:`{new}` ({_unit(new)}).")
