"""``hullslice simulate``: a time history, free fall or along prescribed kinematics."""

from __future__ import annotations

import argparse
import sys

import numpy as np

from .. import plots
from ..motion import DEFAULT_STOP_ON, MAX_FLAGGED_SHARE, STOP_RULES
from ..study import SimulationResult, Study, StudyResult
from ..textout import (
    HISTORY_COLUMNS,
    HISTORY_PITCH_COLUMNS,
    Column,
    history_records,
    history_summary,
    table_text,
)
from .common import (
    Outcome,
    add_fluid_options,
    add_mesh_options,
    add_output_options,
    add_pose_options,
    add_section_options,
    add_solver_options,
    compute,
    finish,
    number,
    positive_int,
    solver_label,
)

TABLE_ROWS = 40


def add_parser(sub) -> None:
    p = sub.add_parser(
        "simulate",
        help="time history of a free fall, or of the force along prescribed kinematics",
        description="Free fall: integrate the body's motion (M + A) dw/dt = F - m g from "
        "first contact (or --draft) with the 2D+t force (A: the added mass of a momentum-form "
        "solver, zero for a free-fall one), with pitch and surge when free. Prescribed: "
        "compute the force along a table of t, draft, velocity (--kinematics). The run "
        "stops early when the body stops sinking, the water reaches a chine, or slices "
        "outside the solver's range carry more than --max-flagged-share of the force "
        "(--continue-invalid goes on with flagged values).",
    )
    add_mesh_options(p, mass_required=True)
    g = p.add_argument_group("motion")
    g.add_argument(
        "--velocity",
        type=number("m/s"),
        metavar="M/S",
        help="initial vertical velocity in m/s, negative downward (free fall)",
    )
    g.add_argument(
        "--t-end", type=number("s"), metavar="S", help="duration of the run in s (free fall)"
    )
    g.add_argument(
        "--dt",
        type=number("s"),
        metavar="S",
        help="time step in s (default: t-end / 1000)",
    )
    g.add_argument(
        "--draft",
        type=number("m"),
        default=0.0,
        metavar="M",
        help="initial draft of the lowest point in m (default: 0, first contact)",
    )
    add_pose_options(g)
    g.add_argument(
        "--free-pitch",
        action="store_true",
        help="integrate the pitch from the moment about the centre of gravity (default: the "
        "pitch changes at the constant --pitch-rate)",
    )
    g.add_argument(
        "--free-surge",
        action="store_true",
        help="integrate the forward speed from the horizontal force (default: constant)",
    )
    g.add_argument(
        "--kinematics",
        metavar="CSV",
        help="prescribed motion: CSV with columns t (s), draft (m, positive), "
        "velocity (m/s, negative down), optionally acceleration (m/s^2, up; derived from "
        "velocity when absent), pitch_deg, pitch_rate_deg_s, forward_speed (m/s)",
    )
    g.add_argument(
        "--continue-invalid",
        action="store_true",
        help="go on to the end when a stop rule is met, with flagged values "
        f"(rules: {', '.join(DEFAULT_STOP_ON)})",
    )
    g.add_argument(
        "--max-flagged-share",
        type=number(""),
        default=MAX_FLAGGED_SHARE,
        metavar="SHARE",
        help="stop when slices outside the solver's range carry more than this share of "
        f"the force, 0 to 1 (default: {MAX_FLAGGED_SHARE:g})",
    )
    m = p.add_argument_group("method")
    m.add_argument(
        "--slices",
        type=positive_int,
        default=32,
        metavar="N",
        help="slices over the wetted length at each instant (default: 32)",
    )
    add_solver_options(m)
    add_section_options(m)
    add_fluid_options(p)
    add_output_options(p, plot="the history (force, acceleration, velocity, draft, pitch)")
    p.set_defaults(func=run)


class Progress:
    """A one-line progress display on a terminal's stderr."""

    def __init__(self) -> None:
        self.shown = -1

    def __call__(self, t: float, t_end: float) -> None:
        pct = int(100 * t / t_end) if t_end > 0 else 100
        if pct != self.shown:
            self.shown = pct
            sys.stderr.write(f"\rsimulating: t = {t:.5f} s of {t_end:g} s ({pct:3d} %)")
            sys.stderr.flush()

    def done(self) -> None:
        if self.shown >= 0:
            sys.stderr.write("\r" + " " * 60 + "\r")
            sys.stderr.flush()


def run(args: argparse.Namespace) -> int:
    return run_study(Study.from_args(args), args.save_case)


def run_study(study: Study, save_case: str | None = None) -> int:
    """Execute ``study`` (with a progress line on a terminal) and give its outputs."""
    progress = Progress() if sys.stderr.isatty() else None
    try:
        result = compute(study, save_case, progress)
    finally:
        if progress is not None:
            progress.done()
    return finish(study, outcome(result), save_case)


def outcome(result: StudyResult) -> Outcome:
    """The table, data and figures of a simulation study's result."""
    assert isinstance(result, SimulationResult)
    study, hull, history = result.study, result.hull, result.history
    summary = history_summary(history)
    title = (
        f"{hull.name}: {history.mode}, pitch {history.settings.get('initial_pitch_deg', 0):g} deg"
        if history.mode != "prescribed"
        else f"{hull.name}: prescribed motion"
    )
    figures = {"history": lambda: plots.plot_history(history, title)}
    if np.any(history.forward_speed != 0):
        x = hull.bounds[:, 0]
        figures["footprint"] = lambda: plots.plot_footprint(
            [history], [hull.name], (float(x[0]), float(x[1]))
        )
    return Outcome(
        table=_table(hull, history, summary, solver_label(study)),
        data={"mesh": str(study.mesh), **summary, "history": history.columns()},
        csv_columns=list(history.COLUMNS),
        csv_rows=history_records(history),
        figures=figures,
    )


def _table(hull, history, summary, solver_text) -> str:
    s = history.settings
    every = max(1, -(-len(history) // TABLE_ROWS))
    columns: tuple[Column, ...] = HISTORY_COLUMNS
    if np.any(history.pitch != 0) or np.any(history.forward_speed != 0):
        columns = (*HISTORY_COLUMNS[:5], *HISTORY_PITCH_COLUMNS, *HISTORY_COLUMNS[5:])
    mass = f"mass {hull.mass:g} kg" if hull.mass is not None else "no mass (not needed)"
    head = f"{hull.name}: {history.mode}, {mass}, solver {solver_text}, " + (
        f"{s['slices']} slices, dt {s['dt']:g} s" if "dt" in s else f"{s['slices']} slices"
    )
    lines = [head, "", table_text(columns, history_records(history, every))]
    if every > 1:
        lines.append(f"(one instant in {every} of {len(history)} shown; --format csv for all)")
    lines.append("")
    if summary["peak"] is not None:
        pk = summary["peak"]
        lines.append(
            f"peak force {pk['force']:.3f} N at t = {pk['t']:.5f} s (draft {pk['draft']:.5f} "
            f"m, velocity {pk['velocity']:.4f} m/s, acceleration {pk['acceleration']:.3f} m/s^2)"
        )
    reason = history.stop_reason
    lines.append(f"ended: {STOP_RULES.get(reason, reason)}")
    lines.append(
        f"flagged share of the force: largest {100 * summary['max_flagged_share']:.3g} % "
        f"(slices outside the solver's range; a run stops above "
        f"{100 * s.get('max_flagged_share', MAX_FLAGGED_SHARE):g} %)"
    )
    for rule, t in history.first_crossed.items():
        if t is not None:
            lines.append(f"limit '{rule}' first crossed at t = {t:.5f} s: {STOP_RULES[rule]}")
    return "\n".join(lines)
