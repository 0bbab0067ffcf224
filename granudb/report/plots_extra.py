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
    are 2-D on ``viscosity_pa_s`` (rows) × ``velocity_m_s`` (columns). ``runs`` as in
    the report's regime map."""
    from matplotlib.colors import ListedColormap
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    names = list(REGIME_COLOURS)
    codes = np.vectorize(names.index)(regime)
    figure, ax = plots.new_axes((plots.FIGSIZE[0], plots.FIGSIZE[1] + 0.8))
    mu_axis = viscosity_pa_s * 1e3
    ax.contourf(velocity_m_s, mu_axis, codes, levels=np.arange(len(names) + 1) - 0.5,
                cmap=ListedColormap([REGIME_COLOURS[n] for n in names]))  # fmt: skip
    handles: list[Any] = [Patch(color=REGIME_COLOURS[n], label=n) for n in names]
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.log(np.asarray(sigma_over_x1, float))
        if np.isfinite(ratio).any():
            ax.contour(velocity_m_s, mu_axis, ratio, levels=[np.log(1 / 3)], colors="black",
                       linewidths=1.4)  # fmt: skip
            ax.contour(velocity_m_s, mu_axis, ratio, levels=[np.log(1 / 4)], colors="black",
                       linewidths=0.9, linestyles=":")  # fmt: skip
            handles.append(Line2D([], [], color="black", lw=1.4, label="σ = x₁/3 (Λ = 1)"))
            handles.append(
                Line2D([], [], color="black", lw=0.9, ls=":", label="σ = x₁/4 (Λ = 4/3)")
            )
        ax.contour(velocity_m_s, mu_axis, np.log(stokes / critical_stokes), levels=[0.0],
                   colors="black", linewidths=1.2, linestyles="--")  # fmt: skip
    handles.append(Line2D([], [], color="black", lw=1.2, ls="--", label="St_n = St_c"))
    handles += plots._draw_runs(ax, runs, colours or {})
    if point is not None:
        (marker,) = ax.plot([point[0]], [point[1] * 1e3], "*", color="crimson", ms=12,
                            label="this collision")  # fmt: skip
        handles.append(marker)
    plots._log(ax, "x", "y")
    ax.set_xlim(float(np.min(velocity_m_s)), float(np.max(velocity_m_s)))
    ax.set_ylim(float(np.min(mu_axis)), float(np.max(mu_axis)))
    ax.set_xlabel("normal impact velocity v_N,in  (m/s)")
    ax.set_ylabel("fluid viscosity μ  (mPa·s)")
    ax.set_title("Regime map")
    plots._legend(ax, handles)
    return plots._svg(figure, figure_id)


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
    figure, ax = plots.new_axes()
    plots._scatter_groups(
        ax, np.asarray(stokes, float), np.asarray(restitution, float), groups, colours
    )
    for curve in predictions:
        ax.plot(curve["st_n"], curve["e"], ":", lw=1.6, color=colours[curve["label"]],
                label=f"{curve['label']}: predicted, e_dry exp(−35/St)")  # fmt: skip
    if fitted is not None:
        ax.plot(fitted[0], fitted[1], "-", color="#555555", lw=1.2, label=fitted[2])
    ax.axvline(critical_stokes, color="grey", ls="--", lw=1.0, label=f"St_c = {critical_stokes:g}")
    plots._log(ax, "x")
    ax.set_ylim(-0.03, 1.05)
    ax.set_xlabel("normal Stokes number St_n = m* v_N,in / (6πμR*²)  (–)")
    ax.set_ylabel("normal restitution e  (–)")
    ax.set_title("Restitution against Stokes number: measured and predicted")
    plots._legend(ax)
    return plots._svg(figure, figure_id)
