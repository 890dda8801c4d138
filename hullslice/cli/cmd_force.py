"""``hullslice force``: the 2D+t force at one state, per slice and in total, with convergence."""

from __future__ import annotations

import argparse
import math

from .. import plots
from ..atomic import write_atomic
from ..errors import InputError
from ..study import ForceStudyResult, Study, StudyResult
from ..textout import (
    SLICE_COLUMNS,
    Column,
    convergence_summary,
    force_csv,
    force_records,
    pressure_text,
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
from .options import add_options
from .outputs import Extra, check_distinct, check_path, out_path


def add_parser(sub) -> None:
    p = sub.add_parser(
        "force",
        help="the vertical force at one draft and velocity, per slice and in total",
        description="The 2D+t force on a hull at one state (draft, pitch, vertical velocity, "
        "forward speed, pitch rate), for one or more slice counts; with three or more, the "
        "Richardson-extrapolated force and its GCI error band (Roache).",
    )
    add_mesh_options(p, "force")
    g = p.add_argument_group("state and method")
    add_options(g, "force", "draft", "velocity")
    add_pose_options(g, "force")
    add_options(g, "force", "acceleration", "slices")
    add_solver_options(g, "force")
    add_section_options(g, "force")
    add_fluid_options(p, "force")
    add_output_options(
        p,
        "force",
        plot="the convergence in the slices (or, with one count, the force "
        "per metre along the body)",
    )
    p.add_argument(
        "--pressures",
        type=out_path("pressure file"),
        metavar="FILE",
        help="write the gauge pressure (Pa) along every wetted section's contour at the "
        "finest slice count to FILE: CSV (slice, x m, side, y m from the keel, z m above "
        "it, weight m, pressure Pa), or JSON when FILE ends in .json; needs a solver that "
        "gives pressures (mlm)",
    )
    p.set_defaults(func=run)


CONVERGENCE_COLUMNS = (
    Column("slices", "slices"),
    Column("force", "force", "N", "~7"),
    Column("valid", "valid"),
)

#: Columns of a pitched or moving-forward state's convergence table: with the
#: horizontal force and the pitch moment.
CONVERGENCE_PITCH_COLUMNS = (
    *CONVERGENCE_COLUMNS[:2],
    Column("force_x", "force_x", "N", "~7"),
    Column("moment", "My", "N m", "~7"),
    CONVERGENCE_COLUMNS[2],
)

#: The per-slice horizontal force, shown after F for a pitched or moving state.
SLICE_FX = Column("force_x", "Fx", "N", "~7")


def pitched(study: Study) -> bool:
    """Whether a force study's state has pitch, forward speed or pitch rate."""
    return study.pitch_rad != 0.0 or study.horizontal_speed != 0.0 or study.pitch_rate_rad_s != 0.0


def run(args: argparse.Namespace) -> int:
    return run_study(Study.from_args(args), args.save_case, getattr(args, "pressures", None))


def run_study(study: Study, save_case: str | None = None, pressures: str | None = None) -> int:
    """Execute ``study`` and give its outputs; ``save_case`` also writes its case file and
    ``pressures`` the pressures along the sections' contours."""
    extra: list[Extra] = []
    if pressures:
        check_pressures(study, pressures, save_case)
    result = compute(study, save_case)
    if pressures:
        assert isinstance(result, ForceStudyResult)
        finest = result.convergence.finest
        path = pressures
        extra.append(("--pressures", path, lambda: write_atomic(path, pressure_text(finest, path))))
    return finish(study, outcome(result), save_case, extra)


def check_pressures(study: Study, path: str, save_case: str | None = None) -> None:
    """Refuse a ``--pressures`` file before any work: a solver that gives none, or a path
    that cannot be written (or that another output writes)."""
    from ..solvers.registry import get_solver

    solver = get_solver(study.solver, **dict(study.solver_options))
    if not getattr(solver, "gives_pressures", False):
        raise InputError(
            f"solver {solver.name!r} gives no pressures along the sections' contours; "
            "use --solver mlm for --pressures"
        )
    check_path(path, study, "--pressures")
    given = [(o, p) for o, p in (("--output", study.output), ("--plot", study.plot),
                                 ("--save-case", save_case)) if p]  # fmt: skip
    check_distinct([*given, ("--pressures", path)])


def outcome(result: StudyResult) -> Outcome:
    """The tables, data and figures of a force study's result."""
    assert isinstance(result, ForceStudyResult)
    spec, hull, slv, study = result.study, result.hull, result.solver, result.convergence
    finest = study.finest
    summary = convergence_summary(study)
    records = force_records(finest)
    data = {
        "mesh": str(spec.mesh),
        "mass": hull.mass,
        "draft": spec.draft,
        "velocity": spec.velocity,
        "pitch_deg": math.degrees(spec.pitch_rad),
        "forward_speed": spec.horizontal_speed,
        "pitch_rate_deg_s": math.degrees(spec.pitch_rate_rad_s),
        "cg": [float(hull.cg[0]), float(hull.cg[2])],
        "force_x": finest.total_x,
        "moment": finest.moment,
        "solver": finest.solver,
        "solver_options": dict(slv.settings),
        "rho": finest.fluid.rho,
        "g": finest.fluid.g,
        "wetted_length": finest.sections.wetted_length,
        "deadrise_method": finest.sections.deadrise_method,
        "slicing": spec.slicing,
        "solver_kind": slv.kind,
        "acceleration": finest.acceleration.vertical if finest.acceleration else None,
        "added_mass": finest.added_mass if slv.kind == "momentum" else None,
        **summary,
        "valid": finest.all_valid,
        "slices": records,
    }
    data["slice_count"] = summary["slices"]
    figures = {
        "force_distribution": lambda: plots.plot_force_distribution(
            finest, f"{hull.name}: force per metre at {study.counts[-1]} slices"
        ),
    }
    if len(study.counts) > 1:
        figures = {
            "convergence": lambda: plots.plot_convergence(
                study, title=f"{hull.name}: convergence in the slice thickness"
            ),
            **figures,
        }
    figures["sections"] = lambda: plots.plot_sections(
        hull, finest.sections, f"{hull.name}: the cut at {study.counts[-1]} slices"
    )
    csv_columns, csv_rows = force_csv(study)
    return Outcome(
        table=_table(hull, spec, study, summary, records),
        data=data,
        csv_columns=csv_columns,
        csv_rows=csv_rows,
        figures=figures,
    )


def _table(hull, spec: Study, study, summary, records) -> str:
    finest = study.finest
    moving = pitched(spec)
    slice_columns: tuple[Column, ...] = SLICE_COLUMNS
    if moving:
        at = [c.key for c in SLICE_COLUMNS].index("force") + 1
        slice_columns = (*SLICE_COLUMNS[:at], SLICE_FX, *SLICE_COLUMNS[at:])
    lines = [
        f"{hull.name}: "
        + (f"mass {hull.mass:g} kg" if hull.mass is not None else "no mass (not needed)")
        + f", draft {spec.draft:g} m, velocity "
        f"{spec.velocity:g} m/s, wetted length {finest.sections.wetted_length:.5f} m",
    ]
    if moving:
        cg = hull.cg
        lines.append(
            f"pitch {spec.pitch_deg or 0.0:g} deg, forward speed {spec.horizontal_speed:g} m/s, "
            f"pitch rate {spec.pitch_rate_deg_s or 0.0:g} deg/s, about the centre of gravity "
            f"({significant(cg[0], 6)}, {significant(cg[2], 6)}) m"
        )
    lines += [
        f"solver {solver_label(spec)}, water {finest.fluid.rho:g} kg/m^3, "
        f"g {finest.fluid.g:g} m/s^2, deadrise by {finest.sections.deadrise_method}",
        "",
        table_text(
            CONVERGENCE_PITCH_COLUMNS if moving else CONVERGENCE_COLUMNS, summary["convergence"]
        ),
        "",
        *_answer(spec, study, moving),
        "",
        f"slices at n = {study.counts[-1]}:",
        table_text(slice_columns, records),
    ]
    return "\n".join(lines)


def _answer(spec: Study, study, moving: bool) -> list[str]:
    """The lines that give the answer, after the convergence table and before the
    per-slice one: the force at the finest count (the momentum form's added mass and
    acceleration, the horizontal force and pitch moment), the extrapolated force, and how
    many slices are outside the validity range."""
    finest = study.finest
    lines = []
    if finest.acceleration is not None:
        how = "given" if spec.acceleration is not None else "free in heave"
        lines.append(
            f"momentum form: heave added mass {finest.added_mass:.6g} kg, body acceleration "
            f"{finest.acceleration.vertical:.6g} m/s^2 ({how})"
        )
    lines.append(f"force {significant(finest.total)} N at {study.counts[-1]} slices")
    if moving:
        lines.append(
            f"horizontal force force_x {significant(finest.total_x)} N, pitch moment My "
            f"{significant(finest.moment)} N m (nose up) about the centre of gravity"
        )
    rich = study.richardson
    if finest.sections.wetted_length == 0.0:
        lines.append("no part of the body is in the water at this draft: no force")
    elif rich is not None:
        if rich.behaviour == "divergent":
            lines.append("extrapolated force: none, the forces do not converge")
        elif rich.behaviour == "converged":
            lines.append(
                f"extrapolated force {significant(rich.extrapolated)} N (the same at every count)"
            )
        else:
            lines.append(
                f"extrapolated force {significant(rich.extrapolated)} N (Richardson, order "
                f"{rich.order:.2f}, GCI {100 * rich.gci:.4f} %, {rich.behaviour})"
            )
    invalid = int((~finest.valid).sum())
    if finest.sections.wetted_length > 0.0:
        lines.append(
            "all slices inside the method's validity range"
            if invalid == 0
            else f"{invalid} of {len(finest)} slices outside the validity range (see 'reason')"
        )
    return lines
