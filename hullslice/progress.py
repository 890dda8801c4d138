"""Progress of a long run on a terminal: one line on stderr, rewritten in place.

A time history (``hullslice simulate``, :func:`hullslice.simulate`), a sweep, a report and
the examples say how far they are with the same line: what is being done, how much of it
(the simulated time, the cases), the wall time elapsed and an estimate of the time left
from the pace so far. It is shown only when the stream is a terminal
(:func:`on_terminal`): piped or redirected, nothing is written, so that logs and scripts
see only the results. The line is cleared when the run ends, whether it succeeds or fails.

No progress-bar library (tqdm, rich) is used: a line rewritten with a carriage return is
all a command needs, works alike in a terminal and over ssh, and adds no dependency to
the core. In a notebook, or for any other display, give the API your own callback:
:func:`hullslice.simulate` calls ``progress(t, t_end)`` after each step (the simulated
time in s), :func:`hullslice.sweep` calls ``progress(done, total, failed)`` after each case;
a tqdm bar's ``update`` fits either.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TextIO

__all__ = [
    "CaseProgress",
    "ProgressLine",
    "TimeProgress",
    "duration",
    "on_terminal",
    "terminal_case_progress",
    "terminal_progress",
]


def on_terminal(stream: TextIO | None = None) -> bool:
    """Whether ``stream`` (default ``sys.stderr``) is a terminal, where progress is shown."""
    stream = stream if stream is not None else sys.stderr
    isatty = getattr(stream, "isatty", None)
    return bool(isatty and isatty())


def duration(seconds: float) -> str:
    """A wall-clock duration as ``12 s``, ``3 min 05 s`` or ``1 h 02 min``."""
    s = max(0, round(seconds))
    if s < 60:
        return f"{s} s"
    if s < 3600:
        return f"{s // 60} min {s % 60:02d} s"
    return f"{s // 3600} h {s // 60 % 60:02d} min"


class ProgressLine:
    """One line of progress on a stream, rewritten in place; a context manager that clears
    it on leaving.

    Parameters
    ----------
    label : str
        What runs, the start of the line: ``"simulating"``, ``"sweep"``, ``"report"``.
    stream : text file, optional
        Where the line is written (default: ``sys.stderr``).
    clock : callable, optional
        Wall clock in s (default: :func:`time.monotonic`).
    """

    #: Shortest wall time between two updates of the line, s (the last one is always shown).
    INTERVAL = 0.25

    def __init__(
        self,
        label: str,
        stream: TextIO | None = None,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.label = label
        self.stream = stream if stream is not None else sys.stderr
        self.clock = clock
        self.start = clock()
        self.last = -float("inf")
        self.width = 0
        self.shown = False

    def show(self, text: str, fraction: float | None = None, *, now: float | None = None) -> None:
        """Write ``label: text``, the wall time elapsed and, given the ``fraction`` done
        (0 to 1), the time left at the pace since the start. Updates closer together than
        :data:`INTERVAL` are skipped, but for the one that completes the work."""
        now = self.clock() if now is None else now
        if now - self.last < self.INTERVAL and not (fraction is not None and fraction >= 1):
            return
        self.last = now
        elapsed = now - self.start
        line = f"{self.label}: {text}, {duration(elapsed)} elapsed"
        if fraction is not None and fraction < 1:
            line += (
                f", about {duration(elapsed * (1 - fraction) / fraction)} left"
                if fraction > 0
                else ", time left unknown"
            )
        self.stream.write("\r" + line.ljust(self.width))
        self.stream.flush()
        self.width = max(self.width, len(line))  # what the terminal's line now holds
        self.shown = True

    def done(self) -> None:
        """Clear the line (nothing when none was shown)."""
        if self.shown:
            self.stream.write("\r" + " " * self.width + "\r")
            self.stream.flush()
            self.shown = False
            self.width = 0

    def __enter__(self):
        return self

    def __exit__(self, *exc: object) -> None:
        self.done()


class TimeProgress(ProgressLine):
    """The progress of a time history: ``progress(t, t_end)``, the simulated time and the
    run's end in s (the callback :func:`hullslice.simulate` takes): ``simulating: t =
    0.02500 s of 0.1 s ( 25 %), 10 s elapsed, about 30 s left``."""

    def __init__(
        self,
        label: str = "simulating",
        stream: TextIO | None = None,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        super().__init__(label, stream, clock)

    def __call__(self, t: float, t_end: float) -> None:
        frac = min(1.0, max(0.0, t / t_end)) if t_end > 0 else 1.0
        self.show(f"t = {t:.5f} s of {t_end:g} s ({int(100 * frac):3d} %)", frac)


class CaseProgress(ProgressLine):
    """The progress of a sweep: ``progress(done, total, failed)``, cases (the callback
    :func:`hullslice.sweep` takes): ``sweep: 4/10 cases done, 1 failed, 4 s elapsed, about
    12 s left``. The pace counts the cases run since the first call only: those found
    finished by a resumed sweep take no time."""

    def __init__(
        self,
        label: str = "sweep",
        stream: TextIO | None = None,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        super().__init__(label, stream, clock)
        self.first: int | None = None

    def __call__(self, done: int, total: int, failed: int) -> None:
        now = self.clock()
        if self.first is None:
            self.first, self.start = done, now
        text = f"{done}/{total} cases done, {failed} failed"
        ran, todo = done - self.first, total - self.first
        self.show(text, ran / todo if todo > 0 else 1.0, now=now)


@contextmanager
def terminal_progress(
    label: str = "simulating", stream: TextIO | None = None
) -> Iterator[TimeProgress | None]:
    """A time history's progress callback while inside, on a terminal only: a
    :class:`TimeProgress` when ``stream`` (default ``sys.stderr``) is a terminal, else None
    (no progress); its line is cleared on leaving.

    ::

        with terminal_progress("pitch 8 deg") as progress:
            history = hs.simulate(hull, -1.5, 1.5, progress=progress)
    """
    line = TimeProgress(label, stream)
    try:
        yield line if on_terminal(line.stream) else None
    finally:
        line.done()


@contextmanager
def terminal_case_progress(
    label: str = "sweep", stream: TextIO | None = None
) -> Iterator[CaseProgress | None]:
    """As :func:`terminal_progress`, for a sweep's cases: a :class:`CaseProgress`."""
    line = CaseProgress(label, stream)
    try:
        yield line if on_terminal(line.stream) else None
    finally:
        line.done()
