"""Where a free-pitch stage's time goes: the envelope study's case, each part timed in the run.

    python benchmarks/stages.py [--t-end 0.5] [--window 100]

The case is the envelope study's (``benchmarks/run.py --envelope``): the 1:10 model
(``meshes/fuselage_model.obj``, 128k faces, 60 kg), free pitch from 5 deg, 19 m/s forward
and 1.5 m/s down, 32 fixed slices, 0.5 s at 1 ms. Every stage of every step is at a new
pitch. The parts of a stage are timed as the run makes them, in windows of ``--window``
steps, so that an early stage (a short wetted length) and a late one (most of the body
wetted) are both shown:

- ``frame``: the new pitch's frame (the side view's keel line, the lowest and highest
  points, the cutter's map);
- ``ranges``: the candidate faces' ranges of the stations cut (``PlaneIndex.ranges``);
- ``cut``: the exact cut's loops on them (``PlaneIndex._cut_by_loops``);
- ``outline``: the outline of the cut stations (``Outline.of``);
- ``window, rest``: the kept cut's own bookkeeping around those three;
- ``evaluation``: the fused evaluation of the stations (the keel line's arrays, the wetted
  properties, the solver's sums; ``FusedEvaluation._pitch`` less the window);
- ``one call``: a stage at a pitch the hull has no frame for (every stage of a step, but
  at a pitch met again), made in one compiled call from the keel line to the sums
  (``FusedEvaluation._one_call``; the first stage's result is then built from it); the
  parts above are then those of the stages that go the steps one by one;
- ``rest``: everything else of the step over its four stages (the first stage's full
  result, the record, the integrator, the calls between the parts).

Each wrapper adds about a microsecond to the part it times. It needs the compiled loops
(the ``fast`` extra).
"""

from __future__ import annotations

import argparse
import time
from collections import defaultdict
from pathlib import Path
from typing import Any

import hullslice as hs
from hullslice import geometry, planecut, planecut_loops
from hullslice.forces import fused
from hullslice.kernel import outline
from hullslice.slicing import fixed

ROOT = Path(__file__).resolve().parents[1]
MESH = ROOT / "meshes" / "fuselage_model.obj"
CASE: dict[str, Any] = {
    "dt": 0.001,
    "pitch_deg": 5.0,
    "forward_speed": 19.0,
    "free_pitch": True,
    "slices": 32,
    "slicing": "fixed",
    "stop_on": (),
}
PARTS = ("frame", "ranges", "cut", "outline", "window, rest", "evaluation", "one call", "rest")


class Clock:
    """Time spent in each timed function, by window of steps."""

    def __init__(self, window: int) -> None:
        self.window = window
        self.step = 0
        self.spent: dict[int, dict[str, float]] = defaultdict(lambda: defaultdict(float))
        self.stages: dict[int, int] = defaultdict(int)
        self.wall: dict[int, float] = defaultdict(float)

    def wrap(self, owner, name: str, label: str) -> None:
        """Time ``owner.name`` (a function or method) under ``label``."""
        inner = getattr(owner, name)
        spent = self.spent

        def timed(*args, **kwargs):
            t0 = time.perf_counter()
            try:
                return inner(*args, **kwargs)
            finally:
                spent[self.step // self.window][label] += time.perf_counter() - t0

        setattr(owner, name, timed)

    def wrap_classmethod(self, owner, name: str, label: str) -> None:
        inner = getattr(owner, name).__func__
        spent = self.spent

        def timed(cls, *args, **kwargs):
            t0 = time.perf_counter()
            try:
                return inner(cls, *args, **kwargs)
            finally:
                spent[self.step // self.window][label] += time.perf_counter() - t0

        setattr(owner, name, classmethod(timed))


def run(t_end: float, window: int) -> tuple[Clock, int]:
    """The envelope case run once to warm up, then once timed; the clock and the steps."""
    if not planecut_loops.available():
        raise SystemExit('stages: the compiled loops are needed: pip install -e ".[fast]"')
    hull = hs.load_hull(MESH, mass=60.0)
    hs.simulate(hull, -1.5, 0.01, **CASE)  # numba's loops loaded, the hull's index made
    clock = Clock(window)
    clock.wrap(geometry, "_frame", "frame")
    clock.wrap(planecut.PlaneIndex, "ranges", "ranges")
    clock.wrap(planecut.PlaneIndex, "_cut_by_memo", "cut")
    clock.wrap_classmethod(outline.Outline, "of", "outline")
    clock.wrap(fixed.FixedCut, "window", "window")
    clock.wrap(fused.FusedEvaluation, "_pitch", "pitch")
    clock.wrap(fused.FusedEvaluation, "_one_call", "one call")
    last = [time.perf_counter()]

    def progress(t: float, _t_end: float) -> None:
        now = time.perf_counter()
        clock.wall[clock.step // window] += now - last[0]
        clock.stages[clock.step // window] += 4
        clock.step += 1
        last[0] = time.perf_counter()

    fresh = hull.with_mass(hull.mass)
    last[0] = time.perf_counter()
    history = hs.simulate(fresh, -1.5, t_end, progress=progress, **CASE)
    return clock, len(history) - 1


def shares(clock: Clock, w: int) -> dict[str, float]:
    """Microseconds a stage in each part, over window ``w``."""
    s, n = clock.spent[w], clock.stages[w]
    window = s["window"] - s["ranges"] - s["cut"] - s["outline"]
    evaluation = s["pitch"] - s["window"]
    rest = clock.wall[w] - s["frame"] - s["pitch"] - s["one call"]
    parts = {
        "frame": s["frame"],
        "ranges": s["ranges"],
        "cut": s["cut"],
        "outline": s["outline"],
        "window, rest": window,
        "evaluation": evaluation,
        "one call": s["one call"],
        "rest": rest,
    }
    return {k: v / n * 1e6 for k, v in parts.items()}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--t-end", type=float, default=0.5, help="case length, s")
    parser.add_argument("--window", type=int, default=100, help="steps of a window")
    args = parser.parse_args()
    clock, steps = run(args.t_end, args.window)
    print(f"envelope case: {MESH.name}, free pitch, {steps} steps of 1 ms, 32 fixed slices")
    print("microseconds a stage (4 stages a step), by window of steps; shares of the stage")
    head = f"{'steps':<10}" + "".join(f"{p:>13}" for p in PARTS) + f"{'stage':>9}"
    print(head)
    for w in sorted(clock.stages):
        us = shares(clock, w)
        total = sum(us.values())
        lo, hi = w * args.window, min((w + 1) * args.window, steps) - 1
        cells = "".join(f"{us[p]:7.0f} {100 * us[p] / total:3.0f}%" for p in PARTS)
        print(f"{lo:>4}-{hi:<5}" + cells + f"{total:9.0f}")
    spent = {p: sum(shares(clock, w)[p] * clock.stages[w] for w in clock.stages) for p in PARTS}
    stages = sum(clock.stages.values())
    total = sum(spent.values()) / stages
    one = spent["one call"] / stages
    print(f"whole case: {total:.0f} us a stage; the one-call stages {one:.0f} us of it "
          f"({100 * one / total:.0f} %)")  # fmt: skip


if __name__ == "__main__":
    main()
