"""Opening a granudb database: engine, pragmas, transactions, first-use setup.

``open_database()`` is the one entry point. It resolves the URL (``granudb.config``),
creates the embedded SQLite file's folder when it is the default, migrates the schema to
the newest revision, and on a brand-new database loads the seed data, all in one
transaction, so two processes starting at once cannot half-create a database.

SQLite runs in WAL mode with foreign keys on and a busy timeout; write transactions start
with ``BEGIN IMMEDIATE`` so a writer waits for the lock up front instead of failing half-way.
"""

from __future__ import annotations

import os
import re
import sqlite3
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sqlalchemy import Engine, create_engine, event, inspect
from sqlalchemy.engine import Connection, make_url
from sqlalchemy.exc import DBAPIError, IntegrityError, OperationalError

from granudb.config import default_database_path, resolve_database_url
from granudb.db import migration, roles
from granudb.errors import DatabaseAccessError, GranudbError, SchemaError
from granudb.lazy import sqlalchemy_orm

if TYPE_CHECKING:  # the ORM is loaded by the commands that use it (see ``reading``)
    from sqlalchemy.orm import Session

BUSY_TIMEOUT_S = 30.0
#: PostgreSQL's SQLSTATE for "permission denied" (an account without the role's right).
INSUFFICIENT_PRIVILEGE = "42501"
# Set in a connection's info by a bulk load that enlarged SQLite's page cache
# (granudb.db.collision_store.insert_collisions): the setting to restore on check-in.
BULK_CACHE_KEY = "granudb_bulk_cache_size"


def _sqlite_file(url: str) -> Path | None:
    parsed = make_url(url)
    if parsed.get_backend_name() != "sqlite" or not parsed.database:
        return None
    if parsed.database == ":memory:" or parsed.database.startswith("file:"):
        return None
    return Path(parsed.database)


def make_engine(url: str) -> Engine:
    """A SQLAlchemy engine for ``url`` with granudb's connection settings."""
    parsed = make_url(url)
    if parsed.get_backend_name() != "sqlite":
        try:
            return create_engine(url, pool_pre_ping=True)
        except (ImportError, ModuleNotFoundError) as exc:
            raise DatabaseAccessError(
                f"database: {parsed.render_as_string(hide_password=True)} needs a driver that "
                f"is not installed ({exc.name}); for PostgreSQL: pip install 'granudb[postgres]'"
            ) from None
        except Exception as exc:  # noqa: BLE001 - any URL parse problem is the user's to fix
            raise DatabaseAccessError(f"database: {url!r} is not a usable URL ({exc})") from None

    engine = create_engine(url, connect_args={"timeout": BUSY_TIMEOUT_S})
    in_memory = _sqlite_file(url) is None

    @event.listens_for(engine, "connect")
    def _on_connect(dbapi_connection: Any, _record: Any) -> None:
        # Let SQLAlchemy, not pysqlite, decide when transactions begin (see _on_begin).
        dbapi_connection.isolation_level = None
        cursor = dbapi_connection.cursor()
        cursor.execute("PRAGMA foreign_keys=ON")
        cursor.execute(f"PRAGMA busy_timeout={int(BUSY_TIMEOUT_S * 1000)}")
        if not in_memory:
            cursor.execute("PRAGMA journal_mode=WAL")
            cursor.execute("PRAGMA synchronous=NORMAL")
        cursor.close()

    @event.listens_for(engine, "checkin")
    def _on_checkin(dbapi_connection: Any, record: Any) -> None:
        # A bulk load's page cache lasts only for its transaction, not the pooled connection.
        cache_size = record.info.pop(BULK_CACHE_KEY, None) if record is not None else None
        if cache_size is not None and dbapi_connection is not None:
            dbapi_connection.execute(f"PRAGMA cache_size={int(cache_size)}")

    @event.listens_for(engine, "begin")
    def _on_begin(connection: Connection) -> None:
        mode = connection.get_execution_options().get("sqlite_begin", "DEFERRED")
        connection.exec_driver_sql(f"BEGIN {mode}")

    return engine


def _check_sqlite_location(path: Path) -> None:
    """Refuse a folder or a missing folder named by the user; create the default's folder.

    The default path (platformdirs) is only worked out when the folder is missing, so a
    command given ``--db`` never imports platformdirs."""
    folder = path.parent
    if path.is_dir():
        raise DatabaseAccessError(f"database: {path} is a folder, not a database file")
    if folder.exists() and not folder.is_dir():
        raise DatabaseAccessError(f"database: {folder} is not a folder (choose another --db)")
    if not folder.exists():
        if path == default_database_path():
            folder.mkdir(parents=True, exist_ok=True)
        else:
            raise DatabaseAccessError(
                f"database: folder {folder} does not exist (create it, or choose another --db)"
            )


def recognise_sqlite(path: Path) -> None:
    """Refuse an existing SQLite file that is not granudb's before anything writes to it.

    Read through a read-only connection (``mode=ro``): the file's header (WAL mode) and
    contents are untouched whatever it is. An empty or absent file is a new database.
    When the probe fails, the cause is diagnosed (``sqlite_failure``): a good file on a
    read-only or full disk is never called "not a SQLite database".
    """
    if not path.is_file() or path.stat().st_size == 0:
        return
    try:
        probe = sqlite3.connect(f"{path.resolve().as_uri()}?mode=ro", uri=True)
        try:
            tables = {row[0] for row in probe.execute("SELECT name FROM sqlite_master")}
        finally:
            probe.close()
    except sqlite3.DatabaseError as exc:
        raise sqlite_failure(path, str(exc), waited_s=PROBE_TIMEOUT_S) from None
    tables = {t for t in tables if not t.startswith("sqlite_")}
    if tables and "alembic_version" not in tables:
        raise SchemaError(
            "database: holds tables but no granudb schema revision "
            f"({', '.join(sorted(tables)[:5])}…); it is not a granudb database; nothing "
            "was changed"
        )


#: How long the read-only probe of ``recognise_sqlite`` waits for a lock (sqlite3's default).
PROBE_TIMEOUT_S = 5.0
#: Free space below which a failing write or open is put down to a full disk (SQLite needs
#: room for its -wal and -shm files and a page or two more).
FULL_DISK_BYTES = 1 << 20


def _statvfs(path: Path) -> os.statvfs_result | None:
    for place in (path, path.parent):
        try:
            return os.statvfs(place)
        except OSError:
            continue
    return None


def sqlite_failure(path: Path, text: str, *, waited_s: float = BUSY_TIMEOUT_S) -> GranudbError:
    """The cause of SQLite's error ``text`` on the file ``path``, as one line.

    SQLite's own words name the symptom ("unable to open database file", "disk I/O
    error"); the cause is read from the file system: the file's words first where they are
    exact (not a database, locked), then a read-only mount, a full disk, missing
    permission, a read-only database. Each cause has its own message and what to do, and
    every one says nothing was changed (the file is only read to diagnose).
    """
    lowered = text.lower()
    folder = path.parent
    if "not a database" in lowered or "malformed" in lowered:
        return DatabaseAccessError(
            f"database: {path} is not a SQLite database ({text}); nothing was changed"
        )
    if "locked" in lowered or "busy" in lowered:
        return DatabaseAccessError(
            f"database: {path} is locked by another program (waited {waited_s:.0f} s: "
            f"{text}); close the other program or try again; nothing was changed"
        )
    stat = _statvfs(path)
    if stat is not None and stat.f_flag & os.ST_RDONLY:
        return DatabaseAccessError(
            f"database: {path} is on a read-only file system (SQLite must write its -wal "
            f"and -shm files beside it: {text}); remount it read-write or copy the file to "
            "a writable folder; nothing was changed"
        )
    free = stat.f_bavail * stat.f_frsize if stat is not None else None
    if free is not None and free < FULL_DISK_BYTES:
        return DatabaseAccessError(
            f"database: the disk holding {folder} is full ({free} bytes free: {text}); "
            "free some space and try again; nothing was changed"
        )
    denied = [
        str(p)
        for p, mode in ((path, os.R_OK | os.W_OK), (folder, os.W_OK | os.X_OK))
        if p.exists() and not os.access(p, mode)
    ]
    if denied:
        return DatabaseAccessError(
            f"database: permission denied on {' and '.join(denied)} (SQLite must read and "
            f"write the file and create its -wal and -shm files in the folder: {text}); "
            "ask for write access or copy the file; nothing was changed"
        )
    if "readonly" in lowered or "read-only" in lowered or "read only" in lowered:
        return DatabaseAccessError(f"database: is read-only ({text}); nothing was changed")
    if "full" in lowered or "disk" in lowered:
        return DatabaseAccessError(f"database: disk full or failing ({text}); nothing was changed")
    return DatabaseAccessError(f"database: cannot open {path} ({text}); nothing was changed")


#: SQLite's words for trouble with the file rather than with a statement.
_FILE_TROUBLE = re.compile(
    r"unable to open|disk|full|read-?only|locked|busy|not a database|"
    r"malformed|permission|i/o"
)


def translate_db_error(exc: DBAPIError, path: Path | None = None) -> GranudbError:
    """A database driver error as one line a person can act on (``path``: the SQLite file,
    whose file system is asked for the cause of an I/O, lock or permission error)."""
    text = str(exc.orig) if exc.orig is not None else str(exc)
    text = text.splitlines()[0]
    lowered = text.lower()
    if getattr(exc.orig, "sqlstate", None) == INSUFFICIENT_PRIVILEGE:
        return roles.refusal(text)
    if path is not None and isinstance(exc, OperationalError) and _FILE_TROUBLE.search(lowered):
        return sqlite_failure(path, text)
    if isinstance(exc, IntegrityError):
        if "check constraint" in lowered:
            return GranudbError(f"database refused a value: {text}")
        return GranudbError(f"database refused the change: {text}")
    if "readonly" in lowered or "read-only" in lowered or "read only" in lowered:
        return DatabaseAccessError(f"database: is read-only ({text}); nothing was changed")
    if "disk" in lowered and ("full" in lowered or "i/o" in lowered):
        return DatabaseAccessError(f"database: disk full or failing ({text}); nothing was changed")
    if "unable to open" in lowered:
        return DatabaseAccessError(f"database: cannot open the file ({text})")
    if "locked" in lowered:
        return DatabaseAccessError(
            f"database: still locked by another writer after "
            f"{BUSY_TIMEOUT_S:.0f} s ({text}); try again"
        )
    if "not a database" in lowered:
        return DatabaseAccessError(f"database: the file is not a SQLite database ({text})")
    if isinstance(exc, OperationalError):
        return DatabaseAccessError(f"database: {text}")
    return GranudbError(f"database error: {text}")


@dataclass
class Database:
    """An opened granudb database: its URL, engine, and how to get a session."""

    url: str
    engine: Engine
    created: bool = False
    seed_report: list[str] = field(default_factory=list)

    @property
    def sqlite_path(self) -> Path | None:
        """The SQLite file (None for PostgreSQL or an in-memory database)."""
        return _sqlite_file(self.url)

    @property
    def dialect(self) -> str:
        return self.engine.dialect.name

    @property
    def display_url(self) -> str:
        return make_url(self.url).render_as_string(hide_password=True)

    def _read_bind(self) -> Engine:
        if self.dialect == "postgresql":
            # One snapshot for every statement of a read (a report runs many): PostgreSQL's
            # default READ COMMITTED would let an import that commits mid-way show half.
            # (SQLite's deferred transaction already reads one snapshot in WAL mode.)
            return self.engine.execution_options(isolation_level="REPEATABLE READ")
        return self.engine

    @contextmanager
    def reading(self) -> Iterator[Connection]:
        """A Core connection in one read transaction (one snapshot), without the ORM.

        For commands that only read the catalogue (``granudb.db.catalog_rows``): building
        the ORM's mapped classes costs more than their query (issue 17).
        """
        try:
            with self._read_bind().connect() as connection, connection.begin():
                yield connection
        except DBAPIError as exc:
            raise translate_db_error(exc, self.sqlite_path) from None

    @contextmanager
    def changing(self) -> Iterator[Connection]:
        """A Core connection in one write transaction (committed on success, rolled back
        on any error; a driver error becomes one line)."""
        try:
            bind = self.engine.execution_options(sqlite_begin="IMMEDIATE")
            with bind.connect() as connection, connection.begin():
                yield connection
        except DBAPIError as exc:
            raise translate_db_error(exc, self.sqlite_path) from None

    @contextmanager
    def session(self, *, write: bool = False) -> Iterator[Session]:
        """A session in one transaction: committed on success, rolled back on any error.

        ``write=True`` takes SQLite's write lock at the start (``BEGIN IMMEDIATE``), so a
        write either waits for another writer and then runs whole, or does not start.
        """
        bind: Engine
        if write:
            bind = self.engine.execution_options(sqlite_begin="IMMEDIATE")
        else:
            bind = self._read_bind()
        session = sqlalchemy_orm.Session(bind=bind, expire_on_commit=False)
        try:
            with _undone_on_error(session.rollback, self.sqlite_path):
                yield session
                session.commit()
        finally:
            session.close()

    def dispose(self) -> None:
        self.engine.dispose()


def open_database(
    url: str | None = None,
    *,
    on_create: Callable[[Session], list[str]] | None = None,
    migrate: bool = True,
) -> Database:
    """Open (and on first use create and migrate) the database at ``url``.

    ``on_create`` fills a brand-new database (the seed data, loaded by the layer above:
    ``granudb.api.connect``) in the same transaction that creates the schema, and returns
    lines to report. ``migrate=False`` opens without touching the schema (used by
    ``granudb db`` commands, which manage it explicitly); an existing database at an older
    revision is otherwise migrated forward, and one at an unknown (newer) revision is
    refused.
    """
    resolved = resolve_database_url(url)
    path = _sqlite_file(resolved)
    if path is not None:
        _check_sqlite_location(path)
        recognise_sqlite(path)
    engine = make_engine(resolved)
    database = Database(resolved, engine)
    if not migrate:
        return database

    def _fill(connection: Connection) -> None:
        assert on_create is not None
        with sqlalchemy_orm.Session(bind=connection) as session:
            database.seed_report = on_create(session)
            session.flush()

    with _undone_on_error(engine.dispose, path):
        database.created = migration.ensure_current(database, _fill if on_create else None)
    return database


@contextmanager
def _undone_on_error(undo: Callable[[], object], path: Path | None = None) -> Iterator[None]:
    """Run ``undo`` when the block fails, then raise: a database error as granudb's one-line
    error (``translate_db_error``), anything else (an interrupt too) as it is."""
    try:
        yield
    except DBAPIError as exc:
        undo()
        raise translate_db_error(exc, path) from None
    except BaseException:
        undo()
        raise


def table_names(database: Database) -> list[str]:
    return inspect(database.engine).get_table_names()
