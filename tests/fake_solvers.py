"""Solver classes for registry tests, loaded through hand-made entry points."""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path
from typing import ClassVar

import numpy as np

from hullslice import SectionLoads, Solver


class ConstantSolver(Solver):
    """Force per metre = mass per metre times a constant acceleration (an exact reference)."""

    name = "constant"
    description = "test solver: f = M * accel"
    options: ClassVar[dict[str, float]] = {"accel": 100.0}

    def section_loads(self, sections, velocity, fluid):
        n = len(sections)
        return SectionLoads(
            force_per_metre=sections.mass_per_metre * self.settings["accel"],
            valid=np.ones(n, dtype=bool),
            reason=np.full(n, "", dtype=object),
        )


class NaNSolver(ConstantSolver):
    name = "nan"

    def section_loads(self, sections, velocity, fluid):
        loads = super().section_loads(sections, velocity, fluid)
        return SectionLoads(np.full(len(sections), np.nan), loads.valid, loads.reason)


class WrongShapeSolver(ConstantSolver):
    name = "wrong-shape"

    def section_loads(self, sections, velocity, fluid):
        n = len(sections) + 1
        return SectionLoads(np.zeros(n), np.ones(n, dtype=bool), np.full(n, "", dtype=object))


class RaisingSolver(ConstantSolver):
    name = "raising"

    def section_loads(self, sections, velocity, fluid):
        raise ZeroDivisionError("boom")


class NotASolver:
    name = "not-a-solver"


class NaNValidSolver(ConstantSolver):
    """Flags every section with NaN instead of a boolean (NaN cast to bool is True)."""

    name = "nan-valid"

    def section_loads(self, sections, velocity, fluid):
        loads = super().section_loads(sections, velocity, fluid)
        return SectionLoads(loads.force_per_metre, np.full(len(sections), np.nan), loads.reason)


class TextValidSolver(ConstantSolver):
    """Flags every section with the text "no" (a non-empty text cast to bool is True)."""

    name = "text-valid"

    def section_loads(self, sections, velocity, fluid):
        loads = super().section_loads(sections, velocity, fluid)
        return SectionLoads(loads.force_per_metre, np.full(len(sections), "no"), loads.reason)


class ExitingSolver(ConstantSolver):
    """Calls sys.exit(0) while it computes."""

    name = "exits"

    def section_loads(self, sections, velocity, fluid):
        sys.exit(0)


class ExitMessageSolver(ConstantSolver):
    """Raises SystemExit with a message while it computes."""

    name = "exits-with-message"

    def section_loads(self, sections, velocity, fluid):
        raise SystemExit("solver gave up")


class ExitOnStartSolver(ConstantSolver):
    """Calls sys.exit(3) when it is built."""

    name = "exits-on-start"

    def __init__(self, **options):
        sys.exit(3)


class TableSolver(ConstantSolver):
    """Reads its acceleration from a CSV table named by the option ``table``."""

    name = "table"
    options: ClassVar[dict] = {"table": ""}

    def section_loads(self, sections, velocity, fluid):
        text = Path(self.settings["table"]).read_text(encoding="utf-8")
        accel = float(text.splitlines()[1].split(",")[0])
        return SectionLoads(
            sections.mass_per_metre * accel,
            np.ones(len(sections), dtype=bool),
            np.full(len(sections), "", dtype=object),
        )


class HangingSolver(ConstantSolver):
    """Never returns; touches the file named by HULLSLICE_TEST_HANGING first."""

    name = "hangs"

    def section_loads(self, sections, velocity, fluid):
        Path(os.environ["HULLSLICE_TEST_HANGING"]).touch()
        while True:
            time.sleep(0.01)


class HugeSolver(ConstantSolver):
    """A finite force per metre, 1e308 N/m, whose total over the slices overflows."""

    name = "huge"

    def section_loads(self, sections, velocity, fluid):
        loads = super().section_loads(sections, velocity, fluid)
        return SectionLoads(np.full(len(sections), 1e308), loads.valid, loads.reason)


class PrintingSolver(ConstantSolver):
    """Prints a line (on stdout) while it computes, and computes f = M * 100 m/s^2."""

    name = "prints"

    def section_loads(self, sections, velocity, fluid):
        print("debug: section_loads called")
        return super().section_loads(sections, velocity, fluid)


class ChdirSolver(ConstantSolver):
    """Changes the working directory to / while it computes (f = M * 100 m/s^2)."""

    name = "chdir"

    def section_loads(self, sections, velocity, fluid):
        os.chdir("/")
        return super().section_loads(sections, velocity, fluid)


class HardExitSolver(ConstantSolver):
    """Ends its process with os._exit(0) while it computes: no clean-up, no exception."""

    name = "hard-exit"

    def section_loads(self, sections, velocity, fluid):
        os._exit(0)


class CrashingSolver(ConstantSolver):
    """Crashes its process (SIGSEGV, as a broken C extension does) while it computes."""

    name = "crashes"

    def section_loads(self, sections, velocity, fluid):
        import signal

        os.kill(os.getpid(), signal.SIGSEGV)
        time.sleep(10)
