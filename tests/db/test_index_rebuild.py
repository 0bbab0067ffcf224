"""A large SQLite import rebuilds the collisions table's plain indexes; a small one into
a large table does not; either way the schema and the rows end as they would have.

``granudb.db.bulk_insert.PlainIndexes`` drops the non-unique indexes inside the import's
transaction and creates them again before it commits, when ``rebuild_pays``. These tests
take both paths, and a refused import on the rebuild path (SQLite's DDL is rolled back
with it). The SIGKILL test in tests/test_reliability.py kills one on this path.
"""

from __future__ import annotations

import sqlite3
from pathlib import Path

import pytest
from support import GOOD_ROW, dump_hash, write_csv

from granudb.api.database import connect as open_database
from granudb.db import bulk_insert
from granudb.errors import ValidationError
from granudb.io.collision_file import estimate_rows
from granudb.io.collision_import import import_collisions

pytestmark = pytest.mark.sqlite_only


def _rows(n: int, prefix: str) -> list[list[str]]:
    rows = []
    for i in range(n):
        row = list(GOOD_ROW)
        row[0] = f"{prefix}-{i}"
        row[3] = ["", "water", "glycerol-37"][i % 3]
        row[12] = "20" if row[3] else ""
        rows.append(row)
    return rows


def _schema(db: str) -> list[tuple[str, str | None]]:
    with sqlite3.connect(db) as connection:
        return connection.execute(
            "SELECT name, sql FROM sqlite_master WHERE tbl_name = 'collisions' ORDER BY name"
        ).fetchall()


def _import(db: str, path: Path, dataset: str, **options) -> int:
    database = open_database(db)
    try:
        return import_collisions(database, path, dataset=dataset, **options).rows
    finally:
        database.dispose()


@pytest.fixture
def calls(monkeypatch) -> list[str]:
    """Which of ``PlainIndexes.drop``/``create`` ran, in order."""
    seen: list[str] = []
    for name in ("drop", "create"):
        original = getattr(bulk_insert.PlainIndexes, name)

        def spy(self, _original=original, _name=name) -> None:
            seen.append(_name)
            _original(self)

        monkeypatch.setattr(bulk_insert.PlainIndexes, name, spy)
    return seen


def test_the_rule() -> None:
    assert bulk_insert.rebuild_pays(1_000_000, 0)
    assert bulk_insert.rebuild_pays(1_000_000, 1_000_000)
    assert not bulk_insert.rebuild_pays(1_000, 10_000_000)
    assert not bulk_insert.rebuild_pays(999_999, 1_000_000)
    assert not bulk_insert.rebuild_pays(bulk_insert.REBUILD_MIN_ROWS - 1, 0)


def test_estimate_rows_is_near_the_count(tmp_path: Path) -> None:
    path = write_csv(tmp_path / "c.csv", _rows(20_000, "r"))
    assert abs(estimate_rows(path) - 20_000) < 1_000
    small = write_csv(tmp_path / "s.csv", _rows(5, "r"))
    assert estimate_rows(small) == 5


def test_large_import_rebuilds_small_one_into_a_large_table_does_not(
    db: str, tmp_path: Path, monkeypatch, calls: list[str]
) -> None:
    monkeypatch.setattr(bulk_insert, "REBUILD_MIN_ROWS", 100)
    schema = _schema(db)
    assert _import(db, write_csv(tmp_path / "a.csv", _rows(600, "a")), "a") == 600
    assert calls == ["drop", "create"]
    assert _schema(db) == schema
    calls.clear()
    assert _import(db, write_csv(tmp_path / "b.csv", _rows(150, "b")), "b") == 150
    assert calls == []  # 150 rows into a table of 600: the indexes are updated
    assert _schema(db) == schema
    with sqlite3.connect(db) as connection:
        assert connection.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
        used = connection.execute(
            "EXPLAIN QUERY PLAN SELECT count(*) FROM collisions WHERE fluid_id = 1"
        ).fetchall()
        assert any("ix_collisions_fluid_id" in str(step) for step in used)
        counted = connection.execute(
            "SELECT count(*) FROM collisions INDEXED BY ix_collisions_pair_fluid "
            "WHERE particle_id > 0"
        ).fetchone()[0]
        assert counted == 750


def test_a_refused_import_on_the_rebuild_path_leaves_the_indexes(
    db: str, tmp_path: Path, monkeypatch, calls: list[str]
) -> None:
    monkeypatch.setattr(bulk_insert, "REBUILD_MIN_ROWS", 100)
    schema, before = _schema(db), dump_hash(db)
    rows = _rows(600, "a")
    rows[550][6] = "-3"  # v_n_in must be positive: refused after 500 rows are written
    with pytest.raises(ValidationError, match="row 552"):
        _import(db, write_csv(tmp_path / "a.csv", rows), "a", chunk_rows=100)
    assert calls == ["drop"]
    assert _schema(db) == schema
    assert dump_hash(db) == before
