"""The Alembic revisions and the SQLAlchemy models describe the same schema, and the
migrations run both ways on a database that holds data."""

from __future__ import annotations

import sqlite3
from pathlib import Path

from sqlalchemy import func, select

from granudb.db import migration
from granudb.db.engine import open_database
from granudb.db.models import Base, Material


def test_autogenerate_finds_no_difference_between_models_and_migrations(db_path: Path) -> None:
    from alembic.autogenerate import compare_metadata
    from alembic.runtime.migration import MigrationContext

    database = open_database(str(db_path))
    with database.engine.connect() as connection:
        context = MigrationContext.configure(connection, opts={"compare_type": True})
        differences = compare_metadata(context, Base.metadata)
    database.dispose()
    assert differences == []


def test_check_constraints_are_in_the_migrated_schema(db_path: Path) -> None:
    with sqlite3.connect(db_path) as connection:
        sql = connection.execute(
            "SELECT sql FROM sqlite_master WHERE name = 'materials'"
        ).fetchone()[0]
    assert "poisson_ratio > -1 AND poisson_ratio < 0.5" in sql
    assert "density_kg_m3 > 0" in sql


def test_upgrade_downgrade_upgrade_with_data(cli, tmp_path: Path) -> None:
    path = tmp_path / "cycle.sqlite"
    assert (
        cli(
            "materials",
            "add",
            "PEEK",
            "--density",
            "1.3 g/cm^3",
            "--youngs-modulus",
            "3.6 GPa",
            "--poisson-ratio",
            "0.38",
            "--roughness",
            "50 nm",
            db=path,
        ).exit_code
        == 0
    )
    database = open_database(str(path))
    with database.session() as session:
        assert session.scalar(select(func.count()).select_from(Material)) == 4
    before, after = migration.downgrade(database, "base")
    assert (before, after) == (migration.head_revision(), None)
    with database.engine.connect() as connection:
        assert migration.current_revision(connection) is None
    # Only Alembic's bookkeeping table may remain.
    with sqlite3.connect(path) as connection:
        tables = {
            r[0] for r in connection.execute("SELECT name FROM sqlite_master WHERE type = 'table'")
        }
    assert tables <= {"alembic_version"}
    database.dispose()

    result = cli("db", "upgrade", db=path)
    assert result.exit_code == 0, result.stderr
    assert f"→ {migration.head_revision()}" in result.stdout
    database = open_database(str(path))
    with database.session() as session:
        names = set(session.scalars(select(Material.name)))
    database.dispose()
    assert names == {"glass", "steel", "Zerodur"}  # re-created and re-seeded
    assert (
        cli(
            "materials",
            "add",
            "PEEK",
            "--density",
            "1.3 g/cm^3",
            "--youngs-modulus",
            "3.6 GPa",
            "--poisson-ratio",
            "0.38",
            "--roughness",
            "50 nm",
            db=path,
        ).exit_code
        == 0
    )


def test_db_upgrade_on_current_database_says_so(cli, db_path: Path) -> None:
    result = cli("db", "upgrade", db=db_path)
    assert result.exit_code == 0
    assert "already at" in result.stdout


def test_cli_downgrade_and_upgrade(cli, db_path: Path) -> None:
    result = cli("db", "downgrade", "base", db=db_path)
    assert result.exit_code == 0, result.stderr
    assert "→ empty" in result.stdout
    current = cli("db", "current", "--format", "json", db=db_path)
    assert '"revision": null' in current.stdout
    assert cli("db", "upgrade", db=db_path).exit_code == 0
    assert "glass" in cli("materials", "list", db=db_path).stdout


def test_sqlite_runs_in_wal_mode_with_foreign_keys_and_busy_timeout(db_path: Path) -> None:
    from sqlalchemy import text

    database = open_database(str(db_path))
    with database.engine.connect() as connection:
        assert connection.execute(text("PRAGMA journal_mode")).scalar() == "wal"
        assert connection.execute(text("PRAGMA foreign_keys")).scalar() == 1
        assert connection.execute(text("PRAGMA busy_timeout")).scalar() >= 5000
    database.dispose()


def test_concurrent_first_use_creates_and_seeds_once(tmp_path: Path) -> None:
    import json
    import subprocess
    import sys

    path = tmp_path / "shared.sqlite"
    procs = [
        subprocess.Popen(
            [
                sys.executable,
                "-m",
                "granudb",
                "materials",
                "list",
                "--format",
                "json",
                "--db",
                str(path),
            ],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for _ in range(4)
    ]
    outputs = [p.communicate(timeout=120) for p in procs]
    assert [p.returncode for p in procs] == [0, 0, 0, 0], [o[1] for o in outputs]
    for out, _ in outputs:
        assert len(json.loads(out)) == 3
    assert sum("created" in err for _, err in outputs) == 1
    with sqlite3.connect(path) as connection:
        assert connection.execute("SELECT count(*) FROM materials").fetchone()[0] == 3
        assert connection.execute("SELECT count(*) FROM sources").fetchone()[0] >= 3
