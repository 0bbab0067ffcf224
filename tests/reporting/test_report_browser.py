"""The HTML report in real headless Chromium, for the shipped example and a dataset of
the paper's pairs: at 1400 px and 390 px, and printed to PDF on A4 and Letter.

Checked: no legend says "nan"; every legend entry has its group's colour (the same as
its points and lines, and as the group's swatch in the tables); no ± value has more than
two significant digits of uncertainty; at 390 px nothing is wider than the viewport
except inside scroll boxes, no table's value cell is off-screen, and every text of every
figure (axis labels, ticks, legends, titles) is at least 10 CSS px as drawn (its computed
font size times the figure's scale); figures fill the column (up to 32rem on a wide
screen, where their text stays below 24 px); no PDF page ends with a heading
(per page, with poppler's ``pdftotext``). With ``GRANUDB_UPDATE_SCREENSHOT=1`` the paper report's
screenshot replaces ``docs/report.png``; otherwise it stays in the test's own folder.

Needs the Debian packages ``chromium`` and ``poppler-utils``.
"""

from __future__ import annotations

import html as htmllib
import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from paper_runs import EXAMPLE

DOCS = Path(__file__).resolve().parents[2] / "docs"
#: Runs in a host page around the report, in a same-origin ``srcdoc`` iframe of the width
#: under test: headless Chromium will not make a window narrower than 500 px.
PROBE = """<script>
window.addEventListener('load', () => {
  const frame = document.getElementById('report'), win = frame.contentWindow;
  const doc = frame.contentDocument, vw = win.innerWidth;
  const out = {vw, doc: doc.documentElement.scrollWidth, over: [], figures: [],
               narrowest: Math.min(...[...doc.querySelectorAll('td')]
                 .filter(td => td.getClientRects().length)  // a closed <details> hides its rows
                 .map(td => td.getBoundingClientRect().width))};
  for (const el of doc.body.querySelectorAll('*')) {
    const r = el.getBoundingClientRect();
    if (r.right > vw + 1 && !el.closest('.scroll'))
      out.over.push(el.tagName + '#' + el.id + '.' + (el.getAttribute('class') || ''));
  }
  for (const svg of doc.querySelectorAll('figure svg'))
    out.figures.push([svg.getBoundingClientRect().width,
                      svg.closest('figure').parentElement.clientWidth]);
  // The size a reader sees: the computed font size (user units) times the figure's scale.
  out.text = [...doc.querySelectorAll('figure svg text')].map(t => [
    parseFloat(win.getComputedStyle(t).fontSize) * t.ownerSVGElement.getScreenCTM().a,
    t.getAttribute('class') || t.parentElement.getAttribute('class') || '', t.textContent]);
  // Every value cell of a table outside a scroll box of runs is inside the viewport.
  out.values = [...doc.querySelectorAll('td.num')].filter(td => !td.closest('table.runs'))
    .map(td => td.getBoundingClientRect().right).filter(right => right > vw + 1);
  document.getElementById('probe').textContent = JSON.stringify(out);
});
</script>"""


def _tool(name: str, package: str) -> str:
    path = shutil.which(name) or (f"/usr/bin/{name}" if Path(f"/usr/bin/{name}").exists() else None)
    if path is None:
        raise AssertionError(f"{name} is required for this test (Debian package {package!r})")
    return path


def _chromium(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    flags = [
        "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync",
        "--hide-scrollbars", f"--user-data-dir={tmp_path / 'profile'}",
    ]  # fmt: skip
    done = subprocess.run(
        [_tool("chromium", "chromium"), *flags, *args], capture_output=True, text=True, timeout=180
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return done


def _with(html: Path, extra: str, name: str) -> Path:
    """A copy of the report with ``extra`` before ``</body>`` (the report has no script)."""
    copy = html.with_name(name)
    copy.write_text(html.read_text("utf-8").replace("</body>", extra + "</body>"), "utf-8")
    return copy


def _probe(tmp_path: Path, html: Path, width: int) -> dict:
    """Layout facts of the report in a viewport ``width`` px wide (see ``PROBE``)."""
    report = htmllib.escape(html.read_text("utf-8"), quote=True)
    page = tmp_path / f"probe-{width}.html"
    page.write_text(
        f'<!DOCTYPE html><html><body style="margin:0"><pre id="probe"></pre>'
        f'<iframe id="report" style="width:{width}px;height:900px;border:0" '
        f'srcdoc="{report}"></iframe>{PROBE}</body></html>',
        "utf-8",
    )
    dom = _chromium(tmp_path, f"--window-size={max(width, 500) + 40},1000",
                    "--virtual-time-budget=5000", "--dump-dom", page.as_uri()).stdout  # fmt: skip
    found = re.search(r'<pre id="probe">(.*?)</pre>', dom, re.S)
    assert found and found.group(1), dom[-500:]
    return json.loads(htmllib.unescape(found.group(1)))


def _legend_entries(svg: str) -> list[tuple[str, str]]:
    """(colour, label) of every legend entry of a report figure, in order: the colour the
    entry's sample is drawn in (not the ``data-colour`` it declares)."""
    entries = []
    for entry in re.findall(r'<g class="legend-entry"[^>]*>(.*?)</g>', svg, re.S):
        colours = re.findall(r'(?:stroke|fill)="(#[0-9a-f]{6})"', entry.split("<text")[0])
        text = re.search(r"<text[^>]*>([^<]*)</text>", entry)
        assert text, entry
        entries.append((colours[0] if colours else "", htmllib.unescape(text.group(1))))
    return entries


def _check_colours(html: str) -> None:
    swatches = dict(
        (group, colour)
        for colour, group in re.findall(
            r'class="swatch" style="background: (#[0-9a-f]{6})" data-group="([^"]+)"', html
        )
    )
    for svg in re.findall(r"<svg id=.*?</svg>", html, re.S):
        figure = re.search(r'<svg id="([^"]+)"', svg).group(1)
        outside = re.sub(r'<g class="legend">.*', "", svg, flags=re.S)
        by_key: dict[str, str] = {}
        entries = _legend_entries(svg)
        assert entries, figure  # every figure has a legend
        for colour, label in entries:
            assert "nan" not in label.lower(), (figure, label)
            key = re.split(r": | \(", htmllib.unescape(label))[0]
            if not colour or key.startswith(("St_", "h_m", "threshold", "this", "rebound", "no ")):
                continue
            assert by_key.setdefault(key, colour) == colour, (figure, key, label)
            assert colour in outside, (figure, label, colour)  # the points or lines drawn
            if key in swatches:
                assert swatches[key] == colour, (figure, key)


def _significant(number: str) -> int:
    digits = number.replace(".", "").lstrip("0")
    return len(digits if "." in number else digits.rstrip("0")) or 1


def _pages(pdf: Path) -> list[str]:
    text = subprocess.run(
        [_tool("pdftotext", "poppler-utils"), "-enc", "UTF-8", str(pdf), "-"],
        capture_output=True, text=True, timeout=60, check=True,
    ).stdout  # fmt: skip
    return [page for page in text.split("\f") if page.strip()]


def _check_print(tmp_path: Path, html: Path, paper: str) -> int:
    page = _with(html, f"<style>@page {{ size: {paper}; }}</style>", f"print-{paper}.html")
    pdf = tmp_path / f"report-{paper}.pdf"
    _chromium(tmp_path, "--no-pdf-header-footer", f"--print-to-pdf={pdf}", page.as_uri())
    source = html.read_text("utf-8")
    headings = {
        " ".join(htmllib.unescape(re.sub(r"<[^>]+>", "", h)).split())
        for h in re.findall(r"<h[1-3][^>]*>(.*?)</h[1-3]>", source, re.S)
    }
    pages = _pages(pdf)
    for number, text in enumerate(pages[:-1], start=1):
        last = " ".join(text.strip().splitlines()[-1].split())
        assert last not in headings, f"{paper} page {number} ends with heading {last!r}"
    return len(pages)


def _check_report(tmp_path: Path, html: Path, screenshot: Path | None = None) -> None:
    source = html.read_text("utf-8")
    _check_colours(source)
    text = htmllib.unescape(re.sub(r"<[^>]+>", " ", source))
    errors = re.findall(r"± ([0-9][0-9.]*(?:e[-+]?\d+)?)", text)
    assert not [e for e in errors if "e" in e or _significant(e) > 2], errors
    wide = _probe(tmp_path, html, 1400)
    assert wide["vw"] == 1400 and wide["figures"], wide
    # a figure fills its column up to 32rem (512 px), where its text is about 15 px
    assert all(abs(w - min(column, 512)) <= 1 for w, column in wide["figures"]), wide["figures"]
    assert min(t[0] for t in wide["text"]) >= 10 and max(t[0] for t in wide["text"]) <= 24
    phone = _probe(tmp_path, html, 390)
    assert phone["vw"] == 390 and phone["doc"] <= 390 and phone["over"] == [], phone
    assert all(abs(w - column) <= 1 for w, column in phone["figures"]), phone["figures"]
    small = [t for t in phone["text"] if t[0] < 10]
    assert phone["text"] and small == [], small[:5]  # axis labels, ticks, legends ≥ 10 px
    assert phone["values"] == [], phone["values"]  # no value column off-screen
    assert phone["narrowest"] >= 70, phone  # tables scroll in their box, columns not squeezed
    assert _check_print(tmp_path, html, "A4") >= 2
    assert _check_print(tmp_path, html, "letter") >= 2
    if screenshot is not None:
        _chromium(tmp_path, "--window-size=900,1000", f"--screenshot={screenshot}", html.as_uri())
        assert 10_000 < screenshot.stat().st_size < 200_000


def _report(cli, db, out: Path, *args: str) -> Path:
    result = cli("report", *args, "--output", str(out), db=db)
    assert result.exit_code == 0, result.stderr
    return out


@pytest.mark.slow
def test_example_report_in_chromium(cli, example_db, tmp_path) -> None:
    html = _report(cli, example_db, tmp_path / "example.html", "--dataset", "example")
    _check_report(tmp_path, html)


@pytest.mark.slow
def test_paper_pairs_report_in_chromium(cli, paper_db, tmp_path) -> None:
    html = _report(cli, paper_db, tmp_path / "paper.html", "--dataset", "paper")
    assert html.read_text("utf-8").count('<svg id="fig-regime-map') == 2
    update = os.environ.get("GRANUDB_UPDATE_SCREENSHOT") == "1"
    _check_report(tmp_path, html, DOCS / "report.png" if update else tmp_path / "report.png")


@pytest.mark.slow
def test_pair_report_in_chromium(cli, db, tmp_path) -> None:
    html = _report(cli, db, tmp_path / "pair.html", "--pair", "steel", "Zerodur", "--fluid",
                   "glycerol-37", "--diameter", "12.7 mm", "--velocity", "0.3 m/s")  # fmt: skip
    _check_report(tmp_path, html)


@pytest.mark.slow
def test_report_with_error_bars_in_chromium(cli, db, tmp_path) -> None:
    """Runs with stated speed uncertainties (issue 27): the bars are drawn in the group's
    colour and the report still lays out and prints as every report does."""
    stated = "v_n_in=± 3 %, v_n_out=± 3 %, v_t_in=± 3 %, v_t_out=± 3 %"
    imported = cli("collisions", "import", str(EXAMPLE), "--dataset", "u",
                   "--uncertainty", stated, db=db)  # fmt: skip
    assert imported.exit_code == 0, imported.stderr
    html = _report(cli, db, tmp_path / "u.html", "--dataset", "u")
    assert html.read_text("utf-8").count('class="errorbar"') >= 2
    _check_report(tmp_path, html)
