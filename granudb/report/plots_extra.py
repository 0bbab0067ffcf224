"""Figures added for the physics of issue 13, beside ``granudb.report.plots`` (whose
helpers they reuse so every figure looks and behaves the same):

- ``regime_map``: the velocity × viscosity plane with the three-state roughness verdict
  (asperity contact / uncertain / film, Davis's band h_m = x₁/4 … x₁/3) and no rebound;
- ``restitution_with_prediction``: measured e against St_n with, per group, the
  predicted curve e_dry exp(−35/St) of Legendre et al. (2006).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from granudb.report import plots
from granudb.report.svg import Plot, Style
from granudb.report.verdicts import ROUGHNESS_WORDS

#: Regions of the regime map, in drawing order, with their fill colours.
REGIME_COLOURS = {
    "no rebound": "#d9d9d9",
    f"rebound, {ROUGHNESS_WORDS['asperity_contact']}": "#fdd9b5",
    f"rebound, {ROUGHNESS_WORDS['uncertain']}": "#f3ecb0",
    f"rebound, {ROUGHNESS_WORDS['film']}": "#cfe3f2",
}


def regime_names(rebound: np.ndarray, roughness: np.ndarray) -> np.ndarray:
    """The region name of each grid cell from ``rebound_expected`` and ``roughness_regime``."""
    names = np.array(
        [f"rebound, {ROUGHNESS_WORDS.get(str(r), ROUGHNESS_WORDS['film'])}" for r in
         np.asarray(roughness, dtype=object).ravel()], dtype=object
    ).reshape(np.shape(roughness))  # fmt: skip
    return np.where(np.asarray(rebound, bool), names, "no rebound").astype(object)


def _edges(centres: np.ndarray) -> np.ndarray:
    """Cell edges around geometric grid points: midway in log space, clipped to the grid."""
    logs = np.log10(np.asarray(centres, float))
    middle = (logs[1:] + logs[:-1]) / 2
    return 10 ** np.concatenate([[logs[0]], middle, [logs[-1]]])


def regime_map(
    velocity_m_s: np.ndarray,
    viscosity_pa_s: np.ndarray,
    regime: np.ndarray,
    sigma_over_x1: np.ndarray,
    stokes: np.ndarray,
    critical_stokes: float,
    *,
    point: tuple[float, float] | None = None,
    runs: Sequence[dict[str, Any]] = (),
    colours: Mapping[str, str] | None = None,
    figure_id: str = "fig-regime-map",
) -> str:
    """The regime plane shaded by ``regime`` (names of ``REGIME_COLOURS``), with the lines
    σ = x₁/3 (Λ = 1), σ = x₁/4 (Λ = 4/3) and St_n = St_c; ``sigma_over_x1`` and ``stokes``
    are 2-D on ``viscosity_pa_s`` (rows) × ``velocity_m_s`` (columns) (geometric grids).
    ``runs`` as in the report's regime map."""
    from granudb.report.contour import level_lines

    names = list(REGIME_COLOURS)
    codes = np.vectorize(names.index, otypes=[int])(regime)
    mu_axis = np.asarray(viscosity_pa_s, float) * 1e3
    velocity = np.asarray(velocity_m_s, float)
    plot = Plot(xlog=True, ylog=True, height=plots_height(), title="Regime map",
                xlabel="normal impact velocity v_N,in  (m/s)",
                ylabel="fluid viscosity μ  (mPa·s)")  # fmt: skip
    plot.cells(_edges(velocity), _edges(mu_axis), codes, [REGIME_COLOURS[n] for n in names])
    for name in names:
        plot.patch(REGIME_COLOURS[name], name)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.log(np.asarray(sigma_over_x1, float))
        if np.isfinite(ratio).any():
            for level, style, label in (
                (np.log(1 / 3), Style("#000000", width=1.4), "σ = x₁/3 (Λ = 1)"),
                (np.log(1 / 4), Style("#000000", width=0.9, dash="1,1.65"), "σ = x₁/4 (Λ = 4/3)"),
            ):
                plot.polylines(level_lines(velocity, mu_axis, ratio, level), style)
                plot.legend.append(("line", style, label))
        stokes_ratio = np.log(np.asarray(stokes, float) / critical_stokes)
    dashed = Style("#000000", width=1.2, dash="4.4,1.9")
    plot.polylines(level_lines(velocity, mu_axis, stokes_ratio, 0.0), dashed)
    plot.legend.append(("line", dashed, "St_n = St_c"))
    plots.draw_runs(plot, runs, colours or {})
    if point is not None:
        plot.points([point[0]], [point[1] * 1e3], Style("#dc143c", marker="*", size=12),
                    "this collision")  # fmt: skip
    plot.xlim = (float(np.min(velocity)), float(np.max(velocity)))
    plot.ylim = (float(np.min(mu_axis)), float(np.max(mu_axis)))
    return plot.svg(figure_id)


def plots_height() -> float:
    """The regime map is taller than the scatter figures (0.8 in more, as before)."""
    from granudb.report.svg import PLOT_HEIGHT

    return PLOT_HEIGHT + 0.8 * 72 * 0.77


def restitution_with_prediction(
    stokes: np.ndarray,
    restitution: np.ndarray,
    groups: Sequence[str],
    colours: Mapping[str, str],
    predictions: Sequence[dict[str, Any]],
    critical_stokes: float,
    fitted: tuple[np.ndarray, np.ndarray, str] | None = None,
    figure_id: str = "fig-restitution",
) -> str:
    """e against St_n with each group's predicted curve in the group's colour (dotted) and
    an optional fitted curve (grey). ``predictions``: dicts with ``label`` (a key of
    ``colours``), ``st_n`` and ``e`` arrays (the curve, on the St_n axis)."""
    plot = Plot(xlog=True, title="Restitution against Stokes number: measured and predicted",
                xlabel="normal Stokes number St_n = m* v_N,in / (6πμR*²)  (–)",
                ylabel="normal restitution e  (–)")  # fmt: skip
    plots._scatter_groups(
        plot, np.asarray(stokes, float), np.asarray(restitution, float), groups, colours
    )
    for curve in predictions:
        dotted = Style(colours[curve["label"]], width=1.6, dash="1.6,2.6")
        plot.line(curve["st_n"], curve["e"], dotted,
                  f"{curve['label']}: predicted, e_dry exp(−35/St)")  # fmt: skip
    if fitted is not None:
        plot.line(fitted[0], fitted[1], Style("#555555"), fitted[2])
    plot.vline(critical_stokes, Style("#808080", width=1.0, dash="3.7,1.6"),
               f"St_c = {critical_stokes:g}")  # fmt: skip
    plot.ylim = (-0.03, 1.05)
    return plot.svg(figure_id)
