"""The report's figures, as deterministic SVG text.

Each function takes plain arrays and returns an SVG string with axis labels, units and a
legend. Output is byte-identical for the same input: matplotlib's SVG ids are seeded
(``svg.hashsalt``) and the date metadata is dropped.

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
- text is never parsed as mathtext (``text.parse_math`` off), so a material called
  ``$\\frac{a}{b}$`` is drawn as typed instead of crashing the report, and a linear axis
  never shows an offset or inflates a spread of 3×10⁻⁴ into the whole height.
"""

from __future__ import annotations

import io
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

#: Runs drawn per scatter figure at most; more add bytes, not information, to a scatter plot.
MAX_POINTS = 2000
THIN_SEED = 20040101
FIGSIZE = (7.0, 4.2)
#: A linear y-axis spans at least this fraction of the data's magnitude.
MIN_RELATIVE_SPAN = 0.25
GAMMA = "(–)"


#: matplotlib settings of every figure (applied before each figure is made).
STYLE = {
    "svg.hashsalt": "granudb",
    "svg.fonttype": "none",  # text stays text: smaller, searchable, selectable
    "font.size": 10,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "text.usetex": False,
    "text.parse_math": False,  # names are data, never mathtext
    "axes.formatter.useoffset": False,
}


def new_axes(figsize: tuple[float, float] = FIGSIZE) -> tuple[Any, Any]:
    """A figure with one axes, on an SVG canvas of its own.

    Why not pyplot: the object API (``Figure`` + ``FigureCanvasSVG``) needs no backend
    selection and no global figure manager, imports a third less of matplotlib, and a
    figure is freed when the last reference goes (no ``close``)."""
    import matplotlib
    from matplotlib.figure import Figure

    matplotlib.rcParams.update(STYLE)
    figure = Figure(figsize=figsize)
    _canvas_class()(figure)
    return figure, figure.subplots()


_CANVAS: list[Any] = []


def _canvas_class() -> Any:
    """``FigureCanvasSVG`` whose renderer styles a call's markers once.

    Why: matplotlib's SVG renderer recomputes the same CSS style for every ``<use>`` of a
    scatter (one graphics context and face per call), a quarter of a figure's time at
    2,000 points. The style is computed once per call and reused: the same bytes."""
    if _CANVAS:
        return _CANVAS[0]
    import codecs

    from matplotlib import cbook
    from matplotlib.backends.backend_mixed import MixedModeRenderer
    from matplotlib.backends.backend_svg import FigureCanvasSVG, RendererSVG

    class Renderer(RendererSVG):
        def draw_markers(self, gc, marker_path, marker_trans, path, trans, rgbFace=None):  # noqa: ANN001, ANN202, N803
            style = self._get_style(gc, rgbFace)
            self._get_style = lambda *_: style  # this call's markers only
            try:
                super().draw_markers(gc, marker_path, marker_trans, path, trans, rgbFace)
            finally:
                del self._get_style

    class Canvas(FigureCanvasSVG):
        def print_svg(self, filename, *, bbox_inches_restore=None, metadata=None, **_):  # noqa: ANN001, ANN202, ANN003
            # FigureCanvasSVG.print_svg (matplotlib 3.7-3.11) with the renderer above; the
            # options matplotlib filters out for its own canvases (dpi, orientation, …)
            # are ignored, as there
            with cbook.open_file_cm(filename, "w", encoding="utf-8") as fh:
                if not cbook.file_requires_unicode(fh):
                    fh = codecs.getwriter("utf-8")(fh)
                dpi = self.figure.dpi
                self.figure.dpi = 72
                width, height = self.figure.get_size_inches()
                renderer = MixedModeRenderer(
                    self.figure, width, height, dpi,
                    Renderer(width * 72, height * 72, fh, image_dpi=dpi, metadata=metadata),
                    bbox_inches_restore=bbox_inches_restore,
                )  # fmt: skip
                self.figure.draw(renderer)
                renderer.finalize()

    _CANVAS.append(Canvas)
    return Canvas


def _svg(figure: Any, figure_id: str) -> str:
    buffer = io.StringIO()
    figure.savefig(buffer, format="svg", bbox_inches="tight", metadata={"Date": None})
    text = buffer.getvalue()
    # Drop the XML prolog and DOCTYPE so the SVG can be inlined in HTML; give it an id.
    start = text.index("<svg")
    svg = text[start:]
    return svg.replace("<svg ", f'<svg id="{figure_id}" role="img" ', 1)


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


def _legend(ax: Any, handles: Sequence[Any] | None = None) -> None:
    """The legend below the axes, outside the data."""
    kwargs: dict[str, Any] = {
        "loc": "upper center",
        "bbox_to_anchor": (0.5, -0.16),
        "fontsize": 8,
        "frameon": False,
        "ncol": 2,
    }
    if handles is not None:
        kwargs["handles"] = list(handles)
    ax.legend(**kwargs)


def _power_of_ten(value: float, _position: Any = None) -> str:
    """A log-axis tick as Unicode (``10⁻³``): mathtext is off, so no ``$10^{-3}$``."""
    from granudb.report.format import superscript

    if value <= 0 or not np.isfinite(value):
        return ""
    exponent = np.log10(value)
    if abs(exponent - round(exponent)) > 1e-9:
        return ""
    exponent = int(round(exponent))
    return f"{10.0**exponent:g}" if -2 <= exponent <= 3 else f"10{superscript(str(exponent))}"


def _log(ax: Any, *axes: str) -> None:
    """Log scale on ``axes`` ("x", "y") with Unicode tick labels at the decades."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    for name in axes:
        getattr(ax, f"set_{name}scale")("log")
        axis = getattr(ax, f"{name}axis")
        axis.set_major_locator(LogLocator(base=10))
        axis.set_major_formatter(FuncFormatter(_power_of_ten))
        axis.set_minor_formatter(NullFormatter())


def _honest_limits(ax: Any, values: np.ndarray) -> None:
    """Widen a linear y-axis around a tiny spread, so noise does not fill the figure."""
    finite = np.asarray(values, float)
    finite = finite[np.isfinite(finite)]
    if finite.size == 0:
        return
    low, high = float(finite.min()), float(finite.max())
    centre = (low + high) / 2
    span = max(high - low, MIN_RELATIVE_SPAN * abs(centre), 1e-12)
    if high - low < span:
        ax.set_ylim(centre - span / 2 * 1.2, centre + span / 2 * 1.2)


def _scatter_groups(
    ax: Any, x: np.ndarray, y: np.ndarray, groups: Sequence[str], colours: Mapping[str, str]
) -> None:
    from granudb.report.groups import sorted_codes

    codes, names = sorted_codes(groups)
    counts = np.bincount(codes, minlength=len(names))
    for index, name in enumerate(names):
        mask = codes == index
        count = int(counts[index])
        gx, gy = thin(x[mask], y[mask], limit=share(count, len(codes)))
        ax.plot(
            gx,
            gy,
            "o",
            ls="none",
            ms=4.5,
            alpha=0.8,
            color=colours[name],
            label=f"{name} ({shown(count, len(gx))})",
        )


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

    figure, ax = new_axes()
    x, y = np.asarray(psi_in, float), np.asarray(psi_out, float)
    _scatter_groups(ax, x, y, groups, colours)
    top = float(np.nanmax(x)) if x.size else 1.0
    line = np.linspace(0.0, top, 50)
    factor = float(gyration_factor())
    for fit in fits:
        colour = colours[fit["label"]]
        beta = fit.get("rotational_restitution")
        mu = fit.get("sliding_friction")
        e = fit.get("normal_restitution_mean")
        if _finite(beta):
            ax.plot(line, -beta * line, "--", color=colour, lw=1.2,
                    label=f"{fit['label']}: sticking, β = {beta:.2g}")  # fmt: skip
        if _finite(mu) and _finite(e):
            ax.plot(line, line - mu * (1 + e) * factor, "-", color=colour, lw=1.2,
                    label=f"{fit['label']}: sliding, μ_f = {mu:.2g}")  # fmt: skip
    ax.axhline(0.0, color="black", lw=0.6)
    ax.set_xlabel("Ψ_in = v_T,in / v_N,in  (–)")
    ax.set_ylabel("Ψ_out = v_T,out / v_N,in  (–)")
    ax.set_title("Tangential rebound (Walton model)")
    _legend(ax)
    return _svg(figure, figure_id)


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
    figure, ax = new_axes()
    y = np.asarray(values, float)
    _scatter_groups(ax, np.asarray(psi_in, float), y, groups, colours)
    _honest_limits(ax, y)
    ax.set_xlabel("Ψ_in = v_T,in / v_N,in  (–)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    _legend(ax)
    return _svg(figure, figure_id)


def friction_vs_shear_strain(
    strain: np.ndarray,
    friction: np.ndarray,
    groups: Sequence[str],
    colours: Mapping[str, str],
    figure_id: str = "fig-shear-strain",
) -> str:
    """μ_f against the shear strain (μ₀U/(E*R))²⁄⁷ (figure 15)."""
    figure, ax = new_axes()
    y = np.asarray(friction, float)
    _scatter_groups(ax, np.asarray(strain, float), y, groups, colours)
    _honest_limits(ax, y)
    _log(ax, "x")
    ax.set_xlabel("shear strain (μ₀U / (E*R))²⁄⁷  (–)")
    ax.set_ylabel("friction coefficient μ_f  (–)")
    ax.set_title("Friction against shear strain")
    _legend(ax)
    return _svg(figure, figure_id)


#: Marker per measured regime of a run on the regime map.
RUN_MARKERS = {"sticking": "o", "sliding": "^", "no rebound": "x", "normal impact": "s"}


def _draw_runs(ax: Any, runs: Sequence[dict[str, Any]], colours: Mapping[str, str]) -> list[Any]:
    """Measured runs: colour by fluid, marker by measured regime; one legend entry each."""
    handles = []
    total = sum(len(series["v"]) for series in runs)
    for series in runs:
        count = len(series["v"])
        v, mu = thin(np.asarray(series["v"], float), np.asarray(series["mu"], float),
                     limit=share(count, total))  # fmt: skip
        marker = RUN_MARKERS.get(series["regime"], "o")
        (dots,) = ax.plot(
            v,
            mu * 1e3,
            marker,
            ls="none",
            ms=6,
            mew=1.3,
            color=colours.get(series["fluid"], "#000000"),
            markerfacecolor="none" if marker != "x" else None,
            label=f"{series['fluid']}: {series['regime']} ({shown(count, len(v))})",
        )
        handles.append(dots)
    return handles
