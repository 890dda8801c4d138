"""One slice of the paper's case, every intermediate value computed by hand (METHOD section 3)."""

from __future__ import annotations

import math

import pytest

import hullslice as hs


def test_single_slice_by_hand(paper_hull):
    draft, v = 0.0383, -3.4943
    g, rho = 9.81, 1000.0
    L, W = 0.35, 0.2
    h0, h1 = 0.1, 0.1 * math.tan(math.radians(10.0))
    volume = (W / 2) * (h0 + h1) / 2 * L  # triangles of area (W/2) h, h linear in x
    # wetted length: where the keel depth below the deck equals the deck height above water
    wet_len = (h0 - (W / 2 - draft)) / (h0 - h1) * L
    x = wet_len / 2  # one slice: its mid-station
    h = h0 + (h1 - h0) * x / L
    p = h - (h0 - draft)  # = draft / 2, Eq. 8 with n = 1
    M = 1.0 / volume * (W / 2) * h  # Eq. 10 with the body's uniform density
    tan_b = h / (W / 2)  # Eq. 11
    beta_deg = math.degrees(math.atan(tan_b))
    gamma = -0.0114 * beta_deg + 1.5669
    zt = -p * gamma / (math.sqrt(M) * tan_b)  # Eq. 9
    at = (
        -0.35026
        - 3093.66877 * zt
        + 11743.57797 * zt**2
        + 2.26181e7 * zt**3
        + 1.28322e9 * zt**4
        + 2.8479e10 * zt**5
        + 2.29482e11 * zt**6
    )  # Eq. 5
    vt = 1.00131 - 0.36998 * zt - 1852.65292 * zt**2 - 56703.97435 * zt**3 - 531047.33189 * zt**4
    v0 = v / vt
    a = at * v0**2 / math.sqrt(M) * gamma / tan_b  # Eq. 4
    F = M * (a + g) * wet_len  # Eq. 12, d = DeltaL / 1

    r = hs.compute_force(paper_hull, draft, v, slices=1, fluid=hs.Fluid(rho=rho, g=g))
    s, d = r.sections, r.loads.diagnostics
    assert len(r) == 1
    # geometry: manifold3d cuts in single precision (1e-7) and the mesh's twisted sides are
    # within 5e-6 m of the ruled surface, 2e-4 of this section's half-beam
    assert s.wetted_length == pytest.approx(wet_len, rel=1e-6)
    assert s.x[0] == pytest.approx(x, rel=1e-6)
    assert s.dx[0] == pytest.approx(wet_len, rel=1e-6)
    assert s.penetration[0] == pytest.approx(p, rel=1e-6)
    assert s.penetration[0] == pytest.approx(draft / 2, rel=1e-6)
    assert s.mass_per_metre[0] == pytest.approx(M, rel=1e-6)
    assert math.tan(s.deadrise[0]) == pytest.approx(tan_b, rel=2e-4)
    assert d["gamma"][0] == pytest.approx(gamma, rel=2e-4)
    assert d["z_tilde"][0] == pytest.approx(zt, rel=5e-4)
    assert d["v_tilde"][0] == pytest.approx(vt, rel=5e-4)
    assert d["a_tilde"][0] == pytest.approx(at, rel=5e-4)
    assert d["v_z0"][0] == pytest.approx(v0, rel=5e-4)
    assert d["acceleration"][0] == pytest.approx(a, rel=1e-3)
    assert r.force[0] == pytest.approx(F, rel=1e-3)
    assert r.total == pytest.approx(F, rel=1e-3)
    assert r.loads.force_per_metre[0] == pytest.approx(M * (a + g), rel=1e-3)
    # and Eq. 2: the slice's free fall has its peak at z* with Fr* = v*/sqrt(g z*)
    z_star = math.sqrt(2 * M / (5 * math.pi * rho * gamma**2)) * tan_b
    fr = abs(5 / 6 * v0) / math.sqrt(g * z_star)
    assert d["froude"][0] == pytest.approx(fr, rel=1e-3)
