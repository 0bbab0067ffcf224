"""Markup from data never reaches a reader (issue 35): the Markdown report and the README
of an exported package, rendered by a CommonMark renderer (markdown-it-py), a GitHub-
flavoured one (cmark-gfm, GitHub's own, with raw HTML let through as GitHub's parser
does before its sanitiser) and markdown-it-py with linkify (which links bare domains too),
hold exactly the elements, attributes and links of the same document written from benign
names: hostile names, run labels, titles, descriptions, citations, DOIs and URLs add none.
The spreadsheet-bound CSV files beside them (a report's runs, posterior draws) carry no
cell a spreadsheet would run as a formula."""

from __future__ import annotations

import csv
import io
from collections import Counter
from html.parser import HTMLParser
from pathlib import Path

import cmarkgfm
import pytest
from cmarkgfm.cmark import Options
from hypothesis import given, settings
from hypothesis import strategies as st
from markdown_it import MarkdownIt

import granudb
from granudb.vocabulary.escaping import FORMULA_STARTS, markdown_link, markdown_text

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"

#: Names and texts an attacker or a careless import could store (each passes the name
#: rules: printable, one line).
HOSTILE = [
    "<img src=x onerror=alert(1)>",
    "<script>alert(1)</script>",
    "https://evil.example/x",
    "www.evil.example",
    "a@evil.example",
    "mailto:b@evil.example",
    "[x](javascript:alert(1))",
    "![i](https://evil.example/i.png)",
    "**bold** | cell ~~s~~ `code`",
    '=HYPERLINK("https://evil.example","click")',
    "evil.example",
    "1. list",
    "# heading",
    "&lt;b&gt; &#60;i&#62;",
]
HOSTILE_DOI = '10.1234/x"><script>alert(1)</script>'
HOSTILE_URL = "https://evil.example/a><img/src=x/onerror=alert(1)>"


def _gfm(text: str) -> str:
    return cmarkgfm.github_flavored_markdown_to_html(text, options=Options.CMARK_OPT_UNSAFE)


RENDERERS = {
    "commonmark": MarkdownIt("commonmark").render,
    "gfm": _gfm,
    "linkify": MarkdownIt("gfm-like").enable("linkify").render,
}


class _Shape(HTMLParser):
    """Every element with its attribute names, and every link and image address."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.elements: Counter = Counter()
        self.addresses: list[str] = []

    def handle_starttag(self, tag: str, attrs: list) -> None:
        self.elements[(tag, tuple(sorted(name for name, _ in attrs)))] += 1
        self.addresses += [value or "" for name, value in attrs if name in ("href", "src")]


def _shape(html: str) -> tuple[Counter, list[str]]:
    parser = _Shape()
    parser.feed(html)
    return parser.elements, parser.addresses


@pytest.mark.parametrize("text", HOSTILE + [HOSTILE_DOI, HOSTILE_URL])
@pytest.mark.parametrize("renderer", sorted(RENDERERS))
def test_escaped_text_is_text_in_every_renderer(renderer: str, text: str) -> None:
    render = RENDERERS[renderer]
    for markdown in (markdown_text(text), f"| h |\n|---|\n| {markdown_text(text)} |"):
        elements, addresses = _shape(render(markdown))
        assert set(elements) <= {
            (t, ()) for t in ("p", "table", "thead", "tbody", "tr", "th", "td")
        }
        assert addresses == []


#: Text built from the pieces of markup, links and autolinks.
PIECES = st.lists(
    st.sampled_from(
        [
            "<",
            ">",
            "img",
            "script",
            " ",
            "src=x",
            "on",
            "=",
            '"',
            "'",
            "/",
            "https",
            "http",
            ":",
            "//",
            "www",
            ".",
            "evil",
            "com",
            "@",
            "a",
            "mailto",
            "[",
            "]",
            "(",
            ")",
            "!",
            "*",
            "_",
            "`",
            "|",
            "~",
            "#",
            "-",
            "1",
            "&",
            ";",
            "#60",
            "lt",
            "\\",
            "javascript",
            "\n",
            "\t",
        ]
    ),  # fmt: skip
    max_size=25,
).map("".join)


@settings(max_examples=300, deadline=None)
@given(PIECES)
def test_any_text_stays_text(text: str) -> None:
    for render in RENDERERS.values():
        for markdown in (markdown_text(text), f"| h |\n|---|\n| {markdown_text(text)} |"):
            elements, addresses = _shape(render(markdown))
            allowed = {(t, ()) for t in ("p", "table", "thead", "tbody", "tr", "th", "td")}
            assert set(elements) <= allowed, (text, markdown, elements)
            assert addresses == [], (text, markdown)


@pytest.mark.parametrize("renderer", sorted(RENDERERS))
def test_an_address_stays_one_link(renderer: str) -> None:
    for address in ("https://doi.org/" + HOSTILE_DOI, HOSTILE_URL):
        elements, addresses = _shape(RENDERERS[renderer](f"See {markdown_link(address)}."))
        assert elements == Counter({("p", ()): 1, ("a", ("href",)): 1})
        assert len(addresses) == 1 and not set(addresses[0]) & set('<>" \\')


def _labelled(tmp_path: Path, labels: list[str] | None) -> Path:
    """The example CSV, its run labels replaced by ``labels`` (cycled, made unique)."""
    rows = list(csv.reader(EXAMPLE.open(encoding="utf-8")))
    if labels is not None:
        for i, row in enumerate(rows[1:]):
            row[0] = f"{labels[i % len(labels)]} {i}"
    path = tmp_path / f"runs-{labels is not None}.csv"
    with path.open("w", newline="", encoding="utf-8") as handle:
        csv.writer(handle).writerows(rows)
    return path


def _world(db: str, tmp_path: Path, dataset: str, names: list[str], doi: str, url: str) -> dict:
    """The Markdown report, package README and runs CSV of ``dataset``, with the example's
    materials renamed to ``names``, its source's DOI and URL, its title and description."""
    granudb.update_source("joseph-hunt-2004", doi=doi, url=url, db=db)
    for old, new in zip(("steel", "Zerodur"), names[:2], strict=True):
        granudb.update_material(old, rename=new, db=db)
    granudb.edit_dataset(dataset, title=names[2], description=f"{names[3]}\n{names[4]}", db=db)
    out = tmp_path / dataset
    out.mkdir()
    granudb.report(dataset=dataset, format="md", output=out / "r.md", title=names[5], db=db)
    granudb.export_dataset(dataset, output=out / "pkg", db=db)
    for new, old in zip(names[:2], ("steel", "Zerodur"), strict=True):  # back, for the other
        granudb.update_material(new, rename=old, db=db)
    return {
        "report": (out / "r.md").read_text(encoding="utf-8"),
        "readme": (out / "pkg" / "README.md").read_text(encoding="utf-8"),
    }


def test_report_and_readme_add_no_markup_from_data(db: str, tmp_path: Path) -> None:
    granudb.import_collisions(_labelled(tmp_path, None), dataset="plain", db=db)
    granudb.import_collisions(_labelled(tmp_path, HOSTILE), dataset="hostile", db=db)
    benign = _world(db, tmp_path, "plain", [f"benign {i}" for i in range(6)],
                    "10.1234/benign", "https://example.org/benign")  # fmt: skip
    hostile = _world(db, tmp_path, "hostile", HOSTILE[:6], HOSTILE_DOI, HOSTILE_URL)
    for document in hostile.values():  # the data is shown, as text
        shown = RENDERERS["commonmark"](document)
        assert "https://evil.example/x" in shown and "&lt;img src=x onerror=alert(1)&gt;" in shown
    for document in ("report", "readme"):
        for name, render in RENDERERS.items():
            plain_elements, plain_links = _shape(render(benign[document]))
            elements, links = _shape(render(hostile[document]))
            assert elements == plain_elements, (document, name, elements - plain_elements)
            assert len(links) == len(plain_links), (document, name, links)
            for link in links:
                assert not set(link) & set('<>" \\'), (document, name, link)
                assert not link.startswith(("javascript:", "mailto:")), (document, name, link)


def test_the_runs_csv_beside_a_report_carries_no_formula() -> None:
    """The runs CSV beside a large report (``runs_csv``) and the ``--draws`` CSV pass
    ``spreadsheet_frame``: a label that a spreadsheet would run is shown, not run; numbers
    (a negative spin too) stay numbers."""
    import pandas as pd

    from granudb.reporting.tables import runs_csv

    labels = [*HOSTILE, "+1", "-x", "@SUM(A1)", "\tx", "plain"]
    frame = pd.DataFrame({"run": labels, "omega_in_rad_s": [-3.5] * len(labels)})
    rows = list(csv.reader(io.StringIO(runs_csv(frame).decode("utf-8"))))
    cells = [c for row in rows[1:] for c in row]
    assert not [c for c in cells if c.startswith(FORMULA_STARTS) and c != "-3.5"]
    assert [row[0] for row in rows[1:]] == [
        "'" + x if x.startswith(FORMULA_STARTS) else x for x in labels
    ]
    assert {row[1] for row in rows[1:]} == {"-3.5"}


def test_spreadsheet_frame_keeps_numbers_and_missing_values() -> None:
    """The one rule of spreadsheet-bound CSV (``--format csv``, runs, ``--draws``) on a
    frame of every column kind: text prefixed where a spreadsheet would run it, the rest
    as it was."""
    import numpy as np
    import pandas as pd

    from granudb.vocabulary.escaping import spreadsheet_cell, spreadsheet_frame

    frame = pd.DataFrame({
        "group": ['=HYPERLINK("https://evil.example","x")', "steel on glass", None],
        "arrow": pd.array(["@SUM(1)", "ok", None], dtype="string[pyarrow]"),
        "chain": [0, 1, 2],
        "value": [-1.5, np.nan, 2.0],
    })  # fmt: skip
    out = spreadsheet_frame(frame)
    for column in ("group", "arrow"):  # missing values stay missing
        assert out[column].isna().tolist() == [False, False, True]
        assert out[column].dtype == frame[column].dtype
    assert list(out["group"][:2]) == ["'" + frame["group"][0], "steel on glass"]
    assert list(out["arrow"][:2]) == ["'@SUM(1)", "ok"]
    assert out["chain"].tolist() == [0, 1, 2] and out["value"].equals(frame["value"])
    assert frame["group"][0].startswith("=")  # the caller's frame is not changed
    assert [spreadsheet_cell(v) for v in ("-x", -1.0, None)] == ["'-x", -1.0, ""]
