"""A small SVG canvas for the report's figures: axes, ticks, markers, lines, shaded cells,
a legend below the axes, as deterministic text.

Why not matplotlib: the report draws six kinds of simple figure, and matplotlib cost a
report on 100,000 runs more than its whole bound (issue 17): 0.7 s to import and about
0.2 s per figure to draw, against a few milliseconds here. What is kept of it: the look
(grid, ticks outside, legend below), log axes labelled at the decades, a 5 % margin around
the data, and NaN breaking a line.

Markup a reader (or a test) can rely on: ``<svg id=… role="img">`` with a ``<title>``;
ticks in ``<g class="xtick">`` / ``<g class="ytick">``; each drawn series is one
``<path class="series">`` (markers: one sub-path per point, so the number of points drawn
is the number of ``M`` commands); the legend is ``<g class="legend">`` with one
``<g class="legend-entry" data-colour=…>`` per entry. Every text is escaped: names are
data, never markup or mathtext.

Sizes are in points (1/72 in), the units of the ``viewBox``; the page scales the figure
to its column. The first half of the module is the model (axes, ticks, a ``Plot`` and
what is drawn on it), the second writes a ``Plot`` as SVG text: the layout (margins from
the tick labels, legend rows below the axes), the grid and ticks, the data clipped to the
axes, the legend and the labels.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from html import escape
from typing import Any

import numpy as np

from granudb.reporting.format import superscript

FONT = "DejaVu Sans, Verdana, Arial, Helvetica, sans-serif"
#: 5 in: a figure 360 pt wide shown on a 390 px phone (374 px of column) keeps its 10.5 pt
#: text above 10 CSS px; the report caps it at 32rem on a wide screen (text about 15 px).
WIDTH = 360.0
PLOT_HEIGHT = 200.0
TICK = 3.5
#: Average advance of a character, as a fraction of the font size (DejaVu Sans); used
#: only to lay out margins and legend columns, so an estimate is enough.
CHAR_WIDTH = 0.6
MINUS = "−"


def text_width(text: str, size: float) -> float:
    return len(text) * size * CHAR_WIDTH


def _number(value: float) -> str:
    """A coordinate in the SVG: two decimals, no "-0.00"."""
    text = f"{value:.2f}"
    return "0.00" if text == "-0.00" else text


@dataclass
class Axis:
    """One axis: its limits (data units) and whether it is logarithmic."""

    log: bool = False
    low: float = math.nan
    high: float = math.nan

    def to_unit(self, values: Any) -> np.ndarray:
        """Positions along the axis, 0 at ``low`` and 1 at ``high``."""
        values = np.asarray(values, dtype=float)
        if self.log:
            with np.errstate(divide="ignore", invalid="ignore"):
                values = np.where(values > 0, np.log10(values), np.nan)
            low, high = math.log10(self.low), math.log10(self.high)
        else:
            low, high = self.low, self.high
        return (values - low) / (high - low)

    def visible(self, values: Any) -> np.ndarray:
        values = np.asarray(values, dtype=float)
        ok = np.isfinite(values)
        return ok & (values > 0) if self.log else ok

    def fit(self, values: Sequence[Any], margin: float = 0.05) -> None:
        """Limits around every finite (positive, on a log axis) value, with a margin."""
        data = [np.asarray(v, dtype=float).ravel() for v in values]
        data = [v[self.visible(v)] for v in data if v.size]
        data = [v for v in data if v.size]
        if not data:
            self.low, self.high = (0.1, 10.0) if self.log else (0.0, 1.0)
            return
        low = min(float(v.min()) for v in data)
        high = max(float(v.max()) for v in data)
        if self.log:
            low, high = math.log10(low), math.log10(high)
        span = high - low
        if span == 0:
            span = abs(low) * 0.1 if low else 1.0
            low, high = low - span / 2, high + span / 2
        else:
            low, high = low - margin * span, high + margin * span
        self.low, self.high = (10**low, 10**high) if self.log else (low, high)

    def ticks(self) -> tuple[list[tuple[float, str]], list[float]]:
        """(major ticks as (value, label), minor tick values) inside the limits."""
        return (
            log_ticks(self.low, self.high) if self.log else (linear_ticks(self.low, self.high), [])
        )


def linear_ticks(low: float, high: float, most: int = 8) -> list[tuple[float, str]]:
    """Round ticks (1, 2, 2.5 or 5 × 10ᵏ apart), at most ``most`` of them, with as many
    decimals as the step needs."""
    span = high - low
    if not (math.isfinite(span) and span > 0):
        return []
    raw = span / (most - 1)
    power = 10.0 ** math.floor(math.log10(raw))
    step = next(m * power for m in (1, 2, 2.5, 5, 10) if m * power >= raw)
    first = math.ceil(low / step - 1e-9)
    values = [(first + k) * step for k in range(int(math.floor(high / step + 1e-9)) - first + 1)]
    decimals = max(0, -math.floor(math.log10(step) + 1e-9))
    if round(step / 10.0 ** math.floor(math.log10(step) + 1e-9), 6) == 2.5:
        decimals += 1
    big = max(abs(low), abs(high))
    ticks = []
    for value in values:
        exponent_form = big >= 1e6 or decimals > 6
        label = f"{value:.3g}" if exponent_form else f"{value:.{decimals}f}"
        if float(label) == 0:
            label = label.lstrip("-")
        ticks.append((value, label.replace("-", MINUS)))
    return ticks


def decade_label(value: float) -> str:
    """A log-axis label as Unicode: ``0.01``, ``1000``, ``10⁻³`` (never TeX)."""
    exponent = round(math.log10(value))
    if abs(math.log10(value) - exponent) > 1e-9:
        return f"{value:g}"
    if -2 <= exponent <= 3:
        return f"{10.0**exponent:g}"
    return f"10{superscript(str(exponent))}"


def log_ticks(low: float, high: float) -> tuple[list[tuple[float, str]], list[float]]:
    """Labelled decades; when fewer than two decades are inside, 2× and 5× (or every
    multiple) are labelled too, so a narrow log axis still reads. Minor ticks at the other
    multiples when the axis spans at most six decades."""
    if not (low > 0 and high > low):
        return [], []
    first, last = math.floor(math.log10(low)), math.ceil(math.log10(high))
    inside = [
        v
        for v in (10.0**k for k in range(first, last + 1))
        if low <= v * (1 + 1e-12) and v <= high * (1 + 1e-12)
    ]

    def multiples(subs: Sequence[int]) -> list[float]:
        out = [m * 10.0**k for k in range(first, last + 1) for m in subs]
        return [v for v in out if low <= v <= high]

    labelled = inside
    for subs in ((1, 2, 5), range(1, 10)):
        if len(labelled) >= 2:
            break
        labelled = multiples(subs)
    minor = [] if last - first > 6 else [v for v in multiples(range(2, 10)) if v not in labelled]
    return [(v, decade_label(v)) for v in labelled], minor


#: Marker outlines around (0, 0) for a marker of size s (points): sub-path templates.
def _marker(kind: str, x: np.ndarray, y: np.ndarray, size: float) -> str:
    r = size / 2
    xs = [_number(v) for v in x.tolist()]
    ys = [_number(v) for v in y.tolist()]
    if kind == "o":
        left = [_number(v - r) for v in x.tolist()]
        arc = f"a{r:.2f},{r:.2f} 0 1,0 {2 * r:.2f},0a{r:.2f},{r:.2f} 0 1,0 {-2 * r:.2f},0"
        return "".join(f"M{a},{b}{arc}" for a, b in zip(left, ys, strict=True))
    if kind == "^":
        tail = f"l{r * 0.866:.2f},{1.5 * r:.2f}h{-1.732 * r:.2f}z"
        top = [_number(v - r) for v in y.tolist()]
        return "".join(f"M{a},{b}{tail}" for a, b in zip(xs, top, strict=True))
    if kind == "s":
        tail = f"h{2 * r:.2f}v{2 * r:.2f}h{-2 * r:.2f}z"
        return "".join(
            f"M{_number(a - r)},{_number(b - r)}{tail}"
            for a, b in zip(x.tolist(), y.tolist(), strict=True)
        )
    if kind == "x":
        return "".join(
            f"M{_number(a - r)},{_number(b - r)}l{2 * r:.2f},{2 * r:.2f}"
            f"m0,{-2 * r:.2f}l{-2 * r:.2f},{2 * r:.2f}"
            for a, b in zip(x.tolist(), y.tolist(), strict=True)
        )
    if kind == "*":
        angles = np.pi / 2 + np.arange(10) * np.pi / 5
        radii = np.where(np.arange(10) % 2 == 0, r, r * 0.382)
        dx, dy = radii * np.cos(angles), -radii * np.sin(angles)
        return "".join(
            "M"
            + "L".join(f"{_number(a + u)},{_number(b + w)}" for u, w in zip(dx, dy, strict=True))
            + "z"
            for a, b in zip(x.tolist(), y.tolist(), strict=True)
        )
    raise ValueError(f"unknown marker {kind!r}")


@dataclass
class Style:
    """How a series is drawn and shown in the legend."""

    colour: str
    marker: str | None = None  # "o", "^", "s", "x", "*"; None for a line
    size: float = 4.5  # marker size, points
    hollow: bool = False
    alpha: float = 1.0
    width: float = 1.2  # line or marker edge width, points
    dash: str | None = None  # an SVG dash array, e.g. "4,2"

    def attributes(self) -> str:
        fill = self.marker is not None and not self.hollow and self.marker != "x"
        parts = [f'fill="{self.colour}"' if fill else 'fill="none"']
        if not fill or self.hollow:
            parts.append(f'stroke="{self.colour}" stroke-width="{self.width:g}"')
        if self.dash:
            parts.append(f'stroke-dasharray="{self.dash}"')
        if self.alpha < 1:
            parts.append(f'opacity="{self.alpha:g}"')
        return " ".join(parts)


@dataclass
class Plot:
    """One axes and its legend; add data, then ``svg``."""

    xlog: bool = False
    ylog: bool = False
    height: float = PLOT_HEIGHT
    title: str = ""
    xlabel: str = ""
    ylabel: str = ""
    x: Axis = field(init=False)
    y: Axis = field(init=False)
    xlim: tuple[float, float] | None = None
    ylim: tuple[float, float] | None = None
    layers: list[tuple[str, Any, Style | None]] = field(default_factory=list)
    legend: list[tuple[str, Style, str]] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.x, self.y = Axis(self.xlog), Axis(self.ylog)

    def points(self, x: Any, y: Any, style: Style, label: str | None = None) -> None:
        self.layers.append(("points", (np.asarray(x, float), np.asarray(y, float)), style))
        if label is not None:
            self.legend.append(("marker", style, label))

    def line(self, x: Any, y: Any, style: Style, label: str | None = None) -> None:
        self.layers.append(("line", (np.asarray(x, float), np.asarray(y, float)), style))
        if label is not None:
            self.legend.append(("line", style, label))

    def errorbars(self, x: Any, y: Any, u_x: Any, u_y: Any, style: Style) -> None:
        """±1 standard uncertainty around each point (``u_x``, ``u_y``; NaN or 0: no bar in
        that direction), one ``<path class="errorbar">``; not used for the limits."""
        data = tuple(np.asarray(v, float) for v in (x, y, u_x, u_y))
        self.layers.append(("errorbars", data, style))

    def band(self, x: Any, low: Any, high: Any, style: Style, label: str | None = None) -> None:
        """A shaded region between the curves ``low`` and ``high`` over ``x`` (a curve's
        uncertainty band), filled in ``style.colour`` at opacity ``style.alpha``; draw it
        before the line it surrounds so that the line stays on top."""
        data = tuple(np.asarray(v, float) for v in (x, low, high))
        self.layers.append(("band", data, style))
        if label is not None:
            self.legend.append(("patch", style, label))

    def polylines(self, lines: Sequence[tuple[np.ndarray, np.ndarray]], style: Style) -> None:
        """Several lines in one style (a contour), not used for the limits."""
        self.layers.append(("polylines", list(lines), style))

    def hline(self, y: float, style: Style, label: str | None = None) -> None:
        self.layers.append(("hline", y, style))
        if label is not None:
            self.legend.append(("line", style, label))

    def vline(self, x: float, style: Style, label: str | None = None) -> None:
        self.layers.append(("vline", x, style))
        if label is not None:
            self.legend.append(("line", style, label))

    def cells(self, x_edges: Any, y_edges: Any, codes: Any, colours: Sequence[str]) -> None:
        """Shade a grid: ``codes[j, i]`` (an index into ``colours``) fills the cell between
        ``x_edges[i:i+2]`` and ``y_edges[j:j+2]``; equal neighbours in a row become one
        rectangle."""
        self.layers.append(("cells", (np.asarray(x_edges, float), np.asarray(y_edges, float),
                                      np.asarray(codes), list(colours)), None))  # fmt: skip

    def patch(self, colour: str, label: str) -> None:
        """A legend entry for a shaded region."""
        self.legend.append(("patch", Style(colour), label))

    # -- layout and output ------------------------------------------------------------

    def _limits(self) -> None:
        xs, ys = [], []
        for kind, data, _ in self.layers:
            if kind in ("points", "line"):
                xs.append(data[0])
                ys.append(data[1])
            elif kind == "hline":
                ys.append([data])
            elif kind == "vline":
                xs.append([data])
            elif kind == "cells":
                xs.append(data[0])
                ys.append(data[1])
            elif kind == "band":
                xs.append(data[0])
                ys += [data[1], data[2]]
        self.x.fit(xs)
        self.y.fit(ys)
        if self.xlim:
            self.x.low, self.x.high = self.xlim
        if self.ylim:
            self.y.low, self.y.high = self.ylim

    def svg(self, figure_id: str) -> str:
        self._limits()
        return render(self, figure_id)


# --- writing a Plot as SVG text ----------------------------------------------------------

TICK_FONT, LABEL_FONT, TITLE_FONT, LEGEND_FONT = 10.5, 10.5, 12.0, 10.5
LEGEND_ROW = 13.5
SAMPLE = 18.0  # legend sample width, points


def wrap(text: str, size: float, width: float) -> list[str]:
    """``text`` in lines no wider than ``width`` at font ``size``, broken at spaces outside
    parentheses and not beside "=" (so "(12 runs)" and "β = 0.4" stay whole); a word wider
    than a line gets its own line.

    >>> wrap("steel/Zerodur dry: sticking (12 runs)", 10.0, 120.0)
    ['steel/Zerodur dry:', 'sticking (12 runs)']
    """
    words, depth, current = [], 0, ""
    for index, char in enumerate(text):
        depth += (char == "(") - (char == ")")
        beside = text[index - 1 : index] == "=" or text[index + 1 : index + 2] == "="
        if char == " " and depth <= 0 and not beside:
            words.append(current)
            current = ""
        else:
            current += char
    words.append(current)
    lines: list[str] = []
    for word in words:
        if lines and text_width(f"{lines[-1]} {word}", size) <= width:
            lines[-1] = f"{lines[-1]} {word}"
        else:
            lines.append(word)
    return lines


def render(plot: Plot, figure_id: str) -> str:
    xticks, xminor = plot.x.ticks()
    yticks, yminor = plot.y.ticks()
    tick_label = max((text_width(t, TICK_FONT) for _, t in yticks), default=0.0)
    left = 8 + LABEL_FONT + 6 + tick_label + TICK + 3
    width = WIDTH - left - 10
    titles = wrap(plot.title, TITLE_FONT, WIDTH - 16) if plot.title else []
    top = 8 + len(titles) * (TITLE_FONT + 4) + (4 if titles else 0)
    xlabels = wrap(plot.xlabel, LABEL_FONT, WIDTH - 16)
    columns, rows = _legend_grid(plot, width)
    labels_height = TICK + 3 + TICK_FONT + 6 + len(xlabels) * (LABEL_FONT + 3)
    bottom = labels_height + (LEGEND_FONT + 6 + (rows - 1) * LEGEND_ROW + 6 if rows else 6)
    total = top + plot.height + bottom
    box = (left, top, width, plot.height)

    def px(values: Any) -> np.ndarray:
        return left + plot.x.to_unit(values) * width

    def py(values: Any) -> np.ndarray:
        return top + (1 - plot.y.to_unit(values)) * plot.height

    out = [
        f'<svg id="{escape(figure_id)}" role="img" xmlns="http://www.w3.org/2000/svg" '
        f'width="{WIDTH:g}pt" height="{total:.1f}pt" viewBox="0 0 {WIDTH:g} {total:.1f}" '
        f'font-family="{FONT}">',
        f"<title>{escape(plot.title)}</title>",
        f'<defs><clipPath id="{escape(figure_id)}-clip"><rect x="{left:.2f}" y="{top:.2f}" '
        f'width="{width:.2f}" height="{plot.height:.2f}"/></clipPath></defs>',
        f'<rect width="{WIDTH:g}" height="{total:.1f}" fill="#ffffff"/>',
    ]
    out += _grid_and_ticks(box, px(np.array([v for v, _ in xticks])), [t for _, t in xticks],
                           py(np.array([v for v, _ in yticks])), [t for _, t in yticks],
                           px(np.array(xminor)), py(np.array(yminor)))  # fmt: skip
    out.append(f'<g clip-path="url(#{escape(figure_id)}-clip)">')
    for kind, data, style in plot.layers:
        out.append(_layer(plot, kind, data, style, px, py, box))
    out.append("</g>")
    out.append(
        f'<rect class="frame" x="{left:.2f}" y="{top:.2f}" width="{width:.2f}" '
        f'height="{plot.height:.2f}" fill="none" stroke="#000000" stroke-width="0.8"/>'
    )
    label_y = top + plot.height + TICK + 3 + TICK_FONT + 6 + LABEL_FONT
    for index, line in enumerate(xlabels):
        y = label_y + index * (LABEL_FONT + 3)
        out.append(_text(WIDTH / 2, y, line, LABEL_FONT, "middle", "xlabel"))
    label_y += (len(xlabels) - 1) * (LABEL_FONT + 3)
    middle = top + plot.height / 2
    out.append(
        f'<text class="ylabel" transform="translate({8 + LABEL_FONT:.2f},{middle:.2f}) '
        f'rotate(-90)" font-size="{LABEL_FONT:g}" text-anchor="middle">{escape(plot.ylabel)}</text>'
    )
    for index, line in enumerate(titles):
        y = 8 + TITLE_FONT + index * (TITLE_FONT + 4)
        out.append(_text(WIDTH / 2, y, line, TITLE_FONT, "middle", "title"))
    out.append(_legend(plot, left, label_y + LEGEND_FONT + 8, width, columns))
    out.append("</svg>")
    return "\n".join(part for part in out if part)


def _text(x: float, y: float, text: str, size: float, anchor: str, cls: str = "") -> str:
    name = f' class="{cls}"' if cls else ""
    return (f'<text{name} x="{x:.2f}" y="{y:.2f}" font-size="{size:g}" '
            f'text-anchor="{anchor}">{escape(text)}</text>')  # fmt: skip


def _grid_and_ticks(
    box: tuple[float, float, float, float],
    xs: np.ndarray, xlabels: list[str], ys: np.ndarray, ylabels: list[str],
    xminor: np.ndarray, yminor: np.ndarray,
) -> list[str]:  # fmt: skip
    left, top, width, height = box
    bottom = top + height
    grid = []
    ticks = []
    for x, label in zip(xs.tolist(), xlabels, strict=True):
        grid.append(f"M{x:.2f},{top:.2f}V{bottom:.2f}")
        text = _text(x, bottom + TICK + 3 + TICK_FONT, label, TICK_FONT, "middle")
        ticks.append(
            f'<g class="xtick"><path d="M{x:.2f},{bottom:.2f}v{TICK}" stroke="#000000" '
            f'stroke-width="0.8"/>{text}</g>'
        )
    for y, label in zip(ys.tolist(), ylabels, strict=True):
        grid.append(f"M{left:.2f},{y:.2f}H{left + width:.2f}")
        text = _text(left - TICK - 3, y + TICK_FONT * 0.35, label, TICK_FONT, "end")
        ticks.append(
            f'<g class="ytick"><path d="M{left:.2f},{y:.2f}h{-TICK}" stroke="#000000" '
            f'stroke-width="0.8"/>{text}</g>'
        )
    minor = "".join(f"M{x:.2f},{bottom:.2f}v2" for x in xminor.tolist())
    minor += "".join(f"M{left:.2f},{y:.2f}h-2" for y in yminor.tolist())
    out = [f'<path class="grid" d="{"".join(grid)}" stroke="#b0b0b0" stroke-opacity="0.3" '
           'stroke-width="0.8" fill="none"/>'] if grid else []  # fmt: skip
    if minor:
        out.append(f'<path class="minor" d="{minor}" stroke="#000000" stroke-width="0.6"/>')
    return out + ticks


def _polyline(x: np.ndarray, y: np.ndarray) -> str:
    """Path data through the finite points; a NaN (or an invisible point) breaks the line."""
    ok = np.isfinite(x) & np.isfinite(y)
    parts, pen = [], False
    for a, b, good in zip(x.tolist(), y.tolist(), ok.tolist(), strict=True):
        if not good:
            pen = False
            continue
        parts.append(f"{'L' if pen else 'M'}{_number(a)},{_number(b)}")
        pen = True
    return "".join(parts)


def _layer(plot: Plot, kind: str, data: Any, style: Style | None, px: Any, py: Any,
           box: tuple[float, float, float, float]) -> str:  # fmt: skip
    left, top, width, height = box
    if kind == "cells":
        x_edges, y_edges, codes, colours = data
        return _cells(x_edges, y_edges, codes, colours, px, py)
    assert style is not None
    if kind == "errorbars":
        return _errorbars(plot, data, style, px, py, box)
    if kind == "band":
        x, low, high = data
        return _band(x, low, high, style, px, py)
    if kind == "points":
        x, y = data
        ok = plot.x.visible(x) & plot.y.visible(y)
        if not ok.any():
            return ""
        d = _marker(style.marker or "o", px(x[ok]), py(y[ok]), style.size)
    elif kind == "line":
        x, y = data
        ok = plot.x.visible(x) & plot.y.visible(y)
        d = _polyline(np.where(ok, px(x), np.nan), np.where(ok, py(y), np.nan))
    elif kind == "polylines":
        d = "".join(_polyline(px(x), py(y)) for x, y in data)
    elif kind == "hline":
        d = f"M{left:.2f},{_number(float(py(data)))}h{width:.2f}" if plot.y.visible(data) else ""
    elif kind == "vline":
        d = f"M{_number(float(px(data)))},{top:.2f}v{height:.2f}" if plot.x.visible(data) else ""
    else:  # pragma: no cover - the kinds are Plot's own
        raise ValueError(kind)
    if not d:
        return ""
    return f'<path class="series" d="{d}" {style.attributes()}/>'


def _errorbars(plot: Plot, data: Any, style: Style, px: Any, py: Any,
               box: tuple[float, float, float, float]) -> str:  # fmt: skip
    """A vertical bar y ± u_y and a horizontal bar x ± u_x through each visible point, one
    sub-path each; an end below zero on a log axis is drawn to the axis' edge."""
    x, y, u_x, u_y = data
    left, top, width, height = box
    ok = plot.x.visible(x) & plot.y.visible(y)
    parts = []
    for axis, values, u, to_px, edge in ((plot.y, y, u_y, py, top + height),
                                         (plot.x, x, u_x, px, left)):  # fmt: skip
        bar = ok & np.isfinite(u) & (u > 0)
        if not bar.any():
            continue
        low, high = values[bar] - u[bar], values[bar] + u[bar]
        low_px = np.where(axis.visible(low), to_px(low), edge)
        centre_x, centre_y = px(x[bar]), py(y[bar])
        for a, b, cx, cy in zip(low_px.tolist(), to_px(high).tolist(), centre_x.tolist(),
                                centre_y.tolist(), strict=True):  # fmt: skip
            if axis is plot.y:
                parts.append(f"M{_number(cx)},{_number(a)}V{_number(b)}")
            else:
                parts.append(f"M{_number(a)},{_number(cy)}H{_number(b)}")
    if not parts:
        return ""
    return (f'<path class="errorbar" d="{"".join(parts)}" fill="none" stroke="{style.colour}" '
            f'stroke-width="{style.width:g}" stroke-opacity="0.7"/>')  # fmt: skip


def _band(x: np.ndarray, low: np.ndarray, high: np.ndarray, style: Style, px: Any,
          py: Any) -> str:  # fmt: skip
    """The region between ``low`` and ``high``: one closed path out along ``low`` and back
    along ``high``, over the points where both are finite (no stroke)."""
    ok = np.isfinite(x) & np.isfinite(low) & np.isfinite(high)
    if ok.sum() < 2:
        return ""
    xs = px(x[ok])
    out = [
        f"{_number(a)},{_number(b)}" for a, b in zip(xs.tolist(), py(low[ok]).tolist(), strict=True)
    ]
    back = zip(xs[::-1].tolist(), py(high[ok])[::-1].tolist(), strict=True)
    out += [f"{_number(a)},{_number(b)}" for a, b in back]
    return (f'<path class="band" d="M{"L".join(out)}Z" fill="{style.colour}" '
            f'fill-opacity="{style.alpha:g}" stroke="none"/>')  # fmt: skip


def _cells(x_edges: np.ndarray, y_edges: np.ndarray, codes: np.ndarray, colours: list[str],
           px: Any, py: Any) -> str:  # fmt: skip
    xe, ye = px(x_edges), py(y_edges)
    out = ['<g class="cells" shape-rendering="crispEdges">']
    for j in range(codes.shape[0]):
        row = codes[j]
        starts = np.flatnonzero(np.r_[True, row[1:] != row[:-1]])
        ends = np.r_[starts[1:], len(row)]
        y0, y1 = sorted((float(ye[j]), float(ye[j + 1])))
        for start, end in zip(starts.tolist(), ends.tolist(), strict=True):
            code = int(row[start])
            if code < 0:
                continue
            x0, x1 = float(xe[start]), float(xe[end])
            out.append(f'<rect x="{x0:.2f}" y="{y0:.2f}" width="{x1 - x0 + 0.3:.2f}" '
                       f'height="{y1 - y0 + 0.3:.2f}" fill="{colours[code]}"/>')  # fmt: skip
    out.append("</g>")
    return "".join(out)


def _legend_lines(plot: Plot, width: float, columns: int) -> list[list[str]]:
    """Each legend entry's label in lines that fit its column."""
    room = width / columns - SAMPLE - 6
    return [wrap(label, LEGEND_FONT, room) for _, _, label in plot.legend]


def _legend_grid(plot: Plot, width: float) -> tuple[int, int]:
    """Two columns when every label fits in half the width, else one (long labels wrap);
    (columns, rows of text)."""
    if not plot.legend:
        return 1, 0
    widest = max(text_width(label, LEGEND_FONT) for _, _, label in plot.legend)
    columns = 2 if widest + SAMPLE + 10 <= width / 2 else 1
    heights = [len(lines) for lines in _legend_lines(plot, width, columns)]
    if columns == 1:
        return 1, sum(heights)
    return 2, sum(max(heights[i : i + 2]) for i in range(0, len(heights), 2))


def _legend(plot: Plot, left: float, top: float, width: float, columns: int) -> str:
    if not plot.legend:
        return ""
    out = ['<g class="legend">']
    column_width = width / columns
    lines = _legend_lines(plot, width, columns)
    y = top
    for index, (kind, style, _) in enumerate(plot.legend):
        column = index % columns
        x = left + column * column_width
        mid = y - LEGEND_FONT * 0.35
        if kind == "patch":
            shade = f' fill-opacity="{style.alpha:g}"' if style.alpha < 1 else ""
            sample = (f'<rect x="{x:.2f}" y="{y - 7:.2f}" width="{SAMPLE:g}" height="7" '
                      f'fill="{style.colour}"{shade}/>')  # fmt: skip
        elif kind == "line":
            sample = f'<path d="M{x:.2f},{mid:.2f}h{SAMPLE:g}" {style.attributes()}/>'
        else:
            d = _marker(
                style.marker or "o", np.array([x + SAMPLE / 2]), np.array([mid]), style.size
            )
            sample = f'<path d="{d}" {style.attributes()}/>'
        texts = "".join(
            _text(x + SAMPLE + 6, y + row * LEGEND_ROW, line, LEGEND_FONT, "start")
            for row, line in enumerate(lines[index])
        )
        out.append(f'<g class="legend-entry" data-colour="{style.colour}">{sample}{texts}</g>')
        if column == columns - 1 or index == len(plot.legend) - 1:
            y += LEGEND_ROW * max(len(x) for x in lines[index - column : index + 1])
    out.append("</g>")
    return "".join(out)
