"""Figures of a time history: the motion and force, and the wetted footprint."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from ._common import (
    FLAGGED_LABEL,
    FLAGGED_MARK,
    _pyplot,
    note_handle,
    one_axes,
    panel_axes,
    place_legend,
    spans,
)

_STOP_LABELS = {"t_end": "the end time", "end of table": "the end of the kinematics table"}


def _is_pitched(history: Any) -> bool:
    return bool(
        len(history) and (np.any(history.pitch != history.pitch[0]) or np.any(history.pitch != 0))
    )


def plot_history(history: Any, title: str | None = None, *, ax: Any = None) -> Any:
    """Force, acceleration, velocity and draft against time (and pitch when it varies).

    The peak force is marked (its value and time), the instant the run stopped is a
    vertical line with its reason (:attr:`History.stop_reason`) in the legend, and the spans
    of instants with over 10 % of the force on slices outside the validity range are
    shaded red (not marked when every instant or none is; the legend says which).

    Parameters
    ----------
    history : History
    title : str, optional
        Drawn above the first panel.
    ax : matplotlib Axes or sequence of Axes, optional
        Where to draw: a sequence of one Axes per panel (4: force, acceleration, velocity,
        draft; 5 with pitch when the pitch varies), or one Axes for the force panel only.
        Without it, a new figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    pitched = _is_pitched(history)
    names = ["force", "acceleration", "velocity", "draft"] + (["pitch"] if pitched else [])
    rows = len(names)
    fig, axes, created = panel_axes(
        ax,
        names,
        "plot_history",
        lambda: _pyplot().subplots(rows, 1, figsize=(9, 1.9 * rows), sharex=True),
    )
    t = np.asarray(history.t, dtype=float)
    force = np.asarray(history.force, dtype=float)
    kilo = bool(len(force) and force.max() > 1e4)
    scale, unit = (1e3, "kN") if kilo else (1.0, "N")
    series = [
        (force / scale, f"force [{unit}]"),
        (history.acceleration, "acceleration [m/s$^2$]"),
        (history.velocity, "velocity [m/s]"),
        (history.draft, "draft [m]"),
    ]
    if pitched:
        series.append((np.degrees(history.pitch), "pitch [deg]"))
    flagged = np.asarray(history.valid_share, dtype=float) < 1.0 - FLAGGED_MARK
    runs = spans(t, flagged)
    peak = history.peak if len(history) else None
    for i, (a, (y, label)) in enumerate(zip(axes, series, strict=True)):
        if a is None:
            continue
        a.plot(t, y, color="C0", lw=1.5)
        for j, (lo, hi) in enumerate(runs):
            a.axvspan(lo, hi, color="C3", alpha=0.15, lw=0,
                      label=FLAGGED_LABEL if i == 0 and j == 0 else None)  # fmt: skip
        if peak is not None:
            a.axvline(peak["t"], color="C1", ls="--", lw=0.8, alpha=0.8)
        if len(t):
            a.axvline(t[-1], color="0.3", ls=":", lw=1.2)
        a.set_ylabel(label)
        a.grid(True, alpha=0.3)
    top = axes[0]
    if peak is not None:
        rising = " (last sample: still rising)" if peak.get("at_end") else ""
        top.plot(
            [peak["t"]], [peak["force"] / scale], "v", color="C1", ms=7,
            label=f"peak {peak['force'] / scale:.4g} {unit} at t = {peak['t']:.4g} s{rising}",
        )  # fmt: skip
    if len(t):
        reason = str(history.stop_reason)
        why = _STOP_LABELS.get(reason, reason)
        top.plot([], [], color="0.3", ls=":", lw=1.2, label=f"stop at t = {t[-1]:.4g} s: {why}")
    handles, labels = top.get_legend_handles_labels()
    if len(t) and flagged.all():
        handles.append(note_handle(f"every instant: {FLAGGED_LABEL}"))
        labels.append(handles[-1].get_label())
    place_legend(top, created, handles, labels)
    drawn = [a for a in axes if a is not None]
    drawn[-1].set_xlabel("time [s]")
    if title:
        top.set_title(title)
    if created:
        fig.align_ylabels(drawn)
        fig.tight_layout()
    return fig


def plot_footprint(
    histories: Sequence[Any],
    labels: Sequence[str],
    body_length: tuple[float, float] | None = None,
    *,
    ax: Any = None,
) -> Any:
    """The wetted footprint (its aft and fore ends along the body) against time.

    Parameters
    ----------
    histories : sequence of History
    labels : sequence of str
        One legend entry per history.
    body_length : (float, float), optional
        The body's ``x`` range in m (tail, nose), drawn as lines labelled tail and nose.
    ax : matplotlib Axes, optional
        Where to draw; without it, a new figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax, created = one_axes(ax, (8.5, 4), "plot_footprint")
    for i, (h, label) in enumerate(zip(histories, labels, strict=True)):
        color = f"C{i}"
        aft, fore = h.footprint[:, 0], h.footprint[:, 1]
        ax.fill_between(h.t, aft, fore, color=color, alpha=0.25, lw=0)
        ax.plot(h.t, aft, color=color, lw=1.2, ls="--")
        ax.plot(h.t, fore, color=color, lw=1.2, label=label)
    if len(histories):
        ax.plot([], [], color="0.3", lw=1.2, label="fore end of the wetted part")
        ax.plot([], [], color="0.3", lw=1.2, ls="--", label="aft end of the wetted part")
    if body_length is not None:
        tail, nose = float(body_length[0]), float(body_length[1])
        pad = 0.08 * abs(nose - tail)
        for x, name, va, off in ((nose, "nose", "bottom", pad), (tail, "tail", "top", -pad)):
            ax.axhline(x, color="0.4", lw=0.8, ls="-.")
            ax.annotate(f"{name} (x = {x:.4g} m)", xy=(0.01, x), xycoords=("axes fraction", "data"),
                        xytext=(0, 2 if va == "bottom" else -2), textcoords="offset points",
                        va=va, ha="left", fontsize=8, color="0.25")  # fmt: skip
            ax.update_datalim([(ax.dataLim.x0, x + off)])
        ax.autoscale_view()
        ax.set_ylabel("wetted part along the body, x [m]")
    else:
        ax.set_ylabel("wetted part along the body, x [m]\n(nose up, tail down)")
    ax.set_xlabel("time [s]")
    ax.set_title("Wetted footprint: aft and fore ends of the wetted part")
    ax.grid(True, alpha=0.3)
    place_legend(ax, created)
    if created:
        fig.tight_layout()
    return fig
