"""Every text field passes the one text rule (issue 35): a correction's reason, a report's
title and a source key as a material's name does; names are stored in NFC and compared
case- and normalisation-insensitively; text stored before the rules is shown escaped."""

from __future__ import annotations

import sqlite3
import unicodedata
from pathlib import Path

import pytest
from support import dump_hash

import granudb
from granudb.vocabulary.text import name_key

MATERIAL = {"density": "1 g/cm^3", "youngs_modulus": "1 GPa", "poisson_ratio": 0.3,
            "roughness": "1 nm"}  # fmt: skip
EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"


@pytest.mark.parametrize(
    ("reason", "rule"),
    [
        ("clear \x1b[2J screen", "U+001B"),
        ("bell \x07", "U+0007"),
        ("carriage \r return", "U+000D"),
        ("reads \u202ebackwards", "U+202E"),
        ("zero\u200bwidth", "U+200B"),
        ("r" * 20_000, "at most 1000 characters"),
    ],
)
def test_a_reason_passes_the_text_rule(db: str, reason: str, rule: str) -> None:
    before = dump_hash(db)
    with pytest.raises(granudb.ValidationError, match="reason") as refused:
        granudb.update_source("johnson-1985", notes="x", reason=reason, db=db)
    assert rule in str(refused.value)
    assert dump_hash(db) == before


def test_a_reason_in_decomposed_form_is_kept_composed(db: str) -> None:
    granudb.update_source("johnson-1985", notes="x", reason="Cafe\u0301 note", db=db)
    reasons = [r["reason"] for r in granudb.source_history("johnson-1985", db=db)]
    assert "sources update: Caf\u00e9 note" in reasons


def test_a_report_title_passes_the_name_rule(db: str) -> None:
    with pytest.raises(granudb.ValidationError, match="title: .*U\\+202E"):
        granudb.report(("steel", "Zerodur"), format="md", title="a\u202eb", db=db)


def test_a_decomposed_name_is_its_composed_twin(db: str) -> None:
    granudb.add_material("Cafe\u0301", db=db, **MATERIAL)  # NFD, as macOS file names are
    names = list(granudb.materials(db=db)["name"])
    assert "Caf\u00e9" in names and "Cafe\u0301" not in names  # stored in NFC
    assert granudb.material("CAFE\u0301", db=db)["name"] == "Caf\u00e9"  # found either way
    before = dump_hash(db)
    for twin in ("Caf\u00e9", "CAF\u00c9", "cafe\u0301"):
        with pytest.raises(granudb.GranudbError, match="already exists as 'Café'"):
            granudb.add_material(twin, db=db, **MATERIAL)
    assert dump_hash(db) == before


def test_name_key_is_canonical_caseless() -> None:
    for one, other in [("Cafe\u0301", "CAF\u00c9"), ("Stra\u00dfe", "STRASSE"),
                       ("\u212bngstr\u00f6m", "\u00c5NGSTRO\u0308M")]:  # fmt: skip
        assert name_key(one) == name_key(other)
        assert unicodedata.is_normalized("NFC", name_key(one))
    assert name_key("glass") != name_key("gla ss")


@pytest.mark.parametrize("twin", ["Johnson-1985", "JOHNSON-1985", "johnson\u20101985"])
def test_a_source_key_refuses_its_case_twin(db: str, twin: str) -> None:
    before = dump_hash(db)
    if twin.isascii():
        with pytest.raises(granudb.GranudbError, match="already exists as 'johnson-1985'"):
            granudb.add_source(twin, citation="A twin.", db=db)
        assert dump_hash(db) == before
    else:  # a different character (U+2010) is a different key, as for materials
        granudb.add_source(twin, citation="Not a twin.", db=db)


@pytest.mark.sqlite_only
def test_text_stored_before_the_rules_is_shown_escaped(cli, db: str) -> None:
    granudb.update_source("johnson-1985", notes="x", reason="ok", db=db)
    with sqlite3.connect(db) as connection:
        connection.execute("UPDATE source_revisions SET reason = ?", ("a\x1b]0;owned\x07\u202eb",))
    shown = cli("sources", "history", "johnson-1985", db=db)
    assert shown.exit_code == 0, shown.stderr
    assert (
        "\x1b" not in shown.stdout and "\u202e" not in shown.stdout and "\x07" not in shown.stdout
    )
    assert "\\x1b]0;owned" in shown.stdout.replace("\n", "").replace("│", "").replace(" ", "")


def _runs_file(path: Path, labels: list[str], notes: list[str]) -> Path:
    """The example's first run under each label, with each note (a CSV file)."""
    header, first = EXAMPLE.read_text(encoding="utf-8").splitlines()[:2]
    cells = first.split(",")
    rows = [
        ",".join([label, *cells[1:-1], note]) for label, note in zip(labels, notes, strict=True)
    ]
    path.write_text("\n".join([header, *rows]) + "\n", encoding="utf-8")
    return path


def test_imported_run_labels_and_notes_are_stored_in_nfc(db: str, tmp_path: Path) -> None:
    """A file's labels and notes in decomposed form (as a Mac's keyboard may give them) are
    stored composed, as every other door stores text."""
    labels, notes = ["Cafe\u0301-1", "run-2"], ["tre\u0300s lent", ""]
    granudb.import_collisions(_runs_file(tmp_path / "nfd.csv", labels, notes), dataset="nfd", db=db)
    stored = granudb.collisions(db=db, dataset="nfd", columns=["run", "notes"], as_frame=False)
    assert sorted(r["run"] for r in stored) == ["Caf\u00e9-1", "run-2"]
    assert [r["notes"] for r in stored if r["run"] == "Caf\u00e9-1"] == ["tr\u00e8s lent"]


@pytest.mark.sqlite_only
def test_a_package_keeps_its_labels_as_stored(db: str, tmp_path: Path) -> None:
    """A Data Package is a copy of stored runs, checked against its content hash: labels
    stored in decomposed form before the rule reached imports come back byte for byte
    (composing them would change the rows the hash vouches for)."""
    granudb.import_collisions(
        _runs_file(tmp_path / "a.csv", ["Caf\u00e9-1"], ["tr\u00e8s"]), dataset="old", db=db
    )
    with sqlite3.connect(db) as connection:  # stored before the rule reached imports
        connection.execute(
            "UPDATE collisions SET run = ?, notes = ?", ("Cafe\u0301-1", "tre\u0300s")
        )
    exported = granudb.export_dataset("old", tmp_path / "old.zip", db=db)
    granudb.import_dataset(exported.path, as_name="new", db=db)
    [row] = granudb.collisions(db=db, dataset="new", columns=["run", "notes"], as_frame=False)
    assert (row["run"], row["notes"]) == ("Cafe\u0301-1", "tre\u0300s")


def test_a_file_with_both_forms_of_one_label_is_refused_in_one_line(
    db: str, tmp_path: Path
) -> None:
    twins = _runs_file(tmp_path / "twins.csv", ["Caf\u00e9-1", "Cafe\u0301-1"], ["", ""])
    before = dump_hash(db)
    with pytest.raises(granudb.ValidationError, match="run") as refused:
        granudb.import_collisions(twins, dataset="twins", db=db)
    assert "Caf\u00e9-1" in str(refused.value) and "\n" not in str(refused.value)
    assert dump_hash(db) == before
