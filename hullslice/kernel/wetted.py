"""Wetted properties of cross-sections at a waterline: pieces, keels, half-beams, deadrise.

All stations and all wetted pieces are evaluated at once, in arrays over the edges of an
:class:`~hullslice.kernel.outline.Outline`. A section may have several wetted pieces (two
floats, a catamaran); its mass is shared first between its separate parts by their areas,
then between the wetted pieces of one part by their widths at the waterline. Pure numpy.

Local deadrise estimators (each per side, port and starboard, of each piece):

``wedge``
    The equivalent wedge of the wetted piece: ``tan(beta) = p / c`` (a side whose
    waterline end lies at the keel or behind it, under an overhang, is a wall: 90 deg).
``waterline-slope``
    The slope of the contour where it meets the water.
``keel-fit``
    A least-squares line through the keel fitted to the wetted contour of that side.

The two sides combine by the harmonic mean of ``tan(beta)``.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from .outline import Outline, Polygons, group_min

__all__ = ["DEADRISE_ESTIMATORS", "section_properties", "wetted_properties"]

#: Deadrise estimators by name, with a one-line description.
DEADRISE_ESTIMATORS: dict[str, str] = {
    "wedge": "equivalent wedge of the wetted piece, tan(beta) = p / c",
    "waterline-slope": "slope of the contour where it meets the water",
    "keel-fit": "least-squares line through the keel fitted to the wetted contour",
}


def section_properties(
    polygons: Sequence[Polygons], tol: float, deadrise: str = "wedge"
) -> dict[str, np.ndarray]:
    """Properties of cross-sections in the earth frame, all stations and pieces at once.

    Parameters
    ----------
    polygons : (s,) sequence of sequences of (k, 2) float
        Contours of each station in ``(y, z)``, m, waterline at ``z = 0``; outer contours
        counter-clockwise, holes clockwise.
    tol : float
        Coordinate tolerance in m.
    deadrise : str
        Deadrise estimator (see :data:`DEADRISE_ESTIMATORS`).

    Returns
    -------
    dict of arrays
        Per station: ``area`` (s,). Per entry (wetted piece, or one per dry station):
        ``station``, ``penetration``, ``half_beam``, ``half_beam_port``,
        ``half_beam_stbd``, ``deadrise``, ``deadrise_port``, ``deadrise_stbd`` (rad),
        ``y_keel``, ``mass_share`` (the piece's share of its station's mass: its part's by
        area, shared between the pieces of one part by waterline width), ``chine_wetted``.
    """
    outline = Outline.of(polygons, tol)
    return wetted_properties(outline, 0.0, tol, deadrise)


def wetted_properties(
    outline: Outline,
    level: float | np.ndarray,
    tol: float,
    deadrise: str = "wedge",
    loops: Callable | None = None,
) -> dict[str, np.ndarray]:
    """Properties of the sections of an :class:`Outline` with the water at height ``level``
    (m; or one height per station, ``(s,)``: each station's properties are those it has
    alone at its own).

    ``loops``, when given (:func:`hullslice.wetted_loops.wetted_loops`, compiled), does it
    for the ``wedge`` and ``waterline-slope`` estimators: the same numbers. See
    :func:`section_properties` for the result.
    """
    s = outline.n_stations
    top = outline.top
    if top < np.inf:  # the outline of the low edges only: the water below them
        high = float(np.fmax.reduce(np.asarray(level).ravel(), initial=-np.inf))  # no NaN
        if high > top:
            raise ValueError(
                f"an outline of the edges below {top:.6g} m cannot serve water at "
                f"{high:.6g} m: make it with a higher top"
            )
    if loops is not None and deadrise in ("wedge", "waterline-slope"):
        return _by_loops(loops, outline, level, tol, deadrise)
    station, ya, za, yb, zb, contour = outline.below(level)
    chine_station = outline.z_chine - level <= tol

    pieces = _wetted_pieces(
        outline, level, station=station, ya=ya, za=za, yb=yb, zb=zb, contour=contour
    )
    ps, yl, yr, tan_l, tan_r, part = pieces
    m = len(ps)
    # underwater parts of the segments, assigned to the piece above them
    za_c, zb_c = np.minimum(za, 0.0), np.minimum(zb, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        yc = ya + (0.0 - za) * (yb - ya) / (zb - za)
        ya_c = np.where(za < 0.0, ya, yc)
        yb_c = np.where(zb < 0.0, yb, yc)
    seg_piece = _assign(station, 0.5 * (ya_c + yb_c), ps, yl, yr)
    # a part with a single wetted piece owns all its underwater edges, also those outside
    # its waterline interval (a section under water beyond its widest point, whose keel
    # may lie outside the interval)
    if m:
        count = np.bincount(part, minlength=len(outline.part_area))
        only = np.full(len(outline.part_area), -1)
        single = count[part] == 1
        only[part[single]] = np.flatnonzero(single)
        own = only[contour]
        seg_piece = np.where(own >= 0, own, seg_piece)
    sel = np.flatnonzero(seg_piece >= 0)
    seg_piece = seg_piece[sel]
    y1, z1, y2, z2 = ya_c[sel], za_c[sel], yb_c[sel], zb_c[sel]
    # keel of each piece: its lowest underwater point
    zk = group_min(seg_piece, np.minimum(z1, z2), m) if m else np.empty(0)
    pts_piece = np.concatenate([seg_piece, seg_piece])
    pts_y = np.concatenate([y1, y2])
    pts_z = np.concatenate([z1, z2])
    # the keel: where the lowest point of each piece is; on a flat bottom, its middle (the
    # points level with it to manifold3d's single precision, a fifth of the tolerance: a
    # finely faceted round bottom must not count as flat)
    at_keel = pts_z <= zk[pts_piece] + tol / 5
    keel_piece, keel_y = pts_piece[at_keel], pts_y[at_keel]
    yk = 0.5 * (group_min(keel_piece, keel_y, m) - group_min(keel_piece, -keel_y, m))
    p = np.maximum(-zk, 0.0)
    c_port = yr - yk
    c_stbd = yk - yl
    if deadrise == "wedge":
        t_port, t_stbd = side_tan(p, c_port), side_tan(p, c_stbd)
    elif deadrise == "waterline-slope":
        t_port, t_stbd = tan_r, tan_l
    else:  # keel-fit
        t_port, t_stbd = _keel_fit(
            seg_piece,
            y1 - yk[seg_piece],
            z1 - zk[seg_piece],
            y2 - yk[seg_piece],
            z2 - zk[seg_piece],
            m,
        )
    with np.errstate(divide="ignore", invalid="ignore"):
        t_mean = 2.0 / (1.0 / t_port + 1.0 / t_stbd)
    width = yr - yl
    share = _mass_share(outline, ps, part, width)

    # one dry entry for each station without a wetted piece
    has_piece = np.zeros(s, dtype=bool)
    has_piece[ps] = True
    dry = np.flatnonzero(~has_piece)
    nd = len(dry)
    entry_station = np.concatenate([ps, dry])
    order = np.argsort(entry_station, kind="stable")
    nan_d = np.full(nd, np.nan)

    def col(wet, fill):
        return np.concatenate([wet, np.full(nd, fill) if np.isscalar(fill) else fill])[order]

    return {
        "area": outline.area,
        "station": entry_station[order],
        "penetration": col(p, 0.0),
        "half_beam": col(0.5 * width, 0.0),
        "half_beam_port": col(c_port, 0.0),
        "half_beam_stbd": col(c_stbd, 0.0),
        "deadrise": col(np.arctan(t_mean), nan_d),
        "deadrise_port": col(np.arctan(t_port), nan_d),
        "deadrise_stbd": col(np.arctan(t_stbd), nan_d),
        "y_keel": col(yk, nan_d),
        "part_half_beam": col(0.5 * (outline.part_ymax - outline.part_ymin)[part], nan_d),
        "mass_share": col(share, 1.0),
        "chine_wetted": col(chine_station[ps], False).astype(bool),
    }


def side_tan(p: np.ndarray, c: np.ndarray) -> np.ndarray:
    """The equivalent wedge's ``tan(beta) = p / c`` of one side of each piece (``p`` its
    penetration, ``c`` the side's half-beam from the keel, m). A side whose waterline end
    lies at the keel or behind it (``c <= 0``: the lowest point under an overhang, or
    beyond the piece's waterline interval) rises as a wall: ``+inf``, 90 deg, not the
    negative angle ``p / c`` would give. A dry entry's ``0 / 0`` stays NaN."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where((c <= 0.0) & (p > 0.0), np.inf, p / c)


def _by_loops(
    loops: Callable, outline: Outline, level: float | np.ndarray, tol: float, deadrise: str
) -> dict[str, np.ndarray]:
    """:func:`wetted_properties` by ``loops``; the deadrise's arctangent by numpy, on the
    wetted pieces' tangents as numpy's path takes it."""
    o = outline
    levels = np.ascontiguousarray(np.broadcast_to(np.asarray(level, dtype=np.float64),
                                                  (o.n_stations,)))  # fmt: skip
    st, wet, p, hb, port, stbd, tm, tp, ts, yk, phb, share, chine = loops(
        o.station, o.ya, o.za, o.yb, o.zb, o.zlo, o.start, o.area, o.contour, o.part_area,
        o.part_station, o.part_zmax, o.part_ymin, o.part_ymax, o.z_chine, levels,
        float(tol), deadrise == "waterline-slope",
    )  # fmt: skip
    angles = {}
    for key, tan in (("deadrise", tm), ("deadrise_port", tp), ("deadrise_stbd", ts)):
        angle = np.full(len(tan), np.nan)
        angle[wet] = np.arctan(tan[wet])  # the pieces' tangents, in order, as numpy's path
        angles[key] = angle
    return {
        "area": o.area,
        "station": st,
        "penetration": p,
        "half_beam": hb,
        "half_beam_port": port,
        "half_beam_stbd": stbd,
        **angles,
        "y_keel": yk,
        "part_half_beam": phb,
        "mass_share": share,
        "chine_wetted": chine,
    }


def _mass_share(
    outline: Outline, ps: np.ndarray, part: np.ndarray, width: np.ndarray
) -> np.ndarray:
    """Each wetted piece's share of its station's mass per metre.

    A separate part of the section (an outer contour with its holes: one float of a
    catamaran) carries its own mass, by area; the wetted pieces of one part share its mass
    by their widths at the waterline.
    """
    part_width = np.bincount(part, weights=width, minlength=len(outline.part_area))
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.where(part_width[part] > 0.0, width / part_width[part], 1.0)
        return outline.part_area[part] / outline.area[ps] * frac


def _wetted_pieces(
    outline: Outline,
    level: float | np.ndarray,
    *,
    station: np.ndarray,
    ya: np.ndarray,
    za: np.ndarray,
    yb: np.ndarray,
    zb: np.ndarray,
    contour: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The wetted pieces of each station: the intervals of the waterline inside the body.

    ``station, ya, za, yb, zb, contour`` are the edges under ``level`` as
    :meth:`Outline.below` gives them (heights from the water, m).

    Along the waterline, a contour going down (into the water) opens an interval inside
    the body to its right, one going up closes it (outer contours run counter-clockwise,
    holes clockwise), so a running winding count finds the intervals. A separate part of a
    section under water altogether (no crossing) is one piece over its whole width.

    Returns
    -------
    station, y_left, y_right, tan_left, tan_right, part : (m,) arrays
        For each piece its station, the ends of its waterline interval (m), the slope
        ``|dz/dy|`` of the contour where it meets the water at each end, and the outer
        contour (separate part of the section, see :class:`Outline`) it belongs to.
    """
    down = (za >= 0.0) & (zb < 0.0)
    up = (za < 0.0) & (zb >= 0.0)
    cross = down | up
    with np.errstate(divide="ignore", invalid="ignore"):
        yc = ya[cross] + (0.0 - za[cross]) * (yb[cross] - ya[cross]) / (zb[cross] - za[cross])
        slope = np.abs((zb - za) / (yb - ya))[cross]
    sc, cc = station[cross], contour[cross]
    step = np.where(down[cross], 1, -1)
    order = np.lexsort((yc, sc))
    sc, yc, step, slope, cc = sc[order], yc[order], step[order], slope[order], cc[order]
    winding = np.cumsum(step)
    # the count restarts at each station (every station's crossings add up to zero)
    opens = (winding == 1) & (step == 1)
    closes = (winding == 0) & (step == -1)
    ps, part = sc[opens], cc[opens]
    yl, yr = yc[opens], yc[closes]
    tl, tr = slope[opens], slope[closes]
    crossed = np.zeros(len(outline.part_area), dtype=bool)
    crossed[cc] = True
    part_level = level if np.isscalar(level) else np.asarray(level)[outline.part_station]
    submerged = np.flatnonzero(~crossed & (outline.part_zmax - part_level < 0.0))
    if len(submerged):
        ps = np.concatenate([ps, outline.part_station[submerged]])
        yl = np.concatenate([yl, outline.part_ymin[submerged]])
        yr = np.concatenate([yr, outline.part_ymax[submerged]])
        tl = np.concatenate([tl, np.full(len(submerged), np.inf)])
        tr = np.concatenate([tr, np.full(len(submerged), np.inf)])
        part = np.concatenate([part, submerged])
        o = np.lexsort((yl, ps))
        ps, yl, yr, tl, tr, part = ps[o], yl[o], yr[o], tl[o], tr[o], part[o]
    return ps, yl, yr, tl, tr, part


def _assign(seg_station, seg_y, ps, yl, yr) -> np.ndarray:
    """Index of the piece whose waterline interval holds each point, or -1.

    Pieces are sorted by ``(station, y_left)``: a point's candidate is the last piece of its
    own station starting at or left of it, found by exact comparisons only (no key mixing
    stations and heights), so that a station's assignment does not depend on the others."""
    if len(ps) == 0:
        return np.full(len(seg_y), -1)
    first = np.searchsorted(ps, seg_station, side="left")
    end = np.searchsorted(ps, seg_station, side="right")
    i = first - 1
    most = int((end - first).max()) if len(seg_y) else 0
    for j in range(most):  # a station's pieces, left to right (one or two, usually)
        cand = first + j
        take = cand < end
        take[take] = yl[cand[take]] <= seg_y[take]
        i = np.where(take, cand, i)
    ok = (i >= first) & (seg_y <= yr[np.maximum(i, 0)])
    return np.where(ok, i, -1)


def _keel_fit(piece, y1, z1, y2, z2, m):
    """Least-squares slopes through the keel, per side: integrals over the contour."""
    # split each segment at the keel's y so that each part lies on one side
    straddle = (y1 < 0.0) != (y2 < 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        zc = np.where(straddle, z1 + (0.0 - y1) * (z2 - z1) / (y2 - y1), 0.0)
    parts = [
        (piece[~straddle], y1[~straddle], z1[~straddle], y2[~straddle], z2[~straddle]),
        (piece[straddle], y1[straddle], z1[straddle], np.zeros(straddle.sum()), zc[straddle]),
        (piece[straddle], np.zeros(straddle.sum()), zc[straddle], y2[straddle], z2[straddle]),
    ]
    pc, a1, b1, a2, b2 = (np.concatenate(v) for v in zip(*parts, strict=True))
    # exact for z linear in y along a segment: int y z dy and int y^2 dy
    iyz = (a2 - a1) * (2 * a1 * b1 + a1 * b2 + a2 * b1 + 2 * a2 * b2) / 6.0
    iyy = (a2**3 - a1**3) / 3.0
    port = (a1 + a2) > 0.0
    num_p = np.bincount(pc[port], weights=iyz[port], minlength=m)
    den_p = np.bincount(pc[port], weights=iyy[port], minlength=m)
    num_s = np.bincount(pc[~port], weights=iyz[~port], minlength=m)
    den_s = np.bincount(pc[~port], weights=iyy[~port], minlength=m)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.abs(num_p / den_p), np.abs(num_s / den_s)
