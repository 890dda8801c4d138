"""Richardson extrapolation and GCI against sequences with a known limit."""

from __future__ import annotations

import math

import pytest

import hullslice as hs
from hullslice import shapes


@pytest.mark.parametrize("p", [1.0, 2.0, 3.5])
def test_recovers_limit_and_order_of_a_power_law(p):
    # f(n) = f0 + C h^p with h = 1/n: the three-grid procedure is exact for it
    f0, C = 147.0, 30.0
    counts = [16, 32, 64]
    values = [f0 + C * n**-p for n in counts]
    r = hs.richardson(counts, values)
    assert r.extrapolated == pytest.approx(f0, rel=1e-12)
    assert r.order == pytest.approx(p, rel=1e-9)
    assert r.behaviour == "monotonic"
    # GCI_fine = 1.25 |e21| / (r^p - 1) (Celik et al. 2008, Eq. 6)
    e21 = abs((values[2] - values[1]) / values[2])
    assert r.gci == pytest.approx(1.25 * e21 / (2**p - 1), rel=1e-9)


def test_non_constant_ratio():
    # refinement ratios 1.5 and 2: the fixed-point iteration for p (Celik et al., Eq. 3)
    f0, C, p = 10.0, -4.0, 2.0
    counts = [10, 20, 30]
    r = hs.richardson(counts, [f0 + C * n**-p for n in counts])
    assert r.order == pytest.approx(p, rel=1e-6)
    assert r.extrapolated == pytest.approx(f0, rel=1e-9)


def test_uses_the_three_finest_in_any_order():
    vals = {8: 9.0, 16: 1.0 + 1 / 16**2, 32: 1.0 + 1 / 32**2, 64: 1.0 + 1 / 64**2}
    r = hs.richardson(list(vals)[::-1], list(vals.values())[::-1])
    assert r.counts == (64, 32, 16)
    assert r.extrapolated == pytest.approx(1.0, rel=1e-12)


def test_oscillatory_and_divergent_sequences_are_labelled():
    osc = hs.richardson([16, 32, 64], [1 + 0.04, 1 - 0.01, 1 + 0.0025])
    assert osc.behaviour == "oscillatory"
    assert osc.order == pytest.approx(2.0, rel=1e-9)
    div = hs.richardson([16, 32, 64], [1.0, 1.1, 1.3])
    assert div.behaviour == "divergent"
    assert math.isnan(div.extrapolated) and math.isinf(div.gci)
    # differences shrinking by 2 % per doubling (observed order 0.03): the limit would be
    # 48 times the last difference away, a number with no meaning
    slow = hs.richardson([16, 32, 64], [1.0 + 1.02**2 * 0.1, 1.0 + 1.02 * 0.1, 1.0 + 0.1])
    assert slow.behaviour == "divergent" and math.isnan(slow.extrapolated)
    assert slow.order == pytest.approx(math.log2(1.02), rel=1e-6) and math.isinf(slow.gci)
    # an order of 0.5 or more is extrapolated
    low = hs.richardson([16, 32, 64], [1.0 + 4**0.6 * 0.1, 1.0 + 2**0.6 * 0.1, 1.0 + 0.1])
    assert low.behaviour == "monotonic" and low.order == pytest.approx(0.6, rel=1e-9)
    assert low.extrapolated == pytest.approx(1.0, rel=1e-9)


def test_too_few_or_repeated_counts():
    with pytest.raises(hs.InputError, match="three slice counts"):
        hs.richardson([16, 32], [1.0, 2.0])
    with pytest.raises(hs.InputError, match="repeat"):
        hs.richardson([16, 16, 32], [1.0, 1.0, 2.0])


def test_solutions_equal_to_rounding_are_converged():
    # a prism of constant wedge section is exact at any slice count: its forces differ in
    # the last digits only (1.3e-12 here), which is rounding, not an order of convergence
    v, f = shapes.wedge_prism(length=1.0, beam=0.3, deadrise_deg=20.0, stations=11)
    hull = hs.Hull.from_arrays(v, f)
    study = hs.convergence(hull, 0.02, -1.0, solver="wagner", acceleration=0.0)
    rich = study.richardson
    assert rich.behaviour == "converged" and rich.gci == 0.0
    assert rich.extrapolated == study.forces[-1]
    # Wagner's closed form per metre, rho pi gamma^2 V^2 p / tan^2(beta), times 1 m
    closed = 1000.0 * math.pi * (math.pi / 2) ** 2 * 0.02 / math.tan(math.radians(20.0)) ** 2
    assert rich.extrapolated == pytest.approx(closed, rel=1e-9)
    # differences above rounding are still an order of convergence
    f1 = 100.0
    noisy = hs.richardson((64, 32, 16), (f1, f1 + 1e-7, f1 + 5e-7))
    assert noisy.behaviour == "monotonic" and noisy.order == pytest.approx(2.0, rel=1e-6)
