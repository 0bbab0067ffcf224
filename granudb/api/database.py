"""Choosing and opening the database, with the seed data loaded on first use.

``connect()`` is what every public function uses when it is given a URL (or nothing): it
opens the database (``granudb.db.engine``), and when the database is brand new it loads
the shipped seed data (``db_seed``'s loader, ``granudb.api.schema.load_seed``) in the
same transaction that creates the schema, and says so on the ``granudb`` logger (the
command line prints it on stderr).
"""

from __future__ import annotations

import logging
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Any

from granudb import api
from granudb.db import roles
from granudb.db.engine import Database, open_database

if TYPE_CHECKING:
    from sqlalchemy.orm import Session

log = logging.getLogger("granudb")


def _seed(session: Session) -> list[str]:
    # Through the API's table: the seed files and the ORM load only when a database is new.
    return api.load_seed(session)


def connect(url: str | Path | None = None) -> Database:
    """Open the granudb database at ``url`` (a SQLAlchemy URL or a SQLite path; default:
    ``GRANUDB_DATABASE_URL``, else ``granudb.sqlite`` in the user data folder), creating,
    migrating and seeding it on first use. Pass the result as ``db=`` to any function.

    Examples
    --------
    >>> import granudb
    >>> db = granudb.connect(tmp / "lab.sqlite")
    >>> db.created
    True
    >>> db.dispose()
    """
    database = open_database(None if url is None else str(url), on_create=_seed)
    if database.created:
        log.info("created %s and loaded the seed data", database.display_url)
    return database


@contextmanager
def opened(db: Database | str | Path | None = None) -> Iterator[Database]:
    """The ``Database`` for ``db`` (an opened one is used as it is; a URL or path is opened
    and closed again afterwards)."""
    if isinstance(db, Database):
        yield db
        return
    database = connect(db)
    try:
        yield database
    finally:
        database.dispose()


def grant_role(account: str, *, role: str, db: Any = None) -> list[str]:
    """Make the PostgreSQL login ``account`` (created if new, without a password) a
    ``role`` of this database: "reader" (reads everything), "contributor" (also imports
    into, edits and removes drafts) or "curator" (also the catalogue, releases and
    removals); run it as an administrator. Returns what was done. SQLite has no accounts
    (the file's permissions decide) and refuses. README "Reliability" states the rules.

    Examples
    --------
    >>> import granudb
    >>> granudb.grant_role("lab reader", role="reader", db=db)
    Traceback (most recent call last):
    ...
    granudb.errors.ValidationError: ROLE: lab reader must be a PostgreSQL role name: ...
    """
    roles.check_account(account)
    roles.check_role(role)
    with opened(db) as database, database.changing() as connection:
        return roles.grant(connection, account, role)
