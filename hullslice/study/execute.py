"""Running a :class:`~hullslice.study.Study`: the hull read, the computation made, the
result returned as objects (no text), for the outputs to be made from."""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, fields, replace
from typing import Any, cast

import numpy as np

from ..errors import InputError, OrientationWarning
from ..forces import ConvergenceStudy, convergence
from ..mass import read_mass_distribution
from ..mesh import Hull, load_hull
from ..motion import DEFAULT_STOP_ON, History, prescribed, read_kinematics, simulate
from ..orientation import Orientation, orientation
from ..sections import Sections, area_curve, cut
from ..solvers.base import SolverBase
from ..solvers.registry import get_solver
from ..state import Fluid, Motion, Pose
from .spec import Study, StudyError

__all__ = [
    "ForceStudyResult",
    "InfoResult",
    "SectionsResult",
    "SimulationResult",
    "StudyResult",
    "execute",
    "load",
    "mesh_options",
    "simulation",
]

#: Commands whose study needs the body's mass (unless a momentum-form solver does without).
_MASS_REQUIRED = ("force", "simulate")


@dataclass(frozen=True)
class StudyResult:
    """What a study computed.

    Attributes
    ----------
    study : Study
        The study that was run.
    hull : Hull
        The body as read (units, axes, scale, parts, mass).
    """

    study: Study
    hull: Hull


@dataclass(frozen=True)
class InfoResult(StudyResult):
    """The description of a mesh: its orientation and sectional area curve.

    Attributes
    ----------
    orientation : Orientation
        The file's axes, the longest one and the end that looks like the nose.
    x : ndarray, shape (stations,)
        Stations along the body, m.
    area : ndarray, shape (stations,)
        Immersed-or-not sectional area at each station, m^2.
    """

    orientation: Orientation
    x: np.ndarray
    area: np.ndarray


@dataclass(frozen=True)
class SectionsResult(StudyResult):
    """The cut of the hull at one pose.

    Attributes
    ----------
    sections : Sections
        The slices of the wetted length.
    """

    sections: Sections


@dataclass(frozen=True)
class ForceStudyResult(StudyResult):
    """The force at one state, for each slice count.

    Attributes
    ----------
    solver : SolverBase
        The 2D solver, with its settings.
    convergence : ConvergenceStudy
        The force at each count, with the extrapolation when there are three or more.
    """

    solver: SolverBase
    convergence: ConvergenceStudy


@dataclass(frozen=True)
class SimulationResult(StudyResult):
    """A time history, free fall or prescribed motion.

    Attributes
    ----------
    solver : SolverBase
        The 2D solver, with its settings.
    history : History
        The motion and the force at each instant.
    """

    solver: SolverBase
    history: History
    check: dict[str, Any] | None = None


def build_solver(study: Study) -> SolverBase:
    """The study's 2D solver, built with its options."""
    return get_solver(study.solver, **study.options)


def fluid(study: Study) -> Fluid:
    """The study's water: its density and gravity; the kinematic viscosity of sea water
    (15 deg C) at a density of :data:`SEA_FROM` or more, else of fresh water (20 deg C)."""
    if study.rho >= SEA_FROM:
        return Fluid.sea(rho=study.rho, g=study.g)
    return Fluid(rho=study.rho, g=study.g)


#: From this density on (kg/m^3) a study's water is sea water, for its viscosity.
SEA_FROM = 1020.0


def _mass_free(study: Study) -> bool:
    """A momentum-form solver's force along a prescribed motion, or at a state with the
    body's acceleration given, needs no mass."""
    if study.kinematics is None and study.acceleration is None:
        return False
    return build_solver(study).kind == "momentum"


def load(study: Study, **overrides: Any) -> Hull:
    """The hull of the study's mesh and mass; ``overrides`` replace keyword arguments of
    :func:`~hullslice.load_hull`.

    Raises
    ------
    StudyError
        A force or a simulation without the body's mass where it is needed.
    """
    dist = None
    if study.mass_distribution:
        dist = read_mass_distribution(study.mass_distribution)
    elif study.command in _MASS_REQUIRED and study.mass is None and not _mass_free(study):
        raise StudyError(
            study.command, "give the body's mass, --mass KG or --mass-distribution CSV"
        )
    options: dict[str, Any] = {
        **mesh_options(study),
        "mass": study.mass,
        "mass_distribution": dist,
        "cg": study.cg,
        "inertia": study.inertia,
    }
    return load_hull(study.mesh, **{**options, **overrides})


#: The fields of a study (and keys of a case) that say how its mesh is read and shaped.
MESH_FIELDS = ("units", "forward", "up", "scale", "length", "repair", "keep", "keep_box",
               "no_fix")  # fmt: skip


def mesh_options(source: Study | Mapping[str, Any]) -> dict[str, Any]:
    """The keyword arguments of :func:`~hullslice.load_hull` that say how a study's mesh is
    read and shaped (units, axes, scale, repair, parts, fixes; :data:`MESH_FIELDS`), without
    its mass: the same for a single run and for every case of a sweep. ``source`` is a
    study or a checked case (a key it lacks takes the study's default)."""
    if isinstance(source, Mapping):
        defaults = {f.name: f.default for f in fields(Study) if f.name in MESH_FIELDS}
        v = {**defaults, **{k: source[k] for k in MESH_FIELDS if k in source}}
    else:
        v = {k: getattr(source, k) for k in MESH_FIELDS}
    return {
        "units": v["units"],
        "forward": v["forward"],
        "up": v["up"],
        "scale": v["scale"],
        "length": v["length"],
        "repair": None if v["repair"] in (None, "none") else v["repair"],
        "keep": v["keep"],
        "keep_box": v["keep_box"],
        "fix": not v["no_fix"],
    }


def _info(study: Study) -> InfoResult:
    # the bodies are listed whatever is kept ("all" keeps all and lists them)
    hull = load(study, keep=study.keep or "all")
    forward = hull.source["forward"]  # as read: given, or the file's declared axes
    orient = orientation(hull, forward, hull.source["up"])
    if not orient.forward_is_longest:
        e = orient.mesh_extents
        warnings.warn(
            f"mesh {hull.name!r} is longest along its {orient.longest} axis "
            f"({e[orient.longest]:.6g} m) but --forward is {forward} "
            f"({e[forward.strip().lstrip('+-').lower()]:.6g} m): if the body's length "
            f"is along {orient.longest}, give --forward {orient.longest} (or "
            f"-{orient.longest})",
            OrientationWarning,
            stacklevel=3,
        )
    x, area = area_curve(hull, 40 if study.stations is None else study.stations)
    return InfoResult(study, hull, orient, x, area)


def _sections(study: Study) -> SectionsResult:
    assert study.draft is not None  # checked by Study
    hull = load(study)
    sections = cut(
        hull,
        Pose(study.draft, study.pitch_rad),
        study.slice_counts[0],
        deadrise=study.deadrise,
        slicing=study.slicing,
    )
    return SectionsResult(study, hull, sections)


def _force(study: Study) -> ForceStudyResult:
    slv = build_solver(study)
    if study.acceleration is not None and slv.kind != "momentum":
        raise StudyError(
            "force",
            f"--acceleration is for momentum-form solvers; {slv.name!r} is of the free-fall "
            "form, whose force follows from each slice's own free fall (leave --acceleration "
            "out, or choose e.g. --solver wagner)",
        )
    assert study.draft is not None and study.velocity is not None  # checked by Study
    hull = load(study)
    result = convergence(
        hull,
        Pose(study.draft, study.pitch_rad),
        Motion(study.velocity, study.horizontal_speed, study.pitch_rate_rad_s),
        slices=list(study.slice_counts),
        solver=slv,
        fluid=fluid(study),
        deadrise=study.deadrise,
        slicing=study.slicing,
        acceleration=study.acceleration,
    )
    return ForceStudyResult(study, hull, slv, result)


def _simulate(
    study: Study, progress: Callable[[float, float], None] | None, sections_every: int = 0
) -> SimulationResult:
    hull = load(study)
    slv = build_solver(study)
    kinematics = None if study.kinematics is None else read_kinematics(study.kinematics)
    history = simulation(
        study, hull, slv, kinematics, progress=progress, sections_every=sections_every
    )
    check = convergence_check(study, hull, slv, history) if study.check else None
    return SimulationResult(study, hull, slv, history, check)


def convergence_check(study: Study, hull: Hull, solver: SolverBase, history: History):
    """The same free motion at half the time step and at twice the slices: how much the
    peak force, its time and the largest pitch move (``--check``).

    Returns a dict: for ``half_step`` and ``double_slices``, the run's ``dt`` (s) and
    ``slices``, its ``peak`` (N), ``peak_t`` (s), ``pitch_max_deg``, and the changes from
    the study's run: ``peak_change`` (a share), ``peak_t_change`` (s),
    ``pitch_max_change_deg``, and ``history_change``, the largest difference of the
    vertical force at the instants both runs hold, as a share of the study's peak (the
    peak of a history sampled at a step moves with where its samples fall; the history
    itself converges or not); and ``largest_change``, the larger peak change of the two.
    """
    if study.kinematics is not None:
        raise InputError(
            "--check refines a free motion's step and slices; a prescribed motion has neither"
        )
    dt = float(cast(float, history.settings["dt"]))
    n = study.slice_counts[0]
    base = _figures(history)
    out: dict[str, Any] = {"dt": dt, "slices": n, **base}
    runs = (("half_step", dt / 2.0, n), ("double_slices", dt, 2 * n))
    for key, step, count in runs:
        other = simulation(replace(study, dt=step, slices=(count,)), hull, solver)
        fig = _figures(other)
        out[key] = {
            "dt": step, "slices": count, **fig,
            "peak_change": fig["peak"] / base["peak"] - 1.0 if base["peak"] else math.nan,
            "peak_t_change": fig["peak_t"] - base["peak_t"],
            "pitch_max_change_deg": fig["pitch_max_deg"] - base["pitch_max_deg"],
            "history_change": _history_change(history, other, dt),
        }  # fmt: skip
    out["largest_change"] = max(abs(out[k]["peak_change"]) for k in ("half_step", "double_slices"))
    return out


def _history_change(base: History, other: History, dt: float) -> float:
    """The largest difference of ``other``'s vertical force from ``base``'s at the instants
    both hold (within a thousandth of ``dt``), as a share of ``base``'s peak."""
    ta, tb = np.asarray(base.t), np.asarray(other.t)
    fa, fb = np.asarray(base.force), np.asarray(other.force)
    if not len(ta) or not len(tb):
        return math.nan
    # each of base's instants and other's nearest
    j = np.clip(np.searchsorted(tb, ta), 0, len(tb) - 1)
    before = np.maximum(j - 1, 0)
    near = np.where(np.abs(tb[before] - ta) < np.abs(tb[j] - ta), before, j)
    shared = np.abs(tb[near] - ta) <= 1e-3 * dt
    peak = float(np.max(np.abs(fa)))
    if not peak or not shared.any():
        return math.nan
    return float(np.max(np.abs(fb[near[shared]] - fa[shared]))) / peak


def _figures(history: History) -> dict[str, float]:
    pk = history.peak
    return {
        "peak": float(pk["force"]),
        "peak_t": float(pk["t"]),
        "pitch_max_deg": float(np.degrees(np.asarray(history.pitch)).max()),
    }


def simulation(
    study: Study,
    hull: Hull,
    solver: SolverBase | None = None,
    kinematics: dict[str, np.ndarray] | None = None,
    *,
    progress: Callable[[float, float], None] | None = None,
    sections_every: int = 0,
) -> History:
    """The history of a ``simulate`` study on a hull already read with its mass: the one
    computation behind ``hullslice simulate``, ``hullslice run`` and every case of a sweep
    (which reads the mesh once for all its cases).

    Parameters
    ----------
    study : Study
        A ``simulate`` study.
    hull : Hull
        Its body, with the study's mass properties.
    solver : SolverBase, optional
        The study's solver, if already built (default: built from the study).
    kinematics : dict of (k,) float arrays, optional
        The study's kinematics table, if already read (:func:`~hullslice.read_kinematics`;
        default: read from the study's file).
    progress : callable, optional
        ``progress(t, t_end)`` (s) called as the run advances.
    sections_every : int
        Keep every Nth instant's slices for the structural loads (default 0: none).
    """
    slv = build_solver(study) if solver is None else solver
    if study.kinematics is not None and kinematics is None:
        kinematics = read_kinematics(study.kinematics)
    common: dict[str, Any] = {
        "slices": study.slice_counts[0],
        "solver": slv,
        "fluid": fluid(study),
        "deadrise": study.deadrise,
        "slicing": study.slicing,
        "progress": progress,
        "sections_every": sections_every,
    }
    if study.cutter is not None:
        common["cutter"] = study.cutter
    if kinematics is None:
        assert study.velocity is not None and study.t_end is not None  # checked by Study
        return simulate(
            hull,
            study.velocity,
            study.t_end,
            dt=study.dt,
            draft=0.0 if study.draft is None else study.draft,
            pitch_rad=study.pitch_rad,
            forward_speed=study.horizontal_speed,
            pitch_rate_rad_s=study.pitch_rate_rad_s,
            free_pitch=study.free_pitch,
            free_surge=study.free_surge,
            stop_on=() if study.continue_invalid else DEFAULT_STOP_ON,
            max_flagged_share=study.max_flagged_share,
            aero=study.aero(),
            friction=study.friction,
            **common,
        )
    # a prescribed motion is evaluated over the whole table, limits flagged
    return prescribed(hull, kinematics, max_flagged_share=study.max_flagged_share, **common)


def execute(
    study: Study,
    *,
    progress: Callable[[float, float], None] | None = None,
    sections_every: int = 0,
) -> StudyResult:
    """Compute a study.

    Parameters
    ----------
    study : Study
        What to compute.
    progress : callable, optional
        ``progress(t, t_end)`` (s) called as a simulation advances.
    sections_every : int
        A simulation keeps every Nth instant's slices (default 0: none).

    Returns
    -------
    StudyResult
        :class:`InfoResult`, :class:`SectionsResult`, :class:`ForceStudyResult` or
        :class:`SimulationResult` by the study's command.
    """
    if study.command == "info":
        return _info(study)
    if study.command == "sections":
        return _sections(study)
    if study.command == "force":
        return _force(study)
    return _simulate(study, progress, sections_every)
