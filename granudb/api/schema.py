"""The database's schema and the shipped seed data: ``granudb db upgrade|downgrade|current|
history|seed`` are ``db_upgrade``, ``db_downgrade``, ``db_current``, ``db_history`` and
``db_seed``.

Opening a database (``connect``) already creates, migrates and seeds it on first use;
these functions manage the schema explicitly. A downgrade that would drop stored values,
and a reseed that would revert the user's edits, say what they lose and ask
``confirm(action, losses)`` first (``granudb.api.consent``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from granudb.api.consent import Confirm, agreed
from granudb.api.database import connect, opened
from granudb.db import migration
from granudb.db.engine import Database, open_database
from granudb.db.seed_store import apply_seed
from granudb.errors import ConfirmationNeeded
from granudb.io.seed import read_seed


def load_seed(session: Any, folder: Path | None = None) -> list[str]:
    """Load the seed files of ``folder`` (default: the shipped ``seed_data``) into the
    session's transaction; one line per change plus a summary (``connect`` calls it for
    a new database)."""
    return apply_seed(session, read_seed(folder))


def _schema(db: Any) -> Database:
    """The database at ``db`` opened without touching its schema."""
    if isinstance(db, Database):
        return db
    return open_database(None if db is None else str(db), migrate=False)


def db_upgrade(revision: str = "head", *, db: Any = None) -> tuple[str | None, str]:
    """Migrate the database forward to ``revision`` (default the newest; a new database
    is created and seeded); returns (revision before, revision after).

    Examples
    --------
    >>> import granudb
    >>> granudb.db_upgrade(db=tmp / "new.sqlite")[0] is None
    True
    """
    database = _schema(db)
    try:
        if revision == "head":
            with database.engine.connect() as connection:
                before = migration.current_revision(connection)
            connect(database.url).dispose()
            return before, migration.head_revision()
        before, after = migration.upgrade(database, revision)
        return before, after or ""
    finally:
        if database is not db:
            database.dispose()


def db_downgrade(
    revision: str,
    *,
    confirm: Confirm | None = None,
    drop_released_values: bool = False,
    db: Any = None,
) -> tuple[str | None, str | None, list[str]]:
    """Migrate the database back to ``revision`` ("base" drops every granudb table);
    returns (before, after, what was lost). What would lose stored values is asked first
    (``confirm``); a downgrade that loses nothing runs at once. One that would change a
    released version (drop values it holds, so its export no longer matches its content
    hash) is refused unless ``drop_released_values`` names that consequence: consent to
    the losses (``--yes``) is not enough.

    Examples
    --------
    >>> import granudb
    >>> _ = granudb.connect(tmp / "old.sqlite").dispose()
    >>> granudb.db_downgrade("0003", db=tmp / "old.sqlite")[1]
    '0003'
    """
    database = _schema(db)
    try:
        losses, releases = migration.preview_downgrade(database, revision)
        if releases and not drop_released_values:
            raise migration.released_refusal(revision, releases, "--drop-released-values")
        agreed(confirm, f"db downgrade {revision}", losses)
        before, after = migration.downgrade(database, revision, accepted=losses, releases=releases)
        return before, after, losses
    finally:
        if database is not db:
            database.dispose()


def db_current(*, db: Any = None) -> dict[str, Any]:
    """The database's schema revision, the newest this granudb knows, and whether they
    agree.

    Examples
    --------
    >>> import granudb
    >>> granudb.db_current(db=db)["up_to_date"]
    True
    """
    database = _schema(db)
    try:
        with database.engine.connect() as connection:
            revision = migration.current_revision(connection)
        head = migration.head_revision()
        return {
            "database": database.display_url,
            "revision": revision,
            "head": head,
            "up_to_date": revision == head,
        }
    finally:
        if database is not db:
            database.dispose()


def db_history() -> list[dict[str, str | None]]:
    """Every schema revision granudb ships, newest first (revision, down_revision,
    message).

    Examples
    --------
    >>> import granudb
    >>> granudb.db_history()[-1]["down_revision"] is None
    True
    """
    return migration.history()


class _DryRun(Exception):
    """Raised inside the transaction to roll a trial load back."""


def db_seed(
    *,
    overwrite_edits: bool = False,
    folder: str | Path | None = None,
    confirm: Confirm | None = None,
    db: Any = None,
) -> list[str]:
    """Reload the seed data (default: the shipped ``seed_data``) in one transaction: adds
    what is missing, updates what the seed changed, and keeps (and reports) every value
    the user changed — unless ``overwrite_edits``, which reverts them after asking
    ``confirm``. Returns one line per change plus a summary.

    Examples
    --------
    >>> import granudb
    >>> granudb.db_seed(db=db)[-1].startswith("seed:")
    True
    """
    data = read_seed(None if folder is None else Path(folder))
    with opened(db) as database:
        if database.created:
            return database.seed_report
        reverts = None
        if overwrite_edits:
            reverts = _reverts(database, data)
            agreed(confirm, "db seed --overwrite-edits", reverts)
        with database.session(write=True) as session:
            lines = apply_seed(session, data, overwrite_edits=overwrite_edits)
            if reverts is not None and _reverted(lines) != reverts:
                raise ConfirmationNeeded(
                    "db seed --overwrite-edits: the edits to revert changed since you "
                    "confirmed; nothing was changed"
                )
        return lines


def _reverts(database: Database, data: Any) -> list[str]:
    """The user's edits an overwrite would revert (a trial load, rolled back)."""
    lines: list[str] = []
    try:
        with database.session(write=True) as session:
            lines = apply_seed(session, data, overwrite_edits=True)
            raise _DryRun
    except _DryRun:
        pass
    return _reverted(lines)


def _reverted(lines: list[str]) -> list[str]:
    prefix = "reverted "
    return [line.removeprefix(prefix) for line in lines if line.startswith(prefix)]
