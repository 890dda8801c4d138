"""A new pitch's keel line by the loops of :mod:`hullslice.frame_loops` (as Python, and
compiled where numba is installed) against numpy's: the refinement of the side view's
lowest points (:func:`refine_loops` against :func:`hullslice.kernel.envelope.refined`:
its gaps, jumps and crossings, then the merge of close break points) equal to the last bit
on a real aircraft, whose wings, nacelles and fairings cross the fuselage's keel in the side
view at every pitch (``meshes/airliner``), and on every catalogued body, at pitches from
-20 to 40 degrees."""

from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np
import pytest

import hullslice as hs
from hullslice import frame_loops, planecut_loops
from hullslice.constants import TOL
from hullslice.geometry import _turn, silhouette_edges
from hullslice.kernel import envelope
from hullslice.kernel.envelope import lowest_segments, refined

from .conftest import MESHES
from .test_planecut import BODIES, _same


def _refines():
    fns = [planecut_loops.LOOPS["refine"]]
    if planecut_loops.available():
        fns.append(planecut_loops.compiled("refine"))
    return fns


#: A real aircraft (its README), whose keel line the loops refine at every pitch.
AIRCRAFT = {"airliner": hs.load_hull(MESHES / "airliner" / "airliner.obj", length=37.6)}


@pytest.mark.parametrize("name", [*AIRCRAFT, *sorted(BODIES)])
def test_the_refinement_by_the_loops_equals_numpy(name):
    hull = AIRCRAFT[name] if name in AIRCRAFT else BODIES[name]
    a, b = silhouette_edges(hull)
    g = np.asarray(hull.cg)
    side = planecut_loops.side_view_loops
    refined_here = 0
    for pitch in np.radians([-20.0, -3.0, 0.0, 0.5, 4.0, 6.0, 9.0, 17.0, 40.0]):
        c, s = np.cos(pitch), np.sin(pitch)
        args = (float(g[0]), float(g[2]), float(c), float(s))
        xa, za, xb, zb, seg, xs, mid, z, zm, _, _ = side(a, b, *args, np.arange(2 * len(a)))
        ta, tb = _turn(a - g, c, s), _turn(b - g, c, s)
        for merge in TOL.keel_merge * hull.size * np.array([0.0, 1.0, 1e3]):
            want = refined(xs, mid, z, zm, merge, lowest_segments(ta, tb))
            for refine in _refines():
                ok, got_x, got_z = refine(xs, mid, z, zm, merge, xa, za, xb, zb, seg)
                assert ok
                assert _same(got_x, want.x) and _same(got_z, want.z), (pitch, merge)
                refined_here += len(want.x) > len(xs)
    if name in AIRCRAFT:  # points added at every pitch: crossings, jumps
        assert refined_here >= 9 * 3 * len(_refines()) - 6


def test_the_lowest_heights_by_a_search_equal_numpys():
    """:func:`lowest_at_loops` (the segments over an abscissa found by a search) gives
    numpy's lowest height of the silhouette segments at any abscissa: at 400 random ones
    and at every segment's ends, on the airliner at three pitches."""
    hull = AIRCRAFT["airliner"]
    a, b = silhouette_edges(hull)
    g = np.asarray(hull.cg)
    names = ("reach", "lowest_at")
    fns = [tuple(planecut_loops.LOOPS[n] for n in names)]
    if planecut_loops.available():
        fns.append(tuple(planecut_loops.compiled(n) for n in names))
    rng = np.random.default_rng(5)
    for pitch in np.radians([-3.0, 4.0, 17.0]):
        c, s = np.cos(pitch), np.sin(pitch)
        args = (float(g[0]), float(g[2]), float(c), float(s))
        xa, za, xb, zb, seg, xs, _, _, _, _, _ = planecut_loops.side_view_loops(
            a, b, *args, np.arange(2 * len(a))
        )
        q = np.concatenate([rng.uniform(xs[0] - 1.0, xs[-1] + 1.0, 400), xa, xb])
        want = lowest_segments(_turn(a - g, c, s), _turn(b - g, c, s))(np.sort(q))
        for reach, lowest_at in fns:
            lo, top = reach(xa, xb, seg)
            got = lowest_at(np.sort(q), lo, top, xa, za, xb, zb, seg)
            assert _same(got, want)


def test_what_the_refinement_leaves_to_numpy():
    """A group of nine close points to merge (numpy sums it pairwise) and an abscissa that
    is not a number: numpy's refinement."""
    xs = np.concatenate([np.arange(5.0), 5.0 + 1e-7 * np.arange(9)])
    z = np.zeros(len(xs))
    zm = np.full(len(xs) - 1, -1.0)
    none = np.empty(0)
    seg = np.empty(0, dtype=np.int64)
    for refine in _refines():
        assert not refine(xs, xs[:-1], z, zm, 1e-6, none, none, none, none, seg)[0]
        bad = xs.copy()
        bad[-1] = np.nan
        assert not refine(bad, xs[:-1], z, zm, 0.0, none, none, none, none, seg)[0]


def test_the_crossing_passes_are_numpys():
    assert frame_loops.CROSSING_PASSES == envelope.CROSSING_PASSES


def test_the_frame_loops_cache_sees_their_helpers():
    """numba's cache of these loops is stale when their own file changes; they call loops
    in another file, whose digest their file holds."""
    root = Path(frame_loops.__file__).parent
    names = ("keel_loops.py", "side_loops.py")
    digest = hashlib.sha256(b"".join((root / n).read_bytes() for n in names)).hexdigest()[:16]
    assert frame_loops.FRAME_HELPERS_DIGEST == digest, (
        f"set FRAME_HELPERS_DIGEST = {digest!r} in hullslice/frame_loops.py (its helpers changed)"
    )
