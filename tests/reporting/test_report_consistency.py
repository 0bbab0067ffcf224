"""One report, one answer (issue 24): each group has one colour in every figure and table
of a dataset report, the regime map included, and its legends name groups in the same
words as the others."""

from __future__ import annotations

import html as htmllib
import re

#: Legend entries that are not a group: the regime map's regions and lines, St_c, fits.
STATIC = ("rebound", "no rebound", "σ = ", "St_n = St_c", "St_c = ", "threshold fit")


def _legend(svg: str) -> list[tuple[str, str]]:
    """(colour drawn, label) of each legend entry of one figure."""
    entries = []
    for entry in re.findall(r'<g class="legend-entry"[^>]*>(.*?)</g>', svg, re.S):
        colour = re.findall(r'(?:stroke|fill)="(#[0-9a-f]{6})"', entry.split("<text")[0])[0]
        label = htmllib.unescape(re.search(r"<text[^>]*>([^<]*)</text>", entry).group(1))
        entries.append((colour, label))
    return entries


def _group_colours(html: str) -> tuple[dict[str, str], dict[str, dict[str, set[str]]]]:
    """The tables' swatch colour per group, and per figure the colours each group is
    drawn in (legend entries whose label starts with the group)."""
    swatches = {
        group: colour
        for colour, group in re.findall(
            r'class="swatch" style="background: (#[0-9a-f]{6})" data-group="([^"]+)"', html
        )
    }
    drawn: dict[str, dict[str, set[str]]] = {}
    for svg in re.findall(r"<svg id=.*?</svg>", html, re.S):
        figure = re.search(r'<svg id="([^"]+)"', svg).group(1)
        for colour, label in _legend(svg):
            if label.startswith(STATIC):
                continue
            group = re.split(r": | \(\d", label)[0]
            drawn.setdefault(figure, {}).setdefault(group, set()).add(colour)
    return swatches, drawn


def test_each_group_has_one_colour_in_every_figure(cli, paper_db, tmp_path) -> None:
    out = tmp_path / "paper.html"
    result = cli("report", "--dataset", "paper", "--output", str(out), db=paper_db)
    assert result.exit_code == 0, result.stderr
    swatches, drawn = _group_colours(out.read_text("utf-8"))
    assert len(swatches) == 4 and len(set(swatches.values())) == 4, swatches
    maps = [f for f in drawn if f.startswith("fig-regime-map")]
    assert len(maps) == 2 and {"fig-walton", "fig-beta", "fig-friction"} <= set(drawn)
    for figure, groups in drawn.items():
        for group, colours in groups.items():
            assert group in swatches, (figure, group)  # one legend vocabulary: the group
            assert colours == {swatches[group]}, (figure, group, colours)
    on_maps = set().union(*(drawn[f] for f in maps))
    assert on_maps == set(swatches)  # every group is drawn on its pair's regime map
