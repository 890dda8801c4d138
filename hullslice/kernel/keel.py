"""The keel line: the lower edge of a body's side view at one pitch, ``Z_k(X)``, as a polyline.

Built from the side views of the body's silhouette edges (their lower envelope, exact at
every end point) and evaluated with a continuous slope and a curvature averaged over a
slice. Pure numpy.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import InitVar, dataclass, field

import numpy as np

__all__ = ["END_FACE_SLOPE", "STEEP_SLOPE", "WINDOW_SPARE", "KeelLine", "window_points"]

#: Slope of the side view beyond which a facet at an end of the keel line is an end face
#: (a transom, a blunt bow or tail; tan 75 deg), not the bottom.
END_FACE_SLOPE = float(np.tan(np.radians(75.0)))
#: Slope of the side view beyond which the keel line is no slender body's bottom (tan 45
#: deg): a section there is flagged, and a facet's turning there is no curvature of the
#: bottom (a corner between the bottom and a step's or an end face's edge seen at the
#: pitch, or such a face itself once the pitch leans it below END_FACE_SLOPE).
STEEP_SLOPE = 1.0
#: Break points a keel line's window keeps beyond its reach on either side (see
#: :func:`window_points`; :data:`hullslice.frame_loops.WINDOW_SPARE`, which a test holds
#: equal).
WINDOW_SPARE = 2


@dataclass(frozen=True, eq=False)
class KeelLine:
    """The lower edge of the body's side view at one pitch: ``Z_k(X)`` as a polyline.

    Coordinates are relative to the centre of gravity in the pitched frame (``X - x_g``,
    ``Z - Z_g``), in m.

    Attributes
    ----------
    x : (k,) float
        Break points, increasing.
    z : (k,) float
        Height of the lowest point of the body's section at each break point; ``inf`` in a
        gap between parts one behind the other.
    """

    x: np.ndarray
    z: np.ndarray
    #: The facets' slopes by run (see :meth:`at`): see :class:`_Runs`.
    _runs: _Runs = field(init=False, repr=False)
    #: Finds the runs' arrays instead of numpy, when given: ``loops(x, z, END_FACE_SLOPE,
    #: STEEP_SLOPE)`` as :func:`hullslice.keel_loops.runs_loops` (compiled: the same arrays).
    loops: InitVar[Callable | None] = None
    #: The runs' arrays already found by those loops for these break points, when given
    #: (``loops``' eleven values: a new pitch's are found with its keel line, see
    #: :func:`hullslice.frame_loops.frame_keel_loops`).
    runs: InitVar[tuple | None] = None

    def __post_init__(self, loops: Callable | None, runs: tuple | None) -> None:
        made = None if runs is None else _Runs.from_loops(self.x, runs)
        if made is None:
            made = _Runs.of(self.x, self.z, loops)
        object.__setattr__(self, "_runs", made)  # frozen: set once here

    def at(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Keel height and slope ``dZ_k/dX`` at relative stations ``x``.

        A mesh's keel line is a polyline whose slope jumps from facet to facet, and a body
        moving forward turns every jump into a jump of penetration velocity (60 m/s times a
        slope change of 0.01 is 0.6 m/s). The slope is therefore taken continuous: each
        facet's slope stands at the facet's middle, linearly in between. It is exact on a
        straight keel, and a kink blends over the two facets beside it only, however thin
        the slices. Facets steeper than :data:`END_FACE_SLOPE` are not bottom: an end face
        (a transom, a blunt bow or tail) or the face of a step. They keep their own slopes
        over their own extent, and the bottom's slope on either side does not blend into
        theirs (it is held from its last facet's middle to the steep face); nor does it
        blend across a gap between parts one behind the other.
        """
        x = np.asarray(x, dtype=np.float64)
        z = np.interp(x, self.x, self.z)
        return z, self._runs.slope(x)

    def height(self, x: np.ndarray) -> np.ndarray:
        """Keel height at relative stations ``x`` (the first of :meth:`at`'s pair)."""
        return np.interp(x, self.x, self.z)

    def mean_slope(self, x: np.ndarray, width: np.ndarray) -> np.ndarray:
        """The keel line's slope averaged over slices ``width`` long centred on ``x``: the
        chord ``(Z_k(x + h) - Z_k(x - h)) / 2h`` of the bottom's run that holds ``x``, with
        ``h`` half the width or less where the run ends closer (at a steep end face, a
        step's face, a gap between parts, an end of the line), so that the chord stays
        centred on ``x`` within that run.

        A facet weighs as much as it is long. In the blend of :meth:`at` a facet's slope
        stands at its middle whatever its length, so a millimetre-long facet at a junction
        of parts (a nacelle's bottom meeting the fuselage's, at a slope of 0.7 between the
        bottom's 0.15) raises the slope over its neighbours' half-lengths, and a section's
        penetration velocity with it (60 m/s times 0.5). Averaged by length over the
        slice, it moves the slope by its own height over the slice. The chord is exact on
        a straight keel and continuous in ``x`` within a run; where ``x`` is on no bottom
        run (on a steep face, in a gap), or the run ends at ``x``, the slope of :meth:`at`.
        """
        x = np.asarray(x, dtype=np.float64)
        chords = self._runs.chords
        if chords is None or not x.size:
            return self._runs.slope(x)
        xs, height, lo, hi = chords
        j = np.searchsorted(xs, x, side="right") - 1
        np.maximum(j, 0, out=j)
        np.minimum(j, len(lo) - 1, out=j)
        h = np.minimum(0.5 * np.asarray(width, dtype=np.float64), x - lo[j])
        np.minimum(h, hi[j] - x, out=h)
        ends = np.interp(np.concatenate([x + h, x - h]), xs, height)
        with np.errstate(divide="ignore", invalid="ignore"):
            chord = (ends[: len(x)] - ends[len(x) :]) / (h + h)
        on = h > 0.0  # else x is on no bottom run, or where its run ends
        if on.all():
            return chord
        return np.where(on, chord, self._runs.slope(x))

    def curvature(self, x: np.ndarray) -> np.ndarray:
        """The keel line's ``d^2 Z_k / dX^2`` at relative stations ``x``, 1/m.

        The derivative of the continuous slope of :meth:`at` within the facets' run: constant
        between two facet middles, zero where the slope is held (beyond a run's first and
        last facet middles); a jump of slope onto a steep face is not curvature.
        """
        return self._runs.curvature(np.asarray(x, dtype=np.float64))

    def mean_curvature(self, x: np.ndarray, dx: np.ndarray) -> np.ndarray:
        """The keel line's curvature averaged over slices of thickness ``dx`` centred on
        ``x``: ``(s(x + dx/2) - s(x - dx/2)) / dx`` with the slope ``s`` of :meth:`at`, 1/m,
        less any jump of slope between runs (a step's or an end face's edge) in between.

        A mesh's keel line zigzags about the true one by the mesh's resolution, and its
        local curvature is noisy with it; over a slice the noise averages out, as it does
        for the force. Where ``dx`` is zero, the local :meth:`curvature`.
        """
        x = np.asarray(x, dtype=np.float64)
        dx = np.asarray(dx, dtype=np.float64)
        if dx.shape != x.shape:
            dx = np.broadcast_to(dx, x.shape)
        runs = self._runs
        if len(runs.mid) < 2:
            return np.zeros(x.shape)
        ds = runs.change(x - dx / 2, x + dx / 2)
        thin = dx <= 0.0
        if not thin.any():
            return ds / dx
        with np.errstate(divide="ignore", invalid="ignore"):
            out = ds / np.where(thin, 1.0, dx)
        return np.where(thin, self.curvature(x), out)

    def below(self, level: float) -> tuple[float, float] | None:
        """The ``x`` range where the keel is below ``level`` (relative), or None."""
        x, z = self.x, self.z
        under = z < level
        first = int(under.argmax())
        if not under[first]:
            return None
        last = len(z) - 1 - int(under[::-1].argmax())

        def crossing(i: int) -> float:  # where the segment i, i + 1 meets the level
            if not np.isfinite(z[i]):  # a gap between parts (z = inf) before point i + 1
                return float(x[i + 1])
            if not np.isfinite(z[i + 1]):  # a gap after point i
                return float(x[i])
            t = (level - z[i]) / (z[i + 1] - z[i])
            return float(x[i] + t * (x[i + 1] - x[i]))

        # the first and last points under the level, or where the line goes under it
        lo = crossing(first - 1) if first > 0 else float(x[0])
        hi = crossing(last) if last < len(z) - 1 else float(x[-1])
        return min(lo, float(x[first])), max(hi, float(x[last]))

    def wet_length(self, level: float, lo: float, hi: float) -> float:
        """The length of ``x`` in ``[lo, hi]`` where the keel is below ``level`` (relative):
        the wetted length of a bottom that leaves the water between ``lo`` and ``hi`` (the
        dry part behind a step, a gap between parts) counts only where it is wet."""
        x, z = self.x, self.z
        a, b = np.clip(x[:-1], lo, hi), np.clip(x[1:], lo, hi)
        za, zb = z[:-1], z[1:]
        finite = np.isfinite(za) & np.isfinite(zb) & (b > a)
        if not finite.any():
            return 0.0
        x0, x1 = x[:-1][finite], x[1:][finite]
        za, zb, a, b = za[finite], zb[finite], a[finite], b[finite]
        with np.errstate(divide="ignore", invalid="ignore"):
            # the keel's height at the clipped ends of each facet, linear along it
            t = np.where(x1 > x0, 1.0 / (x1 - x0), 0.0)
            ha = za + (zb - za) * (a - x0) * t
            hb = za + (zb - za) * (b - x0) * t
            under_a, under_b = ha < level, hb < level
            # where the facet meets the level, as a share of its clipped part
            cross = np.where(hb != ha, (level - ha) / (hb - ha), 0.0)
        span = b - a
        wet = np.where(
            under_a & under_b,
            span,
            np.where(under_a, cross * span, np.where(under_b, (1.0 - cross) * span, 0.0)),
        )
        return float(np.clip(wet, 0.0, span).sum())

    def bottom(self, level: float) -> tuple[float, float] | None:
        """The ``x`` range where the keel is below ``level`` (relative), without an end face
        that the water crosses at an end of it: a pitched transom's face dips under the
        water aft of the keel's corner, over ``draft tan(pitch)``, and the slices of the
        2D+t method cover the bottom, not that face (a face wholly under the water stays).
        The range of :meth:`below` when it holds nothing but such a face; None when the
        keel is nowhere below the level."""
        extent = self.below(level)
        if extent is None:
            return None
        lo, hi = extent
        x, steep = self.x, self._runs.steep
        i = min(max(int(np.searchsorted(x, lo, side="right")) - 1, 0), len(steep) - 1)
        if x[i] < lo:  # the water crosses facet i: past the steep facets from there
            while steep[i] and x[i + 1] < hi:
                lo, i = float(x[i + 1]), i + 1
        j = min(max(int(np.searchsorted(x, hi, side="left")) - 1, 0), len(steep) - 1)
        if hi < x[j + 1]:
            while steep[j] and x[j] > lo:
                hi, j = float(x[j]), j - 1
        return (lo, hi) if hi > lo else extent


@dataclass(frozen=True, eq=False)
class _Runs:
    """A keel line's facets in runs: consecutive bottom facets, consecutive facets steeper
    than :data:`END_FACE_SLOPE` (an end face, a step's face), and gaps between parts (no
    finite slope). A slope blends between the facet middles of its own run only.

    Kept as the slope with the jumps between runs taken out, ``C = s + offset``: ``C`` is
    continuous and piecewise linear between the facet middles (constant from a run's last
    middle to the next run's first), and ``offset`` is constant over a run. The bottom's
    own turn, ``B``, is ``C`` without the turns onto, off and between facets steeper than
    :data:`STEEP_SLOPE` as well: an end face's or a step's facets are not the keel's curve.
    A tail's cap, meshed as a fan of micro-facets, turns from a slope of 800 to one of 1300
    over a few centimetres; where an airliner's keel line passes from the fuselage's
    bottom down to a nacelle's lip, its corner is at some pitches a facet of 0.4 mm with a
    slope of -2.5 between the bottom's 0.1 and the lip's face's -9; a step's face leaned
    by a pitch of more than 15 degrees has a slope below :data:`END_FACE_SLOPE`. None of
    these is a curvature of the bottom a slice beside it stands on.

    Attributes
    ----------
    mid, cont, bend : (f,) float
        Middles of the facets with a finite slope, in order, and ``C`` and ``B`` there.
    starts : (r,) float
        Where each run after the first starts (the first break point of its first facet; a
        gap belongs to the run before it).
    offsets : (r + 1,) float
        ``offset`` over each run.
    steep : (k - 1,) bool
        The facets steeper than :data:`END_FACE_SLOPE`.
    """

    mid: np.ndarray
    cont: np.ndarray
    starts: np.ndarray
    offsets: np.ndarray
    steep: np.ndarray
    bend: np.ndarray
    #: For :meth:`KeelLine.mean_slope`: the break points, the bottom's rise from the first
    #: (the bottom facets' only), and each facet's bottom run's first and last break
    #: points (both the facet's first point on a facet of no bottom run); None without a
    #: bottom facet.
    chords: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None = None

    @classmethod
    def of(cls, x: np.ndarray, z: np.ndarray, loops: Callable | None = None) -> _Runs:
        if loops is not None:
            made = cls.from_loops(x, loops(x, z, END_FACE_SLOPE, STEEP_SLOPE))
            if made is not None:
                return made
        n = len(x) - 1
        with np.errstate(invalid="ignore", divide="ignore"):
            mid, slopes = 0.5 * (x[1:] + x[:-1]), np.diff(z) / np.diff(x)
        finite = np.isfinite(slopes)
        if not finite.any():  # no facet with a slope: held at zero
            none = np.empty(0)
            return cls(mid[:1] if n else np.zeros(1), np.zeros(1), none, np.zeros(1),
                       np.zeros(max(n, 1), dtype=bool), np.zeros(1))  # fmt: skip
        steep = finite & (np.abs(slopes) > END_FACE_SLOPE)
        if finite.all() and not steep.any():  # one run of bottom facets (a window's, most)
            return cls._one_run(x, z, mid, slopes, steep)
        fin = np.flatnonzero(finite)
        fmid, fslopes = mid[fin], slopes[fin]
        # a run starts at a finite facet whose steepness differs from the finite facet
        # before it, or that follows a gap
        new = np.concatenate([[False], (steep[fin][1:] != steep[fin][:-1]) | (np.diff(fin) > 1)])
        jump = np.where(new, np.concatenate([[0.0], fslopes[:-1] - fslopes[1:]]), 0.0)
        offset = np.cumsum(jump)
        # a run after a gap starts where the gap does (the gap is held at the slope before)
        first = fin[new]
        after_gap = np.diff(fin)[new[1:]] > 1
        start_facet = np.where(after_gap, fin[np.flatnonzero(new[1:])] + 1, first)
        starts = x[start_facet]
        offsets = np.concatenate([[0.0], offset[new]])
        cont = fslopes + offset
        # the bottom's turn: ``C`` less the slope's steps from facet to facet within a run
        # onto or off a facet steeper than STEEP_SLOPE (every step within a steep run)
        leaning = np.abs(fslopes) > STEEP_SLOPE
        turn = np.where(new[1:] | ~(leaning[1:] | leaning[:-1]), 0.0, np.diff(fslopes))
        bend = cont - np.concatenate([[0.0], np.cumsum(turn)]) if turn.any() else cont
        return cls(fmid, cont, starts, offsets, steep, bend, _chords(x, z, finite & ~steep))

    @classmethod
    def _one_run(
        cls, x: np.ndarray, z: np.ndarray, mid: np.ndarray, slopes: np.ndarray, steep: np.ndarray
    ) -> _Runs:
        """:meth:`of` for break points whose facets all have a finite slope, none steeper
        than :data:`END_FACE_SLOPE` (``mid``, ``slopes`` and ``steep`` as it finds them):
        one run with no offset, every facet a bottom facet: the same arrays, in fewer
        steps."""
        n = len(slopes)
        cont = slopes + np.zeros(n)  # the offset's sum, as the runs' (a zero's sign too)
        leaning = np.abs(slopes) > STEEP_SLOPE
        turn = np.where(~(leaning[1:] | leaning[:-1]), 0.0, np.diff(slopes))
        bend = cont - np.concatenate([[0.0], np.cumsum(turn)]) if turn.any() else cont
        height = np.concatenate([[0.0], np.cumsum(np.diff(z))])  # the bottom's rise
        chords = (x, height, np.full(n, x[0]), np.full(n, x[n]))
        return cls(mid, cont, np.empty(0), np.zeros(1), steep, bend, chords)

    @classmethod
    def from_loops(cls, x: np.ndarray, out: tuple) -> _Runs | None:
        """The runs of break points ``x`` from what
        :func:`~hullslice.keel_loops.runs_loops` gave for them, or None where it could not
        (no facet with a finite slope: numpy's path)."""
        ok, mid, cont, starts, offsets, steep, bend, bottom, height, lo, hi = out
        if not ok:
            return None
        chords = (x, height, lo, hi) if bottom else None
        return cls(mid, cont, starts, offsets, steep, bend, chords)

    def _offset(self, x: np.ndarray) -> np.ndarray | float:
        if not len(self.starts):
            return 0.0
        return self.offsets[np.searchsorted(self.starts, x, side="right")]

    def slope(self, x: np.ndarray) -> np.ndarray:
        """The continuous slope at ``x``."""
        return np.interp(x, self.mid, self.cont) - self._offset(x)

    def change(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """The bottom's change of slope from ``a`` to ``b``: without the jumps between runs
        and without the turns onto, off and between facets steeper than
        :data:`STEEP_SLOPE`."""
        return np.interp(b, self.mid, self.bend) - np.interp(a, self.mid, self.bend)

    def curvature(self, x: np.ndarray) -> np.ndarray:
        """The slope's derivative at ``x`` within a bottom run (zero where held, and where
        the slope turns onto, off or between facets steeper than :data:`STEEP_SLOPE`)."""
        if len(self.mid) < 2:
            return np.zeros(x.shape)
        k = np.diff(self.bend) / np.diff(self.mid)
        j = np.searchsorted(self.mid, x, side="right") - 1
        inside = (j >= 0) & (j < len(k))
        return np.where(inside, k[np.minimum(np.maximum(j, 0), len(k) - 1)], 0.0)


def _chords(
    x: np.ndarray, z: np.ndarray, bottom: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None:
    """:attr:`_Runs.chords` of the break points ``x``, ``z`` with ``bottom`` facets."""
    if not bottom.any():
        return None
    with np.errstate(invalid="ignore"):  # inf - inf in a gap, not a bottom facet
        rise = np.where(bottom, np.diff(z), 0.0)
    height = np.concatenate([[0.0], np.cumsum(rise)])
    # a run of bottom facets starts where one follows a facet of none (or the line starts)
    edge = np.diff(np.concatenate([[False], bottom, [False]]).astype(np.int8))
    first, last = np.flatnonzero(edge == 1), np.flatnonzero(edge == -1)  # facets first..last-1
    run = np.cumsum(edge[:-1] == 1) - 1  # each facet's latest run start
    lo = np.where(bottom, x[first[np.maximum(run, 0)]], x[:-1])
    hi = np.where(bottom, x[last[np.maximum(run, 0)]], x[:-1])
    return x, height, lo, hi


def window_points(
    x: np.ndarray, z: np.ndarray, level: float, n: int, reach: float
) -> tuple[np.ndarray, np.ndarray] | None:
    """The break points of a keel line (``x``, ``z``, all finite) that an evaluation with
    the water at ``level`` (m) and ``n`` fixed slices reads, as
    :func:`hullslice.frame_loops.window_line_loops` keeps them: from ``reach`` (m; at
    least a station spacing) before the point before the first under the water to
    ``reach`` after the point after the last, :data:`WINDOW_SPARE` more each side, and the
    line's first and last as they are (its ends, length and stations the whole line's).
    Every break point left out is at the level or above. None where the whole line must
    serve: fewer than 8 points, none under the water, or a window of more than half."""
    k = len(x)
    under = np.flatnonzero(z < level)
    if k < 8 or not len(under):
        return None
    first, last = int(under[0]), int(under[-1])
    reach = max(reach, (float(x[-1]) - float(x[0])) / n)
    lo = x[max(first - 1, 0)] - reach
    hi = x[min(last + 1, k - 1)] + reach
    # back from the point before the first under the water to one at or before lo, on
    # from the point after the last to one at or past hi (the loops' walks)
    i0 = min(max(first - 1, 0), max(int(np.searchsorted(x, lo, side="right")) - 1, 0))
    i1 = max(min(last + 1, k - 1), min(int(np.searchsorted(x, hi, side="left")), k - 1))
    i0 = max(i0 - WINDOW_SPARE, 1)  # the first point is kept as it is
    i1 = min(i1 + WINDOW_SPARE, k - 2)  # and the last
    if 2 * (i1 - i0 + 3) > k:  # nearly every point: the whole line
        return None
    keep = np.concatenate(([0], np.arange(i0, i1 + 1), [k - 1]))
    return x[keep], z[keep]
