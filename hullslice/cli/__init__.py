"""The ``hullslice`` command line: a thin layer over the library.

Every command is a module of this package with ``add_parser(subparsers)`` and
``run(args) -> int``. :func:`main` is testable in-process: it takes ``argv`` and returns the
exit status. Errors print one line on stderr with exit status 2 (bad usage, bad input, a failing
solver; 1 for an internal error), never a traceback unless ``HULLSLICE_DEBUG=1``.
"""

from __future__ import annotations

import argparse
import os
import sys
import warnings
from collections.abc import Sequence

from ..errors import HullsliceError, HullsliceWarning
from . import (
    cmd_force,
    cmd_info,
    cmd_report,
    cmd_run,
    cmd_sections,
    cmd_simulate,
    cmd_solvers,
    cmd_sweep,
)
from .common import UsageError

__all__ = ["main", "run"]

COMMANDS = (
    cmd_solvers,
    cmd_info,
    cmd_sections,
    cmd_force,
    cmd_simulate,
    cmd_run,
    cmd_report,
    cmd_sweep,
)


class Parser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are exceptions, so that main() prints one line."""

    def error(self, message: str):  # type: ignore[override]
        raise UsageError(f"{self.prog}: error: {message} (see {self.prog} --help)")


def build_parser() -> Parser:
    from .. import __version__

    parser = Parser(
        prog="hullslice",
        description=(
            "Water-impact loads on hulls and aircraft fuselages by the 2D+t method: the body "
            "is cut into cross-sections, each treated as a 2D wedge entering the water. "
            "SI units throughout: m, kg, s, N; vertical velocity negative downward, forces "
            "positive upward."
        ),
    )
    parser.add_argument("--version", action="version", version=f"hullslice {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=Parser)
    sub.required = True
    for cmd in COMMANDS:
        cmd.add_parser(sub)
    return parser


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    print(f"hullslice: warning: {message}", file=sys.stderr)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line with ``argv`` (default ``sys.argv[1:]``); return the exit status."""
    debug = os.environ.get("HULLSLICE_DEBUG", "") not in ("", "0")
    with warnings.catch_warnings():
        warnings.showwarning = _show_warning
        # a repair or a doubtful unit is always shown, one line each, whatever the filters
        warnings.filterwarnings("always", category=HullsliceWarning)
        try:
            args = build_parser().parse_args(argv)
            return int(args.func(args) or 0)
        except SystemExit as exc:  # --help and --version
            return int(exc.code or 0)
        except UsageError as exc:
            print(str(exc), file=sys.stderr)
            return 2
        except HullsliceError as exc:
            if debug:
                raise
            print(f"hullslice: error: {exc}", file=sys.stderr)
            return 2
        except KeyboardInterrupt:
            print("hullslice: interrupted", file=sys.stderr)
            return 130
        except BrokenPipeError:
            return 0
        except OSError as exc:
            if debug:
                raise
            print(
                f"hullslice: error: {exc.strerror or exc}: {exc.filename or ''}".rstrip(": "),
                file=sys.stderr,
            )
            return 2
        except Exception as exc:
            if debug:
                raise
            print(
                f"hullslice: internal error: {type(exc).__name__}: {exc} "
                "(set HULLSLICE_DEBUG=1 for the traceback and please report it)",
                file=sys.stderr,
            )
            return 1


def run() -> None:
    """Console-script entry point."""
    sys.exit(main())
