"""Shared fixtures: every test gets its own database and its own data directory.

Nothing here touches the real home directory: ``XDG_DATA_HOME`` and ``HOME`` point into
the test's temporary folder, and ``GRANUDB_DATABASE_URL`` is unset unless a test sets it.
A seeded template database is built once per session and copied for each test (copying a
file is ~100× faster than migrating and seeding again).
"""

from __future__ import annotations

import shutil
import sqlite3
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest
from typer.testing import CliRunner

REPO = Path(__file__).resolve().parent.parent
SHARED = REPO.parent / "shared"


@pytest.fixture(autouse=True)
def isolated_environment(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    home = tmp_path / "home"
    home.mkdir()
    monkeypatch.setenv("HOME", str(home))
    monkeypatch.setenv("XDG_DATA_HOME", str(home / ".local" / "share"))
    monkeypatch.delenv("GRANUDB_DATABASE_URL", raising=False)
    monkeypatch.setenv("COLUMNS", "200")  # wide Rich tables: one row per line in tests


@pytest.fixture(scope="session")
def template_db(tmp_path_factory: pytest.TempPathFactory) -> Path:
    from granudb.db.engine import open_database

    path = tmp_path_factory.mktemp("template") / "granudb.sqlite"
    database = open_database(str(path))
    database.dispose()
    _checkpoint(path)
    return path


def _checkpoint(path: Path) -> None:
    """Fold the WAL into the main file so copying the one file copies everything."""
    with sqlite3.connect(path) as connection:
        connection.execute("PRAGMA wal_checkpoint(TRUNCATE)")
        connection.execute("PRAGMA journal_mode=DELETE")


@pytest.fixture
def db_path(template_db: Path, tmp_path: Path) -> Path:
    """A freshly seeded SQLite database file for this test alone."""
    path = tmp_path / "db" / "granudb.sqlite"
    path.parent.mkdir()
    shutil.copy(template_db, path)
    return path


@dataclass
class Run:
    exit_code: int
    stdout: str
    stderr: str


@pytest.fixture
def cli() -> Iterator:
    """Run ``granudb`` in-process: ``cli("materials", "list", db=path)``."""
    from granudb.cli.main import app

    runner = CliRunner()

    def run(*args: str, db: Path | str | None = None) -> Run:
        argv = list(args) + (["--db", str(db)] if db is not None else [])
        result = runner.invoke(app, argv, catch_exceptions=False)
        return Run(result.exit_code, result.stdout, result.stderr)

    yield run
