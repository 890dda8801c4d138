"""The contour method's numerics: the lowest crossing of a contour and Wagner's ``c``,
against brute forces."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from hullslice.solvers import contour


def lowest_dense(edges: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Every edge against every line: the lowest crossing, NaN where none."""
    y1, z1, y2, z2 = (edges[:, i : i + 1] for i in range(4))
    lo, hi = np.minimum(y1, y2), np.maximum(y1, y2)
    span = (lo <= y) & (y <= hi) & (hi > lo)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.where(span, z1 + (y - y1) * (z2 - z1) / (y2 - y1), np.inf)
    out = z.min(axis=0) if len(edges) else np.full(len(y), np.inf)
    return np.where(np.isfinite(out), out, np.nan)


grid = st.integers(-12, 12).map(lambda k: k / 4)  # ties between lines and edge ends


@given(
    edges=st.lists(st.tuples(grid, grid, grid, grid), max_size=25),
    y=st.lists(grid, min_size=1, max_size=30),
)
def test_lowest_crossing_is_the_dense_one(edges, y):
    e = np.array(edges, dtype=np.float64).reshape(-1, 4)
    ys = np.array(y, dtype=np.float64)
    np.testing.assert_array_equal(contour._lowest(e, ys), lowest_dense(e, ys))


@given(
    edges=st.lists(st.tuples(grid, grid, grid, grid, st.integers(0, 2)), max_size=25),
    y=st.lists(st.tuples(grid, st.integers(0, 2)), min_size=1, max_size=30),
)
def test_lowest_crossing_by_group_is_each_groups_dense_one(edges, y):
    # many contours at once: each line meets only the edges of its own group
    e = np.array([t[:4] for t in edges], dtype=np.float64).reshape(-1, 4)
    eg = np.array([t[4] for t in edges], dtype=np.int64)
    ys = np.array([t[0] for t in y], dtype=np.float64)
    yg = np.array([t[1] for t in y], dtype=np.int64)
    want = np.array([lowest_dense(e[eg == g], ys[i : i + 1])[0] for i, g in enumerate(yg)])
    np.testing.assert_array_equal(contour._lowest(e, ys, eg, yg), want)


def wagner_integral(g: np.ndarray, ds: float, c: float) -> float:
    """The quadrature of Wagner's condition, linearly between the samples of ``g``."""
    x = c * contour._SIN / ds
    i0 = np.clip(np.floor(x).astype(int), 0, len(g) - 2)
    f = x - i0
    return float((g[i0] * (1 - f) + g[i0 + 1] * f) @ contour._W)


@given(
    rises=st.lists(st.floats(0.0, 1.0), min_size=8, max_size=96),
    share=st.floats(0.01, 0.99),
)
def test_wagners_c_meets_its_condition_to_rounding(rises, share):
    # a rising piecewise-linear contour (flat pieces too): the root found holds the
    # condition to rounding and agrees with 200 halvings of the bracket
    g = np.concatenate([[0.0], np.cumsum(rises)])
    ds = 0.01
    extent = (len(g) - 1) * ds
    top = wagner_integral(g, ds, extent)
    if top <= 0:
        return
    target = share * top
    c = contour._wagner_root(
        g[None, None, :], np.array([[ds]]), np.array([[extent]]), np.array([[target]]),
        np.array([[False]]),
    )[0, 0]  # fmt: skip
    lo, hi = 0.0, extent
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if wagner_integral(g, ds, mid) < target else (lo, mid)
    assert abs(wagner_integral(g, ds, c) - target) <= 1e-12 * top
    # where the condition is flat around the root any c on the flat holds it
    slope = (wagner_integral(g, ds, hi + 1e-6 * extent) - target) / (1e-6 * extent)
    if slope > 1e-6 * top / extent:
        assert abs(c - 0.5 * (lo + hi)) <= 1e-12 * extent


@pytest.mark.parametrize("deadrise_deg", [15.0, 25.0, 35.0])
@pytest.mark.parametrize("wall", [1.0, 2.0, 5.0])
def test_wagners_c_on_a_v_with_a_step(deadrise_deg, wall):
    # a V with a step (a strake): the condition is S-shaped in c, where plain Newton steps
    # go back and forth between two pieces; the root agrees with 100 halvings
    k = contour.SAMPLES
    worst = 0.0
    for j in range(2, 60, 3):
        rise = np.full(k - 1, np.tan(np.radians(deadrise_deg)))
        rise[j] += wall
        g = np.concatenate([[0.0], np.cumsum(rise)])
        extent = k - 1.0
        top = wagner_integral(g, 1.0, extent)
        for share in np.linspace(0.05, 0.95, 19):
            target = share * top
            c = contour._wagner_root(
                g[None, None, :], np.ones((1, 1)), np.full((1, 1), extent),
                np.full((1, 1), target), np.zeros((1, 1), dtype=bool),
            )[0, 0]  # fmt: skip
            lo, hi = 0.0, extent
            for _ in range(100):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if wagner_integral(g, 1.0, mid) < target else (lo, mid)
            worst = max(worst, abs(c - 0.5 * (lo + hi)) / extent)
    assert worst <= 1e-12
