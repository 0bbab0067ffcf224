"""Alembic, driven from granudb: the schema is always at the revision the code expects.

``granudb db upgrade|downgrade|current|history`` call these functions; ``open_database``
calls ``ensure_current`` so a first use creates the schema and a newer granudb migrates an
older file forward, while a file from a *newer* granudb is refused rather than damaged.
"""

from __future__ import annotations

import io
import re
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING

from sqlalchemy import inspect, text
from sqlalchemy.engine import Connection
from sqlalchemy.exc import DBAPIError

from granudb.errors import ConfirmationNeeded, SchemaError
from granudb.lazy import (
    alembic_command,
    alembic_config,
    alembic_errors,
    alembic_migration,
    alembic_script,
)
from granudb.resources import shipped_dir

if TYPE_CHECKING:
    from alembic.config import Config
    from alembic.script import ScriptDirectory

    from granudb.db.engine import Database


def configuration(
    connection: Connection | None = None, *, output: io.StringIO | None = None
) -> Config:
    """Alembic's configuration for granudb's shipped migrations (on ``connection``)."""
    Config = alembic_config.Config
    cfg = Config(output_buffer=output) if output is not None else Config()
    cfg.set_main_option("script_location", str(shipped_dir("migrations")))
    if connection is not None:
        cfg.attributes["connection"] = connection
    return cfg


def script_directory() -> ScriptDirectory:
    return alembic_script.ScriptDirectory.from_config(configuration())


def head_revision() -> str:
    head = script_directory().get_current_head()
    assert head is not None, "granudb ships at least one migration"
    return head


def current_revision(connection: Connection) -> str | None:
    return alembic_migration.MigrationContext.configure(connection).get_current_revision()


def _lock_for_schema_change(connection: Connection) -> None:
    """Serialise schema changes between processes (SQLite: BEGIN IMMEDIATE already did)."""
    if connection.dialect.name == "postgresql":
        connection.execute(text("SELECT pg_advisory_xact_lock(7418327)"))


@contextmanager
def schema_transaction(database: Database) -> Iterator[Connection]:
    """One write transaction for a schema change, with SQLite's foreign keys off.

    SQLite changes a column by rebuilding its table (Alembic's batch mode): the old table
    is dropped, and with foreign keys on, dropping ``datasets`` would delete every
    collision through ``ON DELETE CASCADE``. ``PRAGMA foreign_keys`` cannot change inside
    a transaction, so it is switched off before ``BEGIN`` and back on afterwards, and
    ``PRAGMA foreign_key_check`` must find nothing before the change commits (SQLite's
    documented procedure for schema changes).
    """
    engine = database.engine.execution_options(sqlite_begin="IMMEDIATE")
    with engine.connect() as connection:
        raw = (
            connection.connection.driver_connection if connection.dialect.name == "sqlite" else None
        )
        if raw is not None:
            raw.execute("PRAGMA foreign_keys=OFF")
        try:
            with connection.begin():
                _lock_for_schema_change(connection)
                yield connection
                if raw is not None:
                    broken = connection.exec_driver_sql("PRAGMA foreign_key_check").fetchall()
                    if broken:
                        raise SchemaError(
                            f"database: the schema change would break {len(broken)} "
                            f"references (first in table {broken[0][0]}); nothing was changed"
                        )
        finally:
            if raw is not None:
                raw.execute("PRAGMA foreign_keys=ON")


def check_revision(current: str | None, connection: Connection) -> None:
    """Refuse a database this granudb does not understand."""
    script = script_directory()
    if current is None:
        tables = set(inspect(connection).get_table_names()) - {"alembic_version"}
        if tables:
            raise SchemaError(
                "database: holds tables but no granudb schema revision "
                f"({', '.join(sorted(tables)[:5])}…); it is not a granudb database"
            )
        return
    try:
        script.get_revision(current)
    except Exception:  # noqa: BLE001 - alembic raises several types for unknown ids
        raise SchemaError(
            f"database: schema revision {current} is newer than this granudb knows "
            f"(newest: {script.get_current_head()}); upgrade granudb to use it"
        ) from None


_REVISION_LINE = re.compile(r"^(down_revision|revision)\b[^=]*=\s*(?:\"([^\"]*)\"|None)", re.M)


def shipped_head() -> str | None:
    """The newest shipped revision, read from the migration files without Alembic.

    Importing Alembic costs about as much as the rest of a command's start-up, and almost
    every run only needs to know "is the database at head?". Each migration file states
    ``revision = "…"`` and ``down_revision = "…"``; the head is the one revision nothing
    revises. Returns None if the files do not form one straight line (then the caller asks
    Alembic, which is authoritative; tests/test_startup.py checks both agree).
    """
    revisions: set[str] = set()
    parents: set[str] = set()
    for path in (shipped_dir("migrations") / "versions").glob("*.py"):
        found = dict((m.group(1), m.group(2)) for m in _REVISION_LINE.finditer(path.read_text()))
        if found.get("revision"):
            revisions.add(found["revision"])
            if found.get("down_revision"):
                parents.add(found["down_revision"])
    heads = revisions - parents
    return heads.pop() if len(heads) == 1 else None


def stored_revisions(connection: Connection) -> list[str] | None:
    """The rows of ``alembic_version``, or None when the table is missing or unreadable."""
    try:
        rows = connection.exec_driver_sql("SELECT version_num FROM alembic_version").fetchall()
    except DBAPIError:
        connection.rollback()  # PostgreSQL: the failed statement aborted the transaction
        return None
    return [row[0] for row in rows]


def is_current(database: Database) -> bool:
    """One cheap query: is the database exactly at the shipped head? (No Alembic import.)"""
    head = shipped_head()
    if head is None:
        return False
    with database.engine.connect() as probe:
        stored = stored_revisions(probe)
        probe.rollback()
    return stored == [head]


def ensure_current(
    database: Database, on_create: Callable[[Connection], None] | None = None
) -> bool:
    """Migrate ``database`` to head if needed; return True when it was created just now.

    The common case, a database already at head, is decided by ``is_current`` with one
    query of ``alembic_version`` and without importing Alembic. Anything else (missing
    table, older, newer or unknown revision, tables that are not granudb's) goes through
    Alembic in one write transaction: checking the revision, migrating and ``on_create``
    (seeding) either all happen or none, and concurrent first uses wait for each other.
    """
    if is_current(database):
        return False
    head = head_revision()
    with schema_transaction(database) as connection:
        current = current_revision(connection)
        if current == head:
            return False
        check_revision(current, connection)
        alembic_command.upgrade(configuration(connection), "head")
        if current is None and on_create is not None:
            on_create(connection)
        return current is None


def upgrade(database: Database, revision: str = "head") -> tuple[str | None, str | None]:
    """Migrate forward to ``revision``; returns (before, after)."""
    return _run(database, "upgrade", revision)


def downgrade(
    database: Database,
    revision: str,
    *,
    accepted: list[str] | None = None,
    releases: list[str] | None = None,
) -> tuple[str | None, str | None]:
    """Migrate back to ``revision`` ("base" drops every granudb table).

    A downgrade that would drop or change stored values (``downgrade_losses``) is refused
    unless ``accepted`` is exactly the list of losses the person agreed to, and one that
    would change a released version (``released_affected``) unless ``releases`` is
    exactly the list of those versions: both recomputed inside the schema transaction, so
    rows written after they agreed are never dropped without their consent.
    """
    return _run(database, "downgrade", revision, accepted=accepted or [], releases=releases or [])


#: Where a revision declares its downgrade's losses (``DOWNGRADE_LOSSES`` in its file,
#: next to ``downgrade()``): a list of (table, column, SQL condition on the rows that lose
#: something, what happens to them). Table "*": every table goes.
LOSSES_ATTRIBUTE = "DOWNGRADE_LOSSES"


def declared_losses(step: str) -> list[tuple[str, str, str, str]]:
    """What revision ``step``'s downgrade declares it loses; a revision that declares
    nothing is refused (an undeclared loss would be dropped without consent)."""
    module = script_directory().get_revision(step).module
    declared = getattr(module, LOSSES_ATTRIBUTE, None)
    if not isinstance(declared, list) or not all(
        isinstance(e, tuple) and len(e) == 4 and all(isinstance(x, str) for x in e)
        for e in declared
    ):
        raise SchemaError(
            f"revision {step}: declares no {LOSSES_ATTRIBUTE} (a list of (table, column, "
            "condition, what happens)) beside its downgrade(); it cannot be downgraded "
            "with consent; nothing was changed"
        )
    return declared


#: The dataset versions whose content a loss in each table reaches: SQL selecting
#: dataset ids, given the declared condition on that table's rows.
_REACHES = {
    "collisions": "SELECT dataset_id FROM collisions WHERE ({c})",
    "datasets": "SELECT id FROM datasets WHERE ({c})",
    "materials": (
        "SELECT dataset_id FROM collisions WHERE particle_id IN (SELECT id FROM materials "
        "WHERE ({c})) OR wall_id IN (SELECT id FROM materials WHERE ({c}))"
    ),
    "fluids": "SELECT dataset_id FROM collisions WHERE fluid_id IN "
    "(SELECT id FROM fluids WHERE ({c}))",
    "fluid_points": "SELECT dataset_id FROM collisions WHERE fluid_id IN "
    "(SELECT fluid_id FROM fluid_points WHERE ({c}))",
    # a release cites its sources as they were: without the history, as they are now
    "source_revisions": "SELECT id FROM datasets WHERE EXISTS (SELECT 1 FROM "
    "source_revisions WHERE ({c}))",
    "*": "SELECT id FROM datasets",
}


def _released(connection: Connection, table: str, condition: str) -> list[str]:
    """NAME@VERSION of the released (or superseded) versions whose content the loss of
    ``table``'s rows matching ``condition`` reaches (their export would change)."""
    reach = _REACHES.get(table)
    columns = {c["name"] for c in inspect(connection).get_columns("datasets")}
    if reach is None or "state" not in columns:  # before 0004 nothing was released
        return []
    rows = connection.execute(
        text(
            "SELECT name, version FROM datasets WHERE state <> 'draft' AND id IN "
            f"({reach.format(c=condition)}) ORDER BY name, version"
        )
    ).all()
    return [f"{name}@{version}" for name, version in rows]


def _steps(connection: Connection, current: str | None, target: str) -> list[str] | None:
    """The revisions whose downgrades run, newest first; None for "all of them" (base)."""
    order = [str(r["revision"]) for r in reversed(history())]  # a revision always has one
    if current is None:
        return []
    if target == "base":
        return None
    at = order.index(current)
    if target.startswith("-") and target[1:].isdigit():
        below = at - int(target[1:])
        if below < 0:
            return None
        target = order[below]
    if target not in order:
        raise SchemaError(
            f"revision: {target!r} is not a revision to go back to (use base, -N or one "
            f"of {', '.join(order)})"
        )
    return list(reversed(order[order.index(target) + 1 : at + 1]))


def downgrade_plan(connection: Connection, revision: str) -> tuple[list[str], list[str]]:
    """(what going back to ``revision`` would drop or alter, one phrase per table or column
    with its row count and the released versions it reaches; the released versions it
    would change). Read only from each revision's ``DOWNGRADE_LOSSES``. Bookkeeping that
    granudb can do without (``seed_records``, ``alembic_version``) is not counted."""
    current = current_revision(connection)
    steps = _steps(connection, current, revision)
    declared = (
        [("*", "*", "1 = 1", "")]
        if steps is None
        else [entry for step in steps for entry in declared_losses(step)]
    )
    losses: list[str] = []
    releases: list[str] = []
    for table, column, condition, what in declared:
        if table == "*":
            tables = sorted(set(inspect(connection).get_table_names()) - {"alembic_version"})
            counts = {
                t: connection.execute(text(f'SELECT count(*) FROM "{t}"')).scalar() for t in tables
            }
            reached = _released(connection, "*", condition) if "datasets" in tables else []
            losses += [
                f"table {t}: all {n} rows" + _in_releases(reached if t == "datasets" else [])
                for t, n in counts.items()
                if n and t != "seed_records"
            ]
        else:
            count = connection.execute(
                text(f'SELECT count(*) FROM "{table}" WHERE {condition}')
            ).scalar()
            if not count:
                continue
            reached = _released(connection, table, condition)
            losses.append(f"{table}.{column}: {count} values {what}" + _in_releases(reached))
        releases += [r for r in reached if r not in releases]
    return losses, sorted(releases)


def _in_releases(reached: list[str]) -> str:
    if not reached:
        return ""
    return f" — changes released versions {', '.join(reached)}"


def downgrade_losses(connection: Connection, revision: str) -> list[str]:
    """The losses of ``downgrade_plan``."""
    return downgrade_plan(connection, revision)[0]


def preview_downgrade(database: Database, revision: str) -> tuple[list[str], list[str]]:
    """``downgrade_plan`` for the database as it is now (read only)."""
    with database.engine.connect() as connection:
        check_revision(current_revision(connection), connection)
        plan = downgrade_plan(connection, revision)
        connection.rollback()
    return plan


def plan_downgrade(database: Database, revision: str) -> list[str]:
    """The losses of ``preview_downgrade``."""
    return preview_downgrade(database, revision)[0]


def released_refusal(revision: str, releases: list[str], option: str) -> ConfirmationNeeded:
    """The refusal of a downgrade that would change released versions without their
    being named: consent to losing values is not consent to changing a release."""
    return ConfirmationNeeded(
        f"db downgrade {revision}: would change released versions {', '.join(releases)} "
        "(values they hold are dropped, so their exports no longer match their content "
        f"hashes); --yes is not enough: add {option} to accept that; nothing was changed"
    )


def _run(
    database: Database,
    action: str,
    revision: str,
    *,
    accepted: list[str] | None = None,
    releases: list[str] | None = None,
) -> tuple[str | None, str | None]:
    with schema_transaction(database) as connection:
        before = current_revision(connection)
        check_revision(before, connection)
        if action == "downgrade":
            losses, reached = downgrade_plan(connection, revision)
            if reached and reached != (releases or []):
                raise released_refusal(revision, reached, "--drop-released-values")
            if losses != (accepted or []):
                raise ConfirmationNeeded(
                    f"db downgrade {revision}: loses {'; '.join(losses)}; not confirmed, "
                    "nothing was changed"
                    if losses
                    else f"db downgrade {revision}: the data changed since you confirmed; "
                    "nothing was changed"
                )
        try:
            getattr(alembic_command, action)(configuration(connection), revision)
        except alembic_errors.CommandError as exc:
            raise SchemaError(f"revision: {revision!r} {str(exc).splitlines()[0]}") from None
        after = current_revision(connection)
    return before, after


def history() -> list[dict[str, str | None]]:
    """Every shipped revision, newest first."""
    return [
        {
            "revision": rev.revision,
            "down_revision": rev.down_revision if isinstance(rev.down_revision, str) else None,
            "message": rev.doc,
        }
        for rev in script_directory().walk_revisions()
    ]
