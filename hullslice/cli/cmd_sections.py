"""``hullslice sections``: the slice table of a hull at one draft."""

from __future__ import annotations

import argparse
import math

from .. import plots
from ..study import SectionsResult, Study, StudyResult
from ..textout import SECTION_COLUMNS, section_records, table_text
from .common import (
    Outcome,
    add_mesh_options,
    add_output_options,
    add_pose_options,
    add_section_options,
    compute,
    finish,
)
from .options import add_option


def add_parser(sub) -> None:
    p = sub.add_parser(
        "sections",
        help="cut a hull into the 2D+t slices at one draft and list them",
        description="Cut the wetted length of a hull at a draft and pitch into equal slices and "
        "list each mid-station's wetted pieces: penetration, half-beam at the waterline, "
        "deadrise, area and mass per metre.",
    )
    add_mesh_options(p, "sections")
    g = p.add_argument_group("pose and slicing")
    add_option(g, "draft", "sections")
    add_pose_options(g, "sections", pitch_rate=False, forward_speed=False)
    add_option(g, "slices", "sections")
    add_section_options(g, "sections")
    add_output_options(
        p, "sections", plot="the cut: the side view with the stations and the section outlines"
    )
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    return run_study(Study.from_args(args), args.save_case)


def run_study(study: Study, save_case: str | None = None) -> int:
    """Execute ``study`` and give its outputs; ``save_case`` also writes its case file."""
    return finish(study, outcome(compute(study, save_case)), save_case)


def outcome(result: StudyResult) -> Outcome:
    """The table, data and figure of a sections study's result."""
    assert isinstance(result, SectionsResult)
    study, hull, sections = result.study, result.hull, result.sections
    records = section_records(sections)
    data = {
        "mesh": str(study.mesh),
        "draft": sections.draft,
        "pitch_deg": math.degrees(sections.pitch),
        "wetted_length": sections.wetted_length,
        "deadrise_method": sections.deadrise_method,
        "slicing": study.slicing,
        "sections": records,
    }
    head = (
        f"{hull.name}: draft {sections.draft:g} m, pitch {math.degrees(sections.pitch):g} deg, "
        f"wetted length {sections.wetted_length:.5f} m, {sections.n_stations} slices "
        f"({study.slicing}), deadrise by {sections.deadrise_method}"
    )
    table = head + "\n" + table_text(SECTION_COLUMNS, records)
    if hull.mass is None:
        table += (
            "\nmass/m is '-': no mass given (give --mass KG or --mass-distribution CSV for "
            "the mass per metre)"
        )
    return Outcome(
        table=table,
        data=data,
        csv_columns=["j", *sections.as_dict()],
        csv_rows=records,
        figures={"sections": lambda: plots.plot_sections(hull, sections, hull.name)},
    )
