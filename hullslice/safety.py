"""Guards against values and plugin code that would end a run badly or pass a wrong result.

- :func:`check_options` refuses solver options that would switch a validity check off
  silently: NaN or infinite numbers anywhere in an option, and a number that is not
  positive where the option's default is a positive number (a threshold such as
  ``froude_min``).
- :func:`failure` describes an exception raised by plugin code, including ``SystemExit``
  (a plugin that calls ``sys.exit()`` must not end hullslice, least of all with status 0).
- :func:`plugin_code` is the frame plugin code runs in: what it prints goes to stderr (stdout
  carries the result, ``--format json`` without ``-o``), and a change of the working folder
  is undone when it returns (a relative ``-o``, ``--plot`` or input path keeps meaning the
  folder the command was started in).
- :func:`terminated_cleanly` turns ``SIGTERM`` (``kill PID``) into an exception, so that a
  run stopped that way removes its temporary files as after an error.
"""

from __future__ import annotations

import contextlib
import math
import os
import signal
import sys
from collections.abc import Iterator, Mapping
from typing import Any

from .errors import InputError

__all__ = [
    "Terminated",
    "check_options",
    "failure",
    "non_finite",
    "plugin_code",
    "terminated_cleanly",
]


def non_finite(value: Any) -> float | None:
    """The first NaN or infinite number in ``value`` (a number, or nested lists and tables of
    them), or None when there is none."""
    stack = [value]
    while stack:
        v = stack.pop()
        if isinstance(v, float) and not math.isfinite(v):
            return v
        if isinstance(v, list | tuple):
            stack.extend(v)
        elif isinstance(v, Mapping):
            stack.extend(v.values())
    return None


def _is_number(v: Any) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool)


def check_options(
    solver: str,
    defaults: Mapping[str, Any],
    given: Mapping[str, Any],
    own: frozenset[str] = frozenset(),
) -> None:
    """Refuse solver options that cannot be meant.

    Parameters
    ----------
    solver : str
        The solver's name, for messages.
    defaults : mapping
        The solver's options with their defaults.
    given : mapping
        The options given.
    own : set of str
        Options the solver checks itself (their range may include zero): only NaN and
        infinities are refused here.

    Raises
    ------
    InputError
        An option holds NaN or an infinity; or its default is a positive number and it is
        not a positive number (a threshold set to -1 or to text would switch its check off).
    """
    for key, value in given.items():
        bad = non_finite(value)
        if bad is not None:
            raise InputError(
                f"solver {solver!r} option {key}={bad!r} is not a finite number: give a finite "
                f"value (default {defaults.get(key)!r})"
            )
        default = defaults.get(key)
        if key not in own and default is not None and _is_number(default) and default > 0:
            if not _is_number(value) or value <= 0:
                raise InputError(
                    f"solver {solver!r} option {key}={value!r} is not a positive number: give "
                    f"one above 0 (default {default!r})"
                )


def failure(exc: BaseException) -> str:
    """``Type: message`` of an exception from plugin code, saying what a ``SystemExit`` is."""
    if isinstance(exc, SystemExit):
        return (
            f"it called sys.exit({exc.code!r}) (SystemExit), which a solver must not do; "
            "raise an exception instead"
        )
    return f"{type(exc).__name__}: {exc}"


#: A pipe's file descriptor that :func:`plugin_code` reports to ("in LABEL", "out"), set
#: in the child process of ``hullslice --isolate`` (:mod:`hullslice.cli.isolate`); None
#: otherwise.
WATCH: int | None = None


def _report(line: str) -> None:
    if WATCH is not None:
        with contextlib.suppress(OSError):
            os.write(WATCH, (line.replace("\n", " ") + "\n").encode("utf-8", "replace"))


@contextlib.contextmanager
def plugin_code(label: str = "plugin code") -> Iterator[None]:
    """Run plugin code (a solver's import, construction or call) with ``sys.stdout`` sent to
    ``sys.stderr``, and the working folder it started in restored after it. ``label`` names
    the code (``solver 'wagner'``) to the parent of an isolated run (:data:`WATCH`)."""
    _report(f"in {label}")
    try:
        cwd: str | None = os.getcwd()
    except OSError:  # the folder was removed: nothing to restore
        cwd = None
    try:
        with contextlib.redirect_stdout(sys.stderr):
            yield
    finally:
        if cwd is not None:
            with contextlib.suppress(OSError):
                if os.getcwd() != cwd:
                    os.chdir(cwd)
        _report("out")


class Terminated(BaseException):  # a signal, like KeyboardInterrupt
    """The process received ``SIGTERM``; raised where it was, so that clean-up runs."""


def _raise_terminated(signum, frame) -> None:
    raise Terminated(signum)


@contextlib.contextmanager
def terminated_cleanly() -> Iterator[None]:
    """Within the block, ``SIGTERM`` raises :class:`Terminated` (main thread only; elsewhere
    the block runs unchanged). The previous handler is restored after it."""
    try:
        previous = signal.signal(signal.SIGTERM, _raise_terminated)
    except (ValueError, OSError):  # not the main thread, or no such signal here
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)
