"""The report's SVG canvas (marker style computed once per scatter call) writes the same
bytes as matplotlib's own SVG canvas."""

from __future__ import annotations

import numpy as np

from granudb.report import plots


def _figure(canvas: str) -> str:
    rng = np.random.default_rng(3)
    figure, ax = plots.new_axes()
    if canvas == "matplotlib":
        from matplotlib.backends.backend_svg import FigureCanvasSVG

        FigureCanvasSVG(figure)
    colours = {"a/b dry": "#0072b2", "a/b water": "#d55e00"}
    groups = ["a/b dry", "a/b water"] * 300
    plots._scatter_groups(ax, rng.uniform(0, 2, 600), rng.normal(0, 1, 600), groups, colours)
    ax.plot([0.1, 0.2], [1.0, 2.0], "x", ms=6, markerfacecolor="none")
    plots._legend(ax)
    return plots._svg(figure, "fig-test")


def test_report_canvas_writes_matplotlibs_bytes() -> None:
    ours, theirs = _figure("report"), _figure("matplotlib")
    assert ours.count("<use ") == theirs.count("<use ") > 600
    assert ours == theirs
