"""Row and column minima and maxima (hullslice.reduce) against numpy's own reductions
along an axis: the same values, exactly, NaN included."""

from __future__ import annotations

import numpy as np
import pytest

from hullslice.reduce import bounds, row_max, row_min


@pytest.mark.parametrize("dtype", [np.float64, np.float32, np.int64, np.int32])
@pytest.mark.parametrize("shape", [(1, 1), (7, 2), (1000, 3), (50, 3, 3)])
def test_the_reductions_equal_numpys(dtype, shape):
    rng = np.random.default_rng(sum(shape))
    a = (rng.normal(size=shape) * 1000).astype(dtype)
    if np.issubdtype(dtype, np.floating) and a.size > 4:
        a.flat[[1, a.size // 2]] = np.nan  # kept, as numpy keeps it
        a.flat[3] = -0.0
    for mine, numpys in ((row_min(a), a.min(axis=1)), (row_max(a), a.max(axis=1))):
        assert mine.dtype == numpys.dtype and mine.shape == numpys.shape
        assert np.array_equal(mine, numpys, equal_nan=True)
    lo, hi = bounds(a.reshape(len(a), -1))
    assert np.array_equal(lo, a.reshape(len(a), -1).min(axis=0), equal_nan=True)
    assert np.array_equal(hi, a.reshape(len(a), -1).max(axis=0), equal_nan=True)
    assert lo.dtype == hi.dtype == a.dtype


def test_a_view_is_reduced_as_a_copy():
    a = np.arange(60.0).reshape(10, 6)[::2, ::2]  # neither row nor column contiguous
    assert np.array_equal(row_min(a), a.min(axis=1))
    assert np.array_equal(bounds(a)[1], a.max(axis=0))
