"""The validation gallery (docs/reference/<dataset>.md and its figures) is what
tools/build_reference_docs.py writes from today's code, and says what the reproduction
returns."""

from __future__ import annotations

import runpy
from pathlib import Path

import granudb

ROOT = Path(__file__).resolve().parents[2]
GALLERY = ROOT / "docs" / "reference"


def test_committed_gallery_is_current(tmp_path: Path) -> None:
    builder = runpy.run_path(str(ROOT / "tools" / "build_reference_docs.py"))
    written = builder["build"](tmp_path)
    assert {f"{d['name']}.md" for d in granudb.reference_list()} <= set(written)
    for file in written:
        committed = GALLERY / file
        assert committed.is_file(), f"{file}: run python tools/build_reference_docs.py"
        assert committed.read_text("utf-8") == (tmp_path / file).read_text("utf-8"), (
            f"{file} is stale: run python tools/build_reference_docs.py"
        )


def test_each_page_says_the_reproductions_verdicts() -> None:
    for entry in granudb.reference_list():
        text = (GALLERY / f"{entry['name']}.md").read_text("utf-8")
        result = granudb.reference_reproduce(entry["name"])
        for line in result["summary"]:
            assert line in text
        rows = [line for line in text.splitlines() if line.startswith("| ") and " | " in line]
        table = [r for r in rows if r.endswith(("agrees |", "differs |", "source) |"))]
        assert len(table) == len(result["checks"]), entry["name"]


def test_the_index_links_every_page() -> None:
    index = (GALLERY / "index.md").read_text("utf-8")
    for entry in granudb.reference_list():
        assert f"({entry['name']}.md)" in index
