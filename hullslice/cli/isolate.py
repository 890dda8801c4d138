"""``hullslice --isolate COMMAND ...``: the command in a child process, watched.

Plugin code runs inside hullslice's process. An exception, or a ``sys.exit()``, is caught
and reported (:func:`hullslice.safety.failure`), but a plugin that ends the process itself
(``os._exit(0)``) or crashes it (a segmentation fault in its C extension) leaves no Python
code to report anything: the command would end with status 0 and no output, or 139 and no
message. With ``--isolate`` the command runs in a forked child; the parent waits for it and,
when it ends without finishing (no "done" from it on a pipe) or is killed by a signal, says
so in one line, naming the plugin code that was running (the child tells the parent through
:data:`hullslice.safety.WATCH` as it enters and leaves plugin code), and exits with status 3.
Ctrl-C reaches both processes (the terminal signals the group): the parent only waits for
the child's own ending; ``kill PID`` of the parent is passed on to the child.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
from collections.abc import Callable, Sequence

from .. import safety

__all__ = ["run_isolated"]

#: Exit status of a child that ended without its result.
FAILED = 3


def _child(run: Callable[[Sequence[str]], int], argv: Sequence[str], fd: int) -> None:
    """The child's side: run the command, say "done", end with its status."""
    code = 1
    try:
        safety.WATCH = fd
        code = run(argv)
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(Exception):
                stream.flush()
        os.write(fd, b"done\n")
    finally:
        os._exit(code)


def _read_all(fd: int) -> bytes:
    chunks: list[bytes] = []
    while True:
        try:
            chunk = os.read(fd, 65536)
        except InterruptedError:  # pragma: no cover - retried by Python itself
            continue
        if not chunk:
            return b"".join(chunks)
        chunks.append(chunk)


def _running(report: bytes) -> str:
    """The plugin code the child was in when it ended, from its reports ("" if none)."""
    where = ""
    for line in report.decode("utf-8", "replace").splitlines():
        if line.startswith("in "):
            where = line[3:]
        elif line == "out":
            where = ""
    return where


def run_isolated(run: Callable[[Sequence[str]], int], argv: Sequence[str]) -> int:
    """Run ``run(argv)`` in a forked child and return its status; a child that ends without
    finishing is reported on stderr (one line) with status :data:`FAILED`."""
    if not hasattr(os, "fork"):
        print(
            "hullslice: error: --isolate needs a system that forks processes (Linux, macOS); "
            "leave it out",
            file=sys.stderr,
        )
        return FAILED
    for stream in (sys.stdout, sys.stderr):
        stream.flush()
    read_fd, write_fd = os.pipe()
    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child ends in os._exit (measured by its parent)
        os.close(read_fd)
        _child(run, argv, write_fd)
    os.close(write_fd)
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)  # the child reports Ctrl-C

    def pass_on(signum, frame) -> None:
        with contextlib.suppress(OSError):
            os.kill(pid, signum)

    previous_term = signal.signal(signal.SIGTERM, pass_on)
    try:
        report = _read_all(read_fd)
        _, status = os.waitpid(pid, 0)
    finally:
        os.close(read_fd)
        signal.signal(signal.SIGINT, previous)
        signal.signal(signal.SIGTERM, previous_term)
    finished = report.endswith(b"done\n")
    where = _running(report)
    who = f" while {where} ran" if where else ""
    if os.WIFSIGNALED(status):
        sig = os.WTERMSIG(status)
        if finished or sig in (signal.SIGINT, signal.SIGTERM):
            return 128 + sig
        name = signal.Signals(sig).name
        print(
            f"hullslice: error: the command's process was killed by {name}{who} (a crash in "
            "plugin or native code); no result was given: run without that plugin, or report "
            "the crash to its authors",
            file=sys.stderr,
        )
        return FAILED
    code = os.waitstatus_to_exitcode(status)
    if finished:
        return code
    print(
        f"hullslice: error: the command's process ended with status {code}{who} before it "
        "gave its result (plugin code that calls os._exit()?); no result was given: run "
        "without that plugin, or report it to its authors",
        file=sys.stderr,
    )
    return FAILED
