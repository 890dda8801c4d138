"""``hullslice simulate --pressures-out DIR``: the face pressures and frame loads of a run,
as files for the structure (:mod:`hullslice.loads.files`)."""

from __future__ import annotations

import argparse
import math
import os
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..atomic import check_writable, remove_stale, temp_prefix
from ..errors import InputError
from ..loads.files import MANIFEST, require_meshio, write_loads
from ..loads.frames import MAX_FRAMES
from .common import positive_int

__all__ = ["LoadsOutput", "add_loads_options", "loads_output"]

#: Most instants ``--pressures-out`` writes by default (``--pressures-every`` sets it).
DEFAULT_INSTANTS = 100


def _stations(text: str) -> list[float]:
    parts = [p.strip() for p in text.split(",") if p.strip()]
    try:
        x = [float(p) for p in parts]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"{text!r} is not a list of stations in m (e.g. 10.5,12,13.5)"
        ) from None
    if not x or not all(math.isfinite(v) for v in x):
        raise argparse.ArgumentTypeError(f"{text!r} is not a list of finite stations in m")
    if len(x) > MAX_FRAMES:
        raise argparse.ArgumentTypeError(f"{len(x)} frames, more than {MAX_FRAMES}")
    return x


def _spacing(text: str) -> float:
    try:
        d = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a spacing in m") from None
    if not (math.isfinite(d) and d > 0.0):
        raise argparse.ArgumentTypeError(f"{text!r} is not a positive spacing in m")
    return d


def add_loads_options(p) -> None:
    """The structural-load options of ``simulate``."""
    g = p.add_argument_group("loads for the structure")
    g.add_argument(
        "--pressures-out",
        metavar="DIR",
        help="write the pressure on every face of the mesh (Pa) at the kept instants into "
        "the folder DIR: pressure.pvd with a .vtu per instant (ParaView), peak.vtu (each "
        "face's peak pressure and its time), faces.csv and face_pressures.csv (for a "
        "finite-element model), frames.csv with --frames; needs a solver that gives "
        "pressures (--solver mlm) and the formats extra (meshio); default: none",
    )
    g.add_argument(
        "--pressures-every",
        type=positive_int,
        metavar="N",
        help=f"keep every Nth instant, with the last (default: at most {DEFAULT_INSTANTS} "
        "instants over the run)",
    )
    fr = g.add_mutually_exclusive_group()
    fr.add_argument(
        "--frames",
        type=_stations,
        metavar="X[,X...]",
        help="frame stations along the mesh's x in m: the load of each bay between frames "
        "over time goes to DIR/frames.csv (default: none)",
    )
    fr.add_argument(
        "--frame-spacing",
        type=_spacing,
        metavar="M",
        help="a frame at every multiple of M metres of the mesh's x (default: none)",
    )


@dataclass(frozen=True)
class LoadsOutput:
    """What ``--pressures-out`` asks for."""

    folder: str
    every: int | None = None
    frames: list[float] | None = None
    spacing: float | None = None

    def sections_every(self, study) -> int:
        """The keeping interval: given, or at most :data:`DEFAULT_INSTANTS` instants."""
        if self.every is not None:
            return self.every
        if study.kinematics is not None:
            from ..motion import read_kinematics

            steps = len(read_kinematics(study.kinematics)["t"])
        else:
            dt = study.dt if study.dt is not None else study.t_end / 1000.0
            steps = math.ceil(study.t_end / dt) + 1
        return max(1, math.ceil(steps / DEFAULT_INSTANTS))

    def check(self, study) -> None:
        """Refuse before any work: a solver without pressures, no meshio, a folder that
        cannot be written or that holds other files."""
        from ..solvers.registry import get_solver

        solver = get_solver(study.solver, **dict(study.solver_options))
        if not getattr(solver, "gives_pressures", False):
            raise InputError(
                f"solver {solver.name!r} gives no pressures along the sections' contours; "
                "use --solver mlm for --pressures-out"
            )
        require_meshio()
        target = Path(self.folder)
        if target.exists() and not target.is_dir():
            raise InputError(
                f"--pressures-out {self.folder!r} is a file, not a folder: give a folder"
            )
        if target.is_dir() and any(target.iterdir()) and not (target / MANIFEST).is_file():
            raise InputError(
                f"--pressures-out folder {self.folder!r} holds other files: give a new or "
                "empty folder (one written by hullslice before is replaced)"
            )
        try:
            check_writable(target)
        except OSError as exc:
            raise InputError(
                f"--pressures-out {self.folder!r} cannot be written: "
                f"{exc.strerror or exc}; give a folder you can write to"
            ) from None

    def stage(self, history, hull) -> tuple[str, Path]:
        """Write the folder's files into a hidden folder beside it. Returns the lines for
        the summary and the staged folder (:meth:`place` puts it in place whole)."""
        frames = None
        if self.frames is not None or self.spacing is not None:
            frames = history.frame_loads(hull, self.frames, spacing=self.spacing)
        target = self.target
        remove_stale(target.parent, target.name)
        stage = Path(tempfile.mkdtemp(prefix=temp_prefix(target.name), dir=target.parent))
        try:
            _, peak = write_loads(history, hull, stage, frames)
        except BaseException:
            shutil.rmtree(stage, ignore_errors=True)
            raise
        return _summary(history, peak, self.folder, frames), stage

    @property
    def target(self) -> Path:
        return Path(os.path.abspath(self.folder))

    def place(self, stage: Path) -> None:
        """Replace the folder (absent, empty or a former output) by the staged one."""
        try:
            _put_in_place(stage, self.target)
        except BaseException:
            shutil.rmtree(stage, ignore_errors=True)
            raise


def _put_in_place(stage: Path, target: Path) -> None:
    """Replace ``target`` (absent, empty or a former output) by ``stage``."""
    old = None
    if target.exists():
        old = Path(tempfile.mkdtemp(prefix=temp_prefix(target.name), dir=target.parent))
        os.rmdir(old)
        os.rename(target, old)
    try:
        os.rename(stage, target)
    except OSError:
        if old is not None:
            os.rename(old, target)
        raise
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)


def _summary(history, peak, folder: str, frames) -> str:
    """The summary's lines: the face pressures' peak (written already, not mapped again)
    and the most loaded frame bay."""
    i = int(np.argmax(peak.pressure))
    line = (
        f"face pressures: {len(history.sections)} instants of {len(peak.pressure)} faces in "
        f"{folder}; peak {peak.pressure[i] / 1e3:.6g} kPa at t = {peak.t[i]:.6g} s on face {i}"
    )
    if frames is not None and len(frames.t):
        pk = frames.peak()
        k = int(np.argmax(pk["vertical"]))
        line += (
            f"\nframe loads: {frames.bays} bays; the most loaded, x = {frames.edges[k]:.6g} to "
            f"{frames.edges[k + 1]:.6g} m, {pk['vertical'][k]:.6g} N at t = {pk['t'][k]:.6g} s"
        )
    return line


def loads_output(args: argparse.Namespace) -> LoadsOutput | None:
    """The ``--pressures-out`` request of a command line, or None."""
    folder = getattr(args, "pressures_out", None)
    every = getattr(args, "pressures_every", None)
    frames, spacing = getattr(args, "frames", None), getattr(args, "frame_spacing", None)
    if folder is None:
        given = [o for o, v in (("--pressures-every", every), ("--frames", frames),
                                ("--frame-spacing", spacing)) if v is not None]  # fmt: skip
        if given:
            raise InputError(f"{given[0]} needs --pressures-out DIR (where to write)")
        return None
    return LoadsOutput(folder, every, frames, spacing)
