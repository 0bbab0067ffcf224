"""The report's figures, as deterministic SVG text.

Each function takes plain arrays and returns an SVG string with axis labels, units and a
legend; the same input gives the same bytes. Drawn with ``granudb.reporting.svg`` (not
matplotlib: that module says why).

Thinning (issue 17): a scatter figure draws at most ``MAX_POINTS`` runs. A figure of N
runs whose series (group, or fluid × regime) holds n of them draws ⌈MAX_POINTS · n / N⌉ of
that series, a fixed-seed sample (``THIN_SEED``), so each group keeps its share and the
same data always gives the same figure; the legend says "k of n runs shown". Fits, tables
and every count use all runs: thinning only spares the reader's browser (and the report's
time: 100,000 runs make a figure of a few hundred kilobytes).

The kinds: the Walton plot (Ψ_out against Ψ_in), β and μ_f against the incidence, the
friction against the shear strain, the restitution against the Stokes number with each
group's prediction, and the regime map of a pair (the velocity × viscosity plane shaded
by the three-state roughness verdict, asperity contact / uncertain / film from Davis's
band h_m = x₁/4 … x₁/3, and no rebound, with its level lines traced by contourpy).

Three rules keep the figures honest and consistent with the tables:
- colours come from the caller (``granudb.reporting.groups``), one per group for the whole
  report, and a group's fit lines share its points' colour;
- legends sit below the axes, never over the data;
- names are data: drawn as typed and escaped, never read as markup or mathtext; a linear
  axis never inflates a spread of 3×10⁻⁴ into the whole height.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from granudb.lazy import contourpy
from granudb.reporting.groups import sorted_codes
from granudb.reporting.svg import PLOT_HEIGHT, Plot, Style
from granudb.reporting.verdicts import ROUGHNESS_WORDS

#: Runs drawn per scatter figure at most; more add bytes, not information, to a scatter plot.
MAX_POINTS = 2000
#: Opacity of a fitted curve's 95 % band (``granudb.analysis.bands``): light enough for the
#: runs and the line to read through it.
BAND_ALPHA = 0.18
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


def scatter_groups(
    plot: Plot,
    x: np.ndarray,
    y: np.ndarray,
    groups: Sequence[str],
    colours: Mapping[str, str],
    errors: tuple[Any, Any] | None = None,
) -> None:
    """One series per group, thinned to its share, labelled with its count; ``errors``
    (u of x, u of y by run; None or NaN: none) draws ±1 u bars (``has_errors``)."""
    codes, names = sorted_codes(groups)
    counts = np.bincount(codes, minlength=len(names))
    nan = np.full(len(x), np.nan)
    u_x, u_y = (nan if u is None else np.asarray(u, float) for u in (errors or (None, None)))
    for index, name in enumerate(names):
        mask = codes == index
        count = int(counts[index])
        gx, gy, gux, guy = thin(x[mask], y[mask], u_x[mask], u_y[mask],
                                limit=share(count, len(codes)))  # fmt: skip
        if errors is not None:
            plot.errorbars(gx, gy, gux, guy, Style(colours[name], width=0.8))
        plot.points(gx, gy, Style(colours[name], marker="o", size=4.5, alpha=0.8),
                    f"{name} ({shown(count, len(gx))})")  # fmt: skip


#: What a figure's caption says of its error bars.
ERROR_BARS = (
    " Error bars: ±1 standard uncertainty u of each run, propagated from the uncertainties "
    "its dataset states for the measured speeds (GUM first order); runs without a stated u "
    "have none."
)


def has_errors(*uncertainties: Any) -> bool:
    """Does any run carry a stated uncertainty to draw (a finite u > 0)?"""
    for u in uncertainties:
        if u is not None:
            u = np.asarray(u, float)
            if (np.isfinite(u) & (u > 0)).any():
                return True
    return False


def walton_plot(
    psi_in: np.ndarray,
    psi_out: np.ndarray,
    groups: Sequence[str],
    lines: Sequence[dict[str, Any]],
    colours: Mapping[str, str],
    figure_id: str = "fig-walton",
    errors: tuple[Any, Any] | None = None,
) -> str:
    """Ψ_out against Ψ_in with the fitted Walton lines (Joseph & Hunt figures 4, 6, 9).

    ``lines``: the lines to draw (``granudb.reporting.figures.walton_lines``), dicts with
    ``label`` (a key of ``colours``), ``branch`` ("sticking" dashed, "sliding" solid),
    ``x``, ``y`` and the legend ``text``; a line with a ``band`` (low, high over ``x``)
    is shaded in its colour behind the runs.
    """
    plot = Plot(title="Tangential rebound (Walton model)", xlabel=PSI_IN,
                ylabel="Ψ_out = v_T,out / v_N,in  (–)")  # fmt: skip
    for line in lines:  # bands first: behind the runs and the lines
        if line.get("band") is not None:
            low, high = line["band"]
            plot.band(line["x"], low, high, Style(colours[line["label"]], alpha=BAND_ALPHA))
    scatter_groups(plot, np.asarray(psi_in, float), np.asarray(psi_out, float), groups, colours,
                   errors)  # fmt: skip
    for line in lines:
        dash = "4.4,1.9" if line["branch"] == "sticking" else None
        plot.line(line["x"], line["y"], Style(colours[line["label"]], dash=dash), line["text"])
    plot.hline(0.0, Style("#000000", width=0.6))
    return plot.svg(figure_id)


def scatter_figure(
    x: np.ndarray, y: np.ndarray, groups: Sequence[str], colours: Mapping[str, str], **plot: Any
) -> str:
    """A per-collision value against ``x``, one series per group; ``plot``: the ``Plot``
    options (title, labels, ``xlog``) and the ``figure_id``."""
    figure_id = plot.pop("figure_id")
    figure = Plot(**plot)
    values = np.asarray(y, float)
    scatter_groups(figure, np.asarray(x, float), values, groups, colours)
    _honest_limits(figure, values)
    return figure.svg(figure_id)


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
    return scatter_figure(psi_in, values, groups, colours, title=title, xlabel=PSI_IN,
                          ylabel=ylabel, figure_id=figure_id)  # fmt: skip


def friction_vs_shear_strain(
    strain: np.ndarray, friction: np.ndarray, groups: Sequence[str], colours: Mapping[str, str]
) -> str:
    """μ_f against the shear strain (μ₀U/(E*R))²⁄⁷ (figure 15)."""
    return scatter_figure(strain, friction, groups, colours, xlog=True,
                          title="Friction against shear strain",
                          xlabel="shear strain (μ₀U / (E*R))²⁄⁷  (–)",
                          ylabel="friction coefficient μ_f  (–)",
                          figure_id="fig-shear-strain")  # fmt: skip


#: Marker per measured regime of a run on the regime map.
RUN_MARKERS = {"sticking": "o", "sliding": "^", "no rebound": "x", "not determined": "s"}


def draw_runs(plot: Plot, runs: Sequence[dict[str, Any]], colours: Mapping[str, str]) -> None:
    """Measured runs on the regime map (viscosity in mPa·s): colour by group (the report's
    one colour per group), hollow marker by measured branch; one legend entry each."""
    total = sum(len(series["v"]) for series in runs)
    for series in runs:
        count = len(series["v"])
        v, mu = thin(np.asarray(series["v"], float), np.asarray(series["mu"], float),
                     limit=share(count, total))  # fmt: skip
        marker = RUN_MARKERS.get(series["regime"], "o")
        style = Style(colours.get(series["group"], "#000000"), marker=marker, size=6,
                      hollow=True, width=1.3)  # fmt: skip
        plot.points(v, mu * 1e3, style,
                    f"{series['group']}: {series['regime']} ({shown(count, len(v))})")  # fmt: skip


def level_lines(
    x: Any, y: Any, field: Any, level: float, *, log: bool = True
) -> list[tuple[np.ndarray, np.ndarray]]:
    """Polylines (x, y in data units) where ``field[j, i]`` (rows on ``y``, columns on
    ``x``) crosses ``level``, traced by contourpy (matplotlib's contouring engine);
    cells with a non-finite corner are skipped. On log axes (``log``) the field is
    interpolated linearly in log x and log y, as the regime map's geometric grids are.

    >>> x = y = np.array([1.0, 2.0, 3.0])
    >>> [(a.tolist(), b.tolist()) for a, b in level_lines(x, y, np.add.outer(y, x), 3.5, log=False)]
    [([1.0, 1.5, 2.0, 2.5], [2.5, 2.0, 1.5, 1.0])]
    """
    field = np.ma.masked_invalid(np.asarray(field, dtype=float))
    if field.mask.all():
        return []
    xs = np.log10(np.asarray(x, float)) if log else np.asarray(x, float)
    ys = np.log10(np.asarray(y, float)) if log else np.asarray(y, float)
    generator = contourpy.contour_generator(
        xs, ys, field, line_type=contourpy.LineType.Separate, corner_mask=False
    )
    lines = []
    for points in generator.lines(level):
        px, py = points[:, 0], points[:, 1]
        lines.append((10**px, 10**py) if log else (px, py))
    return lines


#: Regions of the regime map, in drawing order, with their fill colours.
REGIME_COLOURS = {
    "no rebound": "#d9d9d9",
    f"rebound, {ROUGHNESS_WORDS['asperity_contact']}": "#fdd9b5",
    f"rebound, {ROUGHNESS_WORDS['uncertain']}": "#f3ecb0",
    f"rebound, {ROUGHNESS_WORDS['film']}": "#cfe3f2",
    f"rebound, {ROUGHNESS_WORDS['not_stated']}": "#ffffff",
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
    draw_runs(plot, runs, colours or {})
    if point is not None:
        plot.points([point[0]], [point[1] * 1e3], Style("#dc143c", marker="*", size=12),
                    "this collision")  # fmt: skip
    plot.xlim = (float(np.min(velocity)), float(np.max(velocity)))
    plot.ylim = (float(np.min(mu_axis)), float(np.max(mu_axis)))
    return plot.svg(figure_id)


def plots_height() -> float:
    """The regime map is taller than the scatter figures (0.8 in more, as before)."""
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
    errors: tuple[Any, Any] | None = None,
    band: tuple[np.ndarray, np.ndarray] | None = None,
) -> str:
    """e against St_n with each group's predicted curve in the group's colour (dotted) and
    an optional fitted curve (grey) with its ``band`` (low, high over the fitted curve's
    St_n, shaded grey behind everything). ``predictions``: dicts with ``label`` (a key of
    ``colours``), ``st_n`` and ``e`` arrays (the curve, on the St_n axis)."""
    plot = Plot(xlog=True, title="Restitution against Stokes number: measured and predicted",
                xlabel="normal Stokes number St_n = m* v_N,in / (6πμR*²)  (–)",
                ylabel="normal restitution e  (–)")  # fmt: skip
    if fitted is not None and band is not None:
        plot.band(fitted[0], *band, Style("#555555", alpha=BAND_ALPHA), "95 % band of the fit")
    scatter_groups(plot, np.asarray(stokes, float), np.asarray(restitution, float), groups, colours,
                   errors)  # fmt: skip
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
