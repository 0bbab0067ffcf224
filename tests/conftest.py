"""Shared fixtures: every test gets its own database and its own data directory.

The suite runs against SQLite by default. With ``GRANUDB_TEST_BACKEND=postgresql`` and
``GRANUDB_TEST_POSTGRES_URL`` (a server URL such as
``postgresql+psycopg://postgres@127.0.0.1:55432/postgres``) every database fixture is a
fresh PostgreSQL database instead; if the server cannot be reached the run fails rather
than skipping. Tests about SQLite itself carry ``@pytest.mark.sqlite_only`` and are
deselected on the PostgreSQL leg.

Nothing here touches the real home directory: ``XDG_DATA_HOME`` and ``HOME`` point into
the test's temporary folder, and ``GRANUDB_DATABASE_URL`` is unset unless a test sets it.
A seeded template database is built once per session and copied for each test.
"""

from __future__ import annotations

import os
import shutil
import sqlite3
import uuid
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

REPO = Path(__file__).resolve().parent.parent
SHARED = REPO.parent / "shared"
BACKEND = os.environ.get("GRANUDB_TEST_BACKEND", "sqlite")
POSTGRES_URL = os.environ.get("GRANUDB_TEST_POSTGRES_URL", "")


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line("markers", "sqlite_only: a test of SQLite behaviour itself")
    if BACKEND not in {"sqlite", "postgresql"}:
        raise pytest.UsageError(f"GRANUDB_TEST_BACKEND={BACKEND!r}: use sqlite or postgresql")
    if BACKEND == "postgresql" and not POSTGRES_URL:
        raise pytest.UsageError("GRANUDB_TEST_BACKEND=postgresql needs GRANUDB_TEST_POSTGRES_URL")


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if BACKEND == "sqlite":
        return
    kept = [i for i in items if i.get_closest_marker("sqlite_only") is None]
    deselected = [i for i in items if i.get_closest_marker("sqlite_only") is not None]
    if deselected:
        config.hook.pytest_deselected(items=deselected)
        items[:] = kept


@pytest.fixture(autouse=True)
def isolated_environment(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    home = tmp_path / "home"
    home.mkdir()
    monkeypatch.setenv("HOME", str(home))
    monkeypatch.setenv("XDG_DATA_HOME", str(home / ".local" / "share"))
    monkeypatch.delenv("GRANUDB_DATABASE_URL", raising=False)
    monkeypatch.setenv("COLUMNS", "200")  # wide Rich tables: one row per line in tests


def _postgres_admin():
    from sqlalchemy import create_engine

    return create_engine(POSTGRES_URL, isolation_level="AUTOCOMMIT")


def _postgres_url(database: str) -> str:
    from sqlalchemy.engine import make_url

    return make_url(POSTGRES_URL).set(database=database).render_as_string(hide_password=False)


@pytest.fixture(scope="session")
def template_db(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """A migrated, seeded database to copy: a file path (SQLite) or a database name."""
    from granudb.api.database import connect as open_database

    if BACKEND == "sqlite":
        path = tmp_path_factory.mktemp("template") / "granudb.sqlite"
        open_database(str(path)).dispose()
        with sqlite3.connect(path) as connection:  # fold the WAL into the one file
            connection.execute("PRAGMA wal_checkpoint(TRUNCATE)")
            connection.execute("PRAGMA journal_mode=DELETE")
        yield str(path)
        return
    from sqlalchemy import text

    name = f"granudb_template_{uuid.uuid4().hex[:12]}"
    admin = _postgres_admin()
    with admin.connect() as connection:
        connection.execute(text(f'CREATE DATABASE "{name}"'))
    open_database(_postgres_url(name)).dispose()
    yield name
    with admin.connect() as connection:
        connection.execute(text(f'DROP DATABASE IF EXISTS "{name}" WITH (FORCE)'))
    admin.dispose()


@pytest.fixture
def new_db(tmp_path: Path) -> Iterator[str]:
    """An empty database location (nothing created yet): a SQLite path or a PostgreSQL URL
    of an empty database."""
    if BACKEND == "sqlite":
        yield str(tmp_path / "new.sqlite")
        return
    yield from _postgres_database(None)


def _postgres_database(template: str | None) -> Iterator[str]:
    from sqlalchemy import text

    name = f"granudb_test_{uuid.uuid4().hex[:12]}"
    admin = _postgres_admin()
    clause = f' TEMPLATE "{template}"' if template else ""
    with admin.connect() as connection:
        connection.execute(text(f'CREATE DATABASE "{name}"{clause}'))
    try:
        yield _postgres_url(name)
    finally:
        with admin.connect() as connection:
            connection.execute(text(f'DROP DATABASE IF EXISTS "{name}" WITH (FORCE)'))
        admin.dispose()


@pytest.fixture
def db(template_db: str, tmp_path: Path) -> Iterator[str]:
    """A freshly seeded database for this test alone: a SQLite path or a PostgreSQL URL."""
    if BACKEND == "sqlite":
        path = tmp_path / "db" / "granudb.sqlite"
        path.parent.mkdir()
        shutil.copy(template_db, path)
        yield str(path)
        return
    yield from _postgres_database(template_db)


@pytest.fixture
def opened(db: str) -> Iterator[Any]:
    """``db`` opened with ``granudb.connect`` (for the Python API's ``db=``), disposed after."""
    import granudb

    database = granudb.connect(db)
    yield database
    database.dispose()


@dataclass
class Run:
    exit_code: int
    stdout: str
    stderr: str


@pytest.fixture
def cli() -> Iterator:
    """Run ``granudb`` in-process: ``cli("materials", "list", db=url)``."""
    from granudb.cli.main import app

    runner = CliRunner()

    def run(*args: str, db: Path | str | None = None) -> Run:
        argv = list(args) + (["--db", str(db)] if db is not None else [])
        result = runner.invoke(app, argv, catch_exceptions=False)
        return Run(result.exit_code, result.stdout, result.stderr)

    yield run
