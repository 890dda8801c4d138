"""``hullslice info``: what a mesh file holds: size, volume, mass properties, area curve."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from .. import plots
from ..errors import OpenMeshError
from ..paths import printable
from ..study import InfoResult, Study, StudyResult
from ..textout import Column, coordinate_text, significant, table_text
from . import shells
from .common import (
    Outcome,
    add_mesh_options,
    add_output_options,
    check_output,
    check_path,
    compute,
    finish,
    out_path,
)
from .options import add_option

AREA_COLUMNS = (Column("x", "x", "m", ".5g"), Column("area", "area", "m^2", ".6g"))

#: Relative tolerance of a flat maximum of the area curve: the stations whose area is
#: within it of the largest, next to the largest one, make the span it is reported over.
FLAT_MAXIMUM = 1e-3


def largest_span(x: np.ndarray, area: np.ndarray) -> tuple[float, float]:
    """The x span (m) of the stations around the largest area whose area is within
    :data:`FLAT_MAXIMUM` of it (one station: both ends the same)."""
    i = int(np.argmax(area))
    floor = area[i] - FLAT_MAXIMUM * abs(area[i])
    lo = hi = i
    while lo > 0 and area[lo - 1] >= floor:
        lo -= 1
    while hi < len(area) - 1 and area[hi + 1] >= floor:
        hi += 1
    return float(x[lo]), float(x[hi])


def add_parser(sub) -> None:
    p = sub.add_parser(
        "info",
        help="a mesh's size, volume, mass properties and sectional area curve",
        description="Read a hull mesh as the other commands do (units, axes, checks and "
        "repairs) and describe it: bounding box, faces, volume, the mass properties with "
        "--mass or --mass-distribution, and the sectional area curve. A mesh that is not "
        "one closed surface (holes, parts welded together) is described shell by shell "
        "without --repair: faces, extent, open edges, whether --repair close would close "
        "it and the volume it would then enclose, and its views.",
    )
    add_mesh_options(p, "info")
    add_option(p, "stations", "info")
    add_output_options(p, "info", plot="the sectional area curve")
    p.add_argument(
        "--write-mesh",
        type=out_path(),
        metavar="OUT.stl",
        help="also write the mesh as checked and repaired (after --units, axes, --scale, "
        "--keep, --keep-box), in metres and the body frame (x forward, z up): binary STL, "
        "OBJ or Cart3D .tri by the extension; .ply, .off, .glb or .3mf need "
        "pip install 'hullslice[formats]'",
    )
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    study = Study.from_args(args)
    if args.write_mesh:
        check_mesh_output(args.write_mesh, study, args.save_case)
    return run_study(study, args.save_case, args.write_mesh)


def check_mesh_output(out: str, study: Study, save_case: str | None = None) -> None:
    """Refuse a ``--write-mesh`` path before any work: a folder, a missing or read-only
    folder, one of the inputs, another output of the run (:func:`check_output`), or a
    format hullslice does not write."""
    from ..errors import InputError
    from ..readers.write import WRITERS

    check_path(out, study, "--write-mesh")
    ext = Path(out).suffix.lower().lstrip(".")
    if ext not in WRITERS:
        raise InputError(
            f"cannot write {printable(out)!r} (--write-mesh): a mesh is written as "
            f"{', '.join(WRITERS)} by the file's extension; name it .stl or .obj"
        )
    check_output(study, save_case, out)


def run_study(study: Study, save_case: str | None = None, write_mesh: str | None = None) -> int:
    """Execute ``study`` and give its outputs; ``save_case`` also writes its case file,
    ``write_mesh`` the checked and repaired mesh (m, body frame), all or none. A mesh
    that is not one closed surface, read without ``--repair``, is described shell by shell
    (:mod:`hullslice.cli.shells`)."""
    try:
        result = compute(study, save_case, write_mesh=write_mesh)
    except OpenMeshError as exc:
        if write_mesh or study.repair not in (None, "none"):
            raise
        return finish(study, shells.outcome(study, shells.survey(study, str(exc))), save_case)
    extra = []
    if write_mesh:
        mesh_path = write_mesh
        extra.append(("--write-mesh", mesh_path, lambda: result.hull.save(mesh_path)))
    return finish(study, outcome(result), save_case, extra)


def outcome(result: StudyResult) -> Outcome:
    """The description, data and figures of an info study's result."""
    assert isinstance(result, InfoResult)
    study, hull, orient = result.study, result.hull, result.orientation
    x, area = result.x, result.area
    lo, hi = hull.bounds
    ext = hull.extents
    path = Path(study.mesh)
    data = {
        "mesh": str(study.mesh),
        "name": hull.name,
        "file_bytes": path.stat().st_size,
        "units": hull.source["units"],
        "forward": hull.source["forward"],
        "up": hull.source["up"],
        "faces": len(hull.faces),
        "vertices": len(hull.vertices),
        "closed": True,
        "repairs": list(hull.source.get("repairs", ())),
        "bounds_min": lo,
        "bounds_max": hi,
        "length": ext[0],
        "beam": ext[1],
        "height": ext[2],
        "volume": hull.volume,
        "surface_area": float(hull.manifold.surface_area()),
        "centre_of_volume": hull.centroid,
        "mass": hull.mass,
        "density": hull.density,
        "cg": hull.cg if hull.mass is not None else None,
        "pitch_inertia": hull.pitch_inertia if hull.mass is not None else None,
        "mass_distribution": study.mass_distribution,
        "scale": hull.source.get("scale"),
        "orientation": orient.as_dict(),
        "bodies": hull.source.get("bodies", []),
        "kept": list(hull.source.get("kept", ())),
        "area_curve": {"x": x, "area": area},
        "max_area": float(area.max()),
        "max_area_x": float(x[int(np.argmax(area))]),
    }
    data["max_area_x_from"], data["max_area_x_to"] = largest_span(x, area)
    rows = [{"x": xi, "area": ai} for xi, ai in zip(x, area, strict=True)]
    return Outcome(
        table=_table(hull, data, rows),
        data=data,
        csv_columns=["x", "area"],
        csv_rows=rows,
        figures={
            "views": lambda: plots.plot_views(
                hull, hull.source["forward"], hull.source["up"], orient.nose
            ),
            "area_curve": lambda: plots.plot_area_curve(
                x, area, f"{hull.name}: sectional area curve"
            ),
        },
    )


def _vec(v, size: float) -> str:
    """A point in m, coordinates below the mesh's tolerance (rounding noise) as 0."""
    return "(" + ", ".join(coordinate_text(c, size) for c in v) + ")"


def _table(hull, d, rows) -> str:
    repairs = d["repairs"]
    size = hull.size
    lines = [
        f"{hull.name}: {printable(d['mesh'])} ({d['file_bytes']} bytes), units {d['units']}, "
        f"forward {d['forward']}, up {d['up']}",
        f"  faces {d['faces']}, vertices {d['vertices']}, closed (checked on loading)"
        + (f"; repaired: {'; '.join(repairs)}" if repairs else ", no repair needed"),
        f"  bounding box {_vec(d['bounds_min'], size)} to {_vec(d['bounds_max'], size)} m",
        f"  length {d['length']:.6g} m, beam {d['beam']:.6g} m, height {d['height']:.6g} m",
        f"  volume {d['volume']:.6g} m^3, surface {d['surface_area']:.6g} m^2, centre of volume "
        f"{_vec(d['centre_of_volume'], size)} m",
    ]
    if d["mass"] is not None:
        lines.append(
            f"  mass {d['mass']:.6g} kg, mean density {d['density']:.6g} kg/m^3, centre of "
            f"gravity {_vec(d['cg'], size)} m, pitch inertia {d['pitch_inertia']:.6g} kg*m^2"
        )
    else:
        lines.append("  no mass given (--mass KG for the mass properties)")
    lines += _orientation_lines(d) + _body_lines(d)
    x_from, x_to = d["max_area_x_from"], d["max_area_x_to"]
    where = (
        f"at x = {coordinate_text(d['max_area_x'], size)} m"
        if x_from == x_to
        else f"from x = {coordinate_text(x_from, size)} to {coordinate_text(x_to, size)} m, "
        f"within {FLAT_MAXIMUM:.1%} of it"
    )
    lines += [
        "",
        f"sectional area curve ({len(rows)} stations; largest {significant(d['max_area'], 6)} "
        f"m^2 {where}):",
        table_text(AREA_COLUMNS, rows),
    ]
    return "\n".join(lines)


BODY_COLUMNS = (
    Column("number", "body"),
    Column("faces", "faces"),
    Column("closed", "closed"),
    Column("volume", "volume", "m^3", ".6g"),
    Column("length", "length", "m", ".4g"),
    Column("beam", "beam", "m", ".4g"),
    Column("height", "height", "m", ".4g"),
    Column("x_min", "x from", "m", ".4g"),
    Column("x_max", "x to", "m", ".4g"),
    Column("kept", "kept"),
)


def _orientation_lines(d) -> list[str]:
    o = d["orientation"]
    e = o["mesh_extents"]
    scale = f" (scale {d['scale']:.6g} m per file unit)" if d["scale"] else ""
    fwd = o["forward"].strip().lstrip("+-").lower()
    longest = (
        f"the forward axis {o['forward']} is the longest"
        if o["longest_axis"] == fwd
        else f"the longest is {o['longest_axis']}, not the forward axis {o['forward']}"
    )
    if o["nose"] is None:
        nose = f"  nose: no end looks like one: {o['nose_reason']}"
    else:
        where = (
            "the +x end, where --forward points"
            if o["nose"] == "fore"
            else ("the -x end, against --forward: if so, give the opposite --forward")
        )
        nose = f"  nose: looks like the {o['nose']} end ({where}): {o['nose_reason']}"
    return [
        f"  extents along the file's axes: x {e['x']:.6g} m, y {e['y']:.6g} m, z "
        f"{e['z']:.6g} m{scale}; {longest}",
        nose,
    ]


def _body_lines(d) -> list[str]:
    bodies = d["bodies"]
    if len(bodies) <= 1:
        return [f"  one body ({'closed' if not bodies or bodies[0]['closed'] else 'open'})"]
    rows = [
        {
            "number": b["number"],
            "faces": b["faces"],
            "closed": b["closed"],
            "volume": b["volume"] if b["volume"] is not None else float("nan"),
            "length": b["extents"][0],
            "beam": b["extents"][1],
            "height": b["extents"][2],
            "x_min": b["bounds_min"][0],
            "x_max": b["bounds_max"][0],
            "kept": b["kept"],
        }
        for b in bodies
    ]
    shown = rows[:20]
    more = [f"  ... and {len(rows) - 20} more (--format json lists all)"] if len(rows) > 20 else []
    return [
        "",
        f"{len(bodies)} separate bodies, largest first (--keep largest or --keep N,M keeps "
        "some; body frame, m, after scaling):",
        table_text(BODY_COLUMNS, shown),
        *more,
    ]
