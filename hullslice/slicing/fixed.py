"""Fixed slicing: ``n`` equal slices over the body's length, cut once per pitch and kept.

The stations of a pitch are cut when first wetted and kept in a :class:`FixedCut` on the
pitch's :class:`~hullslice.geometry.Frame`; after :data:`TABLE_AFTER` evaluations their
wetted properties come from a :class:`~hullslice.kernel.waterline_table.WaterlineTable`
instead of a fresh evaluation. The slices at the ends of the wetted part count their wetted
length only.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass, field

import numpy as np

from ..caching import Entry
from ..geometry import Frame, loops_in_use
from ..kernel.keel import END_FACE_SLOPE, STEEP_SLOPE, KeelLine
from ..kernel.outline import Outline, Polygons, prefix_index
from ..kernel.waterline_table import TABULATED, WaterlineTable
from ..kernel.wetted import wetted_properties
from ..mesh import Hull
from ..state import Pose
from .assemble import assemble
from .record import Sections

__all__ = ["FIXED_PAD", "TABLE_AFTER", "FixedCut", "fixed_cut", "fixed_sections", "outline_of"]

#: A kept outline gets a waterline table from its this many-th evaluation on (a table
#: costs some evaluations' time to make: it pays off over a time history, not at once).
TABLE_AFTER = 8
#: Fixed stations cut beyond the ones asked for, on either side (see FixedCut.window).
FIXED_PAD = 2


@dataclass(eq=False)
class FixedCut:
    """The fixed stations of one pitch cut so far, and their waterline tables.

    Attributes
    ----------
    n : int
        Number of fixed slices over the body's length.
    tol : float
        Coordinate tolerance, m.
    polys : dict of int to contours
        The stations cut so far, by index, in the cutter's coordinates.
    range : (int, int) or None
        The stations ``range[0]`` to ``range[1] - 1`` of :attr:`outline` and :attr:`rows`.
    outline : Outline or None
        The outline of those stations: at a new pitch's first evaluation, of their edges
        below its top only (:attr:`Outline.top`, see :meth:`window`).
    rows : list of contours
        Their contours.
    evaluations : int
        How many evaluations asked for wetted properties.
    tables : dict of str to WaterlineTable
        The waterline table of :attr:`outline` by deadrise estimator.
    too_high : dict of str to (Outline, float)
        By estimator, the outline and the water's height at which a table cost too much
        (none is tried again for that outline at a higher water).
    plans : dict of str to tuple
        By estimator, the arrays of :mod:`hullslice.forces.fused` made from its table.
    """

    n: int
    tol: float
    polys: dict[int, Polygons] = field(default_factory=dict)
    range: tuple[int, int] | None = None
    outline: Outline | None = None
    rows: list[Polygons] = field(default_factory=list)
    evaluations: int = 0
    tables: dict[str, WaterlineTable] = field(default_factory=dict)
    too_high: dict[str, tuple[Outline, float]] = field(default_factory=dict)
    #: By estimator, the fused evaluation's arrays of a table (hullslice.forces.fused).
    plans: dict[str, tuple] = field(default_factory=dict)
    _lock: threading.Lock = field(default_factory=threading.Lock, repr=False)

    def window(
        self,
        fr: Frame,
        k0: int = 0,
        k1: int | None = None,
        cutter: str = "manifold3d",
        top: float = np.inf,
    ) -> tuple[Outline, list, int]:
        """The outline of fixed stations ``k0`` to ``k1 - 1`` (mid-stations of equal slices
        over the body's length), cut once and kept.

        ``top`` (m): a new pitch's first outline keeps only the edges whose lower end is
        below it (:meth:`Outline.of`), the edges an evaluation with the water up to it
        reads: most of a new pitch's outlines serve one evaluation. Any later call makes the
        outline of all the edges (a held pitch, or its waterline table), and so does the
        first where its evaluation makes a table (:data:`TABLE_AFTER` at most 1).

        Returns ``(outline, polygons, c0)``: the outline and contours (relative to the cg)
        of stations ``c0`` to ``c0 + len(polygons) - 1``, a range holding the ones asked
        for. Stations are cut when first asked for, a couple beyond the range on either
        side once the range has had to grow, so that a wetted part growing along the body
        is cut a few stations at a time.
        """
        n = self.n
        k1 = n if k1 is None else k1
        with self._lock:
            held = self.range
            # a new pitch's first outline, of its low edges only, where this evaluation
            # makes no waterline table (tabulated, next, counts it); made whole after
            cap = top if held is None and self.evaluations + 1 < TABLE_AFTER else np.inf
            grow = held is None or self.outline is None or k0 < held[0] or k1 > held[1]
            if grow:
                if held is None:  # a new pitch: only what is asked for
                    lo, hi = k0, k1
                else:  # the wetted part grows at this pitch: some stations ahead
                    lo = max(min(k0, held[0]) - FIXED_PAD, 0)
                    hi = min(max(k1, held[1]) + FIXED_PAD, n)
                polys = self.polys
                missing = np.array([k for k in range(lo, hi) if k not in polys], dtype=np.int64)
                cuts: list = []
                if len(missing):
                    cuts = fr.cut(fr.fixed_stations(n)[1][missing], cutter)
                    polys.update(zip(missing.tolist(), cuts, strict=True))
                # all cut just now (a new pitch): the cut itself, with its own array
                self.rows = cuts if len(missing) == hi - lo else [polys[k] for k in range(lo, hi)]
                self.range = held = (lo, hi)
            if grow or self.outline is None or self.outline.top < cap:  # made, or made whole
                self.outline = Outline.of(
                    self.rows, self.tol, fr.origin, fr.scale, loops=loops_in_use("outline"),
                    top=cap,
                )  # fmt: skip
            assert held is not None  # the range, set above where there was none
            return self.outline, self.rows, held[0]

    def tabulated(
        self, outline: Outline, level: float, deadrise: str, k0: int, k1: int
    ) -> dict[str, np.ndarray] | None:
        """The properties of stations ``k0 .. k1 - 1`` of the kept ``outline`` from its
        waterline table (made, or made higher, when needed); None where a table does not
        serve."""
        with self._lock:
            self.evaluations = count = self.evaluations + 1
            if deadrise not in TABULATED or count < TABLE_AFTER:
                return None
            table = self.tables.get(deadrise)
            if table is None or table.outline is not outline or level > table.top:
                # none where one was too costly for this outline at a lower water
                too_high = self.too_high.get(deadrise)
                if too_high is not None and too_high[0] is outline and level >= too_high[1]:
                    return None
                table = WaterlineTable.of(outline, level, self.tol, deadrise)
                if table is None:
                    self.too_high[deadrise] = (outline, level)
                    self.tables.pop(deadrise, None)
                    return None
                self.tables[deadrise] = table
        return table.at(level, k0, k1)


#: A frame's fixed cuts by slice count, tolerance and cutter.
FIXED_CUTS: Entry[dict[tuple[int, float, str], FixedCut]] = Entry("fixed cuts", dict)


def fixed_cut(fr: Frame, n: int, tol: float, cutter: str = "manifold3d") -> FixedCut:
    """The :class:`FixedCut` of ``n`` fixed slices kept on a frame (made empty if new)."""
    cuts = fr.cache[FIXED_CUTS]
    key = (int(n), float(tol), cutter)
    kept = cuts.get(key)
    if kept is None:
        kept = cuts.setdefault(key, FixedCut(key[0], key[1]))
    return kept


def fixed_sections(
    hull: Hull,
    fr: Frame,
    *,
    pose: Pose,
    n: int,
    deadrise: str,
    level: float,
    extent: tuple[float, float] | None,
    tol: float,
    cache: bool = True,
    cutter: str = "manifold3d",
    line: KeelLine | None = None,
) -> Sections:
    """Fixed slices over the body's length; the wetted ones at this waterline.

    ``level`` is the water's height above the centre of gravity in the pitched frame (m),
    ``extent`` the keel line's wetted ``x`` range (m, relative), ``tol`` the coordinate
    tolerance (m); ``cache=False`` cuts the stations afresh; ``cutter`` as for
    :meth:`~hullslice.geometry.Frame.cut`; ``line`` the keel line read (default the
    frame's, see :meth:`~hullslice.geometry.Frame.keel_for`).

    Interior slices use their mid-station's section. A slice only partly wetted counts its
    wetted length and stands at that part's middle, where the keel line gives its
    penetration; its section is that of its own mid-station (or, past the body's end or
    through a pitched transom's face, of its neighbour's) moved up or down to that
    penetration: the section's own contour,
    wetted as deep as the slice's middle is (a prismatic hull between neighbouring
    stations), even where the station itself is still dry. Its force then grows from zero
    as the water reaches it, with no jump as the water passes its mid-station, and a round
    bottom keeps its own shape.
    """
    line = fr.keel if line is None else line
    xa = float(line.x[0])
    d, mids = fr.fixed_stations(n)
    if extent is None:
        return assemble(
            hull,
            fr,
            pose=pose,
            level=level,
            length=0.0,
            rel=np.empty(0),
            dx=np.empty(0),
            props=wetted_properties(Outline.of([], tol), level, tol, deadrise),
            polys=[],
            deadrise=deadrise,
            line=line,
        )
    x0, x1 = extent
    k = np.arange(
        min(max(int((x0 - xa) // d), 0), n - 1), min(max(int((x1 - xa) // d), 0), n - 1) + 1
    )
    lo = np.maximum(xa + k * d, x0)
    hi = np.minimum(xa + (k + 1) * d, x1)
    keep = hi > lo
    k, lo, hi = k[keep], lo[keep], hi[keep]
    # only the stations of the wetted slices and their neighbours matter
    w0, w1 = max(int(k[0]) - 1, 0), min(int(k[-1]) + 2, n)
    props = None
    kept = fixed_cut(fr, n, tol, cutter) if cache else None
    if kept is not None:
        # a moved slice reads its source with the water up to STEEP_SLOPE times 1.5 station
        # spacings higher (or it is cut where it is, below): the edges below twice that
        outline, polys, c0 = kept.window(fr, w0, w1, cutter, top=level + 2.0 * STEEP_SLOPE * d)
        props = kept.tabulated(outline, level, deadrise, w0 - c0, w1 - c0)
    else:
        (outline, polys), c0 = outline_of(fr, mids, tol, cutter), 0
    full = np.abs(hi - lo - d) <= 1e-12 * d
    x = np.where(full, mids[k], 0.5 * (lo + hi))
    keel = line.height(x)
    # a partial slice takes its own mid-station's section, moved down to its depth (it
    # may be dry at this water), or its neighbour's where its own station has no bottom's
    # section (past the body's end, or through a pitched transom's face); with no wetted
    # station near it (the first contact) it is cut where it is
    inward = np.where(k == k.min(), 1, -1)
    neighbour = np.minimum(np.maximum(k + inward, 0), n - 1)
    own = full | np.isfinite(outline.zmin[k - c0])
    if not full.all():
        own[~full] &= np.abs(line.at(mids[k[~full]])[1]) <= END_FACE_SLOPE
    source = np.where(own, k, neighbour)
    # a partial slice's source moved by this much (where the slice takes a moved section)
    with np.errstate(invalid="ignore"):
        depth = np.where(full, 0.0, keel - outline.zmin[source - c0])
    extra: dict[int, dict[str, np.ndarray]] = {}
    if props is None:
        props, extra = _window_properties(
            kept, outline, (w0 - c0, w1 - c0), level, tol, deadrise,
            _guess_moved(outline, k - c0, neighbour - c0, full, level, w0 - c0, w1 - c0),
            source - c0, depth,
        )  # fmt: skip
    props["station"] = props["station"] + w0
    wet_mid = np.zeros(n, dtype=bool)
    wet_mid[props["station"][props["penetration"] > 0]] = True
    fresh = ~full & ~wet_mid[k] & ~wet_mid[neighbour]
    if not full.all():  # nor a section that its move shows to be another part's: moved
        # more steeply than 45 deg from its station to the slice's wet middle (a nacelle's
        # end within the slice, the fuselage's bottom above it at the station)
        part = np.flatnonzero(~full)
        with np.errstate(invalid="ignore"):
            far = np.abs(depth[part]) > STEEP_SLOPE * np.abs(x[part] - mids[source[part]])
        fresh[part[far]] = True
    moved = np.flatnonzero(~full & ~fresh)
    lift = np.zeros(len(x))
    lift[moved] = depth[moved]
    station = props["station"]
    # entries of the chosen sources, one slice after another (entries sorted by station)
    first = np.searchsorted(station, source, side="left")
    count = np.searchsorted(station, source, side="right") - first
    if len(moved):  # a partial slice: its source wetted as deep as the slice's middle is,
        # its entries appended to the window's, from the table in one call where it serves
        table = None if kept is None or extra else kept.tables.get(deadrise)
        each = None
        if table is not None and table.outline is outline:
            each = table.at_each(source[moved] - c0, level - lift[moved])
        if each is not None:
            sizes = np.bincount(each["station"], minlength=len(moved))
            more = [each]
        else:
            more = [
                extra[int(i)] if int(i) in extra else _station_at(
                    kept, outline, int(source[i] - c0), float(level - lift[i]), tol, deadrise
                )
                for i in moved
            ]  # fmt: skip
            sizes = np.array([len(m["station"]) for m in more])
        first[moved] = len(station) + np.cumsum(sizes) - sizes
        count[moved] = sizes
        props = {key: val if key == "area" else np.concatenate([val, *(m[key] for m in more)])
                 for key, val in props.items()}  # fmt: skip
    take = prefix_index(first, count)
    slot = np.repeat(np.arange(len(source)), count)
    sel = {key: val[take] for key, val in props.items() if key != "area"}
    sel["station"] = slot
    sel["area"] = props["area"][source - w0]
    slice_polys = [polys[src - c0] for src in source]
    if fresh.any():  # no wetted section nearby (the first contact): cut where the slice is
        sel, slice_polys = _with_fresh(
            fr, sel, slice_polys, fresh=fresh, x=x, level=level, tol=tol, deadrise=deadrise,
            cutter=cutter,
        )  # fmt: skip
    return assemble(
        hull,
        fr,
        pose=pose,
        level=level,
        length=line.wet_length(level, x0, x1),
        rel=x,
        dx=hi - lo,
        props=sel,
        polys=slice_polys,
        deadrise=deadrise,
        lift=lift,
        keel=keel,
        slope_width=np.maximum(hi - lo, 0.5 * d),
        line=line,
    )


def outline_of(
    fr: Frame, rel: np.ndarray, tol: float, cutter: str = "manifold3d"
) -> tuple[Outline, list[Polygons]]:
    """The outline and contours of the sections at relative stations ``rel`` (m), cut
    afresh."""
    polys = fr.cut(rel, cutter)
    return Outline.of(polys, tol, fr.origin, fr.scale, loops=loops_in_use("outline")), polys


def _guess_moved(
    outline: Outline,
    k: np.ndarray,
    neighbour: np.ndarray,
    full: np.ndarray,
    level: float,
    k0: int,
    k1: int,
) -> np.ndarray:
    """The partial slices that will likely take a moved section (see
    :func:`fixed_sections`): those whose own or neighbouring station of the outline
    (``k``, ``neighbour``) reaches below ``level`` within stations ``k0 .. k1 - 1``. A guess
    only: the wetted properties decide, and a slice guessed wrongly is evaluated apart."""
    inside = (outline.zmin < level) & (np.arange(outline.n_stations) >= k0)
    inside &= np.arange(outline.n_stations) < k1
    return np.flatnonzero(~full & (inside[k] | inside[neighbour]))


def _window_properties(
    kept: FixedCut | None,
    outline: Outline,
    window: tuple[int, int],
    level: float,
    tol: float,
    deadrise: str,
    guess: np.ndarray,
    source: np.ndarray,
    lift: np.ndarray,
) -> tuple[dict[str, np.ndarray], dict[int, dict[str, np.ndarray]]]:
    """The wetted properties of the outline's stations ``window[0] .. window[1] - 1`` at
    ``level``, and in the same evaluation those of the partial slices ``guess`` (their
    ``source`` stations of the outline at ``level - lift``, by slice): one call of
    :func:`wetted_properties`, each station's properties the same as alone. The slices'
    by slice index, each as :func:`_station_at` gives it; none where a waterline table of
    this outline would serve them (:func:`_station_at` reads it), nor for a guess whose
    water is above the outline's top (:attr:`Outline.top`: a slice moved so far is cut
    where it is)."""
    k0, k1 = window
    table = None if kept is None else kept.tables.get(deadrise)
    if table is not None and table.outline is outline:
        guess = guess[:0]
    guess = guess[np.isfinite(lift[guess]) & (level - lift[guess] <= outline.top)]
    nwin = k1 - k0
    stations = np.concatenate([np.arange(k0, k1), source[guess]])
    levels = np.concatenate([np.full(nwin, level), level - lift[guess]])
    both = wetted_properties(outline.take(stations), levels, tol, deadrise, loops_in_use("wetted"))
    ends = np.searchsorted(both["station"], np.arange(nwin, len(stations) + 1))
    props = {key: val[: ends[0]] for key, val in both.items() if key != "area"}
    props["area"] = both["area"][:nwin]
    extra = {}
    for j, i in enumerate(guess.tolist()):
        one = {key: val[ends[j] : ends[j + 1]] for key, val in both.items() if key != "area"}
        one["station"] = one["station"] - (nwin + j)
        one["area"] = both["area"][nwin + j : nwin + j + 1]
        extra[i] = one
    return props, extra


def _station_at(
    kept: FixedCut | None, outline: Outline, k: int, level: float, tol: float, deadrise: str
) -> dict[str, np.ndarray]:
    """The wetted properties of the kept ``outline``'s station ``k`` with the water at
    ``level`` (m): from the pitch's waterline table where it serves, else evaluated."""
    table = None if kept is None else kept.tables.get(deadrise)
    props = None
    if table is not None and table.outline is outline:
        props = table.at(level, k, k + 1)
    if props is None:
        props = wetted_properties(
            outline.window(k, k + 1), level, tol, deadrise, loops_in_use("wetted")
        )
    return props


def _with_fresh(
    fr: Frame,
    sel: dict[str, np.ndarray],
    slice_polys: list[Polygons],
    *,
    fresh: np.ndarray,
    x: np.ndarray,
    level: float,
    tol: float,
    deadrise: str,
    cutter: str = "manifold3d",
) -> tuple[dict[str, np.ndarray], list[Polygons]]:
    """Replace the entries of the slices marked ``fresh`` (at relative stations ``x``, m)
    by a cut at their position."""
    idx = np.flatnonzero(fresh)
    outline, polys = outline_of(fr, x[idx], tol, cutter)
    new = wetted_properties(outline, level, tol, deadrise, loops_in_use("wetted"))
    keep = ~np.isin(sel["station"], idx)
    out = {}
    for key in sel:
        if key == "area":
            area = sel["area"].copy()
            area[idx] = new["area"]
            out["area"] = area
        elif key == "station":
            out["station"] = np.concatenate([sel["station"][keep], idx[new["station"]]])
        else:
            out[key] = np.concatenate([sel[key][keep], new[key]])
    order = np.argsort(out["station"], kind="stable")
    out = {key: (val if key == "area" else val[order]) for key, val in out.items()}
    for j, i in enumerate(idx):
        slice_polys[i] = polys[j]
    return out, slice_polys
