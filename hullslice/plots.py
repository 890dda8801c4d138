"""Figures of results, with matplotlib (the optional extra ``hullslice[plot]``).

Every function takes results and returns a ``matplotlib.figure.Figure``; :func:`save`
writes one to a file completely or not at all. Axes are labelled with their units.
"""

from __future__ import annotations

import io
import os
from collections.abc import Sequence

import numpy as np

from .atomic import write_atomic
from .errors import MissingDependencyError

__all__ = [
    "plot_area_curve",
    "plot_convergence",
    "plot_footprint",
    "plot_force_distribution",
    "plot_history",
    "plot_sections",
    "plot_views",
    "save",
]


def _pyplot():
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise MissingDependencyError(
            "plots need matplotlib: pip install 'hullslice[plot]' (or pip install matplotlib)"
        ) from None
    return plt


def save(fig, path: str | os.PathLike, dpi: int = 120) -> None:
    """Write a figure to ``path`` (PNG, SVG or PDF by extension), completely or not at all."""
    fmt = os.path.splitext(str(path))[1].lstrip(".").lower() or "png"
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, dpi=dpi, bbox_inches="tight")
    write_atomic(path, buf.getvalue())
    _pyplot().close(fig)


def plot_history(history, title: str | None = None):
    """Force, acceleration, velocity and draft against time (and pitch when it varies)."""
    plt = _pyplot()
    pitched = bool(np.any(history.pitch != history.pitch[0]) or np.any(history.pitch != 0))
    rows = 5 if pitched else 4
    fig, axes = plt.subplots(rows, 1, figsize=(7, 1.9 * rows), sharex=True)
    t = history.t
    series = [
        (history.force / 1e3 if history.force.max() > 1e4 else history.force, "force"),
        (history.acceleration, "acceleration [m/s$^2$]"),
        (history.velocity, "velocity [m/s]"),
        (history.draft, "draft [m]"),
    ]
    force_unit = "kN" if history.force.max() > 1e4 else "N"
    series[0] = (series[0][0], f"force [{force_unit}]")
    if pitched:
        series.append((np.degrees(history.pitch), "pitch [deg]"))
    # instants where slices outside the method's range carry more than a tenth of the force
    invalid = history.valid_share < 0.9
    for ax, (y, label) in zip(axes, series, strict=True):
        ax.plot(t, y, color="C0", lw=1.5)
        if invalid.any():
            ax.plot(
                t[invalid],
                y[invalid],
                ".",
                color="C3",
                ms=3,
                label="over 10 % of the force from slices outside the validity range",
            )
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    if invalid.any():
        axes[0].legend(loc="best", fontsize=8)
    axes[-1].set_xlabel("time [s]")
    if title:
        axes[0].set_title(title)
    fig.align_ylabels(axes)
    fig.tight_layout()
    return fig


def plot_footprint(
    histories: Sequence, labels: Sequence[str], body_length: tuple[float, float] | None = None
):
    """The wetted footprint (its aft and fore ends along the body) against time.

    Parameters
    ----------
    histories : sequence of History
    labels : sequence of str
        One legend entry per history.
    body_length : (float, float), optional
        The body's ``x`` range in m, drawn as a band for reference.
    """
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7, 4))
    for i, (h, label) in enumerate(zip(histories, labels, strict=True)):
        color = f"C{i}"
        aft, fore = h.footprint[:, 0], h.footprint[:, 1]
        ax.fill_between(h.t, aft, fore, color=color, alpha=0.25, lw=0)
        ax.plot(h.t, aft, color=color, lw=1.2, label=label)
        ax.plot(h.t, fore, color=color, lw=1.2)
    if body_length is not None:
        ax.axhline(body_length[0], color="0.4", lw=0.8, ls="--")
        ax.axhline(body_length[1], color="0.4", lw=0.8, ls="--")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("wetted part along the body, x [m]")
    ax.set_title("Wetted footprint: aft and fore ends of the wetted part")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    return fig


def plot_convergence(
    study,
    references: dict[str, float] | None = None,
    title: str | None = None,
):
    """Force against slice thickness, with the Richardson-extrapolated force and its GCI band
    (as the paper's Fig. 8).

    Parameters
    ----------
    study : ConvergenceStudy
    references : dict of str to float, optional
        Forces in N drawn as horizontal lines (e.g. the paper's and a CFD value), by label.
    """
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.2))
    d = np.array(
        [r.sections.wetted_length / n for r, n in zip(study.results, study.counts, strict=True)]
    )
    f = study.forces
    ax.plot(d * 1e3, f, "o-", color="C0", label="2D+t force, n slices")
    for di, fi, n in zip(d, f, study.counts, strict=True):
        ax.annotate(
            f"n = {n}", (di * 1e3, fi), textcoords="offset points", xytext=(4, 6), fontsize=8
        )
    rich = study.richardson
    if rich is not None and rich.behaviour != "divergent":
        band = abs(rich.extrapolated) * rich.gci
        ax.errorbar(
            [0.0],
            [rich.extrapolated],
            yerr=[[band], [band]],
            fmt="D",
            color="C3",
            capsize=4,
            label=f"Richardson: {rich.extrapolated:.4f} N (GCI {100 * rich.gci:.3g} %)",
        )
    for i, (label, value) in enumerate((references or {}).items()):
        ax.axhline(value, color=f"C{i + 4}", ls="--", lw=1.0, label=f"{label}: {value:.4f} N")
    ax.set_xlabel("slice thickness d [mm]")
    ax.set_ylabel("vertical force [N]")
    ax.margins(x=0.1, y=0.12)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    ax.set_title(title or "Convergence in the slice thickness")
    fig.tight_layout()
    return fig


def plot_force_distribution(result, title: str | None = None):
    """Force per metre, penetration and deadrise along the body at one instant."""
    plt = _pyplot()
    s = result.sections
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True)
    f = result.loads.force_per_metre
    ax1.bar(s.x, f, width=s.dx, color="C0", alpha=0.75, edgecolor="C0", label="force per metre")
    bad = ~result.valid
    if bad.any():
        ax1.bar(
            s.x[bad],
            f[bad],
            width=s.dx[bad],
            color="C3",
            alpha=0.8,
            label="outside the validity range",
        )
    ax1.set_ylabel("force per metre [N/m]")
    ax1.grid(True, alpha=0.3)
    ax1.legend(loc="best", fontsize=8)
    ax2.plot(s.x, s.penetration * 1e3, "o-", ms=3, color="C1", label="penetration")
    ax2.set_ylabel("penetration [mm]", color="C1")
    ax2.grid(True, alpha=0.3)
    ax3 = ax2.twinx()
    ax3.plot(s.x, s.deadrise_deg, "s-", ms=3, color="C2", label="deadrise")
    ax3.set_ylabel("deadrise [deg]", color="C2")
    ax2.set_xlabel("x along the body [m]")
    ax1.set_title(title or f"Total {result.total:.4f} N over {len(s)} slices")
    fig.tight_layout()
    return fig


def plot_sections(hull, sections, title: str | None = None):
    """The cut: the body's side view with the stations and the waterline, and the section
    outlines at the stations (earth frame, waterline at z = 0)."""
    plt = _pyplot()
    from matplotlib.collections import LineCollection

    from .geometry import frame, silhouette_edges

    fr = frame(hull, sections.pitch)
    a, b = silhouette_edges(hull)
    c, sn = np.cos(sections.pitch), np.sin(sections.pitch)

    def earth(v):
        r = v - fr.cg
        return np.stack(
            [fr.cg[0] + r[:, 0] * c - r[:, 2] * sn, sections.z_cg + r[:, 0] * sn + r[:, 2] * c],
            axis=1,
        )

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2), gridspec_kw={"width_ratios": [3, 2]})
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
    colors = [cmap(i / max(len(xs) - 1, 1)) for i in range(len(xs))]
    for x, col in zip(xs, colors, strict=True):
        ax1.axvline(x, color=col, lw=0.6, alpha=0.8)
    ax1.autoscale()
    ax1.set_aspect("equal", adjustable="datalim")
    ax1.set_xlabel("x [m]")
    ax1.set_ylabel("z [m]")
    ax1.set_title(
        f"Side view: draft {sections.draft:.4g} m, pitch "
        f"{np.degrees(sections.pitch):.3g} deg, {len(xs)} stations"
    )
    ax1.legend(loc="best", fontsize=8)
    for i, col in zip(stations, colors, strict=True):
        for contour in sections.polygons[i]:
            closed = np.vstack([contour, contour[:1]])
            ax2.plot(closed[:, 0], closed[:, 1], color=col, lw=0.8)
    ax2.axhline(0.0, color="C0", lw=1.2)
    ax2.set_aspect("equal", adjustable="datalim")
    ax2.set_xlabel("y [m]")
    ax2.set_ylabel("z [m]")
    ax2.set_title("Sections (aft to fore: dark to light)")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig


def plot_area_curve(x, area, title: str | None = None):
    """The sectional area curve: cross-section area against position along the body."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7, 3.5))
    ax.plot(x, area, "-", color="C0")
    ax.fill_between(x, 0.0, area, color="C0", alpha=0.2)
    ax.set_xlabel("x along the body [m]")
    ax.set_ylabel("section area [m$^2$]")
    ax.grid(True, alpha=0.3)
    ax.set_title(title or "Sectional area curve")
    fig.tight_layout()
    return fig


# cyclic or signed permutations of the body axes (rotations) that bring a view's two axes
# to manifold3d's x and y, for its projection
_VIEWS = (
    ("side (from port)", "x along the body [m]", "z up [m]", ((1, 0, 0), (0, 0, 1), (0, -1, 0))),
    ("top", "x along the body [m]", "y to port [m]", ((1, 0, 0), (0, 1, 0), (0, 0, 1))),
    ("front (from ahead)", "y to port [m]", "z up [m]", ((0, 1, 0), (0, 0, 1), (1, 0, 0))),
)


def plot_views(hull, forward: str = "+x", up: str = "+z", nose: str | None = None):
    """Side, top and front views of the body (its outline), with the forward axis marked.

    Parameters
    ----------
    hull : Hull
    forward, up : str
        The mesh file's axes given as forward and up, for the labels.
    nose : str, optional
        ``"fore"`` or ``"aft"``: the end that looks like a nose
        (:func:`hullslice.orientation.orientation`), marked in the side view.
    """
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path as MplPath

    plt = _pyplot()
    fig, axes = plt.subplots(
        2, 2, figsize=(10, 6.5), gridspec_kw={"width_ratios": [3, 1], "height_ratios": [1, 1]}
    )
    order = (axes[0, 0], axes[1, 0], axes[0, 1])
    lo, hi = hull.bounds
    for ax, (title, xlabel, ylabel, rows) in zip(order, _VIEWS, strict=True):
        m = np.zeros((3, 4))
        m[:, :3] = np.array(rows, dtype=float)
        outline = hull.manifold.transform(m).project()
        verts, codes = [], []
        for poly in outline.to_polygons():
            p = np.asarray(poly, dtype=float)
            if len(p) < 3:
                continue
            verts += [*p.tolist(), p[0].tolist()]
            codes += [MplPath.MOVETO] + [MplPath.LINETO] * (len(p) - 1) + [MplPath.CLOSEPOLY]
        if verts:
            ax.add_patch(PathPatch(MplPath(verts, codes), facecolor="C0", alpha=0.35,
                                   edgecolor="C0", lw=0.8))  # fmt: skip
        ax.autoscale_view()
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_title(title, fontsize=10)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.3)
    length = hi[0] - lo[0]
    for ax, ybase in ((axes[0, 0], lo[2]), (axes[1, 0], lo[1])):
        y0 = ybase - 0.08 * length
        ax.annotate(
            "", xy=(lo[0] + 0.45 * length, y0), xytext=(lo[0] + 0.2 * length, y0),
            arrowprops={"arrowstyle": "->", "color": "C3", "lw": 1.5},
        )  # fmt: skip
        ax.text(lo[0] + 0.47 * length, y0, f"forward (+x, the file's {forward})", color="C3",
                va="center", fontsize=9)  # fmt: skip
        ax.update_datalim([(lo[0], y0 - 0.04 * length)])
        ax.autoscale_view()
    if nose in ("fore", "aft"):
        xn = hi[0] if nose == "fore" else lo[0]
        axes[0, 0].annotate(
            "nose?", xy=(xn, 0.5 * (lo[2] + hi[2])), xytext=(xn, hi[2] + 0.1 * length),
            ha="center", color="C3", arrowprops={"arrowstyle": "->", "color": "C3"},
        )  # fmt: skip
        axes[0, 0].update_datalim([(xn, hi[2] + 0.15 * length)])
        axes[0, 0].autoscale_view()
    axes[1, 1].axis("off")
    axes[1, 1].text(
        0.0, 0.9,
        f"{hull.name}\nlength {length:.4g} m\nbeam {hi[1] - lo[1]:.4g} m\n"
        f"height {hi[2] - lo[2]:.4g} m\nfile axes: forward {forward}, up {up}",
        va="top", fontsize=9, transform=axes[1, 1].transAxes,
    )  # fmt: skip
    fig.suptitle(f"{hull.name}: views of the body frame (x forward, y port, z up)")
    fig.tight_layout()
    return fig
