"""Catalogue reads through SQLAlchemy Core, without the ORM: materials, fluids, sources.

Why a second way to read the same rows: a command that only reads the catalogue
(``materials list``, ``fluids list``, ``sources list``, ``pair``) spent more time building
and configuring the ORM's mapped classes (``granudb.db.models``, about 0.1 s) than asking
the database, and issue 17 bounds those commands at 1.3× and 1.5× the time Python takes to
import SQLAlchemy. Here the same tables are named by lightweight ``table()`` clauses (no
metadata, no mapper), queried in one read transaction (``Database.reading()``), and
returned as frozen records whose attribute names are the models' own, so the record
builders below (the JSON, CSV and table rows every door shows) serve ORM objects and these
records alike. Changes still go through the ORM (``granudb.db.catalog``).

``tests/db/test_catalog_rows.py`` checks every column named here against the models and
that both paths give the same records for the same database.
"""

from __future__ import annotations

import difflib
from dataclasses import fields, make_dataclass
from typing import TYPE_CHECKING, Any

from sqlalchemy import DateTime, column, func, or_, select, table
from sqlalchemy.engine import Connection
from sqlalchemy.sql.expression import TableClause

from granudb.errors import NotFoundError
from granudb.vocabulary.catalog import FLUIDS as FLUID_CATALOGUE
from granudb.vocabulary.catalog import MATERIALS as MATERIAL_CATALOGUE
from granudb.vocabulary.catalog import (
    PAIR_VALUE_COLUMNS,
    POINT_COLUMNS,
    POINT_UNCERTAINTIES,
    SOURCE_COLUMNS,
    Catalogue,
)
from granudb.vocabulary.terms import keyed, stored
from granudb.vocabulary.text import name_key

_PYTHON_TYPES = {"float": float, "integer": int, "text": str, "string": str, "boolean": bool}


def _declared_fields(table: str) -> list[tuple[str, Any]]:
    """The fields of ``table``'s declared columns (``granudb.vocabulary.terms.STORED``),
    each ``u_`` column after the declared ones: a Core row reads every declared column,
    as the model stores it."""
    return [
        (s.column, _PYTHON_TYPES[s.sql] if not s.nullable else _PYTHON_TYPES[s.sql] | None)
        for s in stored(table, uncertainties=True)
    ]


def _row_type(name: str, head: list[tuple[str, Any]], table: str, tail: list[tuple[str, Any]],
              doc: str) -> Any:  # fmt: skip
    made = make_dataclass(name, [*head, *_declared_fields(table), *tail], frozen=True, slots=True)
    made.__doc__ = doc
    made.__module__ = __name__
    return made


class _Generated:
    """What a type checker sees of a generated row: any attribute, ``Any`` (the fields
    come from ``granudb.vocabulary.terms.STORED`` at import)."""

    if TYPE_CHECKING:

        def __init__(self, *values: Any, **named: Any) -> None: ...

        def __getattr__(self, name: str) -> Any: ...


if TYPE_CHECKING:

    class SourceRow(_Generated): ...

    class MaterialRow(_Generated): ...

    class PairValueRow(_Generated): ...

    class FluidPointRow(_Generated): ...

    class FluidRow(_Generated): ...

else:
    SourceRow = _row_type(
        "SourceRow", [], "sources", [], "A source as stored (``granudb.db.models.Source``)."
    )
    _SOURCE = ("source", SourceRow | None)
    _CREATED = [("created_at", Any), ("updated_at", Any)]
    MaterialRow = _row_type(
        "MaterialRow",
        [("name", str), ("description", str | None)],
        "materials",
        [("source_locator", str | None), _SOURCE, *_CREATED],
        "A material as the catalogue stores it (``granudb.db.models.Material``).",
    )
    PairValueRow = _row_type(
        "PairValueRow",
        [("particle", str), ("wall", str)],
        "pair_values",
        [("source_locator", str | None), ("notes", str | None), _SOURCE],
        "Dry values a source measured for one pair (``granudb.db.models.PairValue``), with "
        "the two materials' names.",
    )
    FluidPointRow = _row_type(
        "FluidPointRow",
        [],
        "fluid_points",
        [("source_locator", str | None), _SOURCE],
        "One point of a fluid (``granudb.db.models.FluidPoint``).",
    )
    FluidRow = _row_type(
        "FluidRow",
        [("name", str), ("description", str | None)],
        "fluids",
        [
            ("source_locator", str | None),
            ("density_locator", str | None),
            ("pressure_viscosity_locator", str | None),
            _SOURCE,
            ("density_source", SourceRow | None),
            ("pressure_viscosity_source", SourceRow | None),
            *_CREATED,
            ("points", tuple),
        ],
        "A fluid with its points (``granudb.db.models.Fluid``).",
    )


#: Attributes that are not columns of their own: the cited source (by ``<name>_id``) and
#: a fluid's points (their own table).
_REFERENCES = {"source", "density_source", "pressure_viscosity_source"}


def _stored(record: type) -> list[str]:
    """The columns a record type reads: its fields, with each source read by its id."""
    names = [f.name for f in fields(record) if f.name != "points"]
    return [f"{n}_id" if n in _REFERENCES else n for n in names]


#: Columns read with a type, so every backend gives the same Python value.
TYPED = {
    "created_at": DateTime(timezone=True),
    "updated_at": DateTime(timezone=True),
    "released_at": DateTime(timezone=True),
    "kept_at": DateTime(timezone=True),
}


def lightweight_table(name: str, columns: list[str]) -> TableClause:
    """A Core ``table()`` clause of ``columns`` typed as the models type them: reads
    without building the ORM's mapped classes."""
    return table(name, *(column(c, TYPED.get(c)) for c in columns))


SOURCES = lightweight_table("sources", ["id", *SOURCE_COLUMNS])
MATERIALS = lightweight_table("materials", ["id", "name_key", "revision_of", *_stored(MaterialRow)])
FLUIDS = lightweight_table("fluids", ["id", "name_key", "revision_of", *_stored(FluidRow)])
FLUID_POINTS = lightweight_table("fluid_points", ["id", "fluid_id", *_stored(FluidPointRow)])
PAIR_VALUES = lightweight_table(
    "pair_values",
    ["id", "particle_id", "wall_id", "created_at",
     *(c for c in _stored(PairValueRow) if c not in ("particle", "wall"))],
)  # fmt: skip
SOURCE_REVISIONS = lightweight_table(
    "source_revisions", ["id", "source_id", *SOURCE_COLUMNS, "kept_at", "reason"]
)
#: Every lightweight table above, for the test that holds them to the models.
TABLES = (SOURCES, MATERIALS, FLUIDS, FLUID_POINTS, PAIR_VALUES, SOURCE_REVISIONS)


def _sources(connection: Connection) -> dict[int, SourceRow]:
    rows = connection.execute(select(*SOURCES.c).order_by(SOURCES.c.key)).mappings()
    return {row["id"]: SourceRow(*(row[c] for c in SOURCE_COLUMNS)) for row in rows}


def _build(record: type, row: Any, sources: dict[int, SourceRow], **extra: Any) -> Any:
    values = {}
    for f in fields(record):
        if f.name in _REFERENCES:
            source_id = row[f"{f.name}_id"]
            values[f.name] = None if source_id is None else sources[source_id]
        elif f.name not in extra:
            values[f.name] = row[f.name]
    return record(**values, **extra)


def source_rows(connection: Connection) -> list[SourceRow]:
    """Every source, by key."""
    return list(_sources(connection).values())


def source_revision_rows(connection: Connection, key: str | None = None) -> list[Any]:
    """The kept revisions (of source ``key``, or all), oldest first: each the source's
    values before one change, with ``source_id``, ``kept_at`` and ``reason``."""
    query = select(*SOURCE_REVISIONS.c).order_by(SOURCE_REVISIONS.c.kept_at, SOURCE_REVISIONS.c.id)
    if key is not None:
        query = query.where(SOURCE_REVISIONS.c.source_id == source_id(connection, key))
    return list(connection.execute(query).mappings())


def sources_as_of(connection: Connection, when: Any) -> dict[str, SourceRow]:
    """Every source by key as it was at ``when`` (a release's ``released_at``; None:
    today): the first revision kept after ``when`` holds the values it had then, else
    the live row does."""
    live = {row.key: row for row in source_rows(connection)}
    if when is None:
        return live
    keys = {i: row.key for i, row in _sources(connection).items()}
    earlier: dict[str, SourceRow] = {}
    for revision in source_revision_rows(connection):
        key = keys[revision["source_id"]]
        if revision["kept_at"] > when and key not in earlier:
            earlier[key] = SourceRow(*(revision[c] for c in SOURCE_COLUMNS))
    return {**live, **{k: v for k, v in earlier.items() if k in live}}


def material_rows(connection: Connection, name: str | None = None) -> list[MaterialRow]:
    """Every material by name (case-insensitively), or the one called ``name``; live rows
    only (a release's kept values are revisions, ``granudb.db.catalog_revisions``)."""
    query = select(*MATERIALS.c).order_by(MATERIALS.c.name_key)
    query = query.where(MATERIALS.c.revision_of.is_(None))
    if name is not None:
        query = query.where(MATERIALS.c.name_key == name_key(name))
    sources = _sources(connection)
    return [_build(MaterialRow, row, sources) for row in connection.execute(query).mappings()]


def fluid_rows(connection: Connection, name: str | None = None) -> list[FluidRow]:
    """Every live fluid by name with its points by temperature, or the one called
    ``name``."""
    return list(_fluids(connection, name, live=True).values())


def fluid_rows_by_id(connection: Connection) -> dict[int, FluidRow]:
    """Every fluid keyed by its id, revisions included: stored runs name their fluid by
    id, and a release's runs the revision it keeps."""
    return _fluids(connection, None)


def _fluids(connection: Connection, name: str | None, live: bool = False) -> dict[int, FluidRow]:
    query = select(*FLUIDS.c).order_by(FLUIDS.c.name_key)
    if live:
        query = query.where(FLUIDS.c.revision_of.is_(None))
    if name is not None:
        query = query.where(FLUIDS.c.name_key == name_key(name))
    found = connection.execute(query).mappings().all()
    if not found:
        return {}
    points_query = select(*FLUID_POINTS.c).order_by(
        FLUID_POINTS.c.fluid_id, *(FLUID_POINTS.c[c] for c in keyed("fluid_points"))
    )
    if name is not None:
        points_query = points_query.where(FLUID_POINTS.c.fluid_id == found[0]["id"])
    sources = _sources(connection)
    points: dict[int, list[FluidPointRow]] = {}
    for row in connection.execute(points_query).mappings():
        points.setdefault(row["fluid_id"], []).append(_build(FluidPointRow, row, sources))
    return {
        row["id"]: _build(FluidRow, row, sources, points=tuple(points.get(row["id"], ())))
        for row in found
    }


ENTRY_TABLES = {"material": MATERIALS, "fluid": FLUIDS}


def entry_name(connection: Connection, kind: str, name: str) -> str | None:
    """The stored spelling of the ``kind`` ("material" or "fluid") called ``name``
    (case-insensitively), or ``None``."""
    clause = ENTRY_TABLES[kind]
    query = select(clause.c.name).where(clause.c.name_key == name_key(name))
    return connection.execute(query).scalar_one_or_none()


def entry_id(connection: Connection, kind: str, name: str) -> int:
    """The id of the ``kind`` called ``name``; an error listing the known names if none."""
    clause = ENTRY_TABLES[kind]
    query = select(clause.c.id).where(clause.c.name_key == name_key(name))
    found = connection.execute(query).scalar_one_or_none()
    if found is None:
        raise _not_found(connection, kind, name)
    return int(found)


def entry_ids(connection: Connection, kind: str, name: str) -> list[int]:
    """The ids of the ``kind`` called ``name``: the live row and the revisions released
    runs keep (a filter by name finds a release's runs too)."""
    live = entry_id(connection, kind, name)
    clause = ENTRY_TABLES[kind]
    kept = connection.execute(select(clause.c.id).where(clause.c.revision_of == live))
    return [live, *kept.scalars()]


def _not_found(connection: Connection, kind: str, name: str) -> NotFoundError:
    clause = ENTRY_TABLES[kind]
    live = select(clause.c.name).where(clause.c.revision_of.is_(None))
    names = connection.execute(live.order_by(clause.c.name_key)).scalars()
    known = ", ".join(names) or "none yet"
    return NotFoundError(f"{kind}: {name!r} is not in the database (known: {known})")


def source_id(connection: Connection, key: str) -> int:
    """The id of the source ``key``; an error listing the known keys if none."""
    found = connection.execute(select(SOURCES.c.id).where(SOURCES.c.key == key)).scalar()
    if found is None:
        keys = list(connection.execute(select(SOURCES.c.key).order_by(SOURCES.c.key)).scalars())
        near = difflib.get_close_matches(key, keys, n=1)
        known = ", ".join(keys) or "none yet"
        hint = f"; did you mean {near[0]!r}?" if near else f" (known: {known})"
        raise NotFoundError(f"source: {key!r} is not in the database{hint}")
    return int(found)


def get_source_row(connection: Connection, key: str) -> SourceRow:
    """The source ``key``; an error listing the known keys if none."""
    source_id(connection, key)
    return next(s for s in source_rows(connection) if s.key == key)


def entry_history(connection: Connection, kind: str, name: str) -> list[dict[str, Any]]:
    """The ``kind`` called ``name`` as it is and as released datasets keep it: the live
    row, then its revisions newest first, each a record with ``revision`` ("current" or
    its number), ``kept_at`` (when the live row moved on) and ``used_by`` (the dataset
    versions whose runs use it, with their run counts)."""
    ids = entry_ids(connection, kind, name)
    by_id = fluid_rows_by_id(connection) if kind == "fluid" else None
    records = []
    for number, row_id in enumerate(ids):
        if by_id is not None:
            record = fluid_record(by_id[row_id])
        else:
            record = material_record(material_row_by_id(connection, row_id))
        used = []
        for reference in RUN_REFERENCES[kind]:
            column = RUNS.c[reference]
            query = (
                select(_DATASETS.c.name, _DATASETS.c.version, func.count())
                .join(_DATASETS, _DATASETS.c.id == RUNS.c.dataset_id)
                .where(column == row_id)
                .group_by(_DATASETS.c.name, _DATASETS.c.version)
            )
            used += [
                f"{n}@{v} ({c} runs as {reference[:-3]})" for n, v, c in connection.execute(query)
            ]
        kept = connection.execute(
            select(ENTRY_TABLES[kind].c.updated_at).where(ENTRY_TABLES[kind].c.id == row_id)
        ).scalar()
        records.append(
            {"revision": "current" if number == 0 else str(number),
             "kept_at": None if number == 0 else kept, "used_by": "; ".join(sorted(used)),
             **record}
        )  # fmt: skip
    return [records[0], *reversed(records[1:])]


#: The runs' references, to find the rows a dataset's runs use.
RUNS = lightweight_table("collisions", ["dataset_id", "particle_id", "wall_id", "fluid_id"])
RUN_REFERENCES = {"material": ("particle_id", "wall_id"), "fluid": ("fluid_id",)}
_DATASETS = lightweight_table("datasets", ["id", "name", "version"])


def pinned_id(connection: Connection, kind: str, name: str, dataset_id: int) -> int:
    """The id of the row called ``name`` that dataset ``dataset_id``'s runs use: a
    revision when the dataset is a release that kept one, else the live row."""
    ids = entry_ids(connection, kind, name)
    if len(ids) == 1:  # never revised: the live row is the one
        return ids[0]
    # One "is it used?" probe per candidate row and reference, stopping at the first run
    # found: a DISTINCT over the dataset's runs read every run (0.05 s per call on
    # 100,000 runs, eight calls per report).
    used = {
        i
        for i in ids
        for reference in RUN_REFERENCES[kind]
        if connection.execute(
            select(RUNS.c[reference])
            .where(RUNS.c.dataset_id == dataset_id, RUNS.c[reference] == i)
            .limit(1)
        ).first()
    }
    return used.pop() if len(used) == 1 else ids[0]


def material_row_by_id(connection: Connection, row_id: int) -> MaterialRow:
    """The material row ``row_id`` (live or a kept revision)."""
    row = connection.execute(select(*MATERIALS.c).where(MATERIALS.c.id == row_id))
    return _build(MaterialRow, row.mappings().one(), _sources(connection))


def get_material_row(
    connection: Connection, name: str, dataset_id: int | None = None
) -> MaterialRow:
    """The material called ``name`` (as dataset ``dataset_id``'s runs use it, when
    given); an error listing the known names if there is none."""
    found = material_rows(connection, name)
    if not found:
        raise _not_found(connection, "material", name)
    if dataset_id is None:
        return found[0]
    chosen = pinned_id(connection, "material", name, dataset_id)
    return material_row_by_id(connection, chosen)


def get_fluid_row(connection: Connection, name: str, dataset_id: int | None = None) -> FluidRow:
    """The fluid called ``name`` with its points (as dataset ``dataset_id``'s runs use
    it, when given); an error listing the known names if none."""
    found = fluid_rows(connection, name)
    if not found:
        raise _not_found(connection, "fluid", name)
    if dataset_id is None:
        return found[0]
    return fluid_rows_by_id(connection)[pinned_id(connection, "fluid", name, dataset_id)]


# The records every door shows, built from an ORM object or a record above alike.


def source_key(source: Any) -> str | None:
    return source.key if source is not None else None


def source_record(source: Any) -> dict[str, Any]:
    return {c: getattr(source, c) for c in SOURCE_COLUMNS}


def _entry_record(catalogue: Catalogue, row: Any) -> dict[str, Any]:
    """The listing columns of ``catalogue`` read off ``row`` (sources as their keys)."""
    return {
        c: source_key(getattr(row, c)) if c == "source" or c.endswith("_source")
        else getattr(row, c, None)
        for c in catalogue.columns
    }  # fmt: skip


def material_record(material: Any) -> dict[str, Any]:
    """A material as an SI record; a missing shear modulus is derived, G = E / (2(1 + ν))."""
    record = _entry_record(MATERIAL_CATALOGUE, material)
    derived = material.shear_modulus_pa is None
    if derived:
        record["shear_modulus_pa"] = material.youngs_modulus_pa / (
            2.0 * (1.0 + material.poisson_ratio)
        )
    record["shear_modulus_derived"] = derived
    return record


def fluid_record(fluid: Any) -> dict[str, Any]:
    """A fluid as an SI record; ``points`` counts its viscosity–temperature points."""
    record = _entry_record(FLUID_CATALOGUE, fluid)
    record["points"] = len(fluid.points)
    return record


def point_records(fluid: Any) -> list[dict[str, Any]]:
    """A fluid's points as records (``POINT_COLUMNS`` and their uncertainties), by
    temperature."""
    shown = [c for c in (*POINT_COLUMNS, *POINT_UNCERTAINTIES) if c != "source"]
    return [
        {**{c: getattr(p, c) for c in shown}, "source": source_key(p.source)}
        for p in sorted(fluid.points, key=lambda p: [getattr(p, c) for c in keyed("fluid_points")])
    ]


def pair_value_rows(
    connection: Connection,
    particle: str | None = None,
    wall: str | None = None,
    before: Any = None,
) -> list[PairValueRow]:
    """The pairs' measured dry values, by particle and wall name; with ``particle`` and
    ``wall`` the values of that pair either way round (none: an empty list); with
    ``before`` (a release's ``released_at``) only those stored before it."""
    first, second = MATERIALS.alias("first"), MATERIALS.alias("second")
    query = (
        select(*PAIR_VALUES.c, first.c.name.label("particle"), second.c.name.label("wall"))
        .select_from(PAIR_VALUES)
        .join(first, first.c.id == PAIR_VALUES.c.particle_id)
        .join(second, second.c.id == PAIR_VALUES.c.wall_id)
        .order_by(first.c.name_key, second.c.name_key)
    )
    if particle is not None and wall is not None:
        one, other = name_key(particle), name_key(wall)
        query = query.where(
            or_(
                (first.c.name_key == one) & (second.c.name_key == other),
                (first.c.name_key == other) & (second.c.name_key == one),
            )
        )
    if before is not None:
        query = query.where(PAIR_VALUES.c.created_at <= before)
    sources = _sources(connection)
    return [_build(PairValueRow, row, sources) for row in connection.execute(query).mappings()]


def pair_value_record(row: PairValueRow) -> dict[str, Any]:
    """A pair's measured dry values as a record (``PAIR_VALUE_COLUMNS``)."""
    return {c: source_key(row.source) if c == "source" else getattr(row, c)
            for c in PAIR_VALUE_COLUMNS}  # fmt: skip


def released_at(connection: Connection, dataset_id: int | None) -> Any:
    """When dataset ``dataset_id`` was released (None: a draft, or no dataset)."""
    if dataset_id is None:
        return None
    datasets = lightweight_table("datasets", ["id", "released_at"])
    query = select(datasets.c.released_at).where(datasets.c.id == dataset_id)
    return connection.execute(query).scalar_one_or_none()
