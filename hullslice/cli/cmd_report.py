"""``hullslice report CASE.toml -o DIR``: a report folder for a case, to attach to a study."""

from __future__ import annotations

import argparse
import dataclasses
import html
import shutil
import sys
import tempfile
from pathlib import Path

from .._version import __version__
from ..atomic import _umask, check_writable, remove_stale, temp_prefix, write_atomic
from ..case import SCHEMA, load_case, write_case
from ..errors import InputError
from ..paths import markdown_fence, markdown_text, printable, run_inputs
from ..progress import terminal_progress
from ..study import Study, execute
from ..textout import csv_text, json_text
from . import cmd_info
from .common import check_extras, out_path, write_error
from .studies import command_module


def add_parser(sub) -> None:
    p = sub.add_parser(
        "report",
        help="write a report folder for a case file: inputs, mesh, tables, figures, data",
        description="Run a case file and write a folder with a report (Markdown, or HTML with "
        "--html) that gives the inputs, the mesh summary, the results table, the figures "
        "(PNG) and the data (CSV and JSON), with the case file itself so that the study can "
        "be repeated. The folder is written completely or not at all.",
    )
    p.add_argument("case", metavar="CASE.toml", help="the case file")
    p.add_argument(
        "-o",
        "--output",
        type=out_path("folder"),
        metavar="DIR",
        required=True,
        help="the report folder",
    )
    p.add_argument("--html", action="store_true", help="write report.html (default: report.md)")
    p.add_argument(
        "--overwrite",
        action="store_true",
        help="replace the folder if it exists and is not empty (default: refuse)",
    )
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    target = Path(args.output)
    if target.exists() and not target.is_dir():
        raise InputError(f"report folder {args.output!r} is a file: give a folder name")
    if target.is_dir() and any(target.iterdir()) and not args.overwrite:
        raise InputError(
            f"report folder {args.output!r} exists and is not empty: give another folder, or "
            "--overwrite to replace it"
        )
    parent = target.resolve().parent
    if not parent.is_dir():
        raise InputError(f"the folder {str(parent)!r} does not exist; create it first")
    try:  # a folder made and removed beside the target: the same rights as the report's
        check_writable(parent / target.name)
    except OSError as exc:
        raise write_error(args.output, "--output", exc) from None
    case = load_case(args.case)
    _refuse_inputs_inside(target, args.case, case)
    study = Study.from_case(case, checked=True)
    # the report gives every output itself; the case file is an input, like the mesh
    study = dataclasses.replace(study, format=None, output=None, plot=None, case_file=args.case)
    check_extras(study, figures=True)
    with terminal_progress("report") as progress:
        name = _write_report(args, target, parent, case, study, progress)
    print(f"wrote {target / name}", file=sys.stderr)
    return 0


def _write_report(args, target: Path, parent: Path, case, study: Study, progress) -> str:
    """Compute the case and write its report folder, saying how far it is on a terminal's
    stderr (``progress``, a :class:`~hullslice.progress.TimeProgress`, or None off a
    terminal); the report's name."""

    def note(text: str) -> None:
        if progress is not None:
            progress.show(text)

    command = study.command
    note(f"running the {command} case")
    result = execute(study, progress=progress)
    outcome = command_module(command).outcome(result)
    if command == "info":
        info = outcome
    else:
        note("the mesh summary")
        info = cmd_info.outcome(execute(study.for_command("info")))

    # built beside the target (same depth, so that the case's relative paths hold) and
    # renamed into place only when complete
    remove_stale(parent, target.name)
    work = Path(tempfile.mkdtemp(prefix=temp_prefix(target.name), dir=parent))
    try:
        files = _write_files(work, case, outcome, info, command, note)
        page = _html if args.html else _markdown
        name = "report.html" if args.html else "report.md"
        write_atomic(work / name, page(case, command, outcome, info, files))
        work.chmod(0o777 & ~_umask())  # an ordinary folder, not a private temporary one
        if target.exists():
            shutil.rmtree(target)
        work.rename(target)
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        raise
    return name


def _refuse_inputs_inside(target: Path, case_path: str, case) -> None:
    """The report folder must not hold the case or its inputs: it is replaced whole."""
    folder = target.resolve()
    inputs = [Path(case_path), *(v for v in case.values() if isinstance(v, Path))]
    # a solver's own files (a curve table) are inputs too
    inputs += [p for _, p in run_inputs(_OptionsOf(case.get("solver_options", {})))]
    for path in inputs:
        p = path.resolve()
        if p == folder or folder in p.parents:
            raise InputError(
                f"report folder {str(target)!r} holds the input {str(path)!r}, and the folder "
                "is written anew: give a report folder of its own"
            )
    if folder == Path.cwd().resolve() or folder in Path.cwd().resolve().parents:
        raise InputError(
            f"report folder {str(target)!r} is the working folder or holds it: give a folder "
            "of its own"
        )


class _OptionsOf:
    """The solver options of a case in the form :func:`run_inputs` reads."""

    def __init__(self, options: dict) -> None:
        self.solver_option = list(options.items())


def _write_files(work: Path, case, outcome, info, command, note) -> dict[str, str]:
    files: dict[str, str] = {}
    case_out = {k: v for k, v in case.items() if k not in ("output", "plot", "format")}
    case_out["command"] = command
    write_case(case_out, work / "case.toml")
    files["case.toml"] = "the case, to repeat the study: hullslice run case.toml"
    write_atomic(work / "results.json", json_text(outcome.data))
    files["results.json"] = "the results, every number"
    write_atomic(work / "results.csv", csv_text(outcome.csv_columns, outcome.csv_rows))
    files["results.csv"] = "the results table"
    if command != "info":
        write_atomic(work / "mesh.json", json_text(info.data))
        files["mesh.json"] = "the mesh summary"
    from ..plots import save

    figures = dict(outcome.figures)
    if command != "info":
        figures.update(info.figures)
    for i, (fig_name, build) in enumerate(figures.items()):
        note(f"drawing the figures ({i + 1} of {len(figures)}: {fig_name.replace('_', ' ')})")
        save(build(), work / f"{fig_name}.png")
        files[f"{fig_name}.png"] = fig_name.replace("_", " ")
    return files


#: Keys of a case that are not inputs of its computation: its outputs (the report gives its
#: own), the rows its tables show, and the title (the report's heading).
NOT_INPUTS = ("format", "output", "plot", "every", "at", "title")


def _inputs(case) -> list[tuple[str, str, str]]:
    """The inputs table: ``(key, value, unit)`` of every input of the case (not
    :data:`NOT_INPUTS`), in the case's order."""
    rows = []
    for name, value in case.items():
        if name in NOT_INPUTS:
            continue
        key = SCHEMA[name]
        if isinstance(value, dict):
            value = ", ".join(f"{k} = {v}" for k, v in value.items())
        elif isinstance(value, Path):
            value = value.name
        rows.append((name, printable(value), key.unit))
    return rows


def _markdown(case, command, outcome, info, files) -> str:
    title = markdown_text(case.get("title") or f"{command} of {Path(case['mesh']).name}")
    mesh_fence = markdown_fence(info.table)
    results_fence = markdown_fence(outcome.table)
    lines = [
        f"# {title}",
        "",
        f"hullslice {__version__}, command `{command}`. Units SI (angles in degrees); vertical "
        "velocity negative downward, forces positive upward.",
        "",
        "## Inputs",
        "",
        "| key | value | unit |",
        "| --- | --- | --- |",
        *[f"| {k} | {markdown_text(v)} | {u} |" for k, v, u in _inputs(case)],
        "",
        "## Mesh",
        "",
        mesh_fence,
        info.table.split("\nsectional area curve")[0],
        mesh_fence,
        "",
        "## Results",
        "",
        results_fence,
        outcome.table,
        results_fence,
        "",
        "## Figures",
        "",
        *[f"![{desc}]({name})\n" for name, desc in files.items() if name.endswith(".png")],
        "## Files",
        "",
        *[f"- `{name}`: {desc}" for name, desc in files.items()],
        "",
    ]
    return "\n".join(lines)


def _html(case, command, outcome, info, files) -> str:
    title = html.escape(printable(case.get("title") or f"{command} of {Path(case['mesh']).name}"))
    rows = "".join(
        f"<tr><td>{html.escape(k)}</td><td>{html.escape(v)}</td><td>{html.escape(u)}</td></tr>"
        for k, v, u in _inputs(case)
    )
    figures = "".join(
        f'<figure><img src="{n}" alt="{html.escape(d)}"><figcaption>{html.escape(d)}'
        "</figcaption></figure>"
        for n, d in files.items()
        if n.endswith(".png")
    )
    listing = "".join(
        f"<li><code>{html.escape(n)}</code>: {html.escape(d)}</li>" for n, d in files.items()
    )
    mesh = html.escape(info.table.split("\nsectional area curve")[0])
    return (
        "<!DOCTYPE html>\n<html><head><meta charset='utf-8'>"
        f"<title>{title}</title><style>body{{font-family:sans-serif;max-width:60em;margin:auto}}"
        "table{border-collapse:collapse}td,th{border:1px solid #999;padding:2px 6px}"
        "pre{background:#f4f4f4;padding:6px;overflow-x:auto}img{max-width:100%}</style>"
        f"</head><body><h1>{title}</h1><p>hullslice {__version__}, command <code>{command}"
        "</code>. Units SI (angles in degrees); vertical velocity negative downward, forces "
        f"positive upward.</p><h2>Inputs</h2><table><tr><th>key</th><th>value</th><th>unit"
        f"</th></tr>{rows}</table><h2>Mesh</h2><pre>{mesh}</pre><h2>Results</h2><pre>"
        f"{html.escape(outcome.table)}</pre><h2>Figures</h2>{figures}<h2>Files</h2><ul>"
        f"{listing}</ul></body></html>\n"
    )
