"""Side, top and front views of a body, to check its orientation and scale."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from ._common import _pyplot, panel_axes

# cyclic or signed permutations of the body axes (rotations) that bring a view's two axes
# to manifold3d's x and y, for its projection
_VIEWS = (
    ("side (from port)", "x along the body [m]", "z up [m]", ((1, 0, 0), (0, 0, 1), (0, -1, 0))),
    ("top", "x along the body [m]", "y to port [m]", ((1, 0, 0), (0, 1, 0), (0, 0, 1))),
    ("front (from ahead)", "y to port [m]", "z up [m]", ((0, 1, 0), (0, 0, 1), (1, 0, 0))),
)


def _outline(body: Any, rows: np.ndarray):
    """The body's outline seen along the third of ``rows`` (its view axes first): the
    projection of its manifold3d body, or, for a mesh that is not one closed surface (a
    :class:`~hullslice.survey.Survey`), the union of its projected triangles."""
    manifold = getattr(body, "manifold", None)
    if manifold is not None:
        m = np.zeros((3, 4))
        m[:, :3] = rows
        return manifold.transform(m).project()
    from ..topology import triangle_outline

    return triangle_outline((body.vertices @ rows[:2].T)[body.faces])


def plot_views(
    hull: Any, forward: str = "+x", up: str = "+z", nose: str | None = None, *, ax: Any = None
) -> Any:
    """Side, top and front views of the body (its outline), with the forward axis marked.

    Parameters
    ----------
    hull : Hull or Survey
        The body; or a mesh that is not one closed surface, as ``hullslice info`` describes
        it (:func:`hullslice.survey.survey_mesh`), drawn as the outline of its faces.
    forward, up : str
        The mesh file's axes given as forward and up, for the labels.
    nose : str, optional
        ``"fore"`` or ``"aft"``: the end that looks like a nose
        (:func:`hullslice.orientation.orientation`), marked in the side view.
    ax : matplotlib Axes or sequence of Axes, optional
        Where to draw: three Axes (side, top, front views) or four (and the body's
        dimensions as text), or one Axes for the side view only. Without it, a new figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path as MplPath

    plt = _pyplot()

    def make() -> tuple[Any, list[Any]]:
        fig, grid = plt.subplots(
            2, 2, figsize=(10, 6.5), gridspec_kw={"width_ratios": [3, 1], "height_ratios": [1, 1]}
        )
        return fig, [grid[0, 0], grid[1, 0], grid[0, 1], grid[1, 1]]

    if isinstance(ax, Sequence | np.ndarray) and len(ax) == 3:
        ax = [*list(ax), None]
        names = ["side", "top", "front"]
        fig, axes, created = panel_axes(ax[:3], names, "plot_views", make)
        axes = [*axes, None]
    else:
        fig, axes, created = panel_axes(
            ax, ["side", "top", "front", "dimensions"], "plot_views", make
        )
    lo, hi = hull.bounds
    for a, (title, xlabel, ylabel, rows) in zip(axes[:3], _VIEWS, strict=True):
        if a is None:
            continue
        outline = _outline(hull, np.array(rows, dtype=float))
        verts: list[list[float]] = []
        codes: list[Any] = []
        for poly in outline.to_polygons():
            p = np.asarray(poly, dtype=float)
            if len(p) < 3:
                continue
            verts += [*p.tolist(), p[0].tolist()]
            codes += [MplPath.MOVETO] + [MplPath.LINETO] * (len(p) - 1) + [MplPath.CLOSEPOLY]
        if verts:
            a.add_patch(PathPatch(MplPath(verts, codes), facecolor="C0", alpha=0.35,
                                  edgecolor="C0", lw=0.8))  # fmt: skip
        a.autoscale_view()
        a.set_aspect("equal", adjustable="datalim")
        a.set_title(title, fontsize=10)
        a.set_xlabel(xlabel)
        a.set_ylabel(ylabel)
        a.grid(True, alpha=0.3)
    length = hi[0] - lo[0]
    for a, ybase in ((axes[0], lo[2]), (axes[1], lo[1])):
        if a is None:
            continue
        y0 = ybase - 0.08 * length
        a.annotate(
            "", xy=(lo[0] + 0.45 * length, y0), xytext=(lo[0] + 0.2 * length, y0),
            arrowprops={"arrowstyle": "->", "color": "C3", "lw": 1.5},
        )  # fmt: skip
        a.text(lo[0] + 0.47 * length, y0, f"forward (+x, the file's {forward})", color="C3",
               va="center", fontsize=9)  # fmt: skip
        a.update_datalim([(lo[0], y0 - 0.04 * length)])
        a.autoscale_view()
    if nose in ("fore", "aft"):
        xn = hi[0] if nose == "fore" else lo[0]
        axes[0].annotate(
            "nose?", xy=(xn, 0.5 * (lo[2] + hi[2])), xytext=(xn, hi[2] + 0.1 * length),
            ha="center", color="C3", arrowprops={"arrowstyle": "->", "color": "C3"},
        )  # fmt: skip
        axes[0].update_datalim([(xn, hi[2] + 0.15 * length)])
        axes[0].autoscale_view()
    if axes[3] is not None:
        axes[3].axis("off")
        axes[3].text(
            0.0, 0.9,
            f"{hull.name}\nlength {length:.4g} m\nbeam {hi[1] - lo[1]:.4g} m\n"
            f"height {hi[2] - lo[2]:.4g} m\nfile axes: forward {forward}, up {up}",
            va="top", fontsize=9, transform=axes[3].transAxes,
        )  # fmt: skip
    if created:
        fig.suptitle(f"{hull.name}: views of the body frame (x forward, y port, z up)")
        fig.tight_layout()
    return fig
