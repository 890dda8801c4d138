"""The load each frame bay of the structure carries, in time: :class:`FrameLoads`.

A user gives frame stations (positions ``x`` along the body, in the mesh's own frame, m)
or a spacing. The body between two neighbouring frames is a **bay**; the first bay runs
from the body's aft end to the first frame and the last from the last frame to its fore
end, so that the bays hold the whole body and their loads add up to the body's.

A bay's load is the slices' forces over it: each slice's force (vertical and
horizontal, N) is spread evenly over its thickness along the earth's ``X`` and shared
between the bays by the length of the slice in each. A frame is the plane of its body
station; in the earth frame it is tilted by the pitch, and it meets a slice where the
slice's force acts (its keel for a momentum-form solver, halfway between keel and water
for a free-fall one, as in :attr:`ForceResult.moment <hullslice.ForceResult.moment>`).
Every slice's force lands in some bay, so at every instant the bays' loads add up to the
body's force to rounding.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .record import SectionRecord

__all__ = ["FrameLoads", "frame_loads", "frame_stations"]

#: Most frames a user may give (a bay per frame and one more).
MAX_FRAMES = 10_000


def frame_stations(
    bounds: tuple[float, float],
    frames: Sequence[float] | np.ndarray | None = None,
    spacing: float | None = None,
) -> np.ndarray:
    """The frames' body stations ``x`` (m), sorted, strictly inside the body's length.

    Parameters
    ----------
    bounds : (float, float)
        The body's aft and fore ends along its ``x``, m.
    frames : sequence of float, optional
        The stations, m.
    spacing : float, optional
        A frame at every multiple of ``spacing`` (m) of the mesh's ``x`` inside the body.

    Raises
    ------
    InputError
        Neither or both given, a station that is not finite or outside the body, a repeated
        one, a spacing that is not positive, or more than :data:`MAX_FRAMES` frames.
    """
    lo, hi = float(bounds[0]), float(bounds[1])
    if (frames is None) == (spacing is None):
        raise InputError("give frame stations (frames=..., --frames) or a spacing, not both")
    if spacing is not None:
        d = float(spacing)
        if not np.isfinite(d) or d <= 0.0:
            raise InputError(f"frame spacing {spacing!r} m is not positive: give a spacing in m")
        count = (hi - lo) / d
        if count > MAX_FRAMES:
            raise InputError(
                f"frame spacing {d:g} m gives {count:.3g} frames over the body's "
                f"{hi - lo:.6g} m, more than {MAX_FRAMES}: give a larger spacing"
            )
        k = np.arange(np.floor(lo / d) + 1, np.ceil(hi / d))
        x = k * d
        x = x[(x > lo) & (x < hi)]
    else:
        x = np.asarray(frames, dtype=np.float64).ravel()
        if len(x) > MAX_FRAMES:
            raise InputError(f"{len(x)} frames given, more than {MAX_FRAMES}: give fewer")
        bad = x[~np.isfinite(x) | (x <= lo) | (x >= hi)]
        if len(bad):
            raise InputError(
                f"frame station {bad[0]:g} m is not inside the body ({lo:.6g} to {hi:.6g} m "
                "along its x): give stations between its ends"
            )
        x = np.sort(x)
        twice = x[1:][np.diff(x) == 0.0]
        if len(twice):
            raise InputError(f"frame station {twice[0]:g} m is given twice: give each once")
    if len(x) == 0:
        raise InputError(
            f"no frame falls inside the body ({lo:.6g} to {hi:.6g} m along its x): give a "
            "smaller spacing or stations inside it"
        )
    return x


def _bay_shares(rec: SectionRecord, edges: np.ndarray, cg: np.ndarray) -> np.ndarray:
    """(n, b) the share of each slice's thickness in each bay."""
    c, s = np.cos(rec.pitch), np.sin(rec.pitch)
    # the frame plane r_x = x_f - x_g meets earth height Z at X = x_g + r_x / c - tan * (Z - Z_g)
    height = rec.force_height - rec.z_cg
    planes = rec.x_cg + (edges[None, :] - cg[0]) / c - (s / c) * height[:, None]  # (n, b+1)
    planes[:, 0], planes[:, -1] = -np.inf, np.inf
    lo = (rec.x - 0.5 * rec.dx)[:, None]
    hi = (rec.x + 0.5 * rec.dx)[:, None]
    overlap = np.clip(np.minimum(hi, planes[:, 1:]) - np.maximum(lo, planes[:, :-1]), 0.0, None)
    with np.errstate(invalid="ignore", divide="ignore"):
        share = np.where(rec.dx[:, None] > 0, overlap / rec.dx[:, None], 0.0)
    # a slice of no thickness (or rounding at a bay's edge): all in the bay of its station
    short = np.abs(share.sum(axis=1) - 1.0) > 1e-9
    if short.any():
        mid = (rec.x[short])[:, None]
        inside = (mid >= planes[short, :-1]) & (mid < planes[short, 1:])
        share[short] = inside.astype(np.float64)
    return share


def frame_loads(
    records: Sequence[SectionRecord], frames: np.ndarray, bounds: tuple[float, float], cg
) -> FrameLoads:
    """The frame bays' loads over a run's kept instants (see the module notes).

    Parameters
    ----------
    records : sequence of SectionRecord
        The instants.
    frames : (f,) float
        The frames' body stations, m (from :func:`frame_stations`).
    bounds : (float, float)
        The body's aft and fore ends along its ``x``, m.
    cg : (3,) float
        The centre of gravity in the body frame, m.
    """
    edges = np.concatenate([[bounds[0]], np.asarray(frames, dtype=np.float64), [bounds[1]]])
    cg = np.asarray(cg, dtype=np.float64)
    b = len(edges) - 1
    vertical = np.zeros((len(records), b))
    horizontal = np.zeros((len(records), b))
    for i, rec in enumerate(records):
        share = _bay_shares(rec, edges, cg)
        vertical[i] = rec.force @ share
        horizontal[i] = rec.force_x @ share
    t = np.array([r.t for r in records], dtype=np.float64)
    total = np.array([r.total for r in records], dtype=np.float64)
    return FrameLoads(t, edges, vertical, horizontal, total)


@dataclass(frozen=True, eq=False)
class FrameLoads:
    """The loads of the frame bays over time.

    Attributes
    ----------
    t : (k,) float
        Times, s.
    edges : (b + 1,) float
        The bays' ends along the body's ``x``, m: the body's aft end, the frames, its fore
        end.
    vertical, horizontal : (k, b) float
        Each bay's vertical (up) and horizontal (forward) load at each time, N.
    body : (k,) float
        The body's vertical force at each time, N (the bays' sum).
    """

    t: np.ndarray
    edges: np.ndarray
    vertical: np.ndarray
    horizontal: np.ndarray
    body: np.ndarray

    COLUMNS = ("t", "bay", "x_aft", "x_fore", "vertical", "horizontal")
    UNITS = ("s", "", "m", "m", "N", "N")

    @property
    def bays(self) -> int:
        """The number of bays."""
        return len(self.edges) - 1

    def peak(self) -> dict[str, np.ndarray]:
        """Per bay: the largest vertical load (N) and its time (s)."""
        if not len(self.t):
            return {"vertical": np.zeros(self.bays), "t": np.full(self.bays, np.nan)}
        i = np.argmax(self.vertical, axis=0)
        return {"vertical": self.vertical[i, np.arange(self.bays)], "t": self.t[i]}

    def records(self) -> list[dict[str, float]]:
        """One row per time and bay (:attr:`COLUMNS`)."""
        rows = []
        for i, t in enumerate(self.t):
            for k in range(self.bays):
                rows.append(
                    {
                        "t": float(t),
                        "bay": k,
                        "x_aft": float(self.edges[k]),
                        "x_fore": float(self.edges[k + 1]),
                        "vertical": float(self.vertical[i, k]),
                        "horizontal": float(self.horizontal[i, k]),
                    }
                )
        return rows

    def to_xarray(self):
        """An ``xarray.Dataset`` of ``vertical`` and ``horizontal`` (N) over ``t`` (s) and
        ``bay``, with the bays' ends ``x_aft``, ``x_fore`` (m) as coordinates (needs the
        ``sweep`` extra)."""
        from ..xarray_io import _xarray

        xr = _xarray()
        coords = {
            "t": ("t", self.t, {"units": "s"}),
            "bay": ("bay", np.arange(self.bays)),
            "x_aft": ("bay", self.edges[:-1], {"units": "m"}),
            "x_fore": ("bay", self.edges[1:], {"units": "m"}),
        }
        up = {"units": "N", "long_name": "vertical load, up"}
        forward = {"units": "N", "long_name": "horizontal load, forward"}
        data = {
            "vertical": (("t", "bay"), self.vertical, up),
            "horizontal": (("t", "bay"), self.horizontal, forward),
        }
        return xr.Dataset(data, coords=coords, attrs={"description": "hullslice frame loads"})
