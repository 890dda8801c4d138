"""``hullslice info`` on a mesh that is not one closed surface: its shells, and the views.

Without ``--repair``, such a mesh (:class:`~hullslice.errors.OpenMeshError`) is not loaded
as a hull; ``info`` describes it shell by shell (:func:`hullslice.survey.survey_mesh`) so
that the bodies to keep can be chosen before ``--repair close --keep N``.
"""

from __future__ import annotations

from pathlib import Path

from .. import plots
from ..paths import printable
from ..study import Study
from ..survey import Survey, survey_mesh
from ..textout import Column, coordinate_text, table_text
from .outputs import Outcome

SHELL_COLUMNS = (
    Column("number", "body"),
    Column("faces", "faces"),
    Column("open_edges", "open edges"),
    Column("closes", "closes"),
    Column("inside_out", "inside out"),
    Column("volume", "volume", "m^3", ".6g"),
    Column("length", "length", "m", ".4g"),
    Column("beam", "beam", "m", ".4g"),
    Column("height", "height", "m", ".4g"),
    Column("x_min", "x from", "m", ".4g"),
    Column("x_max", "x to", "m", ".4g"),
)

#: Rows shown in the table: the largest shells that would close, and that would not.
SHOWN_CLOSING, SHOWN_OPEN = 15, 10


def survey(study: Study, reason: str) -> Survey:
    """The study's mesh described shell by shell (its units, axes, scale or length)."""
    return survey_mesh(
        study.mesh, units=study.units, forward=study.forward, up=study.up, scale=study.scale,
        length=study.length, reason=reason,
    )  # fmt: skip


def outcome(study: Study, s: Survey) -> Outcome:
    """The description, data and views of a mesh's shells."""
    lo, hi = s.bounds
    ext = hi - lo
    shells = [sh.as_dict() for sh in s.shells]
    data = {
        "mesh": str(study.mesh),
        "name": s.name,
        "file_bytes": Path(study.mesh).stat().st_size,
        "units": s.units,
        "forward": s.forward,
        "up": s.up,
        "scale": s.scale,
        "closed": False,
        "loaded": False,
        "reason": s.reason,
        "faces": len(s.faces),
        "vertices": len(s.vertices),
        "open_edges": s.open_edges,
        "nonmanifold_edges": s.nonmanifold_edges,
        "stitched": s.stitched,
        "fill_known": s.fill_known,
        "bounds_min": lo.tolist(),
        "bounds_max": hi.tolist(),
        "length": float(ext[0]),
        "beam": float(ext[1]),
        "height": float(ext[2]),
        "shells": shells,
    }
    rows = [_row(sh) for sh in shells]
    return Outcome(
        table=_table(s, data, rows),
        data=data,
        csv_columns=[c.key for c in SHELL_COLUMNS],
        csv_rows=rows,
        figures={"views": lambda: plots.plot_views(s, s.forward, s.up, None)},
    )


def _row(sh: dict) -> dict:
    closes = {True: "yes", False: "no", None: "unknown"}[sh["closes"]]
    return {
        "number": "-" if sh["number"] is None else sh["number"],
        "faces": sh["faces"],
        "open_edges": sh["open_edges"],
        "closes": closes,
        "inside_out": "yes" if sh["inside_out"] else "no",
        "volume": float("nan") if sh["volume"] is None else sh["volume"],
        "length": sh["extents"][0],
        "beam": sh["extents"][1],
        "height": sh["extents"][2],
        "x_min": sh["bounds_min"][0],
        "x_max": sh["bounds_max"][0],
    }


def _edges(n: int) -> str:
    return f"{n} edge belongs to" if n == 1 else f"{n} edges belong to"


def _vec(v, size: float) -> str:
    return "(" + ", ".join(coordinate_text(c, size) for c in v) + ")"


def _table(s: Survey, d: dict, rows: list[dict]) -> str:
    size = float(sum(x * x for x in (d["length"], d["beam"], d["height"])) ** 0.5)
    problems = []
    if d["open_edges"]:
        problems.append(f"{_edges(d['open_edges'])} a single face (holes)")
    if d["nonmanifold_edges"]:
        problems.append(
            f"{_edges(d['nonmanifold_edges'])} more than two faces (parts welded together)"
        )
    closing = [r for r in rows if r["number"] != "-"]
    other = [r for r in rows if r["number"] == "-"]
    lines = [
        f"{s.name}: {printable(d['mesh'])} ({d['file_bytes']} bytes), units {d['units']}, "
        f"forward {d['forward']}, up {d['up']}",
        f"  not one closed surface, so not loaded: {'; '.join(problems) or 'open'}; "
        "--repair close fills the holes and drops what cannot be closed, and --keep N then "
        "keeps the bodies numbered below",
        f"  faces {d['faces']}, vertices {d['vertices']}, bounding box "
        f"{_vec(d['bounds_min'], size)} to {_vec(d['bounds_max'], size)} m",
        f"  length {d['length']:.6g} m, beam {d['beam']:.6g} m, height {d['height']:.6g} m "
        f"(scale {d['scale']:.6g} m per file unit)",
    ]
    if not s.fill_known:
        lines.append(
            "  which open shells would close is unknown: pip install 'hullslice[repair]' "
            "(pymeshfix) to find out"
        )
    lines += [
        "",
        f"{len(rows)} shells; the {len(closing)} that --repair close would close are numbered "
        "by the volume they would enclose, largest first, as --repair close --keep N numbers "
        "them; then the largest of the others (body frame, m, after scaling):",
        table_text(SHELL_COLUMNS, closing[:SHOWN_CLOSING] + other[:SHOWN_OPEN]),
    ]
    hidden = max(0, len(closing) - SHOWN_CLOSING) + max(0, len(other) - SHOWN_OPEN)
    if hidden:
        lines.append(f"  ... and {hidden} more (--format json lists all)")
    return "\n".join(lines)
