"""The documentation site as people get it: built strictly, self-contained, and readable.

The site is built with ``mkdocs build --strict`` (README's command) into a temporary
folder, then:

- no page loads a script, stylesheet, font or image from outside the site (``http(s)://``
  or ``//`` in a ``script``/``link``/``img`` tag, or in a stylesheet's ``url()``), so it
  works offline;
- search works offline: the site's own search index and lunr.js (``search/``) find
  "restitution" in node, as the site's search worker does in the browser;
- in headless Chromium, served from 127.0.0.1, at 390 and 1400 px: the physics page, a
  how-to and the command-line reference render every equation with the site's KaTeX (no
  raw TeX, no KaTeX error), and no table cell is cut off (wider than its box, or past the
  screen's edge). Code blocks may scroll.

Needs the Debian packages ``chromium`` and ``nodejs``. ``GRANUDB_DOCS_SCREENSHOTS=DIR``
also writes each page's screenshot at both widths to DIR.
"""

from __future__ import annotations

import functools
import html
import http.server
import json
import os
import re
import shutil
import subprocess
import sys
import threading
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
PAGES = ["physics/", "guide/fits/", "cli/"]
WIDTHS = [390, 1400]
OUTSIDE = re.compile(r"^(https?:)?//", re.I)


def _tool(name: str, package: str) -> str:
    path = shutil.which(name)
    if path is None:
        raise AssertionError(f"{name} is required for this test (Debian package {package!r})")
    return path


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    folder = tmp_path_factory.mktemp("site")
    done = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(folder)],
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return folder


@pytest.fixture(scope="module")
def served(site: Path):
    handler = functools.partial(_QuietHandler, directory=str(site))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{server.server_address[1]}/"
    server.shutdown()
    server.server_close()


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args: object) -> None:
        pass


def test_no_page_loads_anything_from_outside_the_site(site: Path) -> None:
    offences = []
    pages = list(site.rglob("*.html"))
    assert len(pages) >= 20
    for page in pages:
        text = page.read_text(encoding="utf-8")
        for tag in re.findall(r"<(?:script|link|img|source|iframe)\b[^>]*>", text, re.I):
            for url in re.findall(r"""\b(?:src|href)\s*=\s*["']([^"']*)["']""", tag, re.I):
                if OUTSIDE.match(url):
                    offences.append(f"{page.relative_to(site)}: {tag}")
    for sheet in site.rglob("*.css"):
        for url in re.findall(r"url\(\s*['\"]?([^'\")]+)", sheet.read_text(encoding="utf-8")):
            if OUTSIDE.match(url):
                offences.append(f"{sheet.relative_to(site)}: url({url})")
    assert offences == []


def test_every_local_asset_a_page_names_is_in_the_site(site: Path) -> None:
    missing = []
    for page in site.rglob("*.html"):
        text = page.read_text(encoding="utf-8")
        for tag in re.findall(r"<(?:script|link|img)\b[^>]*>", text, re.I):
            for url in re.findall(r"""\b(?:src|href)\s*=\s*["']([^"'#?]*)""", tag, re.I):
                local = url and not OUTSIDE.match(url) and not url.endswith("/")
                target = site / url.lstrip("/") if url.startswith("/") else page.parent / url
                if local and not target.resolve().exists():
                    missing.append(f"{page.relative_to(site)}: {url}")
    assert missing == []


def test_search_works_offline_with_the_site_s_own_index(site: Path) -> None:
    node = _tool("node", "nodejs")
    script = """
const fs = require('fs');
const lunr = require(process.argv[1] + '/search/lunr.js');
const data = JSON.parse(fs.readFileSync(process.argv[1] + '/search/search_index.json'));
const index = lunr(function () {
  this.field('title'); this.field('text'); this.ref('location');
  for (const doc of data.docs) this.add(doc);
});
console.log(JSON.stringify(index.search('restitution').map(r => r.ref).slice(0, 50)));
"""
    done = subprocess.run(
        [node, "-e", script, str(site)], capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr[-2000:]
    found = json.loads(done.stdout)
    assert any(ref.startswith("physics/") for ref in found), found
    assert any(ref.startswith("guide/fits/") for ref in found), found
    for ref in found:
        assert (site / ref.split("#")[0] / "index.html").exists() or ref.startswith("#"), ref


#: Runs in a host page around the page under test, in a same-origin iframe of the width
#: under test, once the page has rendered (KaTeX runs on DOMContentLoaded).
PROBE = """<!doctype html><html><body style="margin:0">
<iframe id="page" src="%(src)s" style="width:%(width)spx;height:1200px;border:0"></iframe>
<pre id="probe"></pre>
<script>
document.getElementById('page').addEventListener('load', () => setTimeout(() => {
  const win = document.getElementById('page').contentWindow, doc = win.document;
  const vw = doc.documentElement.clientWidth;
  const out = {vw, scroll: doc.documentElement.scrollWidth,
               math: doc.querySelectorAll('.arithmatex').length,
               rendered: doc.querySelectorAll('.arithmatex .katex').length,
               errors: doc.querySelectorAll('.katex-error').length,
               raw: [...doc.querySelectorAll('.arithmatex')]
                      .filter(e => !e.querySelector('.katex')).map(e => e.textContent).slice(0, 5),
               cells: doc.querySelectorAll('.rst-content td').length, cut: []};
  for (const cell of doc.querySelectorAll('.rst-content td, .rst-content th')) {
    if (!cell.getClientRects().length || cell.closest('pre')) continue;
    const r = cell.getBoundingClientRect();
    if (r.right > vw + 1 || cell.scrollWidth > cell.clientWidth + 1)
      out.cut.push(cell.textContent.trim().slice(0, 60));
  }
  out.over = [...doc.body.querySelectorAll('*')].filter(el =>
      el.getBoundingClientRect().right > vw + 1 && !el.closest('pre, .katex-display, .arithmatex')
      && el.getClientRects().length)
    .map(el => el.tagName + '.' + (el.getAttribute('class') || '') + ' ' +
               el.textContent.trim().slice(0, 40)).slice(0, 10);
  document.getElementById('probe').textContent = JSON.stringify(out);
}, 500));
</script></body></html>"""


def _chromium(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    flags = [
        "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync",
        "--hide-scrollbars", f"--user-data-dir={tmp_path / 'profile'}",
    ]  # fmt: skip
    done = subprocess.run(
        [_tool("chromium", "chromium"), *flags, *args], capture_output=True, text=True, timeout=180
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return done


@pytest.mark.parametrize("width", WIDTHS)
@pytest.mark.parametrize("page", PAGES)
def test_equations_render_and_no_table_text_is_cut(
    page: str, width: int, site: Path, served: str, tmp_path: Path
) -> None:
    host = site / f"probe-{width}-{page.strip('/').replace('/', '-')}.html"
    host.write_text(PROBE % {"src": page, "width": width}, encoding="utf-8")
    done = _chromium(tmp_path, "--virtual-time-budget=10000", "--dump-dom", served + host.name)
    match = re.search(r'<pre id="probe">(.*?)</pre>', done.stdout, re.S)
    assert match and match.group(1), done.stdout[-2000:]

    result = json.loads(html.unescape(match.group(1)))
    assert result["vw"] == width, result
    # nothing pushes the page sideways (code blocks and long equations scroll in their box)
    assert result["scroll"] <= width + 1 and result["over"] == [], result
    assert result["errors"] == 0 and result["rendered"] == result["math"], result
    if page == "physics/":
        assert result["math"] >= 60, result  # the relations are math, not plain text
    assert result["cut"] == [], result
    if page != "cli/":  # the reference is lists, which wrap: no table at all
        assert result["cells"] > 0, result
    shots = os.environ.get("GRANUDB_DOCS_SCREENSHOTS")
    if shots:
        name = f"{page.strip('/').replace('/', '-')}-{width}.png"
        _chromium(
            tmp_path,
            f"--window-size={width},2000",
            "--virtual-time-budget=10000",
            f"--screenshot={Path(shots).resolve() / name}",
            served + page,
        )
