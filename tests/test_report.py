"""Reports: content, the roughness flag, escaping of hostile strings, Markdown that parses
as CommonMark, deterministic output, and the HTML rendered in a real headless Chromium."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "collisions_example.csv"
HOSTILE = "<script>alert(1)</script> *bold* [link](http://x) | pipe"


def _pair(cli, db, tmp_path: Path, fmt: str = "html", *extra: str) -> Path:
    out = tmp_path / f"pair.{fmt}"
    result = cli(
        "report",
        "--pair",
        "glass",
        "Zerodur",
        "--fluid",
        "glycerol-45",
        "--velocity",
        "0.1 m/s",
        "--format",
        fmt,
        "--output",
        str(out),
        *extra,
        db=db,
    )
    assert result.exit_code == 0, result.stderr
    assert f"wrote {out}" in result.stdout
    return out


def test_pair_report_has_header_properties_flag_figures_and_methods(cli, db, tmp_path) -> None:
    html = _pair(cli, db, tmp_path).read_text(encoding="utf-8")
    assert "<title>granudb report: glass on Zerodur in glycerol-45</title>" in html
    assert "granudb report --pair glass Zerodur --fluid glycerol-45 --velocity" in html
    assert 'id="roughness-flag"' in html and 'class="flag"' in html
    assert "h_m = x₁/3" in html and "Λ = h_m/σ" in html
    assert "130.5 nm" in html and "60 GPa" in html and "joseph-hunt-2004, table 1" in html
    assert 'id="fig-regime-map"' in html
    assert "(5.8)" in html and "doi.org/10.1017/S002211200400919X" in html
    # self-contained: no script, no external fetch
    assert "<script" not in html.lower()
    assert not re.search(r'(src|href)="(https?:)?//', html)
    # the flag comes before any table, so it is on the first screen
    assert html.index('id="roughness-flag"') < html.index("<table")


def test_smooth_pair_is_not_flagged(cli, db, tmp_path) -> None:
    out = tmp_path / "steel.html"
    result = cli(
        "report",
        "--pair",
        "steel",
        "Zerodur",
        "--fluid",
        "glycerol-78",
        "--velocity",
        "0.1 m/s",
        "--output",
        str(out),
        db=db,
    )
    assert result.exit_code == 0, result.stderr
    html = out.read_text(encoding="utf-8")
    assert 'class="clear" id="roughness-flag"' in html and "Roughness within the gap" in html


def test_dataset_report_has_fits_next_to_published_values(cli, db, tmp_path) -> None:
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db).exit_code == 0
    out = tmp_path / "dataset.html"
    result = cli("report", "--dataset", "example", "--output", str(out), db=db)
    assert result.exit_code == 0, result.stderr
    html = out.read_text(encoding="utf-8")
    assert "Walton fits" in html and "β = 0.34 ± 0.07" in html  # published, dry steel
    for figure in ("fig-walton", "fig-beta", "fig-friction", "fig-restitution", "fig-shear-strain"):
        assert f'id="{figure}"' in html
    assert "content hash" in html


def test_markdown_parses_as_commonmark_with_tables_and_relative_images(cli, db, tmp_path):
    from markdown_it import MarkdownIt

    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db).exit_code == 0
    out = tmp_path / "r.md"
    result = cli("report", "--dataset", "example", "--format", "md", "--output", str(out), db=db)
    assert result.exit_code == 0, result.stderr
    text = out.read_text(encoding="utf-8")
    html = MarkdownIt("commonmark").enable("table").render(text)
    assert "<table>" in html and "<img" in html
    for src in re.findall(r'<img src="([^"]+)"', html):
        assert not src.startswith(("/", "http"))
        assert (out.parent / src).is_file()


def test_hostile_names_are_escaped_everywhere(cli, db, tmp_path) -> None:
    from markdown_it import MarkdownIt

    assert (
        cli(
            "materials",
            "add",
            HOSTILE,
            "--density",
            "2500 kg/m^3",
            "--youngs-modulus",
            "70 GPa",
            "--poisson-ratio",
            "0.2",
            "--roughness",
            "10 nm",
            db=db,
        ).exit_code
        == 0
    )
    html_path = tmp_path / "h.html"
    md_path = tmp_path / "h.md"
    for fmt, path in (("html", html_path), ("md", md_path)):
        result = cli(
            "report",
            "--pair",
            HOSTILE,
            "Zerodur",
            "--format",
            fmt,
            "--output",
            str(path),
            "--title",
            "<b>title</b>",
            db=db,
        )
        assert result.exit_code == 0, result.stderr
    html = html_path.read_text(encoding="utf-8")
    assert "<script>alert(1)</script>" not in html
    assert "&lt;script&gt;alert(1)&lt;/script&gt;" in html and "&lt;b&gt;title&lt;/b&gt;" in html
    rendered = MarkdownIt("commonmark").enable("table").render(md_path.read_text("utf-8"))
    assert "<script>" not in rendered and "<b>" not in rendered
    assert 'href="http://x"' not in rendered and "<em>bold</em>" not in rendered
    assert "&lt;script&gt;alert(1)&lt;/script&gt;" in rendered


def test_output_is_deterministic_but_for_the_timestamp(cli, db, tmp_path) -> None:
    def strip(text: str) -> str:
        return re.sub(r'<p class="meta" id="generated">.*?</p>', "", text)

    first = strip(_pair(cli, db, tmp_path).read_text("utf-8"))
    second = strip(_pair(cli, db, tmp_path, "html", "--force").read_text("utf-8"))
    assert first == second


def test_output_is_not_overwritten_without_force(cli, db, tmp_path) -> None:
    out = tmp_path / "kept.html"
    out.write_text("the copy I handed in", encoding="utf-8")
    args = ("report", "--pair", "steel", "Zerodur", "--output", str(out))
    refused = cli(*args, db=db)
    assert refused.exit_code == 1 and refused.stdout == ""
    assert refused.stderr.strip() == (
        f"Error: --output: {out} exists (use --force to overwrite it)"
    )
    assert out.read_text(encoding="utf-8") == "the copy I handed in"
    forced = cli(*args, "--force", db=db)
    assert forced.exit_code == 0, forced.stderr
    assert "<!DOCTYPE html>" in out.read_text(encoding="utf-8")


def test_default_output_name_in_the_current_folder(cli, db, tmp_path, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    result = cli("report", "--pair", "steel", "Zerodur", db=db)
    assert result.exit_code == 0, result.stderr
    assert (tmp_path / "granudb-report-steel-on-zerodur-dry.html").is_file()


@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (["--format", "pdf"], "--format: pdf must be one of html, md"),
        (["--output", "/no/such/folder/r.html"], "is in a folder that does not exist"),
        (["--velocity", "-1 m/s"], "--velocity: -1 m/s must be > 0"),
    ],
)
def test_bad_report_options(cli, db, args, expected) -> None:
    result = cli("report", "--pair", "steel", "Zerodur", *args, db=db)
    assert result.exit_code == 1 and expected in result.stderr, result.stderr


def _chromium() -> str:
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    raise AssertionError(
        "headless Chromium is required for this test (Debian package "
        "'chromium'; .ci/run installs it)"
    )


def test_html_renders_in_headless_chromium(cli, db, tmp_path) -> None:
    html = _pair(cli, db, tmp_path)
    browser = _chromium()
    flags = [
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        f"--user-data-dir={tmp_path / 'profile'}",
        "--enable-logging=stderr",
        "--v=0",
    ]
    dom = subprocess.run(
        [browser, *flags, "--dump-dom", html.as_uri()], capture_output=True, text=True, timeout=120
    )
    assert dom.returncode == 0, dom.stderr[-2000:]
    assert 'id="roughness-flag"' in dom.stdout and "Roughness exceeds the EHD gap" in dom.stdout
    assert dom.stdout.count("<svg") >= 1 and 'id="fig-regime-map"' in dom.stdout
    console_errors = [line for line in dom.stderr.splitlines() if "CONSOLE" in line]
    assert console_errors == []
    for name, size in (("report-desktop.png", "1200,1600"), ("report-phone.png", "390,844")):
        shot = subprocess.run(
            [
                browser,
                *flags,
                f"--window-size={size}",
                f"--screenshot={tmp_path / name}",
                html.as_uri(),
            ],
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert shot.returncode == 0, shot.stderr[-2000:]
        assert (tmp_path / name).stat().st_size > 10_000


def test_report_takes_the_query_filters_of_collisions_list(cli, db, tmp_path) -> None:
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db).exit_code == 0
    out = tmp_path / "filtered.html"
    result = cli(
        "report",
        "--dataset",
        "example",
        "--fluid",
        "dry",
        "--angle-range",
        "20..61 deg",  # ζ_in from the velocities: the 60° run is at 60.0003°
        "--output",
        str(out),
        db=db,
    )
    assert result.exit_code == 0, result.stderr
    html = out.read_text(encoding="utf-8")
    # dry runs at 25°, 40° and 60° only: too few for two lines of ≥ 2 runs, so all slide
    assert "--angle-range" in html and re.search(r"<td[^>]*>0 / 3 \(of 3\)</td>", html)
    bad = cli("report", "--dataset", "example", "--angle-range", "20 deg", db=db)
    assert bad.exit_code == 1 and "--angle-range: 20 deg must be LOW..HIGH" in bad.stderr
