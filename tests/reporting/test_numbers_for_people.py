"""Numbers for people carry the precision their uncertainty supports: no float noise, and
no "[exact]" for a fitted number (issue 24), even where three runs give a degenerate
bootstrap (issue 23's case: three dry runs, one sticking); and no report of the test
datasets (the shipped example, the paper's pairs) has a number of more than six
significant digits in text meant for people (HTML text, figure texts, Markdown, the run
table)."""

from __future__ import annotations

import html as htmllib
import re

import pytest
from paper_runs import paper_rows, write_csv

#: A number meant for people with more than six significant digits (float noise).
NOISE = re.compile(r"(?<![\w.#/-])\d\.\d{7,}|(?<![\w.#/-])0\.0*[1-9]\d{6,}")


def _text(html: str) -> str:
    text = re.sub(r"<(svg|script|style)\b.*?</\1>", " ", html, flags=re.S)
    return re.sub(r"<[^>]+>", " ", text)


def test_three_runs_give_no_exact_interval_and_no_float_noise(cli, db, tmp_path) -> None:
    rows = [r for r in paper_rows(runs_per_group=3) if r[3] == ""][:3]
    rows = [[*r[:4], *r[4:]] for r in rows]
    source = write_csv(tmp_path / "three.csv", rows)
    assert cli("collisions", "import", str(source), "--dataset", "three", db=db).exit_code == 0
    for fmt in ("html", "md"):
        out = tmp_path / f"r.{fmt}"
        result = cli("report", "--dataset", "three", "--format", fmt, "--output", str(out), db=db)
        assert result.exit_code == 0, result.stderr
        text = _text(out.read_text("utf-8"))
        assert "[exact]" not in text and "(exact fit)" not in text
        assert NOISE.findall(text) == []
    listing = cli("fit", "walton", "--dataset", "three", db=db)
    assert listing.exit_code == 0, listing.stderr
    assert "[exact]" not in listing.stdout and NOISE.findall(listing.stdout) == []


def _people_text(source: str, fmt: str) -> str:
    """What a reader reads: HTML without tags, styles and attributes (figure texts kept);
    Markdown without image targets (data, not text)."""
    if fmt == "md":
        return re.sub(r"\]\([^)]*\)", "]", source)
    source = re.sub(r"<style\b.*?</style>", " ", source, flags=re.S)
    return htmllib.unescape(re.sub(r"<[^>]+>", " ", source))


@pytest.mark.parametrize("fixture", ["example_db", "paper_db"])
@pytest.mark.parametrize("fmt", ["html", "md"])
def test_no_float_noise_nor_exact(cli, request, tmp_path, fixture, fmt) -> None:
    db = request.getfixturevalue(fixture)
    dataset = fixture.removesuffix("_db")
    out = tmp_path / f"r.{fmt}"
    result = cli("report", "--dataset", dataset, "--format", fmt, "--output", str(out), db=db)
    assert result.exit_code == 0, result.stderr
    text = _people_text(out.read_text("utf-8"), fmt)
    assert "Runs" in text and "Walton" in text  # the run table and the fits are scanned
    assert "[exact]" not in text
    assert NOISE.findall(text) == [], NOISE.findall(text)[:5]
