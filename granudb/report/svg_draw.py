"""Writes a ``granudb.report.svg.Plot`` as SVG text: the layout (margins from the tick
labels, legend rows below the axes), the grid and ticks, the data clipped to the axes, the
legend and the labels. Kept apart from ``svg`` so each module reads on its own."""

from __future__ import annotations

import math
from html import escape
from typing import Any

import numpy as np

from granudb.report.svg import FONT, TICK, WIDTH, Plot, Style, _marker, _number, text_width

TICK_FONT, LABEL_FONT, TITLE_FONT, LEGEND_FONT = 10.0, 10.0, 12.0, 8.0
LEGEND_ROW = 13.0
SAMPLE = 20.0  # legend sample width, points


def render(plot: Plot, figure_id: str) -> str:
    xticks, xminor = plot.x.ticks()
    yticks, yminor = plot.y.ticks()
    tick_label = max((text_width(t, TICK_FONT) for _, t in yticks), default=0.0)
    left = 8 + LABEL_FONT + 6 + tick_label + TICK + 3
    top = 8 + (TITLE_FONT + 8 if plot.title else 0)
    width = WIDTH - left - 14
    columns, rows = _legend_grid(plot, width)
    bottom = TICK + 3 + TICK_FONT + 6 + LABEL_FONT + 8 + rows * LEGEND_ROW + 4
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
    out.append(_text(left + width / 2, label_y, plot.xlabel, LABEL_FONT, "middle", "xlabel"))
    middle = top + plot.height / 2
    out.append(
        f'<text class="ylabel" transform="translate({8 + LABEL_FONT:.2f},{middle:.2f}) '
        f'rotate(-90)" font-size="{LABEL_FONT:g}" text-anchor="middle">{escape(plot.ylabel)}</text>'
    )
    if plot.title:
        out.append(
            _text(left + width / 2, 8 + TITLE_FONT, plot.title, TITLE_FONT, "middle", "title")
        )
    out.append(_legend(plot, left, label_y + 10, width, columns))
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
        return _cells(*data, px, py)
    assert style is not None
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


def _legend_grid(plot: Plot, width: float) -> tuple[int, int]:
    """Two columns when every label fits in half the width, else one; (columns, rows)."""
    if not plot.legend:
        return 1, 0
    widest = max(text_width(label, LEGEND_FONT) for _, _, label in plot.legend)
    columns = 2 if widest + SAMPLE + 10 <= width / 2 else 1
    return columns, math.ceil(len(plot.legend) / columns)


def _legend(plot: Plot, left: float, top: float, width: float, columns: int) -> str:
    if not plot.legend:
        return ""
    out = ['<g class="legend">']
    column_width = width / columns
    for index, (kind, style, label) in enumerate(plot.legend):
        row, column = divmod(index, columns)
        x = left + column * column_width
        y = top + row * LEGEND_ROW
        mid = y - LEGEND_FONT * 0.35
        if kind == "patch":
            sample = (f'<rect x="{x:.2f}" y="{y - 7:.2f}" width="{SAMPLE:g}" height="7" '
                      f'fill="{style.colour}"/>')  # fmt: skip
        elif kind == "line":
            sample = f'<path d="M{x:.2f},{mid:.2f}h{SAMPLE:g}" {style.attributes()}/>'
        else:
            d = _marker(
                style.marker or "o", np.array([x + SAMPLE / 2]), np.array([mid]), style.size
            )
            sample = f'<path d="{d}" {style.attributes()}/>'
        out.append(
            f'<g class="legend-entry" data-colour="{style.colour}">{sample}'
            f"{_text(x + SAMPLE + 6, y, label, LEGEND_FONT, 'start')}</g>"
        )
    out.append("</g>")
    return "".join(out)
