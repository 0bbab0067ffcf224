"""Choosing and opening the database, with the seed data loaded on first use.

``connect()`` is what every public function uses when it is given a URL (or nothing): it
opens the database (``granudb.db.engine``), and when the database is brand new it loads
the shipped seed data (read by ``granudb.io.seed``, written by ``granudb.db.seed_store``)
in the same transaction that creates the schema.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from sqlalchemy.orm import Session

    from granudb.db.engine import Database


def load_seed(session: Session, folder: Path | None = None) -> list[str]:
    """Load the seed files of ``folder`` (default: the shipped ``seed_data``) into the
    session's transaction; returns one line per change plus a summary."""
    from granudb.db.seed_store import apply_seed
    from granudb.io.seed import read_seed

    return apply_seed(session, read_seed(folder))


def connect(url: str | Path | None = None) -> Database:
    """Open the granudb database at ``url`` (a SQLAlchemy URL or a SQLite path; default:
    ``GRANUDB_DATABASE_URL``, else ``granudb.sqlite`` in the user data folder), creating,
    migrating and seeding it on first use. Pass the result as ``db=`` to any function.

    >>> import granudb
    >>> db = granudb.connect(tmp / "lab.sqlite")
    >>> db.created
    True
    >>> db.dispose()
    """
    from granudb.db.engine import open_database

    return open_database(None if url is None else str(url), on_create=load_seed)


@contextmanager
def opened(db: object = None) -> Iterator[Database]:
    """The ``Database`` for ``db`` (an opened one is used as it is; a URL or path is opened
    and closed again afterwards)."""
    from granudb.db.engine import Database

    if isinstance(db, Database):
        yield db
        return
    database = connect(db)  # type: ignore[arg-type]
    try:
        yield database
    finally:
        database.dispose()
