"""Which way a mesh points: its extent along each axis and which end looks like a nose.

A mesh from a modelling tool comes in its own axes, and the 2D+t cut needs the body's
length along ``x`` (``--forward``). :func:`orientation` reports the extents along the
file's three axes (after the scale) and guesses the nose from the sections at stations
along the body (the run of them that holds the largest section: a stray part far away is
left out). The guess, in order:

1. **Fullness.** The section of a nose is round: its area over the area of its bounding
   rectangle is about pi/4 = 0.785 for an ellipse. At a tail, the fin and tail planes make
   the sections thin and wide (a cross of plates fills little of its rectangle), and so do
   a propeller or wheels. Over the last fifth of the length at each end, the mean fullness
   is compared: the fuller end is the nose when the two differ by more than
   :data:`FULLNESS_MARGIN`.
2. **Rise.** Otherwise the nose is the end where the sectional area reaches half its
   largest value sooner (a rounded nose fills out over a shorter length than a tail cone),
   when the two distances differ by more than a fifth.
3. Otherwise no end is named (a prism, a box: both ends look alike).

It is a guess, stated as one: ``info`` prints it with its figures. hullslice does not use
it; ``--forward`` decides.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["FULLNESS_MARGIN", "Orientation", "orientation"]

#: Difference of the ends' mean fullness (section area over its bounding rectangle's area)
#: above which the fuller end is taken as the nose.
FULLNESS_MARGIN = 0.1

#: Share of the length at each end over which the fullness is averaged.
END_SHARE = 0.2


@dataclass(frozen=True)
class Orientation:
    """The extents of a mesh and the guess of its nose.

    Attributes
    ----------
    mesh_extents : dict of str to float
        Extent along the file's ``x``, ``y`` and ``z`` axes in m (after the scale).
    longest : str
        The file's axis of the largest extent (``"x"``, ``"y"`` or ``"z"``).
    forward : str
        The file's axis taken as forward, with its sign.
    nose : str or None
        ``"fore"`` (the body's +x end, where ``forward`` points), ``"aft"`` (the other
        end), or None when the ends look alike.
    reason : str
        Why, with the figures.
    fullness : (float, float)
        Mean fullness over the aft and the fore fifth of the length.
    rise : (float, float)
        Distance from the aft and from the fore end to where the area first reaches half
        its largest value, m.
    """

    mesh_extents: dict
    longest: str
    forward: str
    nose: str | None
    reason: str
    fullness: tuple[float, float]
    rise: tuple[float, float]

    @property
    def forward_is_longest(self) -> bool:
        return self.forward.lstrip("+-") == self.longest

    def as_dict(self) -> dict:
        return {
            "mesh_extents": dict(self.mesh_extents),
            "longest_axis": self.longest,
            "forward": self.forward,
            "nose": self.nose,
            "nose_reason": self.reason,
            "fullness_aft_fore": list(self.fullness),
            "half_area_distance_aft_fore": list(self.rise),
        }


def section_profile(hull, stations: int = 40):
    """Area, width and height of the sections at ``stations`` mid-points along the body.

    Returns
    -------
    x, area, width, height : (stations,) float
        m, m^2, m, m; body frame.
    """
    # a cyclic permutation of the axes (a rotation) puts the body's x along z to slice
    turned = hull.manifold.transform(
        np.array([[0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [1.0, 0.0, 0.0, 0.0]])
    )
    lo, hi = hull.bounds[0][0], hull.bounds[1][0]
    x = lo + (np.arange(stations) + 0.5) * (hi - lo) / stations
    area = np.zeros(stations)
    width = np.zeros(stations)
    height = np.zeros(stations)
    for i, xi in enumerate(x):
        cs = turned.slice(float(xi))
        area[i] = cs.area()
        if area[i] > 0.0:
            b = cs.bounds()
            width[i], height[i] = b[2] - b[0], b[3] - b[1]
    return x, area, width, height


def orientation(hull, forward: str = "+x", up: str = "+z", stations: int = 40) -> Orientation:
    """The extents of ``hull`` along its file's axes and the guess of its nose.

    Parameters
    ----------
    hull : Hull
        As loaded (body frame).
    forward, up : str
        The file's axes given as forward and up when it was loaded.
    stations : int
        Sections along the body for the guess (default 40).
    """
    from .axes import axis_matrix

    rot = axis_matrix(forward, up)
    # body = rot @ mesh, and rot is a signed permutation: each file axis is one body axis
    mesh_ext = np.abs(rot.T) @ hull.extents
    names = ("x", "y", "z")
    extents = {a: float(e) for a, e in zip(names, mesh_ext, strict=True)}
    longest = names[int(np.argmax(mesh_ext))]
    x, area, width, height = section_profile(hull, stations)
    # the main body: the run of non-empty stations that holds the largest section (a
    # stray part far away leaves empty stations between)
    filled = area > 0.0
    k = int(np.argmax(area))
    a = k - int(np.argmin(filled[k::-1])) + 1 if not filled[: k + 1].all() else 0
    b = k + int(np.argmin(filled[k:])) if not filled[k:].all() else stations
    x, area, width, height = x[a:b], area[a:b], width[a:b], height[a:b]
    stations = len(x)
    ends = (x[0] - 0.5 * (x[1] - x[0]) if stations > 1 else hull.bounds[0][0],
            x[-1] + 0.5 * (x[-1] - x[-2]) if stations > 1 else hull.bounds[1][0])  # fmt: skip
    length = float(ends[1] - ends[0])
    full = np.where(width * height > 0, area / np.maximum(width * height, 1e-300), 0.0)
    n_end = max(1, round(END_SHARE * stations))
    fullness = (float(full[:n_end].mean()), float(full[-n_end:].mean()))
    half = 0.5 * area.max()
    above = np.flatnonzero(area >= half)
    rise = (float(x[above[0]] - ends[0]), float(ends[1] - x[above[-1]]))
    aft_fore = ("aft", "fore")
    if abs(fullness[1] - fullness[0]) > FULLNESS_MARGIN:
        k = int(fullness[1] > fullness[0])
        nose = aft_fore[k]
        reason = (
            f"its sections are fuller: area over bounding rectangle {fullness[k]:.2f} against "
            f"{fullness[1 - k]:.2f} at the other end (over {END_SHARE:.0%} of the length "
            "each), where planes, fins or a propeller widen the body"
        )
    elif min(rise) < 0.8 * max(rise):
        k = int(rise[1] < rise[0])
        nose = aft_fore[k]
        reason = (
            f"its area rises faster (half the largest area {rise[k]:.3g} m from that end "
            f"against {rise[1 - k]:.3g} m from the other, of {length:.3g} m)"
        )
    else:
        nose = None
        reason = (
            f"both ends look alike (fullness {fullness[0]:.2f} and {fullness[1]:.2f}, half "
            f"the largest area {rise[0]:.3g} and {rise[1]:.3g} m from the ends)"
        )
    return Orientation(extents, longest, str(forward), nose, reason, fullness, rise)
