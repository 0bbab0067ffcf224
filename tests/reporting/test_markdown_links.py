"""Reports that travel (issue 24): every DOI in a Markdown report is a link when a
CommonMark renderer reads it (an autolink, ``<https://doi.org/…>``). The HTML report
stays free of outside references (a test holds it to that), so it prints the DOI."""

from __future__ import annotations

import re

import markdown_it


def test_every_doi_is_a_link(cli, example_db, tmp_path) -> None:
    out = tmp_path / "r.md"
    result = cli("report", "--dataset", "example", "--format", "md", "--output", str(out),
                 db=example_db)  # fmt: skip
    assert result.exit_code == 0, result.stderr
    text = out.read_text("utf-8")
    html = markdown_it.MarkdownIt("commonmark").render(text)
    dois = set(re.findall(r"https://doi\.org/[^\s<>\"]+", text))
    linked = set(re.findall(r'<a href="(https://doi\.org/[^"]+)"', html))
    assert dois and dois == linked, dois - linked
