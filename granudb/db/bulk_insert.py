"""Checked collision rows as columns, and the fastest bulk insert each backend offers.

A ``CollisionChunk`` is what a reader (``granudb.io.collision_chunks``, or a DataFrame via
``block_from_frame``) hands to ``granudb.db.collision_store``: run labels, names as the
file writes them (dictionary-encoded: a million rows name a handful of materials), and the
SI columns as float64 arrays (NaN = no value).

``insert_rows`` writes resolved rows inside the caller's transaction. SQLite: one prepared
``executemany`` per slice of only the columns that carry values (a column empty in the
whole block is left to its NULL default, an id the same in every row is written into the
statement as an integer), each statement inserting ``ROWS_PER_STATEMENT`` rows (a
multi-row ``VALUES``). pysqlite releases the GIL around every ``sqlite3_step`` and must
take it back after; while the reader and the hash worker run on the other core it often
waits for it, so one row a step spent half the insert waiting (measured: 300,000 rows
0.8 s alone, 1.7-2.2 s beside a thread formatting floats with Arrow, 9-14 s beside a
thread running Python). Fifty rows a step make the hand-offs fifty times rarer and save
per-statement work as well (0.4-0.55 s alone, 1.0-1.7 s beside either).

PostgreSQL: ``COPY … FROM STDIN (FORMAT csv)`` of the block written by Arrow, whose
float text is the shortest that reads back as the same double.

``PlainIndexes``: on SQLite a large load into a small table drops the collisions table's
non-unique indexes and creates them again after the last row, inside the same
transaction (SQLite's DDL is transactional: a failed or killed import leaves them as they
were). Creating both from sorted keys took 1.0-1.1 s for a million rows where updating them
row by row took 1.7-2.3 s (benchmarks/import_speed.py's rows); but creating them reads
every row already in the table too, so it is done only when ``rebuild_pays``. The unique
(dataset, run) index is never dropped: it is a constraint.
"""

from __future__ import annotations

import io
import sqlite3
from dataclasses import dataclass
from typing import Any

import numpy as np
from sqlalchemy.exc import DBAPIError

from granudb.db.engine import BULK_CACHE_KEY
from granudb.lazy import pyarrow as pa
from granudb.lazy import pyarrow_csv as pacsv
from granudb.vocabulary import COLLISION_MEASURED
from granudb.vocabulary.text import in_nfc

# Page cache for the length of a bulk load (KiB, negative = size rather than pages), so
# the unique (dataset, run) index is not re-read from the WAL page by page. 16 MB loads a
# million rows as fast as 64 MB did (measured, benchmarks/import_speed.py) for 48 MB less
# memory. The engine restores the connection's own setting when it goes back to the pool
# (granudb.db.engine.BULK_CACHE_KEY).
BULK_CACHE_KIB = 16_384
#: Rows bound per ``executemany`` call: the Python values of a slice (about 300 bytes a
#: row) exist only while it is written, so memory does not grow with the reader's chunks.
INSERT_SLICE_ROWS = 20_000
#: Rows in one SQLite ``INSERT … VALUES (…), (…), …`` (within SQLite's limit on bound
#: parameters, 32,766 by default since 3.32; the statement is cut to fit a lower one).
ROWS_PER_STATEMENT = 50


#: The smallest load for which the plain indexes are rebuilt rather than updated.
REBUILD_MIN_ROWS = 100_000


def rebuild_pays(expected_rows: int, existing_rows: int) -> bool:
    """Whether to rebuild the plain indexes after loading about ``expected_rows`` rows into
    a table holding at most ``existing_rows``: creating them costs about as much per row
    (old and new) as updating them costs per new row, so only a load at least as large as
    the table gains, and never a small one (10 million rows already stored and a
    1,000-row import: updating wins by far)."""
    return expected_rows >= max(REBUILD_MIN_ROWS, existing_rows)


class PlainIndexes:
    """The collisions table's non-unique indexes, dropped for a bulk load and created again
    (their own SQL, as the schema has them) before the transaction commits (SQLite)."""

    def __init__(self, session: Any) -> None:
        self.session = session
        self.statements: list[str] = []

    def existing_rows(self) -> int:
        """At most the rows in the table, without counting them (ids start at 1)."""
        connection = self.session.connection()
        return int(connection.exec_driver_sql("SELECT max(id) FROM collisions").scalar() or 0)

    def drop(self) -> None:
        connection = self.session.connection()
        plain = [
            row[1]
            for row in connection.exec_driver_sql("PRAGMA index_list(collisions)")
            if not row[2] and row[3] == "c"  # not unique, made by CREATE INDEX
        ]
        for name in plain:
            sql = connection.exec_driver_sql(
                "SELECT sql FROM sqlite_master WHERE type = 'index' AND name = ?", (name,)
            ).scalar()
            connection.exec_driver_sql(f'DROP INDEX "{name}"')
            self.statements.append(sql)

    def create(self) -> None:
        connection = self.session.connection()
        for sql in self.statements:
            connection.exec_driver_sql(sql)
        self.statements = []


@dataclass
class NameColumn:
    """Names by row: ``names[codes[i]]``, code -1 = empty (no name)."""

    codes: Any
    names: list[str]


@dataclass
class CollisionChunk:
    """One block of checked rows; ``first_row`` is the spreadsheet row of the first (the
    header is row 1) and ``headers`` the file's header of each column, for messages."""

    first_row: int
    headers: dict[str, str]
    runs: list[str]
    particle: NameColumn
    wall: NameColumn
    fluid: NameColumn
    values: dict[str, Any]
    notes: list[str | None] | None
    #: The file had problems in or before these rows: the block is checked against the
    #: catalogue (so every problem is listed at once) but never written.
    faulty: bool = False

    def __post_init__(self) -> None:
        # run labels and notes in NFC, as every other door stores them (vocabulary.text)
        self.runs = in_nfc(self.runs)
        if self.notes is not None:
            self.notes = in_nfc(self.notes)

    def __len__(self) -> int:
        return len(self.runs)

    def names_by_row(self, column: NameColumn) -> Any:
        """The names as an object array (None where empty), for messages and checks."""
        lookup = np.array([*column.names, None], dtype=object)
        return lookup[np.asarray(column.codes)]


def name_column(values: Any) -> NameColumn:
    """Dictionary-encode a sequence of names (None or NaN = empty)."""
    codes = np.full(len(values), -1, dtype=np.int64)
    index: dict[str, int] = {}
    for position, value in enumerate(values):
        if isinstance(value, str):
            codes[position] = index.setdefault(value, len(index))
    return NameColumn(codes, list(index))


def frame_columns(frame: Any) -> tuple[list[str], dict[str, Any], list[str | None] | None]:
    """(run labels, SI columns as float64, notes or None) of a DataFrame."""
    notes = None
    if "notes" in frame and frame["notes"].notna().any():
        notes = [v if isinstance(v, str) else None for v in frame["notes"].tolist()]
    values = {
        c: frame[c].to_numpy(dtype="float64", na_value=np.nan)
        for c in COLLISION_MEASURED
        if c in frame
    }
    return [str(r) for r in frame["run"].tolist()], values, notes


def block_from_frame(frame: Any) -> CollisionChunk:
    """A ``CollisionChunk`` from a checked SI DataFrame (names as text), as the Data Package
    reader and earlier callers give them."""
    runs, values, notes = frame_columns(frame)
    return CollisionChunk(
        first_row=int(frame.attrs.get("first_row", 2)),
        headers=dict(frame.attrs.get("headers", {})),
        runs=runs,
        particle=name_column(frame["particle"].tolist()),
        wall=name_column(frame["wall"].tolist()),
        fluid=name_column(frame["fluid"].tolist() if "fluid" in frame else [None] * len(frame)),
        values=values,
        notes=notes,
    )


def _bulk_cache(connection: Any, raw: Any) -> None:
    """Enlarge SQLite's page cache for this transaction (restored on check-in)."""
    if BULK_CACHE_KEY not in connection.info:
        connection.info[BULK_CACHE_KEY] = raw.execute("PRAGMA cache_size").fetchone()[0]
        raw.execute(f"PRAGMA cache_size=-{BULK_CACHE_KIB}")


def _python_values(column: Any) -> list[Any]:
    """A bound column as Python values: exact floats, ints, text; None where NaN (floats)
    or -1 (ids)."""
    if isinstance(column, list):
        return column
    if column.dtype.kind == "f":
        missing = np.isnan(column)
        if not missing.any():
            return column.tolist()
    else:
        missing = column < 0
    array = column.astype(object)
    array[missing] = None
    return array.tolist()


def _rows(bound: dict[str, Any], start: int, stop: int) -> Any:
    """Tuples of the bound columns' Python values for rows ``start:stop``."""
    return zip(*(_python_values(c[start:stop]) for c in bound.values()), strict=True)


def _matrix(bound: dict[str, Any], start: int, stop: int) -> Any:
    """The bound columns' Python values for rows ``start:stop`` as an object array, one
    row a row (numpy boxes each float as the exact Python float ``tolist`` gives)."""
    columns = list(bound.values())
    rows = len(columns[0][start:stop])
    matrix = np.empty((rows, len(columns)), dtype=object)
    for j, column in enumerate(columns):
        part = column[start:stop]
        if isinstance(part, list):
            matrix[:, j] = part
            continue
        matrix[:, j] = part
        missing = np.isnan(part) if part.dtype.kind == "f" else part < 0
        if missing.any():
            matrix[missing, j] = None
    return matrix


def _sqlite_insert(raw: Any, head: str, literals: list[str], bound: dict[str, Any], n: int) -> None:
    """``executemany`` of ``ROWS_PER_STATEMENT``-row statements, the rest one row a time,
    ``INSERT_SLICE_ROWS`` rows of Python values at a time.

    A float column holding one value in every row of the block (a diameter, a
    temperature) is bound once per statement as a numbered parameter that every row of
    the statement names, rather than once per row: the same exact double, fewer values
    boxed and bound."""
    shared = [c for c, v in bound.items() if _constant(v)]
    per_row = {c: v for c, v in bound.items() if c not in shared}
    first = {c: bound[c][:1].tolist()[0] for c in shared}
    width = len(per_row)
    limit = raw.getlimit(sqlite3.SQLITE_LIMIT_VARIABLE_NUMBER)
    per = max(1, min(ROWS_PER_STATEMENT, (limit - len(shared)) // max(width, 1)))

    def values(rows: int) -> str:
        """``VALUES`` of ``rows`` rows: the literals, then each bound column's number."""
        out = []
        for row in range(rows):
            own = iter(range(len(shared) + row * width + 1, len(shared) + (row + 1) * width + 1))
            marks = [f"?{shared.index(c) + 1}" if c in shared else f"?{next(own)}" for c in bound]
            out.append(f"({', '.join([*literals, *marks])})")
        return f"{head} VALUES {', '.join(out)}"

    many, single = values(per), values(1)
    cursor = raw.cursor()
    for start in range(0, n, INSERT_SLICE_ROWS):
        matrix = _matrix(per_row, start, min(start + INSERT_SLICE_ROWS, n))
        whole = len(matrix) - len(matrix) % per
        if whole:
            cursor.executemany(many, _with_shared(first, matrix[:whole].reshape(-1, per * width)))
        if whole < len(matrix):
            cursor.executemany(single, _with_shared(first, matrix[whole:]))


def _constant(column: Any) -> bool:
    """A float column with the same value (bit for bit: not NaN, not 0.0 and -0.0) in
    every row."""
    if isinstance(column, list) or column.dtype.kind != "f" or len(column) < 2:
        return False
    bits = column.view(np.int64)
    return bool((bits == bits[0]).all()) and not np.isnan(column[0])


def _with_shared(first: dict[str, Any], rows: Any) -> list[list[Any]]:
    """Each statement's parameters: the shared values, then its rows' own."""
    if not first:
        return rows.tolist()
    out = np.empty((len(rows), len(first) + rows.shape[1]), dtype=object)
    out[:, : len(first)] = list(first.values())
    out[:, len(first) :] = rows
    return out.tolist()


def _columns(
    dataset_id: int, runs: list[str], ids: tuple[Any, Any, Any], values: dict[str, Any], notes: Any
) -> tuple[dict[str, int], dict[str, Any]]:
    """(columns written as integers in the statement, columns bound: float64 arrays with
    NaN, int64 id arrays with -1, or lists of text)."""
    constant: dict[str, int] = {"dataset_id": int(dataset_id)}
    bound: dict[str, Any] = {"run": runs}
    for name, column in zip(("particle_id", "wall_id", "fluid_id"), ids, strict=True):
        column = np.asarray(column, dtype=np.int64)
        if len(column) and (column == column[0]).all():
            if column[0] >= 0:  # an all-dry fluid column stays NULL
                constant[name] = int(column[0])
            continue
        bound[name] = column
    for name in COLLISION_MEASURED:
        column = values.get(name)
        if column is not None:
            column = np.asarray(column, dtype=np.float64)
            if not np.isnan(column).all():
                bound[name] = column
    if notes is not None and any(n is not None for n in notes):
        bound["notes"] = list(notes)
    return constant, bound


def unsigned_zeros(values: dict[str, Any]) -> dict[str, Any]:
    """Each column with -0.0 stored as 0.0. Why: SQLite keeps an integral REAL as an
    integer and gives -0.0 back as 0.0, PostgreSQL keeps the sign; a measured velocity or
    spin of "-0" means the same as 0, so every backend stores 0.0 and a file gets the same
    content hash wherever it is imported. Columns without a zero are not copied."""
    out = {}
    for name, column in values.items():
        column = np.asarray(column, dtype=np.float64)
        out[name] = column + 0.0 if (column == 0).any() else column  # -0.0 + 0.0 is 0.0
    return out


def insert_rows(
    session: Any,
    dataset_id: int,
    runs: list[str],
    ids: tuple[Any, Any, Any],
    values: dict[str, Any],
    notes: list[str | None] | None,
) -> int:
    """Insert resolved rows (ids: particle, wall, fluid with -1 = dry) in the session's
    transaction; returns the count."""
    n = len(runs)
    if n == 0:
        return 0
    constant, bound = _columns(dataset_id, runs, ids, values, notes)
    connection = session.connection()
    raw = connection.connection.driver_connection
    dialect = connection.dialect
    names = ", ".join([*constant, *bound])
    statement = f"INSERT INTO collisions ({names})"
    try:
        if dialect.name == "postgresql" and hasattr(raw, "pgconn"):  # psycopg 3
            statement = f"COPY collisions ({names}) FROM STDIN (FORMAT csv)"
            _copy(raw, statement, n, constant, bound)
            return n
        literals = [str(v) for v in constant.values()]
        if dialect.name == "sqlite":
            _bulk_cache(connection, raw)
            _sqlite_insert(raw, statement, literals, bound, n)
            return n
        mark = "?" if dialect.paramstyle == "qmark" else "%s"
        statement += f" VALUES ({', '.join([*literals, *[mark] * len(bound)])})"
        rows = _rows(bound, 0, n)
    except dialect.loaded_dbapi.Error as exc:
        # The driver's own error, as SQLAlchemy would raise it (the session translates it).
        raise DBAPIError.instance(statement, None, exc, dialect.loaded_dbapi.Error) from None
    connection.exec_driver_sql(statement, list(rows))
    return n


def _copy(
    raw: Any, statement: str, n: int, constant: dict[str, int], bound: dict[str, Any]
) -> None:
    """COPY the rows as CSV written by Arrow (NULL = an unquoted empty field; every value
    quoted, so an empty text could never read as NULL)."""
    arrays = {name: pa.array(np.full(n, value, dtype=np.int64)) for name, value in constant.items()}
    for name, column in bound.items():
        if isinstance(column, list):
            arrays[name] = pa.array(column, type=pa.string())
        elif column.dtype.kind == "f":
            arrays[name] = pa.array(column, from_pandas=True)
        else:
            arrays[name] = pa.array(column, mask=column < 0)
    buffer = io.BytesIO()
    options = pacsv.WriteOptions(include_header=False, quoting_style="all_valid")
    pacsv.write_csv(pa.table(arrays), buffer, write_options=options)
    with raw.cursor() as cursor, cursor.copy(statement) as copy:
        copy.write(buffer.getbuffer())
