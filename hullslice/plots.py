"""Figures of results, with matplotlib (the optional extra ``hullslice[plot]``).

Every function takes results and returns a ``matplotlib.figure.Figure``; :func:`save`
writes one to a file completely or not at all. Axes are labelled with their units.
"""

from __future__ import annotations

import io
import os
from collections.abc import Sequence

import numpy as np

from .errors import HullsliceError
from .report import write_atomic

__all__ = ["plot_footprint", "plot_history", "save"]


class MissingDependencyError(ImportError, HullsliceError):
    """An optional dependency is needed and not installed."""


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
        (history.penetration, "draft [m]"),
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
