"""Figures of the structural loads: the hull seen from below coloured by a face pressure,
and the frame bays' loads over time."""

from __future__ import annotations

from typing import Any

import numpy as np

from ._common import one_axes, place_legend

__all__ = ["plot_face_pressure", "plot_frame_loads"]


def plot_face_pressure(
    hull: Any,
    pressure: Any,
    title: str | None = None,
    *,
    label: str = "pressure",
    ax: Any = None,
) -> Any:
    """The hull seen from below (its own ``x`` along, ``y`` across, m), each face that
    faces down coloured by ``pressure`` (Pa, shown in kPa), dry ones grey.

    Parameters
    ----------
    hull : Hull
    pressure : (m,) float
        A value per face of the mesh, Pa: a :class:`~hullslice.FacePressures`'
        ``pressure``, or each face's peak over a run
        (:meth:`History.peak_face_pressures <hullslice.History.peak_face_pressures>`).
    label : str
        What the colour shows (default ``"pressure"``).
    """
    from matplotlib.collections import PolyCollection

    p = np.asarray(pressure, dtype=np.float64)
    faces = np.asarray(hull.faces)
    if p.shape != (len(faces),):
        from ..errors import InputError

        raise InputError(f"pressure has shape {p.shape}; give one value per face ({len(faces)})")
    fig, ax, created = one_axes(ax, (10.0, 3.0), "plot_face_pressure")
    corners = np.asarray(hull.vertices, dtype=np.float64)[faces]
    normal_z = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])[:, 2]
    below = normal_z < 0.0
    # the dry bottom grey, the loaded faces on top of it, in kPa
    dry = below & (p <= 0.0)
    ax.add_collection(PolyCollection(corners[dry][:, :, :2], facecolors="0.85", edgecolors="none"))
    wet = p > 0.0
    if wet.any():
        kpa = p[wet] / 1e3
        order = np.argsort(kpa)  # the highest drawn last
        coll = PolyCollection(corners[wet][order][:, :, :2], array=kpa[order], cmap="viridis",
                              edgecolors="none")  # fmt: skip
        ax.add_collection(coll)
        bar = fig.colorbar(coll, ax=ax, pad=0.01)
        bar.set_label(f"{label} (kPa)")
    ax.autoscale_view()
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x along the body (m)")
    ax.set_ylabel("y (m), seen from below")
    if title:
        ax.set_title(title)
    if created:
        fig.tight_layout()
    return fig


def plot_frame_loads(frame_loads: Any, title: str | None = None, *, bays: int = 6, ax: Any = None):
    """The vertical load of the most loaded frame bays over time (N), and the body's.

    Parameters
    ----------
    frame_loads : FrameLoads
        From :meth:`History.frame_loads <hullslice.History.frame_loads>`.
    bays : int
        How many bays to draw, the most loaded (default 6).
    """
    fig, ax, created = one_axes(ax, (8.0, 4.0), "plot_frame_loads")
    fl = frame_loads
    t = np.asarray(fl.t)
    peak = fl.peak()["vertical"]
    chosen = np.argsort(peak)[::-1][: max(1, int(bays))]
    ax.plot(t, np.asarray(fl.body) / 1e3, color="k", lw=1.5, label="body")
    for k in sorted(chosen, key=lambda i: fl.edges[i]):
        ax.plot(t, fl.vertical[:, k] / 1e3, lw=1.0,
                label=f"bay x = {fl.edges[k]:.3g} to {fl.edges[k + 1]:.3g} m")  # fmt: skip
    ax.set_xlabel("t (s)")
    ax.set_ylabel("vertical load (kN)")
    ax.grid(True, alpha=0.3)
    place_legend(ax, created)
    if title:
        ax.set_title(title)
    if created:
        fig.tight_layout()
    return fig
