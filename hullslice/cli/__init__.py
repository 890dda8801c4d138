"""The ``hullslice`` command line: a thin layer over the library.

Every command is a module of this package with ``add_parser(subparsers)`` and
``run(args) -> int``. :func:`main` is testable in-process: it takes ``argv`` and returns the
exit status. Errors print one line on stderr, never a traceback unless ``HULLSLICE_DEBUG=1``,
with an exit status that says whose the fault is (:data:`EXIT`): 2 for a command line that
cannot be parsed (usage), 3 for inputs that parse but are refused (a value out of range, a
file that is not a mesh, a solver that fails), 1 for an internal error, 130 and 143 for a
run stopped by Ctrl-C or SIGTERM.
"""

from __future__ import annotations

import argparse
import os
import sys
import warnings
from collections.abc import Sequence

from ..errors import HullsliceError, HullsliceWarning
from ..safety import Terminated, terminated_cleanly
from ..study import StudyError
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

__all__ = ["EXIT", "main", "run"]

#: Exit statuses by outcome.
EXIT = {
    "ok": 0,
    "internal error": 1,
    "usage": 2,  # argparse's own: the command line cannot be parsed
    "bad input": 3,  # the inputs parse, and hullslice refuses them or a solver fails on them
    "interrupted": 130,  # Ctrl-C (128 + SIGINT)
    "terminated": 143,  # kill PID (128 + SIGTERM)
}

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

    def error(self, message: str):
        extra = message.partition("unrecognized arguments:")[2].split()
        if extra and all(t.lstrip("-").isdigit() for t in extra):
            message += " (several slice counts take commas: --slices 16,32,64)"
        raise UsageError(f"{self.prog}: error: {message} (see {self.prog} --help)")


def build_parser() -> Parser:
    from .._version import __version__

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
    parser.add_argument(
        "--isolate",
        action="store_true",
        help="run the command in a child process and report one that ends without its "
        "result (a plugin calling os._exit, a crash in a C extension); give it before the "
        "command: hullslice --isolate force ...",
    )
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
    with warnings.catch_warnings(), terminated_cleanly():
        warnings.showwarning = _show_warning
        # a dependency's deprecations are for programmers, not for the command's user (who
        # can do nothing about them): shown only with HULLSLICE_DEBUG
        if not debug:
            warnings.filterwarnings("ignore", category=DeprecationWarning)
            warnings.filterwarnings("ignore", category=PendingDeprecationWarning)
        # a repair or a doubtful unit is always shown, one line each, whatever the filters
        warnings.filterwarnings("always", category=HullsliceWarning)
        try:
            args = build_parser().parse_args(argv)
            if args.isolate:
                from .isolate import run_isolated

                rest = list(sys.argv[1:] if argv is None else argv)
                rest.remove("--isolate")
                return run_isolated(main, rest)
            return int(args.func(args) or 0)
        except SystemExit as exc:  # --help and --version; or code that exits with a message
            if exc.code is None or isinstance(exc.code, int):
                return int(exc.code or 0)
            print(f"hullslice: error: {exc.code}", file=sys.stderr)
            return EXIT["internal error"]
        except UsageError as exc:
            print(str(exc), file=sys.stderr)
            return EXIT["usage"]
        except StudyError as exc:  # incomplete or inconsistent: the usage's fault
            print(f"hullslice {exc.command}: error: {exc}", file=sys.stderr)
            return EXIT["usage"]
        except HullsliceError as exc:
            if debug:
                raise
            print(f"hullslice: error: {exc}", file=sys.stderr)
            return EXIT["bad input"]
        except KeyboardInterrupt:  # Ctrl-C: temporary files are gone, no output is half written
            print("hullslice: interrupted", file=sys.stderr)
            return EXIT["interrupted"]
        except Terminated:  # kill PID (SIGTERM): the same
            print("hullslice: terminated", file=sys.stderr)
            return EXIT["terminated"]
        except BrokenPipeError:
            return 0
        except OSError as exc:
            if debug:
                raise
            print(
                f"hullslice: error: {exc.strerror or exc}: {exc.filename or ''}".rstrip(": "),
                file=sys.stderr,
            )
            return EXIT["bad input"]
        except Exception as exc:
            if debug:
                raise
            print(
                f"hullslice: internal error: {type(exc).__name__}: {exc} "
                "(set HULLSLICE_DEBUG=1 for the traceback and please report it)",
                file=sys.stderr,
            )
            return EXIT["internal error"]


def run() -> None:
    """Console-script entry point."""
    sys.exit(main())
