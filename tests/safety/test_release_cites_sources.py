"""A release cites its sources as they were when released: after a user corrects a
source (``sources update``), the release's report, ``dataset show`` and package print
the revision the release cites and say that today's text differs (one line, computed
once in ``catalog_differences``), a draft prints today's text, and the release's
package bytes do not change."""

from __future__ import annotations

import json
from pathlib import Path

import granudb

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"
KEY = "joseph-hunt-2004"  # cited by the example's materials
OWN = "cheng-2008"  # the datasets' own source


def _package(database, name: str, folder: Path) -> dict[str, bytes]:
    granudb.export_dataset(name, folder, db=database)
    return {str(p.relative_to(folder)): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def test_a_release_cites_the_revision_it_was_released_with(cli, db: str, tmp_path: Path) -> None:
    for name in ("rel", "draft"):
        granudb.import_collisions(EXAMPLE, dataset=name, source=OWN, db=db)
    granudb.release_dataset("rel", db=db)
    old = granudb.source(KEY, db=db)["citation"]
    old_own = granudb.source(OWN, db=db)["citation"]
    before = _package(db, "rel", tmp_path / "before")
    granudb.report(dataset="rel", format="md", db=db)  # a report reads, changes nothing
    assert granudb.dataset("rel", db=db)["pinned_changes"] == []

    new = old.replace("Oblique", "Oblique (corrected)")
    edited = cli("sources", "update", KEY, "--citation", new, db=db)
    assert edited.exit_code == 0, edited.stderr
    granudb.update_source(OWN, citation=old_own + " Corrected.", db=db)

    # the package: byte for byte what it was
    assert _package(db, "rel", tmp_path / "after") == before

    # one line per changed field, the same wherever it is said
    lines = granudb.dataset("rel", db=db)["pinned_changes"]
    said = [x for x in lines if x.startswith("source ")]
    assert said == [
        f"source {OWN} citation: release cites revision 1, {old_own!r}; revision 2 now reads "
        f"{old_own + ' Corrected.'!r}",
        f"source {KEY} citation: release cites revision 1, {old!r}; revision 2 now reads {new!r}",
    ]
    shown = cli("dataset", "show", "rel", "--format", "json", db=db)
    assert shown.exit_code == 0
    assert json.loads(shown.stdout)["pinned_changes"] == lines
    table = cli("dataset", "show", "rel", db=db)
    printed = " ".join((table.stdout + table.stderr).split())
    assert printed.count("release cites revision 1") == 2 and new in printed
    assert granudb.dataset("rel", db=db)["citation"] == old_own
    assert granudb.dataset("draft", db=db)["citation"] == old_own + " Corrected."
    assert granudb.dataset("draft", db=db)["pinned_changes"] == []

    # the report: references as released, the note in its pinned values
    released = granudb.report(dataset="rel", format="md", db=db)
    cited = _references(released)
    assert old in cited and new not in cited and old_own in cited and "Corrected" not in cited
    for line in said:
        assert line in released
    draft = _references(granudb.report(dataset="draft", format="md", db=db))
    assert new in draft and old not in draft
    out = tmp_path / "rel.md"
    printed = cli("report", "--dataset", "rel", "--format", "md", "--output", str(out), db=db)
    assert printed.exit_code == 0, printed.stderr
    assert _references(out.read_text("utf-8")) == cited


def _references(markdown: str) -> str:
    """The report's reference list."""
    return markdown.split("### References", 1)[1].split("\n#", 1)[0]


def test_each_release_cites_the_revision_of_its_day(db: str) -> None:
    granudb.import_collisions(EXAMPLE, dataset="first", db=db)
    granudb.release_dataset("first", db=db)
    old = granudb.source(KEY, db=db)["citation"]
    granudb.update_source(KEY, citation=old + " A.", db=db)
    granudb.import_collisions(EXAMPLE, dataset="second", db=db)
    granudb.release_dataset("second", db=db)
    granudb.update_source(KEY, citation=old + " B.", reason="typo", db=db)

    def said(name: str) -> list[str]:
        return [x for x in granudb.dataset(name, db=db)["pinned_changes"] if x.startswith("source")]

    assert said("first") == [
        f"source {KEY} citation: release cites revision 1, {old!r}; revision 3 now reads "
        f"{old + ' B.'!r}"
    ]
    assert said("second") == [
        f"source {KEY} citation: release cites revision 2, {old + ' A.'!r}; revision 3 now "
        f"reads {old + ' B.'!r}"
    ]
    history = granudb.source_history(KEY, db=db)
    assert [(r["revision"], r["citation"]) for r in history] == [
        ("current", old + " B."), ("2", old + " A."), ("1", old)
    ]  # fmt: skip
    assert old + " A." in _references(granudb.report(dataset="second", format="md", db=db))
