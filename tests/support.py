"""Helpers tests import (``pythonpath = tests`` in pyproject)."""

from __future__ import annotations

import hashlib
from typing import Any


def engine_for(db: str) -> Any:
    """A plain SQLAlchemy engine on a test database (no granudb settings, no migration)."""
    from sqlalchemy import create_engine

    from granudb.config import resolve_database_url

    return create_engine(resolve_database_url(db))


def dump_hash(db: str) -> str:
    """A hash of the database's logical content: every table, every row.

    Logical, not bytes: a read can checkpoint SQLite's WAL and change the file without
    changing any data, and it is the data that must stay the same. Rows are sorted, so the
    hash does not depend on the order a backend returns them in.
    """
    from sqlalchemy import inspect, text

    engine = engine_for(db)
    digest = hashlib.sha256()
    try:
        with engine.connect() as connection:
            for table in sorted(inspect(connection).get_table_names()):
                rows = connection.execute(text(f'SELECT * FROM "{table}"'))
                digest.update(f"{table}:{list(rows.keys())}".encode())
                for line in sorted(repr(tuple(row)) for row in rows):
                    digest.update(line.encode())
    finally:
        engine.dispose()
    return digest.hexdigest()


def execute(db: str, sql: str, params: dict[str, Any] | None = None) -> None:
    """Run one statement in its own transaction, bypassing granudb (as another tool would)."""
    from sqlalchemy import event, text

    engine = engine_for(db)
    if engine.dialect.name == "sqlite":
        event.listen(engine, "connect", lambda dbapi, _: dbapi.execute("PRAGMA foreign_keys=ON"))
    try:
        with engine.begin() as connection:
            connection.execute(text(sql), params or {})
    finally:
        engine.dispose()
