"""The layout of the fused evaluation's loops (:mod:`hullslice.slices_loops`,
:mod:`hullslice.held_loops`): the columns of their output, a station's entry, their
options, the reasons' bits and their statuses."""

from __future__ import annotations

__all__ = ["COLUMNS", "ENTRY", "I_CHINE", "I_CODE", "I_MOVED", "I_ROWS", "I_SLICE", "I_SOURCE",
           "OPTIONS", "REASON_BITS", "STATUS"]  # fmt: skip

#: The float columns of the per-slice output ``fout``, by name.
COLUMNS = (
    "x", "dx", "penetration", "half_beam", "half_beam_port", "half_beam_stbd", "deadrise",
    "deadrise_port", "deadrise_stbd", "area", "mass_per_metre", "keel_slope", "keel_z",
    "y_keel", "part_half_beam", "keel_curvature", "velocity", "force_per_metre", "gamma",
    "z_tilde", "v_tilde", "a_tilde", "v_z0", "acceleration", "froude", "lift",
)  # fmt: skip
#: The integer rows of ``iout`` (``I_ROWS`` of them), by column: its source station (of
#: the kept cut), chine flag (0 or 1), reason code (bits of :data:`REASON_BITS`), whether
#: it takes its source's section moved to its depth (0 or 1), and its slice. A column is
#: an entry of a slice (a wetted piece of its section, or its dry entry), as numpy's path
#: lists them: a section in two wetted pieces (two nacelles) gives its slice two.
I_SOURCE, I_CHINE, I_CODE, I_MOVED, I_SLICE, I_ROWS = 0, 1, 2, 3, 4, 5
#: The columns of a station's entry (its wetted properties at one height of the water):
#: whether the table serves it (1 or 0), the table's wet flag, then the properties.
ENTRY = ("ok", "wet", "penetration", "half_beam", "half_beam_port", "half_beam_stbd",
         "deadrise", "deadrise_port", "deadrise_stbd", "y_keel", "part_half_beam",
         "mass_share", "chine_wetted")  # fmt: skip
#: The entries of the options array ``opts``, by name.
OPTIONS = (
    "level", "w", "u", "q", "x_cg", "frame_x_cg", "n", "c0", "n_cut", "tol", "top",
    "density", "rho_ratio", "rho_curves", "g", "froude_min", "z_lo", "z_hi", "keel_window",
    "sound", "min_deadrise", "end_face", "steep", "has_chords", "fresh",
)  # fmt: skip
#: Why a section is flagged, as bits in the order the reasons are joined: the curve
#: solver's own four checks, then a section without mass, then the checks of
#: :func:`hullslice.forces.evaluate.evaluate` (a face, a flat bottom, the chine, steep).
REASON_BITS = ("z_range", "v_tilde", "not_down", "froude", "massless", "face", "flat",
               "chine", "steep")  # fmt: skip
#: What :func:`held_loops` returns: 0 when it did the evaluation, else why numpy's path must.
STATUS = {
    0: "done",
    1: "dry: the keel is nowhere under the water",
    2: "a station outside the kept cut",
    3: "the water above the table's top (or a moved slice's)",
    4: "an inexact interval of the table, or a section in two wetted pieces",
    5: "a slice cut afresh (the first contact), opts' fresh unset (else 9)",
    6: "a keel point faster than sound, or a non-finite mass or force",
    7: "the keel line's end faces walk out of its range",
    8: "more entries than the columns hold (sections in many wetted pieces)",
    9: "slices to cut afresh where they are (the caller's: opts' fresh)",
}
