"""The force on a body as the equations of motion need it: :class:`ForceModel`."""

from __future__ import annotations

import math
from typing import cast

from ..constants import SOUND_WATER
from ..forces import ForceResult, MomentumTerms, force_on, momentum_terms
from ..forces.fused import FusedEvaluation, fused_for
from ..geometry import FRAMES, KERNEL_MAX_PITCH, check_cutter, frame
from ..limits import no_mass
from ..mesh import Hull
from ..renamed import renamed_keywords
from ..sections import _check_deadrise, _check_slicing, _height_at, _slice_count, sections_at
from ..solvers.base import MOMENTUM, MomentumFormSolver, SolverBase
from ..solvers.registry import get_solver
from ..state import Acceleration, Fluid, Motion, Pose

__all__ = ["ForceModel"]


class ForceModel:
    """The 2D+t force and moment on a hull as a function of its pose and motion.

    Parameters
    ----------
    hull : Hull
        The body, with its mass.
    slices : int
        Slices over the wetted length (default 32).
    solver : str, Solver or Solver subclass, optional
        The 2D solver (default ``"extended-von-karman"``).
    fluid : Fluid, optional
        Water density and gravity.
    deadrise : str
        Deadrise estimator (default ``"wedge"``).
    slicing : str
        ``"wetted"`` (default) or ``"fixed"`` (cut once per pitch and reused), see
        :data:`~hullslice.sections.SLICINGS`.
    cache : bool
        Reuse the fixed slicing's cut (default); False cuts afresh at every call, for
        checking that both give the same numbers.
    need_mass : bool
        Refuse a hull without mass (default). A momentum-form solver along a prescribed
        motion does not need it.
    cutter : str
        How the stations of a pitch are cut (:data:`~hullslice.geometry.CUTTERS`):
        ``"manifold3d"`` (default), on the mesh turned to the pitch, or ``"exact"``, the
        kernel of :mod:`hullslice.planecut` on the body-frame mesh (the same contours to
        manifold3d's grid, much cheaper at a new pitch).
    """

    def __init__(
        self,
        hull: Hull,
        *,
        slices: int = 32,
        solver: str | SolverBase | type[SolverBase] | None = None,
        fluid: Fluid | None = None,
        deadrise: str = "wedge",
        slicing: str = "wetted",
        cache: bool = True,
        need_mass: bool = True,
        cutter: str = "manifold3d",
    ) -> None:
        self.solver = get_solver(solver)
        if hull.mass is None and (need_mass or self.solver.kind != MOMENTUM):
            raise no_mass(hull.name)
        self.hull = hull
        self.slices = _slice_count(slices)
        self.fluid = fluid or Fluid()
        self.deadrise = _check_deadrise(deadrise)
        self.slicing = _check_slicing(slicing)
        self.cache = bool(cache)
        self.cutter = check_cutter(cutter)
        self._fused: FusedEvaluation | bool | None = False  # not yet looked for

    @property
    def momentum(self) -> bool:
        """True when the solver is a momentum-form solver."""
        return self.solver.kind == MOMENTUM

    def _sections(self, pose: Pose, first: bool = False):
        height = _height_at(self.hull, pose.pitch)
        if pose.draft > height:
            pose = Pose(height, pose.pitch)
        return sections_at(
            self.hull, pose, self.slices, self.deadrise, slicing=self.slicing, cache=self.cache,
            cutter=self.cutter, first=first,
        )  # fmt: skip

    @property
    def fused(self) -> FusedEvaluation | None:
        """The fused evaluation of fixed slicing (:mod:`hullslice.forces.fused`) where its
        compiled loops describe this model, else None."""
        if self._fused is False:
            self._fused = fused_for(self)
        return cast("FusedEvaluation | None", self._fused)

    def __call__(
        self, pose: Pose, motion: Motion, acceleration: Acceleration | None = None
    ) -> ForceResult:
        """The force result at a pose (its draft clipped to the body's height) and motion;
        a momentum-form solver's with the body's ``acceleration`` (default: free in heave,
        see :func:`~hullslice.forces.compute_force`)."""
        fused = self.fused
        if fused is not None:
            r = fused.force(pose, motion)
            if r is not None:
                return r
        return self._numpy(pose, motion, acceleration)

    def _numpy(
        self,
        pose: Pose,
        motion: Motion,
        acceleration: Acceleration | None = None,
        first: bool = False,
    ) -> ForceResult:
        """:meth:`__call__` by numpy's path (the layers' steps, whatever the model);
        ``first`` as :func:`~hullslice.sections.sections_at` takes it."""
        return force_on(
            self._sections(pose, first), motion, self.solver, self.fluid,
            float(self.hull.cg[0]), acceleration=acceleration, mass=self.hull.mass,
        )  # fmt: skip

    def _first_at(
        self, z_cg: float, pitch_rad: float, w: float, u: float, q: float
    ) -> tuple[ForceResult, Pose] | None:
        """By numpy's path, at the state of an equation of motion (as :meth:`totals_at`)
        whose pitch the hull has no frame for (a free-pitch stage's new pitch), its fixed
        slices cut by the exact kernel: the result and the pose (its draft :meth:`draft`),
        the keel line read over the slices the evaluation reads
        (:meth:`~hullslice.geometry.Frame.keel_for`), as the compiled stage reads it at
        such a pitch (:meth:`~hullslice.forces.fused.FusedEvaluation.stage_result`); the
        same result but for rounding. None elsewhere (a pitch with a frame, another
        slicing or cutter, a state not finite)."""
        if not (
            self.slicing == "fixed"
            and self.cache
            and self.cutter == "exact"
            and math.isfinite(z_cg + pitch_rad + w + u + q)
            and max(abs(w), abs(u)) < SOUND_WATER
            and abs(pitch_rad) < KERNEL_MAX_PITCH
            and self.hull.cache[FRAMES].get(float(pitch_rad)) is None
        ):
            return None
        pose = Pose(self.draft(z_cg, pitch_rad), pitch_rad)  # the frame made here
        return self._numpy(pose, Motion(w, u, q), first=True), pose

    def totals(self, pose: Pose, motion: Motion) -> tuple[float, float, float]:
        """The vertical force (N), the moment about the centre of gravity (N m) and the
        horizontal force (N) of a free-fall solver at a pose and motion: what
        :meth:`__call__`'s result gives as ``total``, ``moment`` and ``total_x``, without
        the result where the fused evaluation serves."""
        fused = self.fused
        if fused is not None:
            out = fused.totals(pose, motion)
            if out is not None:
                return out
        r = self._numpy(pose, motion)
        return r.total, r.moment, r.total_x

    def totals_at(
        self, z_cg: float, pitch_rad: float, w: float, u: float, q: float
    ) -> tuple[float, float, float]:
        """:meth:`totals` with the centre of gravity at height ``z_cg`` (m), pitched by
        ``pitch_rad`` (rad), moving at ``w`` (m/s, up), ``u`` (m/s, forward) and ``q``
        (rad/s, nose up): the state of an equation of motion, checked as :class:`Pose` and
        :class:`Motion` check it where the fused evaluation does not serve."""
        fused = self.fused
        if (
            fused is not None
            and math.isfinite(z_cg + pitch_rad + w + u + q)
            and max(abs(w), abs(u)) < SOUND_WATER
        ):
            out = fused.stage_totals(pitch_rad, z_cg, w, u, q)  # a new pitch: one call
            if out is not None:
                return out
            fr = frame(self.hull, pitch_rad)
            out = fused.totals_at(fr, max(0.0, -(fr.lowest + z_cg)), w, u, q)
            if out is not None:
                return out
        got = self._first_at(z_cg, pitch_rad, w, u, q) if fused is None else None
        if got is not None:
            r = got[0]
        else:
            r = self._numpy(Pose(self.draft(z_cg, pitch_rad), pitch_rad), Motion(w, u, q))
        return r.total, r.moment, r.total_x

    def result_at(
        self, z_cg: float, pitch_rad: float, w: float, u: float, q: float
    ) -> tuple[ForceResult, Pose] | None:
        """:meth:`__call__` at the state of an equation of motion (as :meth:`totals_at`)
        with the pose of that state (its draft :meth:`draft`), where the fused evaluation
        makes it in one call at a new pitch (see
        :meth:`~hullslice.forces.fused.FusedEvaluation.stage_result`) or, by numpy's path,
        at a new pitch with its keel line read where the slices are (see
        :meth:`_first_at`), or None."""
        fused = self.fused
        if fused is None:  # numpy's path: at a new pitch, its keel line where it is read
            return self._first_at(z_cg, pitch_rad, w, u, q)
        if not math.isfinite(z_cg + pitch_rad + w + u + q) or not max(abs(w), abs(u)) < SOUND_WATER:
            return None
        return fused.stage_result(z_cg, pitch_rad, Motion(w, u, q))

    def terms(self, pose: Pose, motion: Motion) -> MomentumTerms:
        """A momentum-form solver's terms before the body's accelerations are known."""
        solver = cast(MomentumFormSolver, self.solver)
        return momentum_terms(
            self._sections(pose), motion, solver, self.fluid, float(self.hull.cg[0])
        )

    def settings(self) -> dict[str, object]:
        """The model's inputs, for a history's settings."""
        return {
            "hull": self.hull.name,
            "mass": self.hull.mass,
            "slices": self.slices,
            "solver": self.solver.name,
            "solver_kind": self.solver.kind,
            "solver_options": dict(self.solver.settings),
            "rho": self.fluid.rho,
            "g": self.fluid.g,
            "deadrise": self.deadrise,
            "slicing": self.slicing,
            "cutter": self.cutter,
        }

    @renamed_keywords(pitch="pitch_rad")
    def draft(self, z_cg: float, pitch_rad: float) -> float:
        """The draft (m, >= 0) of the body with its centre of gravity at height ``z_cg`` (m),
        pitched by ``pitch_rad`` (rad, nose up)."""
        return max(0.0, -(frame(self.hull, pitch_rad).lowest + z_cg))
