"""Source edits are kept as revisions (issue 25): a re-seed that changes a source keeps
its values before the change with the time and reason (``sources history``); a release
reads its sources as they were when released (its package's bytes do not change), a draft
reads today's; the pinned-values note and ``dataset diff`` say the change; migration 0009
adds the history and its downgrade names what it drops."""

from __future__ import annotations

import io
import shutil
import zipfile
from pathlib import Path

from sqlalchemy import inspect, text
from support import engine_for

import granudb
from granudb.api.database import connect
from granudb.db import migration
from granudb.resources import shipped_dir

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"
KEY = "joseph-hunt-2004"
OLD = "Oblique particle-wall collisions in a liquid"
NEW = "Oblique particle–wall collisions in a liquid (corrected)"


def _reseed_with_changed_source(database, tmp_path: Path) -> list[str]:
    folder = tmp_path / "seed"
    shutil.copytree(shipped_dir("seed_data"), folder)
    sources = folder / "sources.toml"
    assert OLD in sources.read_text("utf-8")
    sources.write_text(sources.read_text("utf-8").replace(OLD, NEW), encoding="utf-8")
    return granudb.db_seed(folder=folder, db=database)


def _sources_csv(database, name: str, path: Path) -> bytes:
    exported = granudb.export_dataset(name, path, db=database)
    with zipfile.ZipFile(io.BytesIO(Path(exported.path).read_bytes())) as archive:
        return archive.read(next(n for n in archive.namelist() if n.endswith("sources.csv")))


def test_a_source_change_is_a_revision_a_release_keeps(opened, tmp_path: Path) -> None:
    granudb.import_collisions(EXAMPLE, dataset="rel", db=opened)
    granudb.release_dataset("rel", db=opened)
    granudb.import_collisions(EXAMPLE, dataset="draft", db=opened)
    released_before = _sources_csv(opened, "rel", tmp_path / "a.zip")
    assert OLD.encode() in released_before

    report = _reseed_with_changed_source(opened, tmp_path)
    assert any(line.startswith(f"updated source {KEY}: citation") for line in report), report

    history = granudb.source_history(KEY, db=opened)
    assert [r["revision"] for r in history] == ["current", "1"]
    assert NEW in history[0]["citation"] and OLD in history[1]["citation"]
    assert history[1]["kept_at"] is not None and "db seed" in history[1]["reason"]

    assert _sources_csv(opened, "rel", tmp_path / "b.zip") == released_before
    draft = _sources_csv(opened, "draft", tmp_path / "c.zip")
    assert NEW.encode() in draft and OLD.encode() not in draft

    pinned = [
        x for x in granudb.dataset("rel", db=opened)["pinned_changes"] if x.startswith("source ")
    ]
    assert len(pinned) == 1, pinned
    assert pinned[0].startswith(f"source {KEY} citation: release cites revision 1, '")
    assert OLD in pinned[0] and pinned[0].split("; revision 2 now reads ")[1].strip("'").endswith(
        "(corrected). Journal of Fluid Mechanics 510, 71-93."
    )
    assert granudb.dataset("draft", db=opened)["pinned_changes"] == []
    diff = [d["fields"] for d in granudb.diff_datasets("rel", "draft", db=opened)]
    old_text, new_text = pinned[0].split(", '", 1)[1].split("; revision 2 now reads ")
    assert [x for x in diff if x.startswith(KEY)] == [f"{KEY} citation: '{old_text} → {new_text}"]


def test_sources_history_on_the_command_line(opened, db, cli, tmp_path: Path) -> None:
    _reseed_with_changed_source(opened, tmp_path)
    shown = cli("sources", "history", KEY, db=db)
    assert shown.exit_code == 0 and "current" in shown.stdout and "db seed" in shown.stdout
    missing = cli("sources", "history", "no-such-source", db=db)
    assert missing.exit_code == 1 and "no-such-source" in missing.stderr
    assert "Traceback" not in missing.stderr


def _count(db: str, table: str) -> int:
    engine = engine_for(db)
    with engine.connect() as connection:
        count = connection.execute(text(f"SELECT count(*) FROM {table}")).scalar()
    engine.dispose()
    return count


def test_migration_0009_keeps_every_row_and_names_its_downgrade_loss(
    opened, db, tmp_path: Path
) -> None:
    granudb.import_collisions(EXAMPLE, dataset="rel", db=opened)
    granudb.release_dataset("rel", db=opened)
    _reseed_with_changed_source(opened, tmp_path)
    opened.dispose()
    counts = {t: _count(db, t) for t in ("sources", "collisions", "datasets", "materials")}
    database = connect(db)
    losses = migration.plan_downgrade(database, "0008")
    assert losses[-1] == (
        "source_revisions.citation: 1 values dropped (the sources' history; released "
        "datasets then read today's sources) — changes released versions rel@1.0.0"
    )  # after the later steps' own (0010: the seeded roughness not stated)
    assert all(line.startswith("materials.roughness_rms_m") for line in losses[:-1])
    migration.downgrade(database, "0008", accepted=losses, releases=["rel@1.0.0"])
    engine = engine_for(db)
    assert "source_revisions" not in inspect(engine).get_table_names()
    engine.dispose()
    assert {t: _count(db, t) for t in counts} == counts
    # upgraded again: an existing release pins today's values (no history before 0009)
    migration.upgrade(database, "head")
    database.dispose()
    assert {t: _count(db, t) for t in counts} == counts
    assert _count(db, "source_revisions") == 0
    again = granudb.connect(db)
    assert [r["revision"] for r in granudb.source_history(KEY, db=again)] == ["current"]
    assert granudb.dataset("rel", db=again)["pinned_changes"] == []
    again.dispose()


def test_an_unchanged_seed_keeps_no_revision(opened) -> None:
    granudb.db_seed(db=opened)
    assert [r["revision"] for r in granudb.source_history(KEY, db=opened)] == ["current"]
