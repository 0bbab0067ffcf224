"""The report's own SVG canvas (``granudb.reporting.svg``; level lines traced by contourpy
in ``plots``): ticks that read, text that stays text, well-formed XML, level lines where the
field crosses."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from granudb.reporting import plots
from granudb.reporting.plots import level_lines
from granudb.reporting.svg import Plot, Style, linear_ticks, log_ticks

SVG = "{http://www.w3.org/2000/svg}"


def test_linear_ticks_are_round_and_inside() -> None:
    assert [t for _, t in linear_ticks(-0.05, 1.05)] == ["0.0", "0.2", "0.4", "0.6", "0.8", "1.0"]
    assert [t for _, t in linear_ticks(0.0, 0.16)][:3] == ["0.000", "0.025", "0.050"]
    assert [t for _, t in linear_ticks(-1.0, 1.0)][0] == "−1.0"  # a true minus sign
    for low, high in ((0.0, 1.0), (-3e-4, 2e-4), (12.0, 13.5), (-250.0, 7e3), (1e7, 3e7)):
        ticks = linear_ticks(low, high)
        assert 3 <= len(ticks) <= 8, (low, high, ticks)
        assert all(low - 1e-12 <= v <= high + 1e-12 for v, _ in ticks)
        assert len({label for _, label in ticks}) == len(ticks), ticks  # labels distinguish
    assert linear_ticks(1.0, 1.0) == [] and linear_ticks(0.0, math.nan) == []


def test_log_ticks_label_decades_and_a_narrow_axis_still_reads() -> None:
    major, minor = log_ticks(1e-3, 3.0)
    assert [t for _, t in major] == ["10⁻³", "0.01", "0.1", "1"]
    assert 2e-3 in [round(m, 12) for m in minor]
    major, _ = log_ticks(2.5e-4, 6.5e-4)  # no decade inside: multiples are labelled
    assert len(major) >= 2 and all(2.5e-4 <= v <= 6.5e-4 for v, _ in major)
    assert [t for _, t in log_ticks(3e4, 2e5)[0]] == ["50000", "10⁵", "200000"]


def test_text_is_escaped_and_the_svg_is_well_formed_xml() -> None:
    name = '<script>alert(1)</script> & "$\\frac{a}{b}$"'
    svg = plots.against_incidence(np.array([0.1, 0.2]), np.array([0.3, 0.4]), [name, name],
                                  {name: "#0072b2"}, ylabel="y <", title="t & u",
                                  figure_id="fig-x")  # fmt: skip
    root = ET.fromstring(svg)
    assert root.tag == f"{SVG}svg" and root.get("id") == "fig-x" and root.get("role") == "img"
    assert root.find(f"{SVG}title").text == "t & u"
    texts = [t.text for t in root.iter(f"{SVG}text")]
    entries = [g for g in root.iter(f"{SVG}g") if g.get("class") == "legend-entry"]
    legend = [" ".join(t.text for t in g.iter(f"{SVG}text")) for g in entries]  # labels wrap
    assert legend == [f"{name} (2 runs)"] and "y <" in texts
    assert "<script>" not in svg


def test_points_outside_a_log_axis_or_not_finite_are_not_drawn() -> None:
    plot = Plot(xlog=True)
    plot.points([-1.0, 0.0, np.nan, 1.0, 10.0], [1, 1, 1, np.inf, 2], Style("#000000", "o"))
    svg = plot.svg("fig-p")
    drawn = re.search(r'<path class="series" d="([^"]*)"', svg).group(1)
    assert drawn.count("M") == 1  # only (10, 2)


def test_a_nan_breaks_a_line() -> None:
    plot = Plot()
    plot.line([0, 1, 2, 3, 4], [0, 1, np.nan, 3, 4], Style("#000000"))
    drawn = re.search(r'<path class="series" d="([^"]*)"', plot.svg("fig-l")).group(1)
    assert drawn.count("M") == 2 and drawn.count("L") == 2


def test_level_lines_lie_on_the_level() -> None:
    x = np.geomspace(1e-3, 3.0, 60)
    y = np.geomspace(1e-2, 1e3, 50)
    field = np.log(np.outer(y, 1.0 / x**2))  # the level set is y = c·x², a line in log-log
    lines = level_lines(x, y, field, math.log(100.0))
    assert len(lines) == 1
    lx, ly = lines[0]
    assert len(lx) > 10
    np.testing.assert_allclose(ly / lx**2, 100.0, rtol=0.02)
    assert np.all(np.diff(lx) > 0) or np.all(np.diff(lx) < 0)  # one ordered polyline


def test_a_closed_level_line_closes() -> None:
    x = y = np.linspace(-1.0, 1.0, 41)
    field = np.add.outer(y**2, x**2)
    (line,) = level_lines(x, y, field, 0.5, log=False)
    assert line[0][0] == line[0][-1] and line[1][0] == line[1][-1]
    np.testing.assert_allclose(np.hypot(*line), math.sqrt(0.5), rtol=0.01)


def test_level_lines_skip_cells_without_values() -> None:
    x = y = np.linspace(1.0, 2.0, 5)
    field = np.full((5, 5), np.nan)
    assert level_lines(x, y, field, 0.0) == []


def test_a_level_line_stops_where_the_field_has_no_value() -> None:
    """The regime map's σ/x₁ is NaN where a quantity is undefined: no line is invented
    across those cells, and where the field has values the line is on its level."""
    x = y = np.linspace(0.0, 1.0, 21)
    field = np.add.outer(y, x)  # level 1: the anti-diagonal x + y = 1
    field[:, 15:] = np.nan  # no values for x ≥ 0.75
    lines = level_lines(x, y, field, 1.0, log=False)
    assert lines
    for lx, ly in lines:
        assert np.all(lx <= 0.70 + 1e-12)
        np.testing.assert_allclose(lx + ly, 1.0, atol=1e-12)


@pytest.mark.parametrize("point", [None, (0.3, 0.004)])
def test_the_regime_map_shades_every_cell_and_draws_its_lines(point) -> None:
    velocity = np.geomspace(1e-3, 3.0, 12)
    viscosity = np.geomspace(1e-4, 1.0, 10)
    names = list(plots.REGIME_COLOURS)
    regime = np.array([[names[(i + j) % 4] for i in range(12)] for j in range(10)], object)
    ratio = np.outer(viscosity, velocity) * 1e3
    svg = plots.regime_map(velocity, viscosity, regime, ratio, ratio * 50, 10.0,
                                 point=point, figure_id="fig-m")  # fmt: skip
    root = ET.fromstring(svg)
    rects = root.findall(f".//{SVG}g[@class='cells']/{SVG}rect")
    assert len(rects) == 12 * 10  # no two neighbours share a colour in this pattern
    legend = [t.text for t in root.iter(f"{SVG}text") if t.text and t.text.startswith("σ")]
    assert legend == ["σ = x₁/3 (Λ = 1)", "σ = x₁/4 (Λ = 4/3)"]
    assert ("this collision" in svg) == (point is not None)
