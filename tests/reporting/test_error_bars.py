"""Reports draw ±1 u error bars on measured points where runs carry stated uncertainties
(issue 27): e against St_n and Ψ_out against Ψ_in, in HTML and Markdown alike, with the
caption saying what a bar is; a dataset without stated u draws none."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from paper_runs import EXAMPLE

from granudb.reporting.svg import Plot, Style

SVG = "{http://www.w3.org/2000/svg}"
STATED = "v_n_in=± 3 %, v_n_out=± 3 %, v_t_in=± 3 %, v_t_out=± 3 %"


def _figure(html: str, figure_id: str) -> str:
    found = re.search(rf'<svg id="{figure_id}".*?</svg>', html, re.S)
    assert found, figure_id
    return found.group(0)


def _bars(svg: str) -> list[str]:
    root = ET.fromstring(svg)
    paths = [p for p in root.iter(f"{SVG}path") if p.get("class") == "errorbar"]
    return [d for p in paths for d in re.findall(r"M[^M]+", p.get("d"))]


def _report(cli, db: str, out: Path, *options: str) -> str:
    imported = cli("collisions", "import", str(EXAMPLE), "--dataset", "ex", *options, db=db)
    assert imported.exit_code == 0, imported.stderr
    made = cli("report", "--dataset", "ex", "--output", str(out), db=db)
    assert made.exit_code == 0, made.stderr
    return out.read_text("utf-8")


def test_runs_with_stated_u_get_error_bars_and_the_caption_says_what_they_are(
    cli, db: str, tmp_path: Path
) -> None:
    html = _report(cli, db, tmp_path / "u.html", "--uncertainty", STATED)
    restitution, walton = _figure(html, "fig-restitution"), _figure(html, "fig-walton")
    immersed = len(re.findall(r"M", "".join(_bars(restitution))))
    assert immersed >= 4  # every immersed run: a vertical bar (e) and a horizontal (St_n)
    assert len(_bars(walton)) >= 2 * 8  # Ψ_out and Ψ_in bars on every oblique run
    assert html.count("±1 standard uncertainty u of each run") == 2
    markdown = tmp_path / "u.md"
    made = cli("report", "--dataset", "ex", "--format", "md", "--output", str(markdown), db=db)
    assert made.exit_code == 0, made.stderr
    text = markdown.read_text("utf-8")
    assert "±1 standard uncertainty u of each run" in text
    folder = markdown.parent
    svgs = "".join(p.read_text("utf-8") for p in folder.rglob("fig-restitution*.svg"))
    assert 'class="errorbar"' in (svgs or text)


def test_runs_without_stated_u_have_no_error_bars(cli, db: str, tmp_path: Path) -> None:
    html = _report(cli, db, tmp_path / "plain.html")
    assert 'class="errorbar"' not in html
    assert "standard uncertainty u of each run" not in html


def test_a_bar_spans_two_u_on_the_axis() -> None:
    plot = Plot(title="t")
    plot.points([1.0, 2.0], [0.0, 1.0], Style("#000000", marker="o"))
    plot.errorbars([1.0, 2.0], [0.0, 1.0], [np.nan, 0.1], [0.25, np.nan], Style("#000000"))
    plot.ylim, plot.xlim = (-1.0, 2.0), (0.0, 3.0)
    svg = plot.svg("fig-e")
    [vertical, horizontal] = _bars(svg)
    y0, y1 = (float(v) for v in re.findall(r"[-0-9.]+", vertical)[1:3])
    x0, x1 = (float(v) for v in re.findall(r"[-0-9.]+", horizontal)[0::2][:2])
    frame = ET.fromstring(svg).find(f".//{SVG}rect[@class='frame']")
    height, width = float(frame.get("height")), float(frame.get("width"))
    assert abs(y1 - y0) == pytest.approx(0.5 / 3.0 * height, abs=0.02)
    assert abs(x1 - x0) == pytest.approx(0.2 / 3.0 * width, abs=0.02)
