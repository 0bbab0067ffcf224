"""Sources and the numbers printed in them: who published what, and where (Core reads).

Every stored number that came from a publication points to a source plus the table or
figure it was printed in; ``published_records`` lists the numbers as printed. The rows
themselves are read by ``granudb.db.catalog_rows`` (sources) and
``granudb.db.lookup_rows`` (published values), the one read path of those tables.
Changes are ``granudb.db.source_changes`` (the ORM stays off this read path).
"""

from __future__ import annotations

from typing import Any

from sqlalchemy import column, func, select, table
from sqlalchemy.engine import Connection

from granudb.db import catalog_rows, lookup_rows

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
