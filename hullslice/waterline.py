"""Each station's wetted properties against the height of the water, tabulated once.

The table lives in the 2D kernel, :mod:`hullslice.kernel.waterline_table`; the fixed
slicing (:mod:`hullslice.slicing.fixed`) makes and keeps one per pitch. This module keeps
the names where they have always been imported from.
"""

from __future__ import annotations

from .kernel.waterline_table import AFFINE, BUDGET, CONSTANT, TABULATED, WaterlineTable

__all__ = ["AFFINE", "BUDGET", "CONSTANT", "TABULATED", "WaterlineTable"]
