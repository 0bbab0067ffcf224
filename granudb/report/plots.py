"""The report's figures, as deterministic SVG text.

Each function takes plain arrays and returns an SVG string with axis labels, units and a
legend; the same input gives the same bytes. Drawn with ``granudb.report.svg`` (not
matplotlib: that module says why).

Thinning (issue 17): a scatter figure draws at most ``MAX_POINTS`` runs. A figure of N
runs whose series (group, or fluid × regime) holds n of them draws ⌈MAX_POINTS · n / N⌉ of
that series, a fixed-seed sample (``THIN_SEED``), so each group keeps its share and the
same data always gives the same figure; the legend says "k of n runs shown". Fits, tables
and every count use all runs: thinning only spares the reader's browser (and the report's
time: 100,000 runs make a figure of a few hundred kilobytes).

Three rules keep the figures honest and consistent with the tables:
- colours come from the caller (``granudb.report.groups``), one per group for the whole
  report, and a group's fit lines share its points' colour;
- legends sit below the axes, never over the data;
- names are data: drawn as typed and escaped, never read as markup or mathtext; a linear
  axis never inflates a spread of 3×10⁻⁴ into the whole height.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from granudb.report.svg import Plot, Style

#: Runs drawn per scatter figure at most; more add bytes, not information, to a scatter plot.
MAX_POINTS = 2000
THIN_SEED = 20040101
#: A linear y-axis spans at least this fraction of the data's magnitude.
MIN_RELATIVE_SPAN = 0.25
GAMMA = "(–)"
PSI_IN = "Ψ_in = v_T,in / v_N,in  (–)"


def thin(*arrays: np.ndarray, limit: int = MAX_POINTS) -> tuple[np.ndarray, ...]:
    """At most ``limit`` points, the same subset of every array (seeded, so repeatable)."""
    n = len(arrays[0])
    if n <= limit:
        return arrays
    keep = np.sort(np.random.default_rng(THIN_SEED).choice(n, size=limit, replace=False))
    return tuple(np.asarray(a)[keep] for a in arrays)


def share(count: int, total: int) -> int:
    """Points a series of ``count`` of a figure's ``total`` runs may draw."""
    return count if total <= MAX_POINTS else -(-MAX_POINTS * count // total)


def shown(count: int, drawn: int) -> str:
    """The legend's count: "12 runs", or "667 of 33,334 runs shown" when thinned."""
    return f"{count} runs" if drawn == count else f"{drawn:,} of {count:,} runs shown"


def _honest_limits(plot: Plot, values: np.ndarray) -> None:
    """Widen a linear y-axis around a tiny spread, so noise does not fill the figure."""
    finite = np.asarray(values, float)
    finite = finite[np.isfinite(finite)]
    if finite.size == 0:
        return
    low, high = float(finite.min()), float(finite.max())
    centre = (low + high) / 2
    span = max(high - low, MIN_RELATIVE_SPAN * abs(centre), 1e-12)
    if high - low < span:
        plot.ylim = (centre - span / 2 * 1.2, centre + span / 2 * 1.2)


def _scatter_groups(
    plot: Plot, x: np.ndarray, y: np.ndarray, groups: Sequence[str], colours: Mapping[str, str]
) -> None:
    """One series per group, thinned to its share, labelled with its count."""
    from granudb.report.groups import sorted_codes

    codes, names = sorted_codes(groups)
    counts = np.bincount(codes, minlength=len(names))
    for index, name in enumerate(names):
        mask = codes == index
        count = int(counts[index])
        gx, gy = thin(x[mask], y[mask], limit=share(count, len(codes)))
        plot.points(gx, gy, Style(colours[name], marker="o", size=4.5, alpha=0.8),
                    f"{name} ({shown(count, len(gx))})")  # fmt: skip


def walton_plot(
    psi_in: np.ndarray,
    psi_out: np.ndarray,
    groups: Sequence[str],
    fits: Sequence[dict[str, Any]],
    colours: Mapping[str, str],
    figure_id: str = "fig-walton",
) -> str:
    """Ψ_out against Ψ_in with the fitted Walton lines (Joseph & Hunt figures 4, 6, 9).

    ``fits``: one dict per group with ``label`` (a key of ``colours``),
    ``rotational_restitution`` (β), ``sliding_friction`` (μ_f) and
    ``normal_restitution_mean`` (ē): sticking line Ψ_out = −βΨ_in, sliding line
    Ψ_out = Ψ_in − μ_f(1+ē)(1 + 1/K²), K² = 2/5.
    """
    from granudb.physics.impact import gyration_factor

    plot = Plot(title="Tangential rebound (Walton model)", xlabel=PSI_IN,
                ylabel="Ψ_out = v_T,out / v_N,in  (–)")  # fmt: skip
    x, y = np.asarray(psi_in, float), np.asarray(psi_out, float)
    _scatter_groups(plot, x, y, groups, colours)
    top = float(np.nanmax(x)) if np.isfinite(x).any() else 1.0
    line = np.linspace(0.0, top, 50)
    factor = float(gyration_factor())
    for fit in fits:
        colour = colours[fit["label"]]
        beta = fit.get("rotational_restitution")
        mu = fit.get("sliding_friction")
        e = fit.get("normal_restitution_mean")
        if _finite(beta):
            plot.line(line, -beta * line, Style(colour, dash="4.4,1.9"),
                      f"{fit['label']}: sticking, β = {beta:.2g}")  # fmt: skip
        if _finite(mu) and _finite(e):
            plot.line(line, line - mu * (1 + e) * factor, Style(colour),
                      f"{fit['label']}: sliding, μ_f = {mu:.2g}")  # fmt: skip
    plot.hline(0.0, Style("#000000", width=0.6))
    return plot.svg(figure_id)


def _finite(value: Any) -> bool:
    return isinstance(value, int | float) and bool(np.isfinite(value))


def against_incidence(
    psi_in: np.ndarray,
    values: np.ndarray,
    groups: Sequence[str],
    colours: Mapping[str, str],
    *,
    ylabel: str,
    title: str,
    figure_id: str,
) -> str:
    """A per-collision parameter (β or μ_f) against Ψ_in (figures 7, 8, 10, 11)."""
    plot = Plot(title=title, xlabel=PSI_IN, ylabel=ylabel)
    y = np.asarray(values, float)
    _scatter_groups(plot, np.asarray(psi_in, float), y, groups, colours)
    _honest_limits(plot, y)
    return plot.svg(figure_id)


def friction_vs_shear_strain(
    strain: np.ndarray,
    friction: np.ndarray,
    groups: Sequence[str],
    colours: Mapping[str, str],
    figure_id: str = "fig-shear-strain",
) -> str:
    """μ_f against the shear strain (μ₀U/(E*R))²⁄⁷ (figure 15)."""
    plot = Plot(xlog=True, title="Friction against shear strain",
                xlabel="shear strain (μ₀U / (E*R))²⁄⁷  (–)",
                ylabel="friction coefficient μ_f  (–)")  # fmt: skip
    y = np.asarray(friction, float)
    _scatter_groups(plot, np.asarray(strain, float), y, groups, colours)
    _honest_limits(plot, y)
    return plot.svg(figure_id)


#: Marker per measured regime of a run on the regime map.
RUN_MARKERS = {"sticking": "o", "sliding": "^", "no rebound": "x", "normal impact": "s"}


def draw_runs(plot: Plot, runs: Sequence[dict[str, Any]], colours: Mapping[str, str]) -> None:
    """Measured runs on the regime map (viscosity in mPa·s): colour by fluid, hollow
    marker by measured regime; one legend entry each."""
    total = sum(len(series["v"]) for series in runs)
    for series in runs:
        count = len(series["v"])
        v, mu = thin(np.asarray(series["v"], float), np.asarray(series["mu"], float),
                     limit=share(count, total))  # fmt: skip
        marker = RUN_MARKERS.get(series["regime"], "o")
        style = Style(colours.get(series["fluid"], "#000000"), marker=marker, size=6,
                      hollow=True, width=1.3)  # fmt: skip
        plot.points(v, mu * 1e3, style,
                    f"{series['fluid']}: {series['regime']} ({shown(count, len(v))})")  # fmt: skip
