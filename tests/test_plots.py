"""Figures: drawn into given Axes, the backend left to notebooks, and what each shows."""

from __future__ import annotations

import dataclasses
import sys

import numpy as np
import pytest

import hullslice as hs
from hullslice.errors import InputError
from hullslice.sections import area_curve

from .conftest import MESHES

pytest.importorskip("matplotlib")

import matplotlib
import matplotlib.pyplot as plt

from hullslice import plots
from hullslice.plots import _common


@pytest.fixture(scope="module")
def prism() -> hs.Hull:
    return hs.load_hull(MESHES / "paper_prism.stl", mass=1.0)


@pytest.fixture(scope="module")
def history(prism):
    return hs.simulate(prism, -4.0, 0.03, dt=0.0005, slices=16)


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _overlap(a, b) -> bool:
    return not (a.x1 <= b.x0 or b.x1 <= a.x0 or a.y1 <= b.y0 or b.y1 <= a.y0)


# --- ax= and the returned figure ------------------------------------------------------------


def _draw_all(prism, history, axes_for):
    study = hs.convergence(prism, 0.0383, -3.4943, slices=(16, 32, 64))
    sections = hs.cut(prism, 0.0383, slices=16)
    x, area = area_curve(prism, 20)
    return {
        "history": lambda: plots.plot_history(history, "t", ax=axes_for(4)),
        "footprint": lambda: plots.plot_footprint([history], ["a"], (0.0, 0.35), ax=axes_for(1)),
        "convergence": lambda: plots.plot_convergence(study, {"paper": 147.79}, ax=axes_for(1)),
        "distribution": lambda: plots.plot_force_distribution(study.finest, ax=axes_for(2)),
        "sections": lambda: plots.plot_sections(prism, sections, "t", ax=axes_for(2)),
        "area": lambda: plots.plot_area_curve(x, area, ax=axes_for(1)),
        "views": lambda: plots.plot_views(prism, ax=axes_for(4)),
    }


def test_every_plot_draws_into_the_given_axes_and_returns_their_figure(prism, history):
    made = []

    def axes_for(n):
        fig, axes = plt.subplots(1, n, squeeze=False)
        made.append((fig, set(plt.get_fignums())))
        return list(axes[0]) if n > 1 else axes[0, 0]

    for name, draw in _draw_all(prism, history, axes_for).items():
        fig = draw()
        given, before = made[-1]
        assert fig is given, name
        # no other figure made (a colour bar may add Axes to the given figure only)
        assert set(plt.get_fignums()) == before, name
        assert given.axes[0].has_data(), name


def test_one_axes_draws_the_first_panel_only(prism, history):
    fig, ax = plt.subplots()
    assert plots.plot_history(history, ax=ax) is fig
    assert len(fig.axes) == 1 and ax.get_ylabel() == "force [N]"
    fig2, ax2 = plt.subplots()
    sections = hs.cut(prism, 0.0383, slices=16)
    assert plots.plot_sections(prism, sections, ax=ax2) is fig2
    assert ax2.get_ylabel() == "z [m]" and len(fig2.axes) == 1


def test_an_axes_in_a_subfigure_returns_the_whole_figure(history):
    fig = plt.figure()
    sub = fig.subfigures(1, 2)[1]
    ax = sub.subplots()
    assert plots.plot_footprint([history], ["a"], ax=ax) is fig


def test_a_wrong_number_of_axes_is_refused_naming_the_panels(history):
    _, axes = plt.subplots(1, 2)
    with pytest.raises(InputError, match=r"4 panels \(force, acceleration, velocity, draft\)"):
        plots.plot_history(history, ax=list(axes))
    with pytest.raises(InputError, match="one matplotlib Axes"):
        plots.plot_footprint([history], ["a"], ax="not an axes")


def test_without_ax_a_new_figure_each_time(history):
    a = plots.plot_history(history)
    b = plots.plot_history(history)
    assert a is not b and len(a.axes) == 4


# --- the backend ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("chosen", "notebook", "environ", "platform", "expected"),
    [
        (False, False, {}, "linux", "Agg"),  # headless: nothing else would work
        (False, False, {"DISPLAY": ":0"}, "linux", None),
        (False, False, {"WAYLAND_DISPLAY": "wayland-0"}, "linux", None),
        (False, True, {}, "linux", None),  # a notebook picks its own (inline, widget)
        (True, False, {}, "linux", None),  # the user chose one
        (False, False, {"MPLBACKEND": "svg"}, "linux", None),
        (False, False, {}, "darwin", None),
        (False, False, {}, "win32", None),
    ],
)
def test_the_backend_decision(chosen, notebook, environ, platform, expected):
    got = _common.choose_backend(
        chosen=chosen, notebook=notebook, environ=environ, platform=platform
    )
    assert got == expected


def test_in_a_notebook_hullslice_never_selects_agg(monkeypatch):
    monkeypatch.setattr(_common, "in_notebook", lambda: True)
    monkeypatch.setattr(_common, "_backend_chosen", lambda mpl: False)
    monkeypatch.delenv("DISPLAY", raising=False)
    calls = []
    monkeypatch.setattr(matplotlib, "use", lambda *a, **k: calls.append(a))
    plots._pyplot()
    assert calls == []
    monkeypatch.setattr(_common, "in_notebook", lambda: False)
    monkeypatch.setattr(_common.sys, "platform", "linux")
    monkeypatch.delenv("MPLBACKEND", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    plots._pyplot()
    assert calls == [("Agg",)]


def test_an_ipython_kernel_counts_as_a_notebook(monkeypatch):
    class Shell:
        pass

    fake = type(sys)("IPython")
    fake.get_ipython = lambda: Shell()  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "IPython", fake)
    assert _common.in_notebook()
    fake.get_ipython = lambda: None  # type: ignore[attr-defined]
    monkeypatch.delitem(sys.modules, "ipykernel", raising=False)
    assert not _common.in_notebook()


# --- what the figures show -----------------------------------------------------------------------


def test_the_side_view_zooms_on_the_wetted_region(prism):
    sections = hs.cut(prism, 0.0383, slices=16)
    fig = plots.plot_sections(prism, sections)
    side = fig.axes[0]
    wet0 = float(np.min(sections.x - sections.dx / 2))
    wet1 = float(np.max(sections.x + sections.dx / 2))
    x0, x1 = side.get_xlim()
    z0, z1 = side.get_ylim()
    margin = plots.body.WETTED_MARGIN if hasattr(plots, "body") else 0.12
    assert x0 == pytest.approx(wet0 - margin * (wet1 - wet0), abs=1e-9)
    assert x1 == pytest.approx(wet1 + margin * (wet1 - wet0), abs=1e-9)
    assert x1 - x0 < 0.6 * 0.35  # the prism is 0.35 m long, 0.16 m of it wetted
    assert z0 < -0.0383 < 0.0 < z1 < 0.03  # the keel and the waterline, not the deck (0.06)


def test_the_sections_panel_has_a_colour_bar_for_x(prism):
    sections = hs.cut(prism, 0.0383, slices=16)
    fig = plots.plot_sections(prism, sections)
    (bar,) = [a for a in fig.axes if a.get_ylabel() == "station x [m]"]
    lo, hi = bar.get_ylim()
    assert lo == pytest.approx(sections.x.min(), abs=1e-12)
    assert hi == pytest.approx(sections.x.max(), abs=1e-12)


def test_the_footprint_names_nose_and_tail_and_its_legend_is_off_the_data(history):
    fig = plots.plot_footprint([history, history], ["one", "two"], (0.0, 0.35))
    ax = fig.axes[0]
    texts = [t.get_text() for t in ax.texts]
    assert "nose (x = 0.35 m)" in texts and "tail (x = 0 m)" in texts
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    legend = ax.get_legend().get_window_extent(renderer)
    assert not _overlap(legend, ax.get_window_extent(renderer))
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "fore end of the wetted part" in labels and "aft end of the wetted part" in labels
    lo, hi = ax.get_ylim()
    assert lo < 0.0 and hi > 0.35  # room for the labels beyond the body's ends


def test_the_history_marks_the_peak_and_the_stop_with_its_reason(history):
    fig = plots.plot_history(history)
    top = fig.axes[0]
    labels = [t.get_text() for t in top.get_legend().get_texts()]
    pk = history.peak
    assert f"peak {pk['force']:.4g} N at t = {pk['t']:.4g} s" in labels
    assert f"stop at t = {history.t[-1]:.4g} s: {history.stop_reason}" in labels
    for ax in fig.axes:
        xs = {float(line.get_xdata()[0]) for line in ax.lines if len(line.get_xdata()) == 2}
        assert pk["t"] in xs and float(history.t[-1]) in xs
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    assert not _overlap(top.get_legend().get_window_extent(r), top.get_window_extent(r))


def test_flagged_spans_only_where_they_tell_something():
    t = np.arange(6) * 0.1
    assert _common.spans(t, np.zeros(6, bool)) == []
    assert _common.spans(t, np.ones(6, bool)) == []
    got = _common.spans(t, np.array([0, 1, 1, 0, 0, 1], bool))
    assert got == [pytest.approx((0.05, 0.25)), pytest.approx((0.45, 0.5))]


def _span_count(fig) -> int:
    from matplotlib.patches import Rectangle

    return sum(isinstance(p, Rectangle) and p.get_facecolor()[0] > 0.5 for p in fig.axes[0].patches)


def test_the_history_shades_some_flagged_instants_and_says_so_when_all_are(history):
    n = len(history)
    some = np.ones(n)
    some[n // 3 : n // 2] = 0.5
    fig = plots.plot_history(dataclasses.replace(history, valid_share=some))
    assert _span_count(fig) == 1
    assert _common.FLAGGED_LABEL in [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    fig = plots.plot_history(dataclasses.replace(history, valid_share=np.zeros(n)))
    assert _span_count(fig) == 0
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert f"every instant: {_common.FLAGGED_LABEL}" in labels
    fig = plots.plot_history(dataclasses.replace(history, valid_share=np.ones(n)))
    assert _span_count(fig) == 0
    assert _common.FLAGGED_LABEL not in " ".join(
        t.get_text() for t in fig.axes[0].get_legend().get_texts()
    )


def test_the_force_distribution_reds_only_some_flagged_slices(prism):
    result = hs.compute_force(prism, 0.0383, -3.4943, slices=16)
    some = np.zeros(len(result.valid), bool)
    some[:3] = True
    for bad, red_bars, note in ((some, 3, False), (np.ones_like(some), 0, True)):
        res = dataclasses.replace(result, loads=dataclasses.replace(result.loads, valid=~bad))
        fig = plots.plot_force_distribution(res)
        reds = [p for p in fig.axes[0].patches if p.get_facecolor()[0] > 0.7]
        assert len(reds) == red_bars
        labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
        assert ("every slice is outside the validity range" in labels) is note


# --- a user's own layout: legends inside their Axes -------------------------------------------


def _legends_within_their_axes(fig) -> int:
    """Check that every legend of ``fig`` lies within its Axes' box (to half a pixel) and
    that the figure has no legend of its own beyond them; return how many there are."""
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    count = 0
    for a in fig.axes:
        legend = a.get_legend()
        if legend is None:
            continue
        box, frame = legend.get_window_extent(r), a.get_window_extent(r)
        assert frame.x0 - 0.5 <= box.x0 and box.x1 <= frame.x1 + 0.5, (box, frame)
        assert frame.y0 - 0.5 <= box.y0 and box.y1 <= frame.y1 + 0.5, (box, frame)
        count += 1
    assert not fig.legends
    return count


def _grid():
    fig, axes = plt.subplots(2, 2)  # matplotlib's default figure: 6.4 x 4.8 in, 100 dpi
    return fig, list(axes.ravel())


def test_in_a_two_by_two_grid_every_legend_stays_within_its_axes(prism):
    # a history with a long peak label, a flagged span and a stop, and a footprint of three
    history = hs.simulate(prism, -4.0, 0.03, dt=0.0005, slices=16)
    some = np.ones(len(history))
    some[len(history) // 3 : len(history) // 2] = 0.5
    flagged = dataclasses.replace(history, valid_share=some)
    study = hs.convergence(prism, 0.0383, -3.4943, slices=(16, 32, 64))
    result = study.finest
    bad = np.zeros(len(result.valid), bool)
    bad[:3] = True
    some_bad = dataclasses.replace(result, loads=dataclasses.replace(result.loads, valid=~bad))
    sections = hs.cut(prism, 0.0383, slices=16)
    x, area = area_curve(prism, 20)
    kept = hs.simulate(prism, -4.0, 0.01, dt=0.0005, slices=16, sections_every=4)
    frames = kept.frame_loads(prism, spacing=0.05)
    # name, (figure function of the grid's Axes), legends it draws
    figures = [
        ("history", lambda axes: plots.plot_history(flagged, "t", ax=axes), 1),
        ("views", lambda axes: plots.plot_views(prism, ax=axes), 0),
        ("footprint", lambda axes: plots.plot_footprint(
            [history] * 3, ["first run", "second run", "third run"], (0.0, 0.35), ax=axes[0]), 1),
        ("convergence", lambda axes: plots.plot_convergence(
            study, {"the paper's extrapolation": 147.7947, "CFD": 137.9688}, ax=axes[0]), 1),
        ("distribution", lambda axes: plots.plot_force_distribution(some_bad, ax=axes[:2]), 1),
        ("sections", lambda axes: plots.plot_sections(prism, sections, "t", ax=axes[2:]), 1),
        ("area", lambda axes: plots.plot_area_curve(x, area, ax=axes[3]), 0),
        ("frame loads", lambda axes: plots.plot_frame_loads(frames, ax=axes[1]), 1),
        ("face pressure", lambda axes: plots.plot_face_pressure(
            prism, np.linspace(0.0, 1e5, len(prism.faces)), ax=axes[0]), 0),
    ]  # fmt: skip
    for name, draw, legends in figures:
        fig, axes = _grid()
        assert draw(axes) is fig
        assert _legends_within_their_axes(fig) == legends, name
        plt.close(fig)
    # the one-Axes figures side by side in one grid, each with its neighbours
    fig, axes = _grid()
    plots.plot_footprint([history], ["a run"], (0.0, 0.35), ax=axes[0])
    plots.plot_convergence(study, {"paper": 147.7947}, ax=axes[1])
    plots.plot_history(flagged, ax=axes[2])
    plots.plot_force_distribution(some_bad, ax=axes[3])
    assert _legends_within_their_axes(fig) == 4


def test_on_its_own_figure_a_legend_stays_beside_the_axes(prism, history):
    """Without ax=, hullslice lays out its own figure with the legend clear of the data."""
    study = hs.convergence(prism, 0.0383, -3.4943, slices=(16, 32))
    fig = plots.plot_convergence(study, {"paper": 147.7947})
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    ax = fig.axes[0]
    assert ax.get_legend().get_window_extent(r).x0 >= ax.get_window_extent(r).x1
