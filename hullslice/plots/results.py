"""Figures of a force computation: the convergence in the slice thickness and the force
along the body."""

from __future__ import annotations

from typing import Any

import numpy as np

from ._common import _pyplot, note_handle, one_axes, panel_axes, place_legend


def plot_convergence(
    study: Any,
    references: dict[str, float] | None = None,
    title: str | None = None,
    *,
    ax: Any = None,
) -> Any:
    """Force against slice thickness, with the Richardson-extrapolated force and its GCI band
    (as the paper's Fig. 8).

    Parameters
    ----------
    study : ConvergenceStudy
    references : dict of str to float, optional
        Forces in N drawn as horizontal lines (e.g. the paper's and a CFD value), by label.
    title : str, optional
    ax : matplotlib Axes, optional
        Where to draw; without it, a new figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax, created = one_axes(ax, (8.5, 4.2), "plot_convergence")
    d = np.array([float(r.sections.dx.max()) if len(r.sections.dx) else 0.0 for r in study.results])
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
    place_legend(ax, created)
    ax.set_title(title or "Convergence in the slice thickness")
    if created:
        fig.tight_layout()
    return fig


def plot_force_distribution(result: Any, title: str | None = None, *, ax: Any = None) -> Any:
    """Force per metre, penetration and deadrise along the body at one instant.

    Slices outside the validity range are red (when only some are; when every slice is,
    the legend says so instead).

    Parameters
    ----------
    result : ForceResult
    title : str, optional
    ax : matplotlib Axes or sequence of two Axes, optional
        Where to draw: two Axes (force per metre; penetration and deadrise, the deadrise on
        a twin axis), or one Axes for the force per metre only. Without it, a new figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, (ax1, ax2), created = panel_axes(
        ax,
        ["force per metre", "penetration and deadrise"],
        "plot_force_distribution",
        lambda: _pyplot().subplots(2, 1, figsize=(8.5, 5.5), sharex=True),
    )
    s = result.sections
    f = result.loads.force_per_metre
    bad = ~np.asarray(result.valid, dtype=bool)
    ax1.bar(s.x, f, width=s.dx, color="C0", alpha=0.75, edgecolor="C0", label="force per metre")
    if bad.any() and not bad.all():
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
    handles, labels = ax1.get_legend_handles_labels()
    if len(bad) and bad.all():
        handles.append(note_handle("every slice is outside the validity range"))
        labels.append(handles[-1].get_label())
    place_legend(ax1, created, handles, labels)
    ax1.set_title(title or f"Total {result.total:.4f} N over {len(s)} slices")
    if ax2 is None:
        ax1.set_xlabel("x along the body [m]")
    else:
        ax2.plot(s.x, s.penetration * 1e3, "o-", ms=3, color="C1", label="penetration")
        ax2.set_ylabel("penetration [mm]", color="C1")
        ax2.grid(True, alpha=0.3)
        ax3 = ax2.twinx()
        ax3.plot(s.x, s.deadrise_deg, "s-", ms=3, color="C2", label="deadrise")
        ax3.set_ylabel("deadrise [deg]", color="C2")
        ax2.set_xlabel("x along the body [m]")
    if created:
        fig.tight_layout()
    return fig
