"""``hullslice sweep CASE.toml``: many time histories on Dask, as one labelled dataset."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..atomic import check_writable
from ..errors import InputError
from ..paths import check_not_an_input
from ..progress import terminal_case_progress
from .common import check_path, out_path, positive_int, write_error
from .outputs import print_result

#: Shown by a terminal table of cases: result, heading, unit, format.
TABLE = (
    ("peak_force", "peak F", "N", ".4g"),
    ("peak_time", "at t", "s", ".5f"),
    ("peak_acceleration", "peak a", "m/s^2", ".4g"),
    ("peak_moment", "peak M", "N m", ".4g"),
    ("max_flagged_share", "flagged", "", ".3f"),
    ("stop_reason", "ended", "", ""),
    ("error", "error", "", ""),
)


def add_parser(sub) -> None:
    p = sub.add_parser(
        "sweep",
        help="run a case file's [sweep] of time histories on Dask, results as one dataset",
        description="Run the time history of a case file (command 'simulate') for every "
        "combination of the values in its [sweep] table (key = [values], full factorial, in "
        'the case file\'s units: SI, angles in degrees; or cases = "design.csv", one case '
        "per row; any number key of the case, slices, or cg_x and cg_z for a part of cg) on "
        "Dask: a local cluster of worker processes by default, one per core. "
        "The results are an xarray dataset with one dimension per swept key: peak force (N), "
        "acceleration (m/s^2) and moment (N m) with their times (s), the final state, why "
        "each run ended, the share of the force on flagged slices and any error. Needs the "
        "optional extra: pip install 'hullslice[sweep]'.",
    )
    p.add_argument("case", metavar="CASE.toml", help="the case file, with a [sweep] table")
    p.add_argument(
        "-o",
        "--output",
        type=out_path(),
        metavar="PATH",
        help="write the dataset to PATH.nc (netCDF), PATH.zarr (Zarr) or PATH.parquet (one "
        "row per case), completely or not at all; finished cases are kept in PATH.partial/ "
        "until then (default: a table of the cases on the terminal)",
    )
    where = p.add_mutually_exclusive_group()
    where.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="run on an existing Dask cluster, e.g. tcp://10.0.0.5:8786 (waits up to 10 s "
        "for it to answer; default: a local cluster)",
    )
    where.add_argument(
        "--workers",
        type=positive_int,
        metavar="N",
        help="worker processes of the local cluster (default: one per core); 1 runs in this "
        "process, without a cluster",
    )
    p.add_argument(
        "--resume",
        action="store_true",
        help="continue an interrupted sweep from PATH.partial/, skipping the finished cases",
    )
    p.add_argument(
        "--keep-histories",
        action="store_true",
        help="also keep every case's time history along a dimension t (s) (netCDF or Zarr)",
    )
    p.set_defaults(func=run)


def _inputs(case: str, plan) -> list[tuple[str, Path]]:
    """The files a sweep reads: its case file, the mesh, the cases table, the kinematics
    and mass distribution, and every solver option that names a file."""
    found = [("case", Path(case)), ("mesh", Path(plan.base["mesh"]))]
    for key, what in (("kinematics", "kinematics"), ("mass_distribution", "mass distribution")):
        if key in plan.base:
            found.append((what, Path(plan.base[key])))
    table = plan.grid.get("cases")
    if isinstance(table, str):
        found.append(("cases table", Path(case).parent / table))
    for key, value in plan.base.get("solver_options", {}).items():
        if isinstance(value, str) and Path(value).is_file():
            found.append((f"solver option {key}", Path(value)))
    return found


def _check_extras(base: dict) -> None:
    """The libraries the sweep's cases need besides the sweep's own, before any work: the
    mesh format's, and pymeshfix for ``repair = "close"``."""
    from ..extras import need
    from ..readers.extra import require_format

    if base.get("repair") == "close":
        need("repair", "pymeshfix", 'repair = "close"')
    require_format(Path(base["mesh"]).suffix)


def run(args: argparse.Namespace) -> int:
    from .. import sweeps
    from ..xarray_io import require_output, write_dataset

    sweeps.require("xarray")
    if args.workers != 1 or args.scheduler:
        sweeps.require("distributed")
    partial = None
    if args.output:
        ext = require_output(args.output)  # the format's library, before any work
        target = Path(args.output)
        store = ext == ".zarr" and target.is_dir()
        if store and not ((target / "zarr.json").is_file() or (target / ".zgroup").is_file()):
            raise InputError(
                f"cannot write {args.output!r} (--output): it is a folder that is not a Zarr "
                "store; give another name"
            )
        if store:  # written beside the store and moved into place, as its partial folder
            try:
                check_writable(args.output + ".partial")
            except OSError as exc:
                raise write_error(args.output, "--output", exc) from None
        else:
            check_path(args.output, args, "--output")
        if args.keep_histories and ext == ".parquet":
            raise InputError(
                f"cannot write {args.output!r} with --keep-histories: a Parquet file holds one "
                "row per case; write the histories to .nc or .zarr"
            )
        partial = Path(args.output + ".partial")
    elif args.resume:
        raise InputError("--resume continues the sweep written to -o PATH: give -o PATH")
    plan = sweeps.load_sweep(args.case)
    _check_extras(plan.base)
    if args.output:
        check_not_an_input(args.output, _inputs(args.case, plan), "--output")
    with terminal_case_progress() as progress:
        ds = sweeps.sweep(
            plan,
            client=args.scheduler,
            workers=args.workers,
            keep_histories=args.keep_histories,
            partial=partial,
            resume=args.resume,
            progress=progress,
        )
    failures = list(sweeps.iter_failures(ds))
    for label, error in failures[:5]:
        print(f"hullslice: case {label} failed: {error}", file=sys.stderr)
    if len(failures) > 5:
        print(f"hullslice: ... and {len(failures) - 5} more failed cases", file=sys.stderr)
    if args.output:
        ds.attrs.pop("partial", None)
        try:
            write_dataset(ds, args.output)
        except OSError as exc:
            raise write_error(args.output, "--output", exc) from None
        if partial is not None:
            sweeps.remove_partial(partial)
        print(
            f"wrote {args.output} ({len(plan.cases)} cases, {len(failures)} failed)",
            file=sys.stderr,
        )
    else:
        print_result(_table(plan, ds))
    if failures and len(failures) == len(plan.cases):
        # every case failed: the results are written (each with its error), and the exit
        # status says the inputs were refused (3), as for a single run
        print("hullslice: every case of the sweep failed", file=sys.stderr)
        return 3
    return 0


def _table(plan, ds) -> str:
    from ..textout import Column, table_text

    keys = list(plan.table) + [d for d in plan.dims if d != "case"]
    columns = [Column(k, k, ds[k].attrs.get("units", ""), "g") for k in keys]
    columns += [Column(k, label, unit, fmt) for k, label, unit, fmt in TABLE]
    flat = ds.stack(point=plan.dims) if plan.dims else ds
    rows = []
    for i in range(len(plan.cases)):
        row = {k: v for k, v in plan.cases[i].items()}
        point = flat.isel(point=i)
        for k, *_ in TABLE:
            v = point[k].values.item()
            row[k] = v
        rows.append(row)
    return table_text(columns, rows)
