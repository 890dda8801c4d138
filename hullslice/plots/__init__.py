"""Figures of results, with matplotlib (the optional extra ``hullslice[plot]``).

Every function takes results and returns a ``matplotlib.figure.Figure``; given ``ax=`` (a
matplotlib Axes, or a sequence of Axes for a figure of several panels) it draws there and
returns the Axes' figure instead of making one. :func:`save` writes a figure to a file
completely or not at all. Axes are labelled with their units.

hullslice selects matplotlib's Agg backend only when there is no display and nothing else
was chosen (:func:`choose_backend`); in a notebook the notebook's backend stands.
"""

from __future__ import annotations

from ._common import _pyplot as _pyplot
from ._common import choose_backend, in_notebook, save
from .body import plot_area_curve, plot_sections
from .history import plot_footprint, plot_history
from .loads import plot_face_pressure, plot_frame_loads
from .results import plot_convergence, plot_force_distribution
from .views import plot_views

__all__ = [
    "choose_backend",
    "in_notebook",
    "plot_area_curve",
    "plot_convergence",
    "plot_face_pressure",
    "plot_footprint",
    "plot_force_distribution",
    "plot_frame_loads",
    "plot_history",
    "plot_sections",
    "plot_views",
    "save",
]
