"""The fused evaluation's :class:`~hullslice.forces.result.ForceResult`
(:mod:`hullslice.forces.fused`): its loops' columns made into the sections, the loads and
the result numpy's path makes (:func:`fused_result`), a dry instant's included (no row:
the empty sections numpy's path gives a body clear of the water)."""

from __future__ import annotations

import numpy as np

from ..slices_loops import COLUMNS, I_CHINE, I_CODE, I_SLICE, I_SOURCE
from ..slicing.record import Sections, ShiftedPolygons
from ..solvers.base import SectionLoads
from ..state import Fluid, Motion, Pose
from .evaluate import CHINE_REASON, FACE_REASON, FLAT_REASON, MASSLESS_REASON, STEEP_REASON
from .result import ForceResult

__all__ = ["Reasons", "fused_result", "reason_texts"]

_COL = {name: i for i, name in enumerate(COLUMNS)}
#: The diagnostics of the curve solver, in its order.
_DIAGNOSTICS = ("gamma", "z_tilde", "v_tilde", "a_tilde", "v_z0", "acceleration", "froude")
#: The per-entry arrays of :class:`Sections` taken from the loops' columns.
_SECTION_COLUMNS = (
    "x", "dx", "penetration", "half_beam", "half_beam_port", "half_beam_stbd", "deadrise",
    "deadrise_port", "deadrise_stbd", "area", "mass_per_metre", "keel_slope", "keel_z",
    "y_keel", "part_half_beam", "keel_curvature",
)  # fmt: skip
#: The loops' columns a result reads, with their rows.
_USED = tuple(
    (name, _COL[name])
    for name in (*_SECTION_COLUMNS, *_DIAGNOSTICS, "velocity", "force_per_metre", "lift")
)


class Reasons:
    """The texts of the loops' reason codes (bit k: the k-th of ``texts``, those of
    :data:`hullslice.held_loops.REASON_BITS`), each code's joined once, as the solver and
    the checks join them."""

    def __init__(self, texts: tuple[str, ...]) -> None:
        self.texts = texts
        self._joined: dict[int, str] = {0: ""}

    def __call__(self, code: np.ndarray) -> np.ndarray:
        """The reasons' texts of the codes ``code``."""
        joined = self._joined
        out = np.empty(len(code), dtype=object)
        out[:] = [joined.get(c) if c in joined else self._join(c) for c in code.tolist()]
        return out

    def _join(self, c: int) -> str:
        text = self._joined[c] = "; ".join(t for bit, t in enumerate(self.texts) if c >> bit & 1)
        return text


def reason_texts(solver, lo: float, hi: float) -> tuple[str, ...]:
    """The texts of :data:`hullslice.held_loops.REASON_BITS`, as the solver and
    :func:`~hullslice.forces.evaluate.evaluate` word them."""
    fr_min = float(solver.settings["froude_min"])
    return (
        f"z~ outside the curves' range [{lo:.4g}, {hi:.4g}]",
        "v~ <= 0 (past the end of the curves)",
        "section not moving down into the water (no force)",
        f"Fr* <= {fr_min:g} (gravity not negligible)",
        MASSLESS_REASON,
        FACE_REASON,
        FLAT_REASON,
        CHINE_REASON,
        STEEP_REASON,
    )


def fused_result(
    rows, level: float, draft: float, m: int, length: float, fout, iout, pose: Pose,
    motion: Motion, origin: tuple[float, float], scale: float, solver: str, fluid: Fluid,
    x_cg: float, reasons: Reasons,
) -> ForceResult:  # fmt: skip
    """The :class:`ForceResult` of the loops' columns ``fout`` and ``iout`` (their first
    ``m`` rows, a slice's one after another; none where the body is dry) and the wetted
    ``length`` (m), its sections' contours from the cut's ``rows`` (by the window's
    stations) in the cutter's coordinates (``origin``, ``scale``), at the water's ``level``
    (m) and the clipped ``draft`` (m), of ``solver`` (its name) in ``fluid``, the centre
    of gravity at ``x_cg`` (m)."""
    block, ints = fout[:, :m].copy(), iout[:, :m].copy()  # the thread's to reuse
    cols = {name: block[i] for name, i in _USED}
    code = ints[I_CODE]
    z_cg = -level
    slot = ints[I_SLICE]
    first: slice | np.ndarray = slice(None)  # each slice's first row (all: one entry each)
    if m and slot[m - 1] != m - 1:  # sections in several wetted pieces
        starts = np.ones(m, dtype=bool)
        np.not_equal(slot[1:], slot[:-1], out=starts[1:])
        first = np.flatnonzero(starts)
    sections = Sections(
        station=slot,
        **{name: cols[name] for name in _SECTION_COLUMNS},
        chine_wetted=ints[I_CHINE] > 0,
        polygons=ShiftedPolygons(
            rows, (origin[0], origin[1] + z_cg), scale, cols["lift"][first], ints[I_SOURCE, first]
        ),
        deadrise_method="wedge",
        draft=draft,
        pitch=pose.pitch,
        wetted_length=length,
        z_cg=z_cg,
    )
    loads = SectionLoads(
        force_per_metre=cols["force_per_metre"],
        valid=code == 0,
        reason=reasons(code),
        # as numpy's path: none where the solver was given no section
        diagnostics={name: cols[name] for name in _DIAGNOSTICS}
        if np.isfinite(cols["gamma"]).any()
        else {},
    )
    return ForceResult(
        sections, cols["velocity"], loads, solver, fluid, Pose(sections.draft, sections.pitch),
        motion, x_cg,
    )  # fmt: skip
