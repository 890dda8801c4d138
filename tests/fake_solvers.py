"""Solver classes for registry tests, loaded through hand-made entry points."""

from __future__ import annotations

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
