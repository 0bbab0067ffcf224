"""Reliability: concurrent writers and readers, a killed import, read-only databases."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from sqlalchemy import text
from support import dump_hash, engine_for

HEADER = (
    "run,particle,wall,fluid,diameter [mm],incidence_angle [deg],v_n_in [mm/s],"
    "v_t_in [mm/s],omega_in [rad/s],v_n_out [mm/s],v_t_out [mm/s],omega_out [rad/s]\n"
)
WRITERS = 4
ROWS = 2_000

READER = """
import json, sys, time
from granudb.api.database import connect as open_database
from granudb.db.dataset_catalog import dataset_records
database = open_database(sys.argv[1])
seen = []
deadline = time.time() + float(sys.argv[2])
while time.time() < deadline:
    with database.session() as session:
        seen.append({r["name"]: r["runs"] for r in dataset_records(session)})
    time.sleep(0.02)
print(json.dumps(seen))
"""


def _csv(path: Path, rows: int, prefix: str) -> Path:
    """``rows`` valid runs; a million are written in about half a second (one join)."""
    line = ",steel,Zerodur,,12.7,20,300,109,0,280,40,-5\n"
    with path.open("w", encoding="utf-8") as handle:
        handle.write(HEADER)
        handle.write("".join(f"{prefix}-{i}{line}" for i in range(rows)))
    return path


def _granudb(*args: str) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "granudb", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def test_concurrent_imports_and_readers_lose_nothing(db: str, tmp_path: Path) -> None:
    files = [_csv(tmp_path / f"w{i}.csv", ROWS, f"w{i}") for i in range(WRITERS)]
    readers = [
        subprocess.Popen(
            [sys.executable, "-c", READER, db, "8"],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for _ in range(2)
    ]
    writers = [
        _granudb("collisions", "import", str(f), "--dataset", f"set-{i}", "--db", db)
        for i, f in enumerate(files)
    ]
    listers = [_granudb("collisions", "list", "--format", "csv", "--db", db) for _ in range(2)]
    for process in writers + listers:
        out, err = process.communicate(timeout=300)
        assert process.returncode == 0, err
        assert "locked" not in err.lower()
    for process in readers:
        out, err = process.communicate(timeout=300)
        assert process.returncode == 0, err
        for snapshot in json.loads(out):
            for name, runs in snapshot.items():
                assert runs == ROWS, f"a reader saw {runs} runs of {name}: half an import"
    engine = engine_for(db)
    with engine.connect() as connection:
        total = connection.execute(text("SELECT count(*) FROM collisions")).scalar()
        imports = connection.execute(text("SELECT count(*) FROM collision_imports")).scalar()
    engine.dispose()
    assert total == WRITERS * ROWS and imports == WRITERS


@pytest.mark.sqlite_only
def test_sigkill_during_a_large_import_leaves_none_of_it(db: str, tmp_path: Path) -> None:
    import sqlite3

    # A million rows (issue 17), through the one-pass import and its bulk insert.
    big = _csv(tmp_path / "big.csv", 1_000_000, "big")
    before = dump_hash(db)
    indexes = _indexes(db)
    process = _granudb("collisions", "import", str(big), "--dataset", "big", "--db", db)
    # Kill once rows are being written: the write-ahead log has grown past 2 MB (the bulk
    # load's 16 MB page cache spills to it long before the million rows are in).
    wal = Path(db + "-wal")
    deadline = time.time() + 60
    while time.time() < deadline and process.poll() is None:
        if wal.exists() and wal.stat().st_size > 2_000_000:
            break
        time.sleep(0.02)
    assert process.poll() is None, "the import finished before it could be killed"
    os.kill(process.pid, signal.SIGKILL)
    process.wait(timeout=30)
    with sqlite3.connect(db) as connection:
        assert connection.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
        assert connection.execute("SELECT count(*) FROM collisions").fetchone()[0] == 0
    assert dump_hash(db) == before
    # A million rows into an empty table drop the plain indexes until the last row is in
    # (granudb.db.bulk_insert.PlainIndexes); the killed transaction never dropped them.
    assert _indexes(db) == indexes and len(indexes) >= 3
    # and the database still works, and the killed import can be run again whole
    again = subprocess.run(
        [sys.executable, "-m", "granudb", "collisions", "import", str(big), "--dataset", "big"]
        + ["--db", db],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert again.returncode == 0, again.stderr
    with sqlite3.connect(db) as connection:
        assert connection.execute("SELECT count(*) FROM collisions").fetchone()[0] == 1_000_000
        assert connection.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
    assert _indexes(db) == indexes
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "granudb",
            "collisions",
            "import",
            str(_csv(tmp_path / "small.csv", 10, "s")),
            "--dataset",
            "after",
            "--db",
            db,
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr


def _indexes(db: str) -> list[tuple[str, str | None]]:
    """The collisions table's indexes (name, SQL) as the schema has them."""
    import sqlite3

    with sqlite3.connect(db) as connection:
        return connection.execute(
            "SELECT name, sql FROM sqlite_master WHERE type = 'index' "
            "AND tbl_name = 'collisions' ORDER BY name"
        ).fetchall()


@pytest.mark.sqlite_only
def test_read_only_database_is_refused_in_one_line(cli, db: str) -> None:
    before = dump_hash(db)
    url = f"sqlite:///file:{db}?mode=ro&uri=true"
    assert cli("materials", "list", db=url).exit_code == 0
    result = cli(
        "materials",
        "add",
        "x",
        "--density",
        "1 g/cm^3",
        "--youngs-modulus",
        "1 GPa",
        "--poisson-ratio",
        "0.3",
        "--roughness",
        "1 nm",
        db=url,
    )
    assert result.exit_code == 1
    assert result.stderr.strip() == (
        "Error: database: is read-only (attempt to write a readonly database); nothing was changed"
    )
    assert dump_hash(db) == before


@pytest.mark.sqlite_only
def test_a_full_disk_is_refused_in_one_line_with_nothing_written(db: str, tmp_path: Path) -> None:
    """SQLite's ``max_page_count`` makes the file "full" exactly as a full disk does
    (SQLITE_FULL): the import is refused with one line and the database is unchanged."""
    from sqlalchemy import event

    from granudb.api.database import connect as open_database
    from granudb.errors import DatabaseAccessError
    from granudb.io.collision_import import import_collisions

    before = dump_hash(db)
    database = open_database(db)
    with database.engine.connect() as connection:
        pages = connection.execute(text("PRAGMA page_count")).scalar()
    database.engine.dispose()

    @event.listens_for(database.engine, "connect")
    def _cap(dbapi_connection, _record) -> None:
        dbapi_connection.execute(f"PRAGMA max_page_count={pages + 5}")

    with pytest.raises(DatabaseAccessError) as info:
        import_collisions(database, _csv(tmp_path / "full.csv", 20_000, "f"), dataset="full")
    database.dispose()
    assert str(info.value).startswith("database: disk full or failing")
    assert "\n" not in str(info.value)
    assert dump_hash(db) == before
