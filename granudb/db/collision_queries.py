"""Reading stored collisions as plain columns (not ORM objects), chunk by chunk.

One select gives each run with the ids of its dataset, particle, wall and fluid; names
and properties are looked up per id. Rows come in chunks from the driver's cursor, so a
million runs read in bounded memory: 100,000 rows load in a fraction of a second.
"""

from __future__ import annotations

import itertools
import operator
from collections.abc import Collection, Iterator, Mapping, Sequence
from typing import Any

from sqlalchemy import func, or_, select
from sqlalchemy.engine import Connection

from granudb.db import catalog_rows, lookup_rows
from granudb.db.catalog_rows import MATERIALS, lightweight_table
from granudb.db.lookup_rows import DATASETS
from granudb.lazy import numpy as np
from granudb.lazy import pandas as pd
from granudb.vocabulary import COLLISION_MEASURED, MATERIAL_PROPERTIES
from granudb.vocabulary.listings import STORED_FILTERS

#: Rows read and derived at a time: bounds the memory of a read of a million runs (the
#: driver's row tuples of one chunk, about 40 MB), while a chunk stays large enough that
#: numpy, not Python, does the work.
CHUNK_ROWS = 50_000
_IDS = ["dataset_id", "particle_id", "wall_id", "fluid_id"]
_NUMBERS = [*_IDS, *COLLISION_MEASURED]
_TEXT = ["run", "notes"]
#: Core clauses (no ORM: a read needs no mapped classes; see ``lookup_rows``). A reader
#: is a Core connection (``Database.reading()``) or a session, whose connection is used.
COLLISIONS = lightweight_table("collisions", ["id", *_NUMBERS, *_TEXT])
TABLES = (COLLISIONS,)
Reader = Any


def reading(reader: Reader) -> Connection:
    """The Core connection of ``reader`` (itself, or a session's connection)."""
    return reader if isinstance(reader, Connection) else reader.connection()


def iter_collisions(
    reader: Reader,
    *,
    chunk_rows: int = CHUNK_ROWS,
    text: bool = True,
    measured: Collection[str] | None = None,
    **filters: str | None,
) -> Iterator[dict[str, Any]]:
    """The stored collisions matching the ``filters`` (``dataset``, ``version``,
    ``particle``, ``wall``, ``fluid``: names case-insensitive, ``fluid`` "dry" for dry
    runs; ``None`` or not given: any), in order, as dicts of numpy arrays of at most
    ``chunk_rows`` runs each: ``dataset``, ``version``, ``run``, ``particle``,
    ``wall`` (names), ``fluid_id`` (float, NaN for dry), every measured column, ``notes``
    and ``particle_<property>``/``wall_<property>``. ``text`` False: no ``run`` and
    ``notes`` (a reader that needs neither: every cell is then a number, and a chunk
    converts to floats in one step, without a Python object per cell). ``measured``: the
    measured columns to read (``survey_collisions``: those holding a value), the others
    come back as NaN without being read (default: every one).

    Why this way: the select returns each run's own columns and the ids of its dataset
    and materials; names and material properties are looked up once per id and spread
    with an index (not joined into every row). Rows come from the driver's cursor in
    chunks (no SQLAlchemy row objects), each chunk's number cells become one float array
    and its text cells object arrays, at C speed (no object array of every cell), so a
    million runs read at the driver's pace in bounded memory. PostgreSQL streams through
    a server-side (named) cursor."""
    connection = reading(reader)
    read = [c for c in COLLISION_MEASURED if measured is None or c in measured]
    query = _collision_select(connection, filters, text=text, measured=read)
    sets = sorted(connection.execute(select(DATASETS.c.id, DATASETS.c.name, DATASETS.c.version)))
    set_ids = np.array([r[0] for r in sets], dtype=np.int64)
    set_names = np.array([r[1] for r in sets], dtype=object)
    set_versions = np.array([r[2] for r in sets], dtype=object)
    properties = [MATERIALS.c[name] for name in MATERIAL_PROPERTIES]
    materials = sorted(connection.execute(select(MATERIALS.c.id, MATERIALS.c.name, *properties)))
    material_ids = np.array([r[0] for r in materials], dtype=np.int64)
    material_names = np.array([r[1] for r in materials], dtype=object)
    table = np.stack([_floats([r[2 + i] for r in materials]) for i in range(len(properties))], 1)
    names = [*_IDS, *read, *(_TEXT if text else ())]
    at = {name: i for i, name in enumerate(names)}
    width = len(names) - (len(_TEXT) if text else 0)  # the number cells lead each row
    numbers = operator.itemgetter(slice(0, width))
    for rows in _driver_chunks(connection, query, chunk_rows):
        try:
            # fromiter over the flattened number cells: about twice as fast as np.array on
            # the tuples, with the same conversions (None is NaN, a text cell is parsed or
            # refused); the text cells (last in each row) are taken apart below
            cells = itertools.chain.from_iterable(map(numbers, rows) if text else rows)
            block = np.fromiter(cells, dtype=float, count=len(rows) * width)
            block = block.reshape(len(rows), width)
        except (TypeError, ValueError):  # a bad stored cell (NaN, as below)
            block = np.array(rows, dtype=object).reshape(len(rows), len(names))
        data: dict[str, Any] = {}
        where = np.searchsorted(set_ids, block[:, at["dataset_id"]].astype(np.int64))
        data["dataset"], data["version"] = set_names[where], set_versions[where]
        if text:
            data["run"] = _cells(rows, at["run"])
        roles = {}
        for role in ("particle", "wall"):
            ids = block[:, at[f"{role}_id"]].astype(np.int64)
            roles[role] = np.searchsorted(material_ids, ids)
            data[role] = material_names[roles[role]]
        data["fluid_id"] = _floats(block[:, at["fluid_id"]])
        for name in COLLISION_MEASURED:
            data[name] = _floats(block[:, at[name]]) if name in at else np.full(len(rows), np.nan)
        if text:
            data["notes"] = _cells(rows, at["notes"])
        for role in ("particle", "wall"):
            for i, name in enumerate(MATERIAL_PROPERTIES):
                data[f"{role}_{name}"] = table[roles[role], i]
        del block, rows
        yield data


def survey_collisions(reader: Reader, **filters: str | None) -> tuple[int, frozenset[str]]:
    """(how many runs ``iter_collisions`` with the same ``filters`` (``dataset``,
    ``version``, ``particle``, ``wall``, ``fluid``) yields, so a reader can
    allocate its arrays once; the measured columns holding a value in any of them), in one
    pass. Why: most datasets leave whole columns empty (the target sphere's
    six, spin, temperature); ``iter_collisions`` then skips them instead of converting a
    NULL per run. In one read transaction (``Database.reading()``, or a session's) the
    survey and the read see the same snapshot."""
    connection = reading(reader)
    query = _collision_select(connection, filters, text=False)
    runs = query.order_by(None).subquery()
    counts = [func.count(runs.c[name]) for name in COLLISION_MEASURED]
    row = connection.execute(select(func.count(), *counts).select_from(runs)).one()
    present = frozenset(c for c, n in zip(COLLISION_MEASURED, row[1:], strict=True) if n)
    return int(row[0]), present


def _collision_select(
    connection: Connection,
    filters: Mapping[str, str | None],
    *,
    text: bool,
    measured: Sequence[str] = COLLISION_MEASURED,
) -> Any:
    """The select of ``iter_collisions``: each run's ids, ``measured`` columns and (with
    ``text``) its label and notes, filtered by ``filters`` (``STORED_FILTERS``), in order."""
    unknown = set(filters) - set(STORED_FILTERS)
    if unknown:
        raise TypeError(f"not a filter of the stored collisions: {sorted(unknown)}")
    runs = COLLISIONS.c
    query = select(*(runs[name] for name in (*_IDS, *measured, *(_TEXT if text else ()))))
    first, second = (
        MATERIALS.alias("particle_material"),
        MATERIALS.alias("wall_material"),
    )  # inner joins: as
    query = (  # before, a run whose dataset or material is missing is not read
        query.select_from(COLLISIONS)
        .join(DATASETS, runs.dataset_id == DATASETS.c.id)
        .join(first, runs.particle_id == first.c.id)
        .join(second, runs.wall_id == second.c.id)
    )
    dataset = filters.get("dataset")
    if dataset is not None:
        chosen = lookup_rows.dataset_row(connection, dataset, filters.get("version"))
        query = query.where(runs.dataset_id == chosen.id)
    for role in ("particle", "wall"):
        material = filters.get(role)
        if material is not None:
            ids = catalog_rows.entry_ids(connection, "material", material)
            query = query.where(_one_of(runs[f"{role}_id"], ids))
    fluid = filters.get("fluid")
    if fluid is not None:
        if fluid.strip().casefold() == "dry":
            query = query.where(runs.fluid_id.is_(None))
        else:
            ids = catalog_rows.entry_ids(connection, "fluid", fluid)
            query = query.where(_one_of(runs.fluid_id, ids))
    return query.order_by(DATASETS.c.name, DATASETS.c.version, runs.run)


def _one_of(column: Any, ids: list[int]) -> Any:
    """``column`` equal to one of ``ids`` (a live row and its revisions), as plain
    parameters: the query is also run through the driver directly, where an expanding
    IN parameter cannot go."""
    return or_(*(column == i for i in ids))


def _driver_chunks(connection: Any, query: Any, chunk_rows: int) -> Iterator[list[tuple]]:
    """The rows of ``query`` as the driver's tuples, ``chunk_rows`` at a time, on the
    session's own connection (so inside its transaction)."""
    compiled = query.compile(dialect=connection.dialect)
    params = compiled.construct_params()
    if compiled.positional:
        params = tuple(params[name] for name in compiled.positiontup)
    raw = connection.connection.dbapi_connection
    named = connection.dialect.name == "postgresql"
    cursor = raw.cursor(name="granudb_collisions") if named else raw.cursor()
    try:
        cursor.execute(str(compiled), params)
        while rows := cursor.fetchmany(chunk_rows):
            yield rows
    finally:
        cursor.close()


def _cells(rows: list[tuple], at: int) -> Any:
    """The cells at position ``at`` of the driver's ``rows``, as an object array (the
    driver's own objects: a text cell is the driver's string)."""
    return np.fromiter(map(operator.itemgetter(at), rows), dtype=object, count=len(rows))


def _floats(values: Any) -> Any:
    """A float array (None is NaN); a value that is not a number (a bad stored cell)
    becomes NaN, as ``pandas.to_numeric(errors="coerce")`` makes it."""
    if isinstance(values, np.ndarray) and values.dtype.kind == "f":
        return values.copy()  # a column of a float block: its own contiguous array
    try:
        return np.asarray(values, dtype=object).astype(float)
    except (TypeError, ValueError):
        return pd.to_numeric(pd.Series(list(values), dtype=object), errors="coerce").to_numpy(
            dtype=float
        )
