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
from typing import Any

import numpy as np
from sqlalchemy import func, select

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


def insert_collisions(session: Any, dataset_id: int, frame: Any) -> int:
    """Bulk-insert SI rows (ids already resolved); returns the count.

    Rows go to the driver's ``executemany`` as tuples with one parameterised statement:
    several times faster than ORM objects or dicts, and still no SQL built from data.
    """
    n = len(frame)
    if n == 0:
        return 0
    columns: list[list[Any]] = [[dataset_id] * n]
    for name in INSERT_COLUMNS[1:]:
        values = frame[name]
        array = values.to_numpy(dtype=object)
        missing = values.isna().to_numpy()
        if name in ("particle_id", "wall_id", "fluid_id"):
            array = [None if m else int(v) for v, m in zip(array, missing, strict=True)]
        elif missing.any():
            array = [None if m else v for v, m in zip(array, missing, strict=True)]
        else:
            array = array.tolist()
        columns.append(array)
    connection = session.connection()
    mark = "?" if connection.dialect.paramstyle == "qmark" else "%s"
    statement = (
        f"INSERT INTO collisions ({', '.join(INSERT_COLUMNS)}) "
        f"VALUES ({', '.join([mark] * len(INSERT_COLUMNS))})"
    )
    connection.exec_driver_sql(statement, list(zip(*columns, strict=True)))
    return n
