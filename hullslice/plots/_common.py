"""What every figure shares: matplotlib and its backend, the axes to draw into, legends and
marks, and :func:`save`."""

from __future__ import annotations

import io
import os
import sys
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ..atomic import write_atomic
from ..errors import InputError, MissingDependencyError
from ..extras import need

#: Instants (or slices) whose share of the force on slices outside the validity range is
#: above this are marked.
FLAGGED_MARK = 0.1

FLAGGED_LABEL = "over 10 % of the force on slices outside the validity range"


def choose_backend(
    *, chosen: bool, notebook: bool, environ: Mapping[str, str], platform: str
) -> str | None:
    """The backend hullslice selects itself: ``"Agg"`` only when there is no display and
    nothing else was chosen, else None (matplotlib's own choice stands).

    Parameters
    ----------
    chosen : bool
        A backend was already selected (``matplotlib.use``, ``MPLBACKEND``, a matplotlibrc).
    notebook : bool
        An IPython shell or kernel (a notebook) is running: it picks its own backend.
    environ : mapping of str to str
        The environment (``os.environ``).
    platform : str
        ``sys.platform``.
    """
    if chosen or notebook or environ.get("MPLBACKEND"):
        return None
    if platform.startswith(("win", "cygwin", "darwin")):
        return None  # these always have a display
    if environ.get("DISPLAY") or environ.get("WAYLAND_DISPLAY"):
        return None
    return "Agg"


def in_notebook() -> bool:
    """True when an IPython shell or kernel (a Jupyter notebook) runs this process."""
    if "IPython" not in sys.modules and "ipykernel" not in sys.modules:
        return False
    try:
        from IPython import get_ipython
    except ImportError:
        return "ipykernel" in sys.modules
    return get_ipython() is not None or "ipykernel" in sys.modules


def _backend_chosen(matplotlib: Any) -> bool:
    try:
        from matplotlib import rcsetup

        return matplotlib.rcParams._get("backend") is not rcsetup._auto_backend_sentinel
    except AttributeError:  # a matplotlib without these internals: leave it alone
        return True


def _pyplot() -> Any:
    matplotlib = need("plot", "matplotlib", "drawing figures")
    try:
        backend = choose_backend(
            chosen=_backend_chosen(matplotlib),
            notebook=in_notebook(),
            environ=os.environ,
            platform=sys.platform,
        )
        if backend is not None:
            matplotlib.use(backend)
        import matplotlib.pyplot as plt
    except ImportError:  # a broken installation: its own error, with the install hint
        raise MissingDependencyError(
            "drawing figures needs matplotlib.pyplot, which cannot be imported: pip install "
            "'hullslice[plot]' (or pip install matplotlib)"
        ) from None
    return plt


def save(fig: Any, path: str | os.PathLike, dpi: int = 120) -> None:
    """Write a figure to ``path`` (PNG, SVG or PDF by extension), completely or not at all."""
    fmt = os.path.splitext(str(path))[1].lstrip(".").lower() or "png"
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, dpi=dpi, bbox_inches="tight")
    write_atomic(path, buf.getvalue())
    _pyplot().close(fig)


def _is_axes(ax: object) -> bool:
    from matplotlib.axes import Axes

    return isinstance(ax, Axes)


def root_figure(ax: Any) -> Any:
    """The figure an Axes belongs to (the whole figure for an Axes in a subfigure)."""
    fig = ax.figure
    return getattr(fig, "figure", None) or fig


def one_axes(ax: Any, figsize: tuple[float, float], what: str) -> tuple[Any, Any, bool]:
    """``(figure, axes, created)``: a new figure and Axes, or the given Axes' figure."""
    plt = _pyplot()
    if ax is None:
        fig, new = plt.subplots(figsize=figsize)
        return fig, new, True
    if not _is_axes(ax):
        raise InputError(
            f"{what} draws into one matplotlib Axes: ax={ax!r} is not one; give an Axes "
            "(e.g. fig, ax = plt.subplots()) or leave ax out for a new figure"
        )
    return root_figure(ax), ax, False


def panel_axes(ax: Any, panels: Sequence[str], what: str, make: Any) -> tuple[Any, list[Any], bool]:
    """``(figure, axes, created)`` for a figure of several panels, named ``panels``.

    ``ax`` None: ``make()`` builds the figure and its Axes. One Axes: the first panel only
    (the others are None). A sequence: one Axes per panel.
    """
    _pyplot()
    if ax is None:
        fig, axes = make()
        return fig, list(np.ravel(axes))[: len(panels)], True
    if _is_axes(ax):
        return root_figure(ax), [ax] + [None] * (len(panels) - 1), False
    axes = (
        list(np.ravel(np.asarray(ax, dtype=object)))
        if isinstance(ax, Sequence | np.ndarray)
        else []
    )
    if len(axes) != len(panels) or not all(_is_axes(a) for a in axes):
        raise InputError(
            f"{what} draws {len(panels)} panels ({', '.join(panels)}): give ax as "
            f"{len(panels)} matplotlib Axes, or one Axes for the {panels[0]} panel only "
            f"(got {ax!r})"
        )
    return root_figure(axes[0]), axes, False


#: Legend font sizes (pt) tried, largest first, for a legend inside a user's Axes.
INSIDE_FONT_SIZES = (8.0, 7.0, 6.0)


def place_legend(ax: Any, created: bool, handles: Any = None, labels: Any = None) -> Any:
    """The legend of ``ax`` (its labelled artists, or ``handles`` and ``labels``); nothing
    when nothing is labelled.

    On a figure hullslice made (``created``), to the right of the Axes, clear of the data:
    the figure is laid out around it. In a user's Axes (``ax=``), inside the Axes where it
    hides the least data, its labels wrapped and its font made smaller (down to the last of
    :data:`INSIDE_FONT_SIZES`) until it fits: never over a neighbouring Axes of the user's
    layout.
    """
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    if not handles:
        return None
    if created:
        return ax.legend(
            handles,
            labels,
            loc="upper left",
            bbox_to_anchor=(1.01, 1.0),
            borderaxespad=0.0,
            fontsize=8,
        )
    box = ax.get_window_extent()
    dpi = root_figure(ax).dpi
    width, height = box.width * 72.0 / dpi, box.height * 72.0 / dpi  # pt
    size = INSIDE_FONT_SIZES[-1]
    wrapped = list(labels)
    for size in INSIDE_FONT_SIZES:
        wrapped = [_wrap(str(label), width, size) for label in labels]
        if _legend_height(wrapped, size) <= height:
            break
    legend = ax.legend(
        handles,
        wrapped,
        loc="best",
        fontsize=size,
        borderaxespad=0.3,
        handlelength=1.5,
        framealpha=0.8,
    )
    legend.set_in_layout(False)  # inside the Axes: nothing for a layout to make room for
    return legend


def _wrap(label: str, width: float, size: float) -> str:
    """``label`` in lines that fit a legend inside an Axes ``width`` pt wide at ``size`` pt
    (a character taken as 0.6 em, mathematical text left whole)."""
    import textwrap

    # the handle (1.5 em), its pad (0.8), the borders (0.4 each) and the pads to the Axes
    # (0.3 each), in em
    text = width / size - 1.5 - 0.8 - 2 * 0.4 - 2 * 0.3
    chars = max(8, int(text / 0.6))
    if "$" in label or len(label) <= chars:
        return label
    return "\n".join(textwrap.wrap(label, chars, break_on_hyphens=False))


def _legend_height(labels: Sequence[str], size: float) -> float:
    """The height in pt of a legend of ``labels`` at ``size`` pt: lines of 1.2 em, 0.5 em
    between entries, borders of 0.4 em and pads to the Axes of 0.3 em."""
    lines = sum(label.count("\n") + 1 for label in labels)
    return size * (1.2 * lines + 0.5 * (len(labels) - 1) + 2 * 0.4 + 2 * 0.3)


def note_handle(label: str) -> Any:
    """A legend entry that is only text (no mark)."""
    from matplotlib.patches import Patch

    return Patch(facecolor="none", edgecolor="none", label=label)


def spans(t: np.ndarray, flag: np.ndarray) -> list[tuple[float, float]]:
    """The runs of consecutive flagged instants as ``(start, end)`` times, s, each reaching
    halfway to the unflagged neighbours. Empty when none or every instant is flagged (marks
    would tell nothing there)."""
    t = np.asarray(t, dtype=float)
    flag = np.asarray(flag, dtype=bool)
    if len(t) == 0 or not flag.any() or flag.all():
        return []
    out = []
    edges = np.diff(np.concatenate([[0], flag.astype(np.int8), [0]]))
    for i0, i1 in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1, strict=True):
        lo = 0.5 * (t[i0 - 1] + t[i0]) if i0 > 0 else t[i0]
        hi = 0.5 * (t[i1] + t[i1 + 1]) if i1 < len(t) - 1 else t[i1]
        out.append((float(lo), float(hi)))
    return out
