"""``hullslice simulate``: a time history, free fall or along prescribed kinematics."""

from __future__ import annotations

import argparse
import shutil
import sys
from dataclasses import replace

import numpy as np

from .. import plots
from ..aero import AERO_NUMBERS
from ..errors import InputError
from ..motion import MAX_FLAGGED_SHARE, STOP_RULES
from ..motion.history import STEP_CHANGE_WARN
from ..progress import terminal_progress
from ..study import SimulationResult, Study, StudyResult
from ..textout import (
    HISTORY_COLUMNS,
    HISTORY_PITCH_COLUMNS,
    Column,
    history_records,
    history_summary,
    significant,
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
    solver_label,
)
from .loads_out import LoadsOutput, add_loads_options, loads_output
from .options import add_option, add_options

TABLE_ROWS = 40


def add_aero_options(p) -> None:
    """The air's forces and the water's friction (a free motion)."""
    a = p.add_argument_group("air and friction")
    add_options(a, "simulate", "lift", *(name for name, _, _ in AERO_NUMBERS))
    add_options(a, "simulate", "friction", "check")


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
    add_mesh_options(p, "simulate")
    g = p.add_argument_group("motion")
    add_options(g, "simulate", "velocity", "t_end", "dt", "draft")
    add_pose_options(g, "simulate")
    add_options(g, "simulate", "free_pitch", "free_surge", "kinematics", "continue_invalid")
    add_option(g, "max_flagged_share", "simulate")
    add_aero_options(p)
    m = p.add_argument_group("method")
    add_option(m, "slices", "simulate")
    add_solver_options(m, "simulate")
    add_section_options(m, "simulate")
    add_option(m, "cutter", "simulate")
    add_fluid_options(p, "simulate")
    add_output_options(
        p, "simulate", plot="the history (force, acceleration, velocity, draft, pitch)"
    )
    add_loads_options(p)
    r = p.add_argument_group("rows")
    rows = r.add_mutually_exclusive_group()
    add_options(rows, "simulate", "every", "at")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    return run_study(Study.from_args(args), args.save_case, loads_output(args))


def run_study(study: Study, save_case: str | None = None, loads: LoadsOutput | None = None) -> int:
    """Execute ``study`` (with a progress line on a terminal, :mod:`hullslice.progress`)
    and give its outputs; ``loads`` also writes the face pressures and frame loads
    (``--pressures-out``)."""
    every = 0
    if loads is not None:
        loads.check(study)
        every = loads.sections_every(study)
    with terminal_progress() as progress:
        result = compute(study, save_case, progress, sections_every=every)
    out = outcome(result)
    if loads is None:
        return finish(study, out, save_case)
    assert isinstance(result, SimulationResult)
    line, stage = loads.stage(result.history, result.hull)
    data = {**out.data, "pressures_out": {"folder": loads.folder, "summary": line}}
    out = replace(out, table=out.table + "\n" + line, data=data)
    try:
        code = finish(study, out, save_case)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
    loads.place(stage)
    print(f"wrote {loads.folder}", file=sys.stderr)
    return code


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
    chosen = chosen_rows(history, study.every, study.at)
    data: dict = {"mesh": str(study.mesh), **summary}
    if chosen is None:
        data["history"] = history.columns()
    else:
        data["rows"] = {"every": study.every, "at": study.at, "index": chosen}
        data["history"] = {k: v[chosen] for k, v in history.columns().items()}
    if np.any(history.forward_speed != 0):
        x = hull.bounds[:, 0]
        figures["footprint"] = lambda: plots.plot_footprint(
            [history], [hull.name], (float(x[0]), float(x[1]))
        )
    table = _table(hull, history, summary, solver_label(study), chosen, study)
    if result.check is not None:
        data["check"] = result.check
        table += "\n" + check_text(result.check)
    return Outcome(
        table=table,
        data=data,
        csv_columns=list(history.COLUMNS),
        csv_rows=history_records(history, indices=chosen),
        figures=figures,
    )


def chosen_rows(history, every: int | None, at) -> list[int] | None:
    """The instants asked for: every ``every``-th with the first and the last, or the one
    nearest each time of ``at`` (s, in time order, each once); None when neither is given.

    Raises
    ------
    InputError
        A time of ``at`` outside the run, naming its range.
    """
    n = len(history)
    if every is not None:
        idx = list(range(0, n, every))
        if n and idx[-1] != n - 1:
            idx.append(n - 1)
        return idx
    if at is None:
        return None
    t = np.asarray(history.t, dtype=float)
    if n == 0:
        raise InputError("--at: the run has no instant to show")
    lo, hi = float(t[0]), float(t[-1])
    slack = 1e-9 * max(abs(lo), abs(hi), 1e-300)
    for ti in at:
        if not lo - slack <= ti <= hi + slack:
            ended = STOP_RULES.get(history.stop_reason, history.stop_reason)
            raise InputError(
                f"--at {ti:g} s is outside the run, which goes from t = {lo:g} to {hi:g} s "
                f"(ended: {ended}); give times in that range"
            )
    return sorted({int(np.argmin(np.abs(t - ti))) for ti in at})


def _table(hull, history, summary, solver_text, chosen, study) -> str:
    s = history.settings
    every = max(1, -(-len(history) // TABLE_ROWS))
    columns: tuple[Column, ...] = HISTORY_COLUMNS
    if np.any(history.pitch != 0) or np.any(history.forward_speed != 0):
        columns = (*HISTORY_COLUMNS[:5], *HISTORY_PITCH_COLUMNS, *HISTORY_COLUMNS[5:])
    mass = f"mass {hull.mass:g} kg" if hull.mass is not None else "no mass (not needed)"
    head = f"{hull.name}: {history.mode}, {mass}, solver {solver_text}, " + (
        f"{s['slices']} slices, dt {s['dt']:g} s" if "dt" in s else f"{s['slices']} slices"
    )
    if chosen is not None:
        lines = [head, "", table_text(columns, history_records(history, indices=chosen))]
        how = f"every {study.every}" if study.every is not None else "nearest the times asked"
        lines.append(f"({len(chosen)} of {len(history)} instants shown, {how})")
    else:
        lines = [head, "", table_text(columns, history_records(history, every))]
        if every > 1:
            lines.append(
                f"(one instant in {every} of {len(history)} shown; --every N or --at S,S for "
                "others, --format csv for all)"
            )
    lines.append("")
    if summary["peak"] is not None:
        pk = summary["peak"]
        lines.append(
            f"peak force {significant(pk['force'])} N at t = {pk['t']:.5f} s "
            f"(draft {pk['draft']:.5f} m, velocity {pk['velocity']:.4f} m/s, "
            f"acceleration {pk['acceleration']:.3f} m/s^2)"
        )
        if pk.get("at_end"):
            lines.append(
                "the largest force is the last sample: still rising at the end of the run "
                "(the peak may lie beyond it; run longer)"
            )
    jump = history.step_change
    if history.mode != "prescribed" and jump["share"] > STEP_CHANGE_WARN:
        lines.append(
            f"the force changes by {100 * jump['share']:.3g} % of its peak in one step (to "
            f"t = {jump['t']:.5f} s): the step may be too long for the load; halve --dt or "
            "run --check"
        )
    hz = summary.get("horizontal")
    if hz is not None and np.any(history.forward_speed != 0):
        lines.append(
            f"largest horizontal load {significant(hz['force'])} N against the motion at "
            f"t = {hz['t']:.5f} s ({hz['g']:.3f} g; water, air and friction)"
        )
    reason = history.stop_reason
    lines.append(f"ended: {STOP_RULES.get(reason, reason)}")
    hint = solver_hint(history)
    if hint:
        lines.append(hint)
    lines.append(
        f"flagged share of the force: largest {100 * summary['max_flagged_share']:.3g} % "
        f"(slices outside the solver's range; a run stops above "
        f"{100 * s.get('max_flagged_share', MAX_FLAGGED_SHARE):g} %)"
    )
    suction = history.suction_share
    if len(suction) and suction.max() > 0.0:
        i = int(np.argmax(suction))
        lines.append(
            f"suction held at the water's bound (it cavitates or ventilates) on up to "
            f"{100 * suction[i]:.3g} % of the wetted length, at t = {history.t[i]:.5f} s"
        )
    for rule, t in history.first_crossed.items():
        if t is not None:
            lines.append(f"limit '{rule}' first crossed at t = {t:.5f} s: {STOP_RULES[rule]}")
    return "\n".join(lines)


#: Solvers that carry a body with forward speed and round sections through a ditching.
DITCHING_SOLVERS = ("mlm", "zarnick")


def solver_hint(history) -> str:
    """A line naming the solvers that can run a case whose solver stopped it early (its
    range left in the first tenth of the run), or ``""``."""
    s = history.settings
    solver = str(s.get("solver", ""))
    t_end = s.get("t_end")
    if history.stop_reason not in ("validity", "chine") or solver in DITCHING_SOLVERS:
        return ""
    if not len(history) or t_end is None or history.t[-1] > 0.1 * float(t_end):
        return ""
    return (
        f"the solver {solver!r} left its range at t = {history.t[-1]:.4g} s of {t_end:g} s: "
        "for a ditching, a planing hull or round sections use --solver mlm (the MLM: "
        "separation, round sections, pressures) or --solver zarnick (planing strip theory)"
    )


#: A peak that moves more than this share under --check is said not to be converged.
CHECK_TOLERANCE = 0.02


def check_text(check: dict) -> str:
    """The lines of a ``--check``: what the peak, its time and the largest pitch did at half
    the time step and at twice the slices."""
    lines = [f"check (peak {significant(check['peak'])} N at t = {check['peak_t']:.5f} s, "
             f"largest pitch {check['pitch_max_deg']:.3f} deg, dt {check['dt']:g} s, "
             f"{check['slices']} slices):"]  # fmt: skip
    for key, what in (("half_step", "half the time step"), ("double_slices", "twice the slices")):
        c = check[key]
        lines.append(
            f"  {what} (dt {c['dt']:g} s, {c['slices']} slices): peak "
            f"{100 * c['peak_change']:+.3f} %, its time {c['peak_t_change']:+.5f} s, largest "
            f"pitch {c['pitch_max_change_deg']:+.4f} deg; the force at the instants both "
            f"hold within {100 * c['history_change']:.3f} % of the peak"
        )
    worst = check["largest_change"]
    verdict = "converged" if worst <= CHECK_TOLERANCE else "NOT converged"
    shares = [check[k]["history_change"] for k in ("half_step", "double_slices")]
    history = max((v for v in shares if v == v), default=float("nan"))  # NaN: no instant
    if worst <= CHECK_TOLERANCE:
        hint = ""
    elif (
        check["half_step"]["history_change"]
        <= CHECK_TOLERANCE
        < abs(check["half_step"]["peak_change"])
    ):
        hint = (
            " (at half the step the force agrees at the instants both hold: the peak"
            " falls between the step's samples; compare peaks at the step you will use)"
        )
    else:
        hint = " (refine the step or the slices)"
    lines.append(
        f"  the peak moved by {100 * worst:.3f} % at most, the force at shared instants by "
        f"{100 * history:.3f} % of the peak: {verdict} to {100 * CHECK_TOLERANCE:g} %{hint}"
    )  # fmt: skip
    return "\n".join(lines)
