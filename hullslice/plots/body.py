"""Figures of the body: the cut at one instant, the sectional area curve and the views."""

from __future__ import annotations

from typing import Any

import numpy as np

from ._common import _pyplot, one_axes, panel_axes, place_legend

#: The side view of the cut shows the wetted region, widened by this share of its length
#: (and the draft by this share of its depth, above and below).
WETTED_MARGIN = 0.12

#: A wetted region longer than this many times its height is drawn with an exaggerated
#: vertical scale (else with equal scales).
MAX_EQUAL_ASPECT = 6.0


def _zoom_on_wetted(ax: Any, sections: Any) -> str:
    """Limit the side view to the wetted region with a margin; the title's note on scale."""
    if len(sections.x) == 0:
        ax.autoscale()
        ax.set_aspect("equal", adjustable="datalim")
        return ""
    x = np.asarray(sections.x, dtype=float)
    dx = np.asarray(sections.dx, dtype=float)
    x0, x1 = float(np.min(x - dx / 2)), float(np.max(x + dx / 2))
    length = max(x1 - x0, 1e-12)
    depth = max(float(sections.draft), 1e-3 * length)
    pad_x = WETTED_MARGIN * length
    pad_z = (
        max(WETTED_MARGIN * length, 0.5 * depth)
        if length / depth <= MAX_EQUAL_ASPECT
        else 0.5 * depth
    )
    ax.set_xlim(x0 - pad_x, x1 + pad_x)
    ax.set_ylim(-depth - pad_z, pad_z)
    if length / depth <= MAX_EQUAL_ASPECT:
        ax.set_aspect("equal", adjustable="box")
        return ""
    return ", z exaggerated"


def plot_sections(hull: Any, sections: Any, title: str | None = None, *, ax: Any = None) -> Any:
    """The cut: the body's side view with the stations and the waterline, zoomed on the
    wetted region, and the section outlines at the stations coloured by their ``x`` (a
    colour bar gives it), in the earth frame, waterline at z = 0.

    Parameters
    ----------
    hull : Hull
    sections : Sections
    title : str, optional
        The figure's title (above both panels; on the side view with one Axes).
    ax : matplotlib Axes or sequence of two Axes, optional
        Where to draw: two Axes (side view, sections), or one Axes for the side view only.
        Without it, a new figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.cm import ScalarMappable
    from matplotlib.collections import LineCollection
    from matplotlib.colors import Normalize

    from ..geometry import frame, silhouette_edges

    plt = _pyplot()
    fig, (ax1, ax2), created = panel_axes(
        ax,
        ["side view", "sections"],
        "plot_sections",
        lambda: plt.subplots(1, 2, figsize=(12, 4.2), gridspec_kw={"width_ratios": [3, 2]}),
    )
    fr = frame(hull, sections.pitch)
    a, b = silhouette_edges(hull)
    c, sn = np.cos(sections.pitch), np.sin(sections.pitch)

    def earth(v: np.ndarray) -> np.ndarray:
        r = v - fr.cg
        return np.stack(
            [fr.cg[0] + r[:, 0] * c - r[:, 2] * sn, sections.z_cg + r[:, 0] * sn + r[:, 2] * c],
            axis=1,
        )

    ax1.add_collection(
        LineCollection(list(np.stack([earth(a), earth(b)], axis=1)), colors="0.3", linewidths=0.6)
    )
    ax1.axhline(0.0, color="C0", lw=1.2, label="waterline")
    stations = np.unique(sections.station)
    xs = (
        np.array([sections.x[sections.station == i][0] for i in stations])
        if len(stations)
        else np.empty(0)
    )
    cmap = plt.get_cmap("viridis")
    lo, hi = (float(xs.min()), float(xs.max())) if len(xs) else (0.0, 1.0)
    if hi <= lo:
        lo, hi = lo - 0.5, hi + 0.5
    norm = Normalize(lo, hi)
    colors = [cmap(norm(x)) for x in xs]
    for x, col in zip(xs, colors, strict=True):
        ax1.axvline(x, color=col, lw=0.6, alpha=0.8)
    note = _zoom_on_wetted(ax1, sections)
    ax1.set_xlabel("x [m]")
    ax1.set_ylabel("z [m]")
    ax1.set_title(
        f"Side view: draft {sections.draft:.4g} m, pitch "
        f"{np.degrees(sections.pitch):.3g} deg, {len(xs)} stations{note}",
        fontsize=10,
    )
    place_legend(ax1, created)
    if ax2 is not None:
        for i, col in zip(stations, colors, strict=True):
            for contour in sections.polygons[i]:
                closed = np.vstack([contour, contour[:1]])
                ax2.plot(closed[:, 0], closed[:, 1], color=col, lw=0.8)
        ax2.axhline(0.0, color="C0", lw=1.2)
        ax2.set_aspect("equal", adjustable="datalim")
        ax2.set_xlabel("y [m]")
        ax2.set_ylabel("z [m]")
        ax2.set_title("Sections at the stations", fontsize=10)
        fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=ax2, label="station x [m]")
    if title:
        if created:
            fig.suptitle(title)
        else:
            ax1.set_title(f"{title}\n{ax1.get_title()}", fontsize=10)
    if created:
        fig.tight_layout()
    return fig


def plot_area_curve(x: Any, area: Any, title: str | None = None, *, ax: Any = None) -> Any:
    """The sectional area curve: cross-section area against position along the body.

    Parameters
    ----------
    x : (n,) float
        Stations along the body, m.
    area : (n,) float
        Cross-section areas, m^2.
    title : str, optional
    ax : matplotlib Axes, optional
        Where to draw; without it, a new figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax, created = one_axes(ax, (7, 3.5), "plot_area_curve")
    ax.plot(x, area, "-", color="C0")
    ax.fill_between(x, 0.0, area, color="C0", alpha=0.2)
    ax.set_xlabel("x along the body [m]")
    ax.set_ylabel("section area [m$^2$]")
    ax.grid(True, alpha=0.3)
    ax.set_title(title or "Sectional area curve")
    if created:
        fig.tight_layout()
    return fig
