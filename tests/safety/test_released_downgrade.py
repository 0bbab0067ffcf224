"""A consented downgrade does not silently change a release (issue 35), and every
revision declares its downgrade's losses beside ``downgrade()`` (issue 34).

``db downgrade 0007`` drops the collisions' stated uncertainties: in a released version
that changes its ``collisions.csv`` while its recorded content hash stays. The loss lines
name the releases each reaches, ``--yes`` alone is refused, ``--drop-released-values``
names the consequence; afterwards ``dataset show`` says the release no longer matches its
hash and ``dataset export`` refuses it in one line. Both backends.
"""

from __future__ import annotations

import csv
import re
from pathlib import Path

import pytest
from support import dump_hash

import granudb
from granudb.db import migration
from granudb.errors import SchemaError

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"
VERSIONS = Path(__file__).resolve().parents[2] / "migrations" / "versions"


def _with_u(tmp_path: Path) -> Path:
    rows = list(csv.reader(EXAMPLE.open(encoding="utf-8")))
    path = tmp_path / "runs_with_u.csv"
    with path.open("w", encoding="utf-8", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow([*rows[0], "u(v_n_in) [mm/s]"])
        writer.writerows([*row, "5"] for row in rows[1:])
    return path


@pytest.fixture
def released_with_u(opened, tmp_path: Path) -> str:
    """lab@1.0.0 released with a stated u(v_n_in) on each of its 12 runs; draft@1.0.0 a
    draft of the same runs."""
    granudb.import_collisions(_with_u(tmp_path), dataset="lab", db=opened)
    granudb.release_dataset("lab", db=opened)
    granudb.import_collisions(_with_u(tmp_path), dataset="draft", db=opened)
    return opened.url


def test_the_loss_names_the_release_and_yes_is_not_enough(
    cli, released_with_u: str, tmp_path: Path
) -> None:
    db = released_with_u
    losses = migration.plan_downgrade(granudb.connect(db), "0007")
    assert (
        "collisions.u_v_n_in_m_s: 24 values dropped (the stated standard uncertainty) — "
        "changes released versions lab@1.0.0"
    ) in losses
    before = dump_hash(db)
    for refused in (
        cli("db", "downgrade", "0007", "--yes", db=db),
        cli("db", "downgrade", "0007", db=db),
    ):
        assert refused.exit_code == 1
        assert refused.stderr.count("\n") == 1
        assert refused.stderr.startswith(
            "Error: db downgrade 0007: would change released versions lab@1.0.0 (values "
            "they hold are dropped, so their exports no longer match their content hashes); "
            "--yes is not enough: add --drop-released-values"
        )
    with pytest.raises(granudb.GranudbError, match="would change released versions lab@1"):
        granudb.db_downgrade("0007", db=db)  # Python: the call is consent to losses only
    assert dump_hash(db) == before

    shown = granudb.dataset("lab", db=db)["content_hash"]
    done = cli("db", "downgrade", "0007", "--yes", "--drop-released-values", db=db)
    assert done.exit_code == 0, done.stderr
    assert "changes released versions lab@1.0.0" in done.stdout
    assert cli("db", "upgrade", db=db).exit_code == 0

    # the release still records its hash, and granudb says its runs no longer give it
    record = granudb.dataset("lab", db=db)
    assert record["content_hash"] == shown
    said = [line for line in record["pinned_changes"] if line.startswith("content hash:")]
    assert len(said) == 1 and "no longer give the content hash it was released with" in said[0]
    show = cli("dataset", "show", "lab", db=db)
    assert show.exit_code == 0 and "no longer give the content hash" in show.stderr
    target = tmp_path / "lab-package"
    export = cli("dataset", "export", "lab", "--output", str(target), db=db)
    assert export.exit_code == 1 and export.stderr.count("\n") == 1
    assert re.match(
        r"Error: dataset lab@1\.0\.0: its runs no longer give the content hash it was "
        r"released with \([0-9a-f]{16}…; now [0-9a-f]{16}…\)",
        export.stderr,
    )
    assert not target.exists()
    # the draft's hash follows its rows: it exports, declaring what show says
    assert granudb.dataset("draft", db=db)["pinned_changes"] == []
    assert cli("dataset", "export", "draft", "--output", str(tmp_path / "d"), db=db).exit_code == 0


def test_a_downgrade_that_reaches_only_drafts_needs_no_flag(opened, tmp_path: Path) -> None:
    granudb.import_collisions(_with_u(tmp_path), dataset="draft", db=opened)
    losses, releases = migration.preview_downgrade(opened, "0007")
    assert releases == [] and "changes released" not in " ".join(losses)
    granudb.db_downgrade("0007", db=opened)
    granudb.db_upgrade(db=opened)


def test_every_revision_declares_its_losses_beside_its_downgrade() -> None:
    """Read from the files: ``DOWNGRADE_LOSSES`` is assigned right before ``def
    downgrade`` in every shipped revision, and the consent reads it (issue 34)."""
    files = sorted(VERSIONS.glob("[0-9]*.py"))
    assert len(files) == len(migration.history())
    for path in files:
        source = path.read_text(encoding="utf-8")
        declared = source.index("\nDOWNGRADE_LOSSES: list[tuple[str, str, str, str]] = [")
        between = source[declared : source.index("\ndef downgrade(")]
        assert between.count("\ndef ") == 0, path.name  # nothing in between but the list
        assert migration.declared_losses(path.name[:4]) is not None


def test_a_revision_without_the_declaration_cannot_be_downgraded(
    opened, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The test the issue asks for: the shipped migrations with one revision's declaration
    taken out of its file (as a new revision written without it would be): a downgrade
    through it is refused, the database unchanged; one that does not pass it runs."""
    import shutil

    copy = tmp_path / "migrations"
    shutil.copytree(VERSIONS.parent, copy, ignore=shutil.ignore_patterns("__pycache__"))
    path = next((copy / "versions").glob("0008_*.py"))
    source = path.read_text(encoding="utf-8")
    start = source.index("#: What ``downgrade()`` drops")
    stripped = source[:start] + source[source.index("def downgrade(", start) :]
    assert "DOWNGRADE_LOSSES" not in stripped
    path.write_text(stripped, encoding="utf-8")
    monkeypatch.setattr(migration, "shipped_dir", lambda name: copy)
    before = dump_hash(opened.url)
    with pytest.raises(SchemaError, match="revision 0008: declares no DOWNGRADE_LOSSES"):
        granudb.db_downgrade("0007", db=opened)
    assert dump_hash(opened.url) == before
    assert migration.plan_downgrade(opened, "0008") is not None  # 0008 itself not undone
