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
to its column.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

FONT = "DejaVu Sans, Verdana, Arial, Helvetica, sans-serif"
WIDTH = 504.0  # 7 in
PLOT_HEIGHT = 230.0
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
    from granudb.report.format import superscript

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
        self.x.fit(xs)
        self.y.fit(ys)
        if self.xlim:
            self.x.low, self.x.high = self.xlim
        if self.ylim:
            self.y.low, self.y.high = self.ylim

    def svg(self, figure_id: str) -> str:
        from granudb.report.svg_draw import render

        self._limits()
        return render(self, figure_id)
