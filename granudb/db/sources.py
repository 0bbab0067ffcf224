"""Sources and the numbers printed in them: who published what, and where.

Every stored number that came from a publication points to a source plus the table or
figure it was printed in; ``published_records`` lists the numbers as printed. The rows
themselves are read by ``granudb.db.catalog_rows`` (sources) and
``granudb.db.lookup_rows`` (published values), the one read path of those tables.

``add_source`` and ``update_source`` change them (``granudb sources add|update``): an
update first keeps the source as it was as a revision
(``catalog_revisions.keep_source_revision``, as a re-seed does), so ``sources history``
lists it and a release goes on citing the text it was released with.
"""

from __future__ import annotations

from typing import Any

from sqlalchemy import column, func, select, table
from sqlalchemy.engine import Connection
from sqlalchemy.orm import Session

from granudb.db import catalog_rows, lookup_rows
from granudb.db.catalog_revisions import keep_source_revision
from granudb.db.models import Source
from granudb.db.upsert import Change
from granudb.errors import ConflictError
from granudb.vocabulary.catalogue import check_source
from granudb.vocabulary.rules import same_value

#: The tables whose rows cite a source, as people call them.
CITING_TABLES = ("materials", "fluids", "published_values", "datasets")


def source_usage(connection: Connection, key: str) -> dict[str, int]:
    """How many rows of each kind cite the source ``key``."""
    source_id = catalog_rows.source_id(connection, key)
    counts = {}
    for name in CITING_TABLES:
        clause = table(name, column("source_id"))
        query = select(func.count()).select_from(clause).where(clause.c.source_id == source_id)
        counts[name] = connection.execute(query).scalar() or 0
    return counts


def published_records(connection: Connection, key: str | None = None) -> list[dict[str, Any]]:
    """The published values (of the source ``key``, or all), in stored order."""
    if key is not None:
        catalog_rows.source_id(connection, key)  # refuses an unknown key
    rows = lookup_rows.published_rows(connection)
    return [r for r in rows if key is None or r["source"] == key]


def add_source(session: Session, values: dict[str, Any]) -> None:
    """Add the source ``values`` (``key`` and ``citation`` required, the other columns
    of ``SOURCE_COLUMNS`` optional, ``kind`` "publication" unless given); refuses a key
    that exists and a field that breaks its rule (``check_source``)."""
    values = {"kind": "publication", **values}
    check_source(values)
    found = (
        session.connection()
        .execute(
            select(catalog_rows.SOURCES.c.key).where(catalog_rows.SOURCES.c.key == values["key"])
        )
        .scalar()
    )
    if found is not None:
        raise ConflictError(
            f"source: {values['key']!r} already exists (use `granudb sources update`); "
            "nothing was changed"
        )
    session.add(Source(**values))
    session.flush()


def update_source(session: Session, key: str, values: dict[str, Any], reason: str) -> Change:
    """Change the given fields of the source ``key`` (a value None: cleared; the citation
    cannot be); the source as it was is kept first as a revision, with ``reason``.
    Returns what changed, field by field (nothing kept when nothing changes)."""
    check_source(values)
    row = session.get(Source, catalog_rows.source_id(session.connection(), key))
    before = catalog_rows.source_record(row)
    diffs = [(c, before[c], new) for c, new in values.items() if not same_value(before[c], new)]
    label = f"source {key}"
    if not diffs:
        return Change("unchanged", label, diffs)
    keep_source_revision(session, row.id, before, reason)
    for field, _, new in diffs:
        setattr(row, field, new)
    session.flush()
    return Change("updated", label, diffs)
