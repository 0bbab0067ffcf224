"""Reading the catalogue, for Python users and the command line: materials, fluids and
sources.

``granudb materials list|show``, ``fluids list|show`` and ``sources list|show`` are
``materials``, ``material``, ``fluids``, ``fluid``, ``sources`` and ``source``. They read
through SQLAlchemy Core (``granudb.db.catalog_rows``), so a listing builds none of the
ORM's classes; changes are ``granudb.api.catalog_changes``.
"""

from __future__ import annotations

from typing import Any

from granudb.api import inputs
from granudb.api.database import opened
from granudb.api.frames import records_frame
from granudb.db import catalog_rows
from granudb.db import sources as source_reads
from granudb.reporting.history import with_changes
from granudb.vocabulary import FLUIDS, MATERIALS, Catalogue
from granudb.vocabulary.catalog import SOURCE_COLUMNS


def entry(catalogue: Catalogue, name: str, database: Any) -> dict[str, Any]:
    """One material or fluid as ``material``/``fluid`` return it."""
    row: catalog_rows.MaterialRow | catalog_rows.FluidRow
    with database.reading() as connection:
        if catalogue is MATERIALS:
            row = catalog_rows.get_material_row(connection, name)
            record = catalog_rows.material_record(row)
        else:
            row = catalog_rows.get_fluid_row(connection, name)
            record = catalog_rows.fluid_record(row)
    record["citation"] = row.source.citation if row.source else None
    record["created_at"] = row.created_at
    record["updated_at"] = row.updated_at
    if catalogue is FLUIDS:
        record["points"] = catalog_rows.point_records(row)
    return record


def materials(db: Any = None, *, as_frame: bool = True) -> Any:
    """Every material with its properties (SI) and source, by name: a DataFrame (units in
    ``attrs["units"]``), or a list of records with ``as_frame=False``.

    Examples
    --------
    >>> import granudb
    >>> frame = granudb.materials(db=db)
    >>> float(frame.set_index("name").loc["glass", "youngs_modulus_pa"])
    60000000000.0
    """
    return _listing(
        catalog_rows.material_rows, catalog_rows.material_record, MATERIALS.columns, db, as_frame
    )


def material(name: str, *, db: Any = None) -> dict[str, Any]:
    """One material: its properties (SI), source with the full citation, and when it was
    added and last changed.

    Examples
    --------
    >>> import granudb
    >>> granudb.material("STEEL", db=db)["density_kg_m3"]
    7780.0
    """
    with opened(db) as database:
        return entry(MATERIALS, inputs.text(name, "name"), database)


def material_history(name: str, *, db: Any = None) -> list[dict[str, Any]]:
    """A material as it is and as released datasets keep it: the current values, then
    each revision (newest first) with when it was kept and which dataset versions use it
    (``granudb.db.catalog_revisions``: a release never changes); ``changes`` says what
    each change did (``field: old → new``, from the revision before).

    Examples
    --------
    >>> import granudb
    >>> [r["revision"] for r in granudb.material_history("Zerodur", db=db)]
    ['current']
    """
    with opened(db) as database, database.reading() as connection:
        found = catalog_rows.entry_history(connection, "material", inputs.text(name, "name"))
    return with_changes(found)


def fluid_history(name: str, *, db: Any = None) -> list[dict[str, Any]]:
    """A fluid as it is and as released datasets keep it (with its points), newest first;
    as ``material_history``.

    Examples
    --------
    >>> import granudb
    >>> current = granudb.fluid_history("water", db=db)[0]
    >>> current["revision"], current["points"]
    ('current', 11)
    """
    with opened(db) as database, database.reading() as connection:
        found = catalog_rows.entry_history(connection, "fluid", inputs.text(name, "name"))
    return with_changes(found)


def fluids(db: Any = None, *, as_frame: bool = True) -> Any:
    """Every fluid with its reference values (SI), sources and number of viscosity points:
    a DataFrame, or a list of records with ``as_frame=False``.

    Examples
    --------
    >>> import granudb
    >>> records = {r["name"]: r for r in granudb.fluids(db=db, as_frame=False)}
    >>> records["glycerol-45"]["reference_viscosity_pa_s"]
    0.0045
    """
    return _listing(
        catalog_rows.fluid_rows, catalog_rows.fluid_record, FLUIDS.columns, db, as_frame
    )


def fluid(name: str, *, db: Any = None) -> dict[str, Any]:
    """One fluid with its sources and its viscosity–temperature points (``points``: a
    list of records ``temperature_c``, ``viscosity_pa_s``, ``density_kg_m3``, ``source``).

    Examples
    --------
    >>> import granudb
    >>> len(granudb.fluid("glycerol-45", db=db)["points"]) > 2
    True
    """
    with opened(db) as database:
        return entry(FLUIDS, inputs.text(name, "name"), database)


def sources(db: Any = None, *, as_frame: bool = True) -> Any:
    """Every source (key, citation, DOI, …) by key: a DataFrame or a list of records.

    Examples
    --------
    >>> import granudb
    >>> "joseph-hunt-2004" in set(granudb.sources(db=db)["key"])
    True
    """
    return _listing(
        catalog_rows.source_rows, catalog_rows.source_record, SOURCE_COLUMNS, db, as_frame
    )


def source_history(key: str, *, db: Any = None) -> list[dict[str, Any]]:
    """The source ``key`` as it is and as it was before each change, newest first: each
    record its values with ``revision`` ("current" or its number), ``kept_at`` (when it
    changed), ``reason`` (why) and ``changes`` (``field: old → new`` from the revision
    before, so a change to a field a table does not show is still said). A released
    dataset reads a source as it was when released, so its package's sources never
    change.

    Examples
    --------
    >>> import granudb
    >>> [r["revision"] for r in granudb.source_history("joseph-hunt-2004", db=db)]
    ['current']
    """
    key = inputs.text(key, "key")
    with opened(db) as database, database.reading() as connection:
        current = catalog_rows.source_record(catalog_rows.get_source_row(connection, key))
        kept = catalog_rows.source_revision_rows(connection, key)
    records = [{"revision": "current", "kept_at": None, "reason": None, **current}]
    for number, row in enumerate(kept, start=1):
        values = {c: row[c] for c in current}
        records.append({"revision": str(number), "kept_at": row["kept_at"],
                        "reason": row["reason"], **values})  # fmt: skip
    return with_changes([records[0], *reversed(records[1:])])


def _listing(rows: Any, record: Any, columns: list[str], db: Any, as_frame: bool) -> Any:
    """Every row ``rows(connection)`` reads, as ``record(row)``: a DataFrame of ``columns``
    or the list of records."""
    with opened(db) as database, database.reading() as connection:
        records = [record(row) for row in rows(connection)]
    return records_frame(records, columns) if as_frame else records


def source(key: str, *, db: Any = None) -> dict[str, Any]:
    """One source: its citation, how many stored rows cite it (``cited_by``), and the
    numbers it printed as printed (``published_values``).

    Examples
    --------
    >>> import granudb
    >>> granudb.source("joseph-hunt-2004", db=db)["year"]
    2004
    """
    key = inputs.text(key, "key")
    with opened(db) as database, database.reading() as connection:
        record = catalog_rows.source_record(catalog_rows.get_source_row(connection, key))
        record["cited_by"] = source_reads.source_usage(connection, key)
        record["published_values"] = source_reads.published_records(connection, key)
    return record
