"""Writing imported collisions: one transaction, names resolved, runs unique, all or nothing.

The reader (``granudb.io.collisions_csv`` or a Data Package) yields checked SI DataFrames
with material and fluid names as text; here they are resolved to ids (case-insensitively),
refused when a run label repeats, bulk-inserted, and the import recorded with the file's
sha256, all inside one write transaction: a failure anywhere, in reading or writing, rolls
everything back.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from itertools import repeat
from typing import Any

import numpy as np
from sqlalchemy import func, select
from sqlalchemy.exc import DBAPIError

from granudb.db import datasets
from granudb.db.models import (
    Collision,
    CollisionImport,
    Fluid,
    FluidPoint,
    Material,
    name_key,
)
from granudb.errors import ConflictError, ValidationError
from granudb.vocabulary import COLLISION_MEASURED


@dataclass(frozen=True)
class ImportTarget:
    """Where the rows go and where they came from."""

    dataset: str
    version: str
    source: str | None
    title: str | None
    license: str | None
    file_sha256: str
    file_name: str


def _first(mask: Any) -> int:
    return int(np.flatnonzero(np.asarray(mask))[0])


class NameIndex:
    """Case-insensitive lookup of material and fluid names to ids, vectorized."""

    def __init__(self, session: Any) -> None:
        self.materials = {
            name_key(n): i for i, n in session.execute(select(Material.id, Material.name))
        }
        self.material_names = sorted(
            (n for (n,) in session.execute(select(Material.name))), key=str.casefold
        )
        self.fluids = {name_key(n): i for i, n in session.execute(select(Fluid.id, Fluid.name))}
        self.fluid_names = sorted(
            (n for (n,) in session.execute(select(Fluid.name))), key=str.casefold
        )

    def ids(
        self, names: Any, table: dict[str, int], known: list[str], header: str, first_row: int
    ) -> Any:
        unique = {n: table.get(name_key(n)) for n in names.dropna().unique() if isinstance(n, str)}
        ids = names.map(unique)
        unknown = names.notna() & ids.isna()
        if unknown.any():
            pos = _first(unknown)
            raise ValidationError(
                header,
                repr(str(names.iloc[pos])),
                f"is not in the database (known: {', '.join(known)})",
                row=first_row + pos,
            )
        return ids


#: A run this close to its fluid's reference temperature is derived with the printed


class FluidRanges:
    """Which temperatures each fluid's stored data can serve, so no run is imported that
    every later read (listing, fits, reports) would then fail to derive.

    A run's viscosity comes from the fluid's points (two or more), anchored to the printed
    reference value, anywhere between the lowest and highest point; a fluid with fewer
    points has a viscosity only at its reference temperature. Nothing is extrapolated.
    This mirrors ``granudb.analysis.fluid_state.fluid_states_per_row`` (a test imports
    runs at the edges and checks every read derives them).
    """

    def __init__(self, session: Any) -> None:
        spans = {
            fluid_id: (low, high, count)
            for fluid_id, low, high, count in session.execute(
                select(
                    FluidPoint.fluid_id,
                    func.min(FluidPoint.temperature_c),
                    func.max(FluidPoint.temperature_c),
                    func.count(),
                ).group_by(FluidPoint.fluid_id)
            )
        }
        self.fluids = {
            name_key(name): (name, reference, *spans.get(fluid_id, (None, None, 0)))
            for fluid_id, name, reference in session.execute(
                select(Fluid.id, Fluid.name, Fluid.reference_temperature_c)
            )
        }

    def check(self, frame: Any, dataset: str) -> None:
        """Refuse the first row whose temperature its fluid's data does not cover."""
        temperatures = frame["temperature_c"].to_numpy(dtype=float)
        fluids = frame["fluid"]
        given = ~np.isnan(temperatures) & fluids.notna().to_numpy()
        if not given.any():
            return
        bad = np.zeros(len(frame), dtype=bool)
        rules: dict[str, str] = {}
        for name in fluids[given].unique():
            known = self.fluids.get(name_key(str(name)))
            if known is None:
                continue  # refused as unknown when names are resolved
            shown, reference, low, high, count = known
            rows = given & (fluids == name).to_numpy()
            t = temperatures
            if count < 2:
                off = rows & (t != reference)
                rules[name] = (
                    f"differs from fluid {shown}'s reference temperature ({reference:g} °C) "
                    "and the fluid has no viscosity–temperature points"
                )
            else:
                off = rows & ((t < low) | (t > high))
                rules[name] = (
                    f"is outside fluid {shown}'s viscosity data ({low:g}–{high:g} °C), which "
                    "granudb does not extrapolate"
                )
            bad |= off
        if bad.any():
            pos = _first(bad)
            header = frame.attrs.get("headers", {}).get("temperature_c", "temperature_c")
            raise ValidationError(
                header,
                f"{temperatures[pos]:g} °C",
                f"{rules[fluids.iloc[pos]]}; nothing was imported into dataset {dataset}",
                row=int(frame.attrs.get("first_row", 2)) + pos,
            )


def store_collisions(
    database: Any,
    target: ImportTarget,
    frames: Iterable[Any],
    *,
    progress: Callable[[int], None] | None = None,
) -> int:
    """Write every frame of ``frames`` into ``target`` in one write transaction."""
    from granudb.db.sources import get_source

    rows = 0
    with database.session(write=True) as session:
        source_id = get_source(session, target.source).id if target.source else None
        dataset, _ = datasets.get_or_create_dataset(
            session,
            target.dataset,
            target.version,
            title=target.title,
            license=target.license,
            source_id=source_id,
        )
        earlier = session.scalars(
            select(CollisionImport).filter_by(dataset_id=dataset.id, file_sha256=target.file_sha256)
        ).first()
        if earlier is not None:
            raise ConflictError(
                f"FILE: {target.file_name} was already imported into dataset {target.dataset} "
                f"{target.version} on {earlier.imported_at:%Y-%m-%d %H:%M} ({earlier.rows} "
                "rows); nothing was imported again"
            )
        names = NameIndex(session)
        ranges = FluidRanges(session)
        seen = set(session.scalars(select(Collision.run).filter_by(dataset_id=dataset.id)))
        for frame in frames:
            ranges.check(frame, target.dataset)
            rows += _store_frame(session, dataset.id, frame, names, seen)
            if progress is not None:
                progress(rows)
        session.add(
            CollisionImport(
                dataset_id=dataset.id,
                file_sha256=target.file_sha256,
                file_name=target.file_name[:500],
                rows=rows,
            )
        )
        datasets.update_content_hash(session, dataset)
    return rows


def _store_frame(
    session: Any, dataset_id: int, frame: Any, names: NameIndex, seen: set[str]
) -> int:
    first_row = int(frame.attrs.get("first_row", 2))
    runs = frame["run"]
    repeated = runs.duplicated() | runs.isin(seen)
    if repeated.any():
        pos = _first(repeated)
        raise ValidationError(
            "run",
            repr(runs.iloc[pos]),
            "appears twice (in this file or already in the dataset)",
            row=first_row + pos,
        )
    seen.update(runs)
    frame = frame.copy()
    frame["particle_id"] = names.ids(
        frame.pop("particle"), names.materials, names.material_names, "particle", first_row
    )
    frame["wall_id"] = names.ids(
        frame.pop("wall"), names.materials, names.material_names, "wall", first_row
    )
    frame["fluid_id"] = names.ids(
        frame.pop("fluid"), names.fluids, names.fluid_names, "fluid", first_row
    )
    return insert_collisions(session, dataset_id, frame)


INSERT_COLUMNS = [
    "dataset_id",
    "run",
    "particle_id",
    "wall_id",
    "fluid_id",
    *COLLISION_MEASURED,
    "notes",
]


# Page cache for the length of a bulk load (KiB, negative = size rather than pages): the
# unique (dataset, run) index of a million rows no longer spills to the WAL mid-way. The
# engine restores the connection's own setting when it goes back to the pool
# (granudb.db.engine.BULK_CACHE_KEY).
BULK_CACHE_KIB = 65_536
_ID_COLUMNS = ("particle_id", "wall_id", "fluid_id")


def _column_values(frame: Any, name: str) -> list[Any]:
    """One column as Python values with missing → None, built by numpy, not per row.

    Floats stay the exact float64 values (Python floats round-trip them); ids become ints.
    """
    values = frame[name]
    missing = values.isna().to_numpy()
    if name in _ID_COLUMNS:
        numbers = values.to_numpy(dtype="float64", na_value=0.0).astype(np.int64)
        array = numbers.astype(object)
    elif name in ("run", "notes"):
        array = values.to_numpy(dtype=object, copy=True)
    else:
        array = values.to_numpy(dtype="float64", na_value=np.nan).astype(object)
    if missing.any():
        array[missing] = None
    return array.tolist()


def _bulk_cache(connection: Any, raw: Any) -> None:
    """Enlarge SQLite's page cache for this transaction (restored on check-in)."""
    from granudb.db.engine import BULK_CACHE_KEY

    if BULK_CACHE_KEY not in connection.info:
        connection.info[BULK_CACHE_KEY] = raw.execute("PRAGMA cache_size").fetchone()[0]
        raw.execute(f"PRAGMA cache_size=-{BULK_CACHE_KIB}")


def insert_collisions(session: Any, dataset_id: int, frame: Any) -> int:
    """Bulk-insert SI rows (ids already resolved) in the session's transaction; the count.

    The fastest path each backend offers, still inside the one all-or-nothing transaction
    of the import: PostgreSQL ``COPY … FROM STDIN`` through psycopg 3; SQLite one prepared
    ``executemany`` over a generator of tuples (no SQL built from data) with a larger page
    cache for the load. SQLite's durability settings (WAL, ``synchronous=NORMAL``) are left
    as they are: an import killed mid-way leaves the file intact with none of its rows.
    """
    n = len(frame)
    if n == 0:
        return 0
    columns = [_column_values(frame, name) for name in INSERT_COLUMNS[1:]]
    rows = zip(repeat(dataset_id, n), *columns, strict=False)
    connection = session.connection()
    raw = connection.connection.driver_connection
    names = ", ".join(INSERT_COLUMNS)
    dialect = connection.dialect
    try:
        if dialect.name == "postgresql" and hasattr(raw, "pgconn"):  # psycopg 3
            statement = f"COPY collisions ({names}) FROM STDIN"
            with raw.cursor() as cursor, cursor.copy(statement) as copy:
                for row in rows:
                    copy.write_row(row)
            return n
        if dialect.name == "sqlite":
            statement = (
                f"INSERT INTO collisions ({names}) VALUES ({', '.join('?' * len(INSERT_COLUMNS))})"
            )
            _bulk_cache(connection, raw)
            raw.cursor().executemany(statement, rows)
            return n
    except dialect.loaded_dbapi.Error as exc:
        # The driver's own error, as SQLAlchemy would raise it (the session translates it).
        raise DBAPIError.instance(statement, None, exc, dialect.loaded_dbapi.Error) from None
    mark = "?" if connection.dialect.paramstyle == "qmark" else "%s"
    connection.exec_driver_sql(
        f"INSERT INTO collisions ({names}) VALUES ({', '.join([mark] * len(INSERT_COLUMNS))})",
        list(rows),
    )
    return n
