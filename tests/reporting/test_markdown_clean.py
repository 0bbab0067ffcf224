"""CommonMark-clean Markdown (issue 24): a value rendered by a CommonMark renderer reads
exactly as intended, as a paragraph, a list item and a table cell, and carries a backslash
only where CommonMark would otherwise read markup (no "\\(σ \\> x₁/3\\)")."""

from __future__ import annotations

import html as htmllib
import re

import markdown_it
from hypothesis import given, settings
from hypothesis import strategies as st

import granudb
from granudb.reporting.render import markdown_escape

RENDERER = markdown_it.MarkdownIt("commonmark").enable("table").enable("strikethrough")
#: Text as reports have it: names, units, formulas, and every ASCII punctuation mark.
TEXT = st.text(
    alphabet=st.sampled_from(list("aZ09 _*`[]()<>#!|~&;-+=.:/\\'\"{}^%$@,?σΛ₁²·–")), max_size=30
)


def _rendered(markdown: str) -> str:
    html = RENDERER.render(markdown)
    return htmllib.unescape(re.sub(r"<[^>]+>", "", html)).strip()


@settings(max_examples=400, deadline=None)
@given(TEXT)
def test_escaped_text_renders_as_written(text: str) -> None:
    intended = " ".join(text.split())
    escaped = markdown_escape(text)
    assert _rendered(escaped) == intended
    assert _rendered(f"- {escaped}") == intended
    cells = re.findall(r"<td>(.*?)</td>", RENDERER.render(f"| head |\n|---|\n| {escaped} |"))
    assert [htmllib.unescape(re.sub(r"<[^>]+>", "", c)) for c in cells] == [intended]


def test_plain_text_keeps_no_needless_backslash() -> None:
    for text in ("asperity contact σ > x₁/3 (Λ = h_m/σ < 1)", "St_n = m* v_N,in",
                 "1/G = (2−ν₁)/G₁ + (2−ν₂)/G₂", "Joseph & Hunt (2004) §4", "-0.0276",
                 "e = e_dry exp(−35/St)", "3 runs: 1 value {a}"):  # fmt: skip
        escaped = markdown_escape(text)
        assert escaped.count("\\") == text.count("*"), escaped  # only the asterisk of m*
        assert _rendered(escaped) == text


def test_report_markdown_has_no_needless_escapes(example_db) -> None:
    text = granudb.report(dataset="example", format="md", db=example_db)
    assert not re.findall(r"\\[(){}>#!-]", text), re.findall(r".{20}\\[(){}>#!-].{20}", text)
    # a dot is escaped only before a letter, where a linkifying renderer would read a domain
    # ("model_public.m", "4TU.ResearchData"): granudb.vocabulary.escaping.markdown_text
    assert not re.findall(r"\\\.(?![A-Za-z])", text), re.findall(r".{20}\\\..{20}", text)
    assert "σ > x₁/3" in text and "St_n" in text
