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
import threading
from collections.abc import Callable, Sequence

from .. import safety

__all__ = ["run_isolated"]

#: Exit status of a child that ended without its result.
FAILED = 3

#: Seconds the parent waits, once the child has ended, for the rest of its reports.
READ_TIMEOUT = 5.0


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


class _Watch:
    """The parent's reader of the child's reports: what plugin code it is in, and whether
    it said "done" (only the state is kept, however much the child reports)."""

    def __init__(self, fd: int) -> None:
        self.fd = fd
        self.where = ""
        self.finished = False
        self._rest = b""
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self) -> None:
        while True:
            try:
                chunk = os.read(self.fd, 65536)
            except OSError:
                return
            if not chunk:
                return
            *lines, self._rest = (self._rest + chunk).split(b"\n")
            for line in lines:
                self._line(line.decode("utf-8", "replace"))

    def _line(self, line: str) -> None:
        if line == "done":
            self.finished = True
        elif line.startswith("in "):
            self.where = line[3:]
        elif line == "out":
            self.where = ""


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
    watch = _Watch(read_fd)
    try:
        _, status = os.waitpid(pid, 0)
        # the rest of the reports; a process the child started may still hold the pipe
        watch.thread.join(timeout=READ_TIMEOUT)
    finally:
        signal.signal(signal.SIGINT, previous)
        signal.signal(signal.SIGTERM, previous_term)
    if not watch.thread.is_alive():
        os.close(read_fd)
    finished, where = watch.finished, watch.where
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
