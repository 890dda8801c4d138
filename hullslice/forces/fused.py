"""The fused evaluation of fixed slicing: the compiled loops of :mod:`hullslice.held_loops`
in place of the slicing's, the solver's and the sums' numpy steps.

It serves a :class:`~hullslice.motion.model.ForceModel` whose evaluation those loops
describe: fixed slicing cut once per pitch and kept (``slicing="fixed"``, ``cache=True``),
the ``wedge`` deadrise, a curve solver with the paper's pile-up law and polynomial curves
(the default ``extended-von-karman``), and a body of one piece whose mass is spread by
volume. At a held pitch with its waterline table it reads the table; at a new pitch (every
stage of a free-pitch run) it evaluates the sections of the stations it cuts, as numpy's
path does; at a pitch the hull has no frame for (every stage of a free-pitch step), one
compiled call makes the keel line, the cut, the outline and the sums
(:meth:`FusedEvaluation.stage_totals`, and :meth:`FusedEvaluation.stage_result` with the
result), with no frame kept. The first contact's slices (no wetted station near) are cut
where they are, as numpy's path cuts them, by the call or, at a frame, by numpy's cut
(:meth:`FusedEvaluation._fresh`). At any evaluation the loops hand back (a section in two
wetted pieces, the evaluation that makes a pitch's table), numpy's path serves. Both give
the same numbers (to 1e-12; the tests compare them over whole histories); the fused one
costs some microseconds an evaluation where numpy's costs some hundreds. It needs numba
(the ``fast`` extra) and is switched off with ``HULLSLICE_NUMBA=0``, as the other
compiled loops.
"""

from __future__ import annotations

import math
import threading
from collections import deque
from typing import Any

import numpy as np

from .. import planecut_loops
from ..constants import SOUND_WATER, TOL
from ..contour_loops import empty_memo
from ..geometry import CUTTER_SIZE, FRAMES, KERNEL_MAX_PITCH, _side_order, frame
from ..kernel.keel import END_FACE_SLOPE, STEEP_SLOPE
from ..kernel.waterline_table import WaterlineTable
from ..planecut import StationRings, plane_index
from ..slices_loops import COLUMNS, ENTRY, I_MOVED, I_ROWS, OPTIONS
from ..slicing import fixed as fixed_slicing
from ..slicing.assemble import keel_window
from ..slicing.own_keel import pieces
from ..solvers.base import FREE_FALL
from ..solvers.karman import CurveSolver
from ..state import Fluid, Motion, Pose
from .evaluate import MIN_DEADRISE
from .fused_arrays import keel_arrays, stage_arrays, table_arrays
from .fused_result import Reasons, fused_result, reason_texts
from .result import ForceResult

__all__ = ["FusedEvaluation", "fused_for"]

#: How many of its last pitches a thread remembers having cut in one call: one met again
#: goes the steps one by one, which make and keep its frame (a pitch held still, whose
#: kept cut and waterline tables then serve).
SEEN_PITCHES = 8
#: The one call's status where the keel line is nowhere under the water, and what
#: :meth:`FusedEvaluation._one_call` returns in place of the contours then (numpy's path
#: sums no section: zero, and its result has none).
DRY_STATUS = 1
#: The one-call stage's hint of its outline's order (see
#: :func:`~hullslice.outline_loops.outline_loops`): room for this many edges less one, a
#: few hundred kB a thread; a stage with more edges sorts them.
HINT_SIZE = 1 << 15
DRY = "dry"
#: The loops' columns per slice: room for the entries of sections in several wetted
#: pieces (a fuselage and its two nacelles); beyond it numpy's path serves.
ROWS_PER_SLICE = 4

_OPT = {name: i for i, name in enumerate(OPTIONS)}
# the options FusedEvaluation._run sets at each evaluation, by place
assert [_OPT[k] for k in ("level", "w", "u", "q", "frame_x_cg", "c0", "n_cut", "top",
                          "has_chords", "fresh")] == [0, 1, 2, 3, 5, 7, 8, 10, 23, 24]  # fmt: skip
#: No slice cut afresh (see :func:`~hullslice.held_loops.pitch_loops`): the loops' first
#: call, which asks for those of the first contact.
_NO_FRESH = (np.empty((0, len(ENTRY))), np.zeros(1, dtype=np.int64), np.empty(0))


def _serves(solver) -> bool:
    """Whether the loops compute ``solver``'s force: a curve solver with the paper's pile-up
    law and polynomial curves, as :class:`~hullslice.solvers.karman.CurveSolver` has them."""
    kind = type(solver)
    return (
        isinstance(solver, CurveSolver)
        and solver.kind == FREE_FALL
        and kind.section_loads is CurveSolver.section_loads
        and kind.pile_up is CurveSolver.pile_up
        and solver.curves.table is None
        and set(solver.settings) == {"froude_min"}
    )


def fused_for(model) -> FusedEvaluation | None:
    """The fused evaluation for a force model, or None where its loops do not describe the
    model's evaluation (see the module notes), or numba is not installed or switched off
    (``HULLSLICE_NUMBA=0``, read here: when the model first evaluates)."""
    hull = model.hull
    if not (
        model.slicing == "fixed"
        and model.cache
        and model.deadrise == "wedge"
        and hull.mass is not None
        and hull.mass_distribution is None
        and _serves(model.solver)
    ):
        return None
    loops = _loops()  # numba's, before the body's pieces are counted (a second on 1M faces)
    return None if loops is None or pieces(hull).n > 1 else FusedEvaluation(model, loops)


def _loops():
    """The compiled loops of :mod:`hullslice.held_loops` (``held_loops``, ``pitch_loops``,
    ``window_loops``), or None without numba (or with ``HULLSLICE_NUMBA=0``)."""
    if not planecut_loops.available():
        return None
    return tuple(planecut_loops.compiled(name) for name in ("held", "pitch", "window"))


class FusedEvaluation:
    """A force model's fused evaluation: :meth:`force` and :meth:`totals` give what the
    model gives at a pose and motion, or None where numpy's path must."""

    def __init__(self, model, loops) -> None:
        self.model = model
        self.loops, self.pitch, self.window = loops
        # the keel line's arrays by the compiled loops where these are compiled
        compiled = self.loops is not planecut_loops.LOOPS["held"]
        self.pack = planecut_loops.compiled("keel_arrays") if compiled else None
        # a new pitch's frame, cut, outline and sums in one call, with the compiled loops,
        # its arguments kept in one object (hullslice.stage_kit)
        self.stage = planecut_loops.compiled("stage") if compiled else None
        self.kit_stage: Any = None
        self.kit_rings: Any = None
        if self.stage is not None:
            from .. import stage_kit

            self.kit_stage, self.kit_rings = stage_kit.kit_stage_loops, stage_kit.kit_rings_loops
        # the wetted entries of sections cut afresh (the first contact's slices)
        entries = planecut_loops.compiled("h_entries") if compiled else None
        self.entries = entries or planecut_loops.LOOPS["h_entries"]
        self._stage_args: tuple | None = None
        hull = model.hull
        self.hull = hull
        self.key = (model.slices, float(TOL.coordinate * hull.size), model.cutter)
        self.fluid: Fluid = model.fluid
        solver = model.solver
        curves = solver.curves
        lo, hi = curves.z_range
        opts = np.zeros(len(OPTIONS))
        for name, value in {
            "x_cg": float(hull.cg[0]),
            "n": model.slices,
            "tol": self.key[1],
            "density": hull.mass / hull.volume,
            "rho_ratio": curves.rho / self.fluid.rho,
            "rho_curves": curves.rho,
            "g": self.fluid.g,
            "froude_min": float(solver.settings["froude_min"]),
            "z_lo": lo,
            "z_hi": hi,
            "keel_window": keel_window(hull),
            "sound": SOUND_WATER,
            "min_deadrise": MIN_DEADRISE,
            "end_face": END_FACE_SLOPE,
            "steep": STEEP_SLOPE,
        }.items():
            opts[_OPT[name]] = value
        self._opts = opts  # each thread fills a copy (see _buffers)
        self.a_c = np.array(curves.a_coeffs, dtype=np.float64)
        self.v_c = np.array(curves.v_coeffs, dtype=np.float64)
        self.reasons = Reasons(reason_texts(solver, lo, hi))
        self._local = threading.local()
        self.x_cg = float(hull.cg[0])

    def _buffers(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """This thread's options, sums and scratch columns (a model may serve the threads
        of a Dask worker at once, and the loops release the GIL)."""
        buffers = getattr(self._local, "buffers", None)
        if buffers is None:
            n = self.model.slices
            buffers = self._local.buffers = (
                self._opts.copy(), np.empty(8), *_columns(n),
            )  # fmt: skip
        return buffers

    def _keel(self, fr, kept) -> dict[str, Any]:
        """The loops' arrays of a frame's keel line, made once per kept cut (by the
        compiled :func:`~hullslice.keel_loops.keel_arrays_loops` with the compiled loops:
        the same arrays)."""
        arrays = kept.plans.get("keel")
        if arrays is None:
            arrays = kept.plans["keel"] = keel_arrays(fr, self.pack)
        return arrays

    def _run(self, fr, draft: float, w: float, u: float, q: float, fout, iout):
        """The loops at a frame (its pitch), a draft (m, clipped to the body's height) and
        the body's velocities (m/s, m/s, rad/s): ``(rows, c0, level, draft, sums)`` when
        they did the evaluation (the kept cut's contours from its station ``c0``; the
        loops' ``scal``, this thread's), or None.

        With the kept cut's waterline table, :func:`~hullslice.held_loops.held_loops`;
        before the evaluation that makes one (or where one costs too much),
        :func:`~hullslice.held_loops.pitch_loops` on the stations it cuts, as numpy's path
        cuts them. An evaluation counts as numpy's path counts them."""
        height = fr.highest - fr.lowest
        if draft > height:
            draft = height
        level = fr.lowest + draft
        kept = fixed_slicing.fixed_cut(fr, *self.key)
        with kept._lock:  # the kept cut's table, outline and contours of one moment
            table = kept.tables.get("wedge")
            outline, rows, held = kept.outline, kept.rows, kept.range
        opts, scal, _, _ = self._buffers()
        args = (level, w, u, q, fout, iout, opts, scal)
        if table is not None and held is not None and table.outline is outline:
            done = self._held(fr, kept, table, rows, held[0], *args)
        elif table is None:
            done = self._pitch(fr, kept, *args)
        else:  # the kept cut grew: numpy's path makes its table again
            return None
        if done is None:
            return None
        with kept._lock:
            kept.evaluations += 1
        return (*done, level, draft, scal)

    def _options(self, opts, level, w, u, q, fr, c0, n_cut, top, keel) -> np.ndarray:
        opts[0], opts[1], opts[2], opts[3] = level, w, u, q
        opts[5] = fr.cg[0]
        opts[7] = c0
        opts[8] = n_cut
        opts[10] = top
        opts[23] = keel["has_chords"]
        return opts

    def _held(self, fr, kept, table, rows, c0, level, w, u, q, fout, iout, opts, scal):
        """The loops with the kept cut's waterline table (``rows`` from station ``c0``:
        its outline's contours)."""
        plan = kept.plans.get("wedge")
        if plan is None or plan[0] is not table:
            plan = kept.plans["wedge"] = (table, table_arrays(table))
        keel = self._keel(fr, kept)
        arrays = plan[1]
        self._options(opts, level, w, u, q, fr, c0, arrays["n_cut"], table.top, keel)
        status, fresh = self._fresh(fr, level, fout, iout, opts, scal, lambda *f: self.loops(
            fout, iout, scal, opts, keel["keel"], keel["runs"], keel["chords"],
            arrays["stations"], arrays["heights"], arrays["tkey"], arrays["tvals"], self.a_c,
            self.v_c, *f,
        ))  # fmt: skip
        if status == 3:
            higher = self._higher(kept, table, float(scal[7]))
            if higher is not None:
                return self._held(fr, kept, higher, rows, c0, level, w, u, q, fout, iout, opts,
                                  scal)  # fmt: skip
        return ([*rows, *fresh] if fresh else rows, c0) if status == 0 else None

    def _fresh(self, fr, level: float, fout, iout, opts, scal, call) -> tuple[int, list]:
        """``call(e_f, f_f, area_f)`` of the loops (:func:`~hullslice.held_loops.held_loops`
        or :func:`~hullslice.held_loops.pitch_loops`) with the first contact's slices (no
        wetted station near) cut where they are, as numpy's path cuts them
        (``slicing.fixed._with_fresh``: its outline and wetted properties), where the loops
        ask for them: ``(status, polys)``, the slices' contours (none asked)."""
        opts[24] = 1.0
        status = call(*_NO_FRESH)
        if status != 9:
            return status, []
        m = int(scal[0])
        x = fout[0, :m][iout[I_MOVED, :m] == 2]  # their relative x, in order
        o, polys = fixed_slicing.outline_of(fr, x, self.key[1], self.model.cutter)
        e_f, f_f = self.entries(_outline_arrays(o), np.full(len(x), level), self.key[1])
        return call(e_f, f_f, o.area), list(polys)

    def _pitch(self, fr, kept, level, w, u, q, fout, iout, opts, scal):
        """The loops on the stations cut afresh: the evaluations of a pitch before its
        table, or where its table costs too much."""
        keel = self._keel(fr, kept)
        status, w0, w1 = self.window(keel["keel"], level, self.model.slices)
        if status != 0:
            return None
        outline, rows, c0 = kept.window(fr, w0, w1, self.model.cutter)
        if kept.evaluations + 1 >= fixed_slicing.TABLE_AFTER:  # numpy's path makes a table
            too_high = kept.too_high.get("wedge")
            if too_high is None or too_high[0] is not outline or level < too_high[1]:
                return None
        o = outline
        stations = np.stack([o.zmin, o.z_chine, o.area])
        self._options(opts, level, w, u, q, fr, c0, o.n_stations, math.inf, keel)
        status, fresh = self._fresh(fr, level, fout, iout, opts, scal, lambda *f: self.pitch(
            fout, iout, scal, opts, keel["keel"], keel["runs"], keel["chords"], stations,
            _outline_arrays(o), self.a_c, self.v_c, *f,
        ))  # fmt: skip
        return ([*rows, *fresh] if fresh else rows, c0) if status == 0 else None

    def _higher(self, kept, table, need: float):
        """The kept cut's waterline table made again, up to above ``need`` (m, the water's
        height the loops asked for: the water's own, or that at which a partial slice takes
        its moved section), or None where it would cost too much (kept on the cut, for
        every model). The table's intervals and their samples do not depend on its top:
        the same values, more of them; numpy's path reads it as its own."""
        outline = table.outline
        too_high = kept.plans.get("too_high")
        if too_high is not None and too_high[0] is outline and need >= too_high[1]:
            return None
        new = WaterlineTable.of(outline, need, table.tol, "wedge")
        if new is None or new.top < need:
            kept.plans["too_high"] = (outline, need)
            return None
        with kept._lock:
            if kept.tables.get("wedge") is not table:  # another thread made one
                return None
            kept.tables["wedge"] = new
        return new

    def _one_call(self, pitch: float, z_cg: float, w: float, u: float, q: float):
        """:func:`~hullslice.planecut_loops.stage_loops` at a pitch (rad) the hull has no
        frame for and this thread has not cut in one call lately, the centre of gravity at
        height ``z_cg`` (m), the body's velocities ``w``, ``u``, ``q``, all finite, by
        :func:`~hullslice.stage_kit.kit_stage_loops` on this thread's kit (its buffers,
        the sums and columns those of :meth:`_buffers`): ``(kit, extra, scal)`` (the
        contours kept on the kit, :func:`~hullslice.stage_kit.kit_rings_loops`; ``extra``
        and ``scal`` the call's, see there), or None where the steps one by one must
        serve: numpy's loops, another cutter, a pitch with a frame (its kept cut and
        tables), a pitch met again (its frame is made then, and its kept cut and tables
        serve it from there on), or a status of the call. Where the keel line is nowhere
        under the water, ``(DRY, extra, None)``: the pitch is not kept as met (a frame
        would serve it no better; the two middle stages of a step in the air share a
        pitch).

        The stage's loops are compiled (numba, read when the model first evaluated: see
        :func:`fused_for`), so the keel line of the steps one by one would be too
        (:func:`~hullslice.geometry.keel_loops`): the same numbers either way."""
        call = self.kit_stage
        pitch = float(pitch)
        if call is None or self.key[2] != "exact" or not abs(pitch) < KERNEL_MAX_PITCH:
            return None
        if self.hull.cache[FRAMES].get(pitch) is not None:
            return None
        state = getattr(self._local, "stage", None)
        if state is None:  # this thread's: the pitches met, the kit, and what it holds
            state = self._local.stage = (deque(maxlen=SEEN_PITCHES), *self._kit())
        seen, kit, extra, scal = state[:4]
        if pitch in seen:
            return None
        seen.append(pitch)
        status = call(kit, float(np.cos(pitch)), float(np.sin(pitch)), z_cg, w, u, q)
        if status == DRY_STATUS:
            seen.pop()
            return DRY, extra, None
        if status != 0:
            return None
        return kit, extra, scal

    def _kit(self) -> tuple:
        """This thread's kit of :func:`~hullslice.planecut_loops.stage_loops`'s arguments
        (:func:`~hullslice.stage_kit.new_kit`), its ``extra`` and ``scal``, then the
        arguments it holds: those it reads of the hull, in its order up to ``reach_z``,
        with this thread's own (the ends' order, the scratch array, the candidate ranges
        found last, by station (its guesses), and the outline's last order, its hint of
        :data:`HINT_SIZE` integers), and its buffers after the six numbers of a stage but
        the memo. The memo of the stations cut last
        (:func:`~hullslice.contour_loops.memo_cut_loops`) starts empty."""
        from ..stage_kit import new_kit

        args = self._stage_args
        if args is None:
            args = self._stage_args = stage_arrays(self.hull, self.key[1], self.model.slices)
        index = plane_index(self.hull)
        order = _side_order(self.hull, 2 * len(args[0]))
        guess = np.full((self.model.slices, len(index.bin_zlo), 2), -1)
        hint = np.full(HINT_SIZE, -1, dtype=np.int64)  # the outline's last order
        hull = (*args[:4], order, *args[4:20], index.scratch(), guess, hint, *args[20:])
        opts, scal, fout, iout = self._buffers()
        extra = np.empty(8)
        buffers = (fout, iout, scal, extra, opts, self.a_c, self.v_c)
        kit = new_kit(hull, buffers, empty_memo(len(index.bin_zlo)))
        return kit, extra, scal, hull, buffers

    def stage_totals(
        self, pitch: float, z_cg: float, w: float, u: float, q: float
    ) -> tuple[float, float, float] | None:
        """:meth:`totals_at` at a new pitch (rad; every later stage of a free-pitch step),
        the centre of gravity at height ``z_cg`` (m), all finite: the keel line, the cut,
        the outline and the sums in one compiled call, with no frame made or kept; the
        same sums. None where the steps one by one must serve (see :meth:`_one_call`)."""
        done = self._one_call(pitch, z_cg, w, u, q)
        if done is None:
            return None
        return (0.0, 0.0, 0.0) if done[0] is DRY else _sums(done[-1])  # dry: no section

    def stage_result(
        self, z_cg: float, pitch: float, motion: Motion
    ) -> tuple[ForceResult, Pose] | None:
        """:meth:`force` at a new pitch (rad; the first stage of a free-pitch step), the
        centre of gravity at height ``z_cg`` (m), all finite, in one compiled call (as
        :meth:`stage_totals`), with the pose the model gives that state
        (:meth:`~hullslice.motion.model.ForceModel.draft`): the same result and pose.
        None where the steps one by one must serve (see :meth:`_one_call`). A dry body's
        result has no section, as numpy's path's."""
        _, _, fout, iout = self._buffers()  # the result takes copies of what it needs
        done = self._one_call(pitch, z_cg, motion.velocity, motion.forward_speed,
                              motion.pitch_rate)  # fmt: skip
        if done is None:
            return None
        kit, extra, scal = done
        dry = kit is DRY
        if dry:
            rows: Any = ()
        else:
            points, ring_start, ring_station = self.kit_rings(kit)
            rows = StationRings(points, ring_start, ring_station, int(extra[1]))
        m, length = (0, 0.0) if dry else (int(scal[0]), float(scal[1]))
        pose = Pose(float(extra[6]), pitch)
        scale = CUTTER_SIZE / self.hull.size  # the frame's (geometry._frame)
        r = self._result(rows, float(extra[4]), float(extra[5]), m, length, fout, iout, pose,
                         motion, (float(extra[2]), float(extra[3])), scale)  # fmt: skip
        return r, pose

    def totals(self, pose: Pose, motion: Motion) -> tuple[float, float, float] | None:
        """The vertical force (N), the moment about the centre of gravity (N m) and the
        horizontal force (N) at a pose and motion, or None where numpy's path must."""
        fr = frame(self.hull, pose.pitch)
        return self.totals_at(fr, pose.draft, motion.velocity, motion.forward_speed,
                              motion.pitch_rate)  # fmt: skip

    def totals_at(
        self, fr, draft: float, w: float, u: float, q: float
    ) -> tuple[float, float, float] | None:
        """:meth:`totals` at a frame (its pitch), a draft (m, >= 0) and the body's vertical
        velocity, forward speed (m/s) and pitch rate (rad/s), all finite."""
        _, _, fout, iout = self._buffers()
        done = self._run(fr, draft, w, u, q, fout, iout)
        return None if done is None else _sums(done[-1])

    def force(self, pose: Pose, motion: Motion) -> ForceResult | None:
        """The :class:`ForceResult` at a pose and motion, or None where numpy's path must."""
        _, _, fout, iout = self._buffers()  # the result takes copies of what it needs
        fr = frame(self.hull, pose.pitch)
        done = self._run(fr, pose.draft, motion.velocity, motion.forward_speed,
                         motion.pitch_rate, fout, iout)  # fmt: skip
        if done is None:
            return None
        rows, _, level, draft, scal = done
        return self._result(rows, level, draft, int(scal[0]), float(scal[1]), fout, iout, pose,
                            motion, fr.origin, fr.scale)  # fmt: skip

    def _result(self, rows, level, draft, m, length, fout, iout, pose, motion, origin, scale):
        """:func:`~hullslice.forces.fused_result.fused_result` of this model."""
        return fused_result(rows, level, draft, m, length, fout, iout, pose, motion, origin,
                            scale, self.model.solver.name, self.fluid, self.x_cg,
                            self.reasons)  # fmt: skip


def _outline_arrays(o) -> tuple:
    """An :class:`~hullslice.kernel.outline.Outline`'s arrays as the loops read them."""
    return (o.station, o.ya, o.za, o.yb, o.zb, o.zlo, o.start, o.area, o.contour, o.part_area,
            o.part_station, o.part_zmax, o.part_ymin, o.part_ymax, o.z_chine)  # fmt: skip


def _columns(n: int) -> tuple[np.ndarray, np.ndarray]:
    """The loops' float and integer columns for ``n`` slices (see
    :data:`~hullslice.slices_loops.COLUMNS`, :data:`~hullslice.slices_loops.I_ROWS`)."""
    size = ROWS_PER_SLICE * n
    return np.empty((len(COLUMNS), size)), np.empty((I_ROWS, size), dtype=np.int64)


def _sums(scal: np.ndarray) -> tuple[float, float, float]:
    """The vertical force (N), the moment (N m) and the horizontal force (N) of the loops'
    sums."""
    return float(scal[2]), float(scal[4]), float(scal[3])
