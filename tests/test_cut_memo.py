"""The exact cut's memo (hullslice.contour_loops): a station served from its recipe gives
the points of a fresh cut to the last bit, and a station where a vertex has crossed its
plane is cut afresh.

The reference is the fresh cut by the same loops (:func:`cut_loops`), itself compared with
numpy's and manifold3d's in ``tests/test_planecut.py``. Each test runs the loops as Python
and, where numba is installed, compiled.
"""

from __future__ import annotations

import numpy as np
import pytest

import hullslice as hs
from hullslice import contour_loops, planecut_loops, planecut_numpy, shapes
from hullslice.forces.fused_arrays import stage_arrays
from hullslice.geometry import CUTTER_SIZE, MERGE, frame
from hullslice.planecut import plane_index

from .conftest import MESHES


def _bodies():
    yield "fuselage_model.obj", hs.load_hull(MESHES / "fuselage_model.obj", mass=60.0)
    yield "paper_prism.stl", hs.load_hull(MESHES / "paper_prism.stl", mass=1.0)
    shaped = {
        "cylinder": shapes.circular_cylinder(),
        "asymmetric wedge": shapes.asymmetric_wedge_prism(),
        "fuselage": shapes.fuselage(stations=40, points=24),
    }
    for name, (v, f) in shaped.items():
        yield name, hs.Hull.from_arrays(v, f, name=name)


BODIES = dict(_bodies())


def _paths():
    paths = [("python", {n: planecut_loops.LOOPS[n] for n in ("memo_cut", "cut", "ranges")})]
    if planecut_loops.available():
        paths.append(("numba", {n: planecut_loops.compiled(n) for n in ("memo_cut", "cut",
                                                                         "ranges")}))  # fmt: skip
    return paths


PATHS = _paths()


class Cutter:
    """A hull's cut at a pitch and stations, by the memo and afresh, with the same loops."""

    def __init__(self, hull, fns):
        self.hull, self.fns = hull, fns
        self.index = index = plane_index(hull)
        self.reach = stage_arrays(hull, 1e-9 * hull.size, 8)[-2:]  # the body's x and z reach
        self.g = np.asarray(hull.cg, dtype=np.float64)
        self.memo = contour_loops.empty_memo(len(index.bin_zlo))
        self.guess = np.full((0, len(index.bin_zlo), 2), -1)
        self.merge = MERGE * CUTTER_SIZE

    def _common(self, pitch):
        ix = self.index
        c, s = float(np.cos(pitch)), float(np.sin(pitch))
        m = np.ascontiguousarray(frame(self.hull, pitch)._matrix[:2])
        return ix, c, s, m

    def served(self, x_rel, pitch) -> np.ndarray:
        """Which stations the memo serves at a pitch (its station, or -1): the loops'
        test, by their Python functions."""
        ix, c, s, _ = self._common(pitch)
        src = contour_loops.match_loops(x_rel, c, s, self.memo, *self.reach, ix.margin)
        for i in np.flatnonzero(src <= -2):
            k = -2 - src[i]
            st = self.memo[0]
            move = (abs(c - st[1, k]) * self.reach[0] + abs(s - st[2, k]) * self.reach[1]
                    + abs(x_rel[i] - st[0, k]))  # fmt: skip
            same = contour_loops.same_sides_loops(self.memo[1][k], self.memo[3], self.memo[6],
                                                  self.memo[2][0][k], ix.corners, x_rel[i],
                                                  self.g[0], self.g[2], c, s, move,
                                                  ix.margin)  # fmt: skip
            src[i] = k if same else -1
        return src

    def by_memo(self, x_rel, pitch):
        ix, c, s, m = self._common(pitch)
        pts, start, station, area, status, self.memo = self.fns["memo_cut"](
            ix.key, ix.bin_start, ix.bin_zlo, ix.bin_zhi, ix.bin_reach, ix.margin, ix.key_span,
            ix.key_x0, ix.xmin, ix.corners, ix.ends, x_rel, self.g[0], self.g[2], c, s, m,
            self.merge, ix.scratch(), planecut_loops.K_OUT, planecut_loops.K_IN, self.guess, 0,
            self.memo, *self.reach,
        )  # fmt: skip
        assert status == 0
        return pts, start, station, area

    def fresh(self, x_rel, pitch):
        ix, c, s, m = self._common(pitch)
        first, last = self.fns["ranges"](
            ix.key, ix.bin_start, ix.bin_zlo, ix.bin_zhi, ix.bin_reach, x_rel, self.g[0],
            self.g[2], c, s, ix.margin, ix.key_span, ix.key_x0, self.guess, 0,
        )  # fmt: skip
        pts, start, station, status, area = self.fns["cut"](
            first, last, ix.corners, ix.ends, x_rel, self.g[0], self.g[2], c, s, m, self.merge,
            ix.scratch(), planecut_loops.K_OUT, planecut_loops.K_IN,
        )  # fmt: skip
        assert status == 0
        return pts, start, station, area


def _walk(hull):
    """60 pitches (steps of 1e-5 to 3e-3 rad) and their stations, drifting and growing in
    number, as a free-pitch run's."""
    rng = np.random.default_rng(7)
    pitch = 0.06
    _, stations = frame(hull, pitch).fixed_stations(24)
    for step in range(60):
        pitch += rng.choice([1e-5, 3e-4, 3e-3]) * rng.choice([-1.0, 1.0])
        lo, hi = 6 + step // 20, 12 + step // 6
        yield pitch, np.ascontiguousarray(stations[lo:hi] + 1e-4 * hull.size * np.sin(pitch * 40))


def _assert_same(got, want):
    names = ("points", "ring starts", "ring stations", "ring areas")
    for a, b, what in zip(got, want, names[: len(want)], strict=True):
        np.testing.assert_array_equal(a, b, err_msg=what)


@pytest.mark.parametrize("path", [p[0] for p in PATHS])
@pytest.mark.parametrize("name", sorted(BODIES))
def test_the_memo_gives_a_fresh_cuts_points_to_the_bit(name, path):
    """A walk of 60 pitches (steps of 1e-5 to 3e-3 rad) and stations drifting and growing
    in number, as a free-pitch run's: every cut by the memo equals the fresh cut to the
    bit, most stations are served by it, and some are cut afresh."""
    hull = BODIES[name]
    cutter = Cutter(hull, dict(PATHS)[path])
    served = total = 0
    for pitch, x_rel in _walk(hull):
        src = cutter.served(x_rel, pitch)
        served += int((src >= 0).sum())
        total += len(src)
        _assert_same(cutter.by_memo(x_rel, pitch), cutter.fresh(x_rel, pitch))
    assert served >= 0.3 * total, (served, total)
    assert served < total


@pytest.mark.parametrize("path", [p[0] for p in PATHS])
def test_a_vertex_crossing_its_plane_is_cut_afresh(path):
    """A station moved just past the candidate vertex nearest its plane (its recipe no
    longer holds, though the faces out of its ranges are far): the sign test finds the
    crossing, and the cut equals the fresh one."""
    hull = BODIES["fuselage"]
    cutter = Cutter(hull, dict(PATHS)[path])
    pitch = 0.05
    x_rel = np.ascontiguousarray(frame(hull, pitch).fixed_stations(40)[1][10:14])
    cutter.by_memo(x_rel, pitch)
    near = cutter.memo[0][3, 1]  # the second station's nearest candidate vertex, m
    assert 0.0 < near < 1e-3 * hull.size
    moved = x_rel.copy()
    for sign in (1.0, -1.0):
        moved[1] = x_rel[1] + sign * 1.5 * near / np.cos(pitch)
        src = cutter.served(moved, pitch)
        got = cutter.by_memo(moved, pitch)
        _assert_same(got, cutter.fresh(moved, pitch))
        if src[1] == -1:
            break
        cutter.by_memo(x_rel, pitch)  # the memo of the first cut again
    assert src[1] == -1  # one of the two ways crosses the nearest vertex
    assert src[0] >= 0 and src[2] >= 0  # the others served


@pytest.mark.parametrize("name", sorted(BODIES))
def test_numpys_memo_gives_a_fresh_cuts_contours_to_the_bit(name):
    """numpy's path (:mod:`hullslice.planecut_numpy`) over the same walk: each cut by the
    memo equals a cut with an empty memo (every station afresh) to the bit, most stations
    are served, and the memo holds the last cut's stations (and more where it served
    them all)."""
    hull = BODIES[name]
    index = plane_index(hull)
    g = np.asarray(hull.cg, dtype=np.float64)
    empty = contour_loops.empty_memo(len(index.bin_zlo))
    memo = empty
    served = total = 0
    for pitch, x_rel in _walk(hull):
        c, s = np.cos(pitch), np.sin(pitch)
        src = planecut_numpy.served(index, memo, x_rel, c, s, g)
        served += int((src >= 0).sum())
        total += len(src)
        m = frame(hull, pitch)._matrix
        got, memo = planecut_numpy.memo_cut(index, memo, x_rel, pitch, g, m, MERGE * CUTTER_SIZE)
        want, _ = planecut_numpy.memo_cut(index, empty, x_rel, pitch, g, m, MERGE * CUTTER_SIZE)
        assert len(got) == len(want)
        for a, b in zip(got, want, strict=True):
            assert len(a) == len(b)
            for p, q in zip(a, b, strict=True):
                np.testing.assert_array_equal(p, q)
        assert memo[0].shape[1] >= len(x_rel)  # these stations, and more where all were served
    assert served >= 0.3 * total, (served, total)
    assert served < total


@pytest.mark.parametrize("name", ["fuselage_model.obj", "fuselage"])
def test_a_check_tests_again_only_the_faces_near_the_plane(name):
    """Over the walk, wherever a station's candidates are checked: the faces whose
    nearest corner was farther from the recipe's plane than a vertex can have moved (by
    more than rounding's room) are taken as they were, and the answer is that of the sign
    test on every candidate; on these meshes a small share of the candidates is tested
    again. numpy's memo keeps the same distances as the loops'."""
    hull = BODIES[name]
    fns = PATHS[-1][1]  # compiled where numba is installed
    cutter = Cutter(hull, fns)
    index = plane_index(hull)
    g = np.asarray(hull.cg, dtype=np.float64)
    numpy_memo = contour_loops.empty_memo(len(index.bin_zlo))
    checks = tested = candidates = 0
    for pitch, x_rel in _walk(hull):
        c, s = float(np.cos(pitch)), float(np.sin(pitch))
        src = contour_loops.match_loops(x_rel, c, s, cutter.memo, *cutter.reach, index.margin)
        memo = cutter.memo
        for i in np.flatnonzero(src <= -2):
            k = -2 - src[i]
            st = memo[0]
            move = (abs(c - st[1, k]) * cutter.reach[0] + abs(s - st[2, k]) * cutter.reach[1]
                    + abs(x_rel[i] - st[0, k]))  # fmt: skip
            args = (memo[1][k], memo[3], memo[6], memo[2][0][k], index.corners, x_rel[i], g[0],
                    g[2], c, s)  # fmt: skip
            quick = contour_loops.same_sides_loops(*args, move, index.margin)
            assert quick == contour_loops.same_sides_loops(*args, np.inf, index.margin)
            near = memo[6][memo[2][0][k] : memo[2][0][k + 1]]
            checks += 1
            candidates += len(near)
            tested += int(np.count_nonzero(~(move < near - index.margin)))
        cutter.by_memo(x_rel, pitch)
        m = frame(hull, pitch)._matrix
        _, numpy_memo = planecut_numpy.memo_cut(index, numpy_memo, x_rel, pitch, g, m,
                                                MERGE * CUTTER_SIZE)  # fmt: skip
        assert np.array_equal(numpy_memo[6], cutter.memo[6])
        assert np.array_equal(numpy_memo[3], cutter.memo[3])
    assert checks > 5
    assert tested < 0.2 * candidates, (tested, candidates)


def test_a_contours_shoelace_sum_keeps_the_sign_and_the_zero_of_the_sum_term_by_term():
    """The cut's test of a contour's area: four running sums where their rounding cannot
    have changed the sign, else the sum term by term (numpy's): random contours within
    1e-14 of the terms' size of that sum and of its sign; a figure of eight whose two loops
    cancel, and a flat contour, exactly its zero."""
    fns = [contour_loops.shoelace_loops]
    if planecut_loops.available():
        fns.append(planecut_loops.compiled("shoelace"))

    def term_by_term(p):
        y, z = p[:, 0].tolist(), p[:, 1].tolist()
        total = 0.0
        for k in range(len(y) - 1):
            total += y[k] * z[k + 1] - y[k + 1] * z[k]
        return total + (y[-1] * z[0] - y[0] * z[-1])

    rng = np.random.default_rng(5)
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    eight = np.concatenate([square, square * [-1.0, 1.0]]) * 0.37  # the second clockwise
    flat = np.stack([np.linspace(0.0, 1.0, 9), np.linspace(0.0, 3.0, 9)], axis=1)
    for fn in fns:
        for n in (3, 4, 5, 7, 40, 661):
            angle = np.sort(rng.uniform(0.0, 2.0 * np.pi, n))
            pts = np.stack([np.cos(angle), 0.3 + np.sin(angle)], axis=1) * rng.uniform(0.1, 50)
            for p in (pts, pts[::-1].copy()):
                want = term_by_term(p)
                size = float(np.abs(p[:, 0] * np.roll(p[:, 1], -1)).sum()
                             + np.abs(np.roll(p[:, 0], -1) * p[:, 1]).sum())  # fmt: skip
                got = fn(p)
                assert abs(got - want) <= 1e-14 * size and np.sign(got) == np.sign(want)
        for p in (eight, flat):
            assert term_by_term(p) == 0.0
            assert fn(np.ascontiguousarray(p)) == 0.0
