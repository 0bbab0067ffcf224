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
from granudb.vocabulary import COLLISION_TARGET, COLLISION_UNCERTAINTIES
from granudb.vocabulary.catalogue import FLUIDS, MATERIALS

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
    database: Database, revision: str, *, accepted: list[str] | None = None
) -> tuple[str | None, str | None]:
    """Migrate back to ``revision`` ("base" drops every granudb table).

    A downgrade that would drop or change stored values (``downgrade_losses``) is refused
    unless ``accepted`` is exactly the list of losses the person agreed to: recomputed
    inside the schema transaction, so rows written after they agreed are never dropped
    without their consent.
    """
    return _run(database, "downgrade", revision, accepted=accepted or [])


#: What each revision's downgrade drops or alters, as (table, column, SQL condition on the
#: rows that lose something, what happens to them). Checked constraints are not data.
_STEP_LOSSES: dict[str, list[tuple[str, str, str, str]]] = {
    "0012": [("reported_runs", "run", "1 = 1", "dropped (the runs as papers report them)")],
    "0011": [
        (table, "conditions", "conditions IS NOT NULL", "dropped (the values' conditions)")
        for table in ("materials", "fluids")
    ],
    "0010": [
        (
            "materials",
            "roughness_rms_m",
            "roughness_rms_m IS NULL",
            "not stated, become 0.0 (the older schema needs a number; an upgrade keeps the 0)",
        )
    ],
    "0009": [
        (
            "source_revisions",
            "citation",
            "1 = 1",
            "dropped (the sources' history; released datasets then read today's sources)",
        ),
    ],  # fmt: skip
    "0008": [
        ("collisions", c, f"{c} IS NOT NULL", "dropped (the stated standard uncertainty)")
        for c in COLLISION_UNCERTAINTIES
    ],
    "0007": [
        *(
            ("materials", c, f"{c} IS NOT NULL", "dropped")
            for c in (
                "dry_restitution",
                "dry_friction",
                "dry_provenance",
                "brittleness",
                "u_dry_restitution",
                "u_dry_friction",
            )
        ),
        ("pair_values", "dry_restitution", "1 = 1", "dropped (the pair values table goes)"),
    ],
    "0006": [
        (table, c, f"{c} IS NOT NULL", "dropped (the standard uncertainty)")
        for table, columns in (
            ("materials", MATERIALS.uncertainties.values()),
            ("fluids", FLUIDS.uncertainties.values()),
            ("fluid_points", ("u_viscosity_pa_s", "u_density_kg_m3")),
        )
        for c in columns
        if c not in ("u_dry_restitution", "u_dry_friction")  # 0007's
    ],
    "0005": [
        (
            "collisions",
            "v_n_in_m_s",
            "wall_v_n_in_m_s IS NOT NULL AND (v_n_in_m_s <= 0 OR v_n_out_m_s < 0)",
            "removed (two-sphere runs the older schema cannot hold)",
        ),
        *(
            (
                table,
                "revision_of",
                "revision_of IS NOT NULL",
                "dropped (released datasets then read today's values)",
            )
            for table in ("materials", "fluids")
        ),
    ],  # fmt: skip
    "0004": [
        ("datasets", "authors", "authors IS NOT NULL", "dropped"),
        ("datasets", "keywords", "keywords IS NOT NULL", "dropped"),
        ("datasets", "state", "state <> 'draft'", "dropped (released versions become drafts)"),
        ("datasets", "released_at", "released_at IS NOT NULL", "dropped"),
    ],
    "0003": [
        ("materials", "yield_stress_pa", "yield_stress_pa IS NOT NULL", "dropped"),
        # 0003 added the free target sphere's velocities: the vocabulary's COLLISION_TARGET
        *(("collisions", c, f"{c} IS NOT NULL", "dropped") for c in COLLISION_TARGET),
        ("collisions", "omega_in_rad_s", "omega_in_rad_s IS NULL", "not measured, become 0.0"),
        ("collisions", "omega_out_rad_s", "omega_out_rad_s IS NULL", "not measured, become 0.0"),
        (
            "collisions",
            "nominal_angle_rad",
            "nominal_angle_rad IS NULL",
            "not recorded, become the centre's path angle",
        ),
    ],
    "0002": [("datasets", "doi", "doi IS NOT NULL", "dropped")],
}


def _steps(connection: Connection, current: str | None, target: str) -> list[str] | None:
    """The revisions whose downgrades run, newest first; None for "all of them" (base)."""
    order = [r["revision"] for r in reversed(history())]
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


def downgrade_losses(connection: Connection, revision: str) -> list[str]:
    """What going back to ``revision`` would drop or alter, one phrase per table or column
    with its row count (nothing listed: nothing is lost). Bookkeeping that granudb can do
    without (``seed_records``, ``alembic_version``) is not counted."""
    current = current_revision(connection)
    steps = _steps(connection, current, revision)
    if steps is None:
        tables = sorted(set(inspect(connection).get_table_names()) - {"alembic_version"})
        counts = {
            t: connection.execute(text(f'SELECT count(*) FROM "{t}"')).scalar() for t in tables
        }
        return [f"table {t}: all {n} rows" for t, n in counts.items() if n and t != "seed_records"]
    losses = []
    for step in steps:
        for table, column, condition, what in _STEP_LOSSES.get(step, []):
            count = connection.execute(
                text(f'SELECT count(*) FROM "{table}" WHERE {condition}')
            ).scalar()
            if count:
                losses.append(f"{table}.{column}: {count} values {what}")
    return losses


def plan_downgrade(database: Database, revision: str) -> list[str]:
    """``downgrade_losses`` for the database as it is now (read only)."""
    with database.engine.connect() as connection:
        check_revision(current_revision(connection), connection)
        losses = downgrade_losses(connection, revision)
        connection.rollback()
    return losses


def _run(
    database: Database, action: str, revision: str, *, accepted: list[str] | None = None
) -> tuple[str | None, str | None]:
    with schema_transaction(database) as connection:
        before = current_revision(connection)
        check_revision(before, connection)
        if action == "downgrade":
            losses = downgrade_losses(connection, revision)
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
