"""Core lookups a read of stored runs needs: a dataset's identity by name and version, and
the published values; without the ORM (a material's or fluid's id is
``catalog_rows.entry_id``).

Why: a report (and any read of collisions) only reads. Building the ORM's mapped classes
and compiling its queries cost a report on 100,000 runs about a sixth of its 2 s bound
(issue 17), for a handful of lookups. These use lightweight ``table()`` clauses, like
``catalog_rows``, with the same names, the same case-insensitive matching and the same
errors as ``granudb.db.datasets``;
``tests/db/test_catalog_rows.py`` holds their columns to the models and both paths to the
same answers.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from sqlalchemy import select
from sqlalchemy.engine import Connection

from granudb.db.catalog_rows import FLUIDS, MATERIALS, SOURCES, lightweight_table
from granudb.errors import NotFoundError

DATASETS = lightweight_table("datasets", ["id", "name", "version", "content_hash"])
PUBLISHED = lightweight_table(
    "published_values",
    ["id", "source_id", "source_locator", "label", "quantity", "value", "uncertainty",
     "value_as_printed", "particle_id", "wall_id", "fluid_id", "condition"],
)  # fmt: skip
#: The lightweight tables of this module, for the test that holds them to the models.
TABLES = (DATASETS, PUBLISHED)


@dataclass(frozen=True, slots=True)
class DatasetRow:
    id: int
    name: str
    version: str
    content_hash: str | None


def dataset_row(connection: Connection, name: str, version: str | None = None) -> DatasetRow:
    """The dataset ``name`` at ``version`` (default: the most recently created version);
    the same errors as ``datasets.get_dataset``."""
    query = select(*DATASETS.c).where(DATASETS.c.name == name).order_by(DATASETS.c.id)
    versions = [DatasetRow(*row) for row in connection.execute(query)]
    if not versions:
        names = connection.execute(select(DATASETS.c.name).distinct()).scalars()
        known = ", ".join(sorted(names)) or "none yet"
        raise NotFoundError(f"dataset: {name!r} is not in the database (known: {known})")
    if version is None:
        return versions[-1]
    for dataset in versions:
        if dataset.version == version:
            return dataset
    raise NotFoundError(
        f"dataset: {name!r} has no version {version!r} (versions: "
        f"{', '.join(d.version for d in versions)})"
    )


def single_dataset_id(connection: Connection, frame: Any) -> int | None:
    """The id of the one dataset version a frame of runs (columns ``dataset`` and
    ``version``) comes from, or None when it holds several (or none): what a report reads
    the catalogue as (a release keeps the values it used)."""
    if "dataset" not in frame or "version" not in frame:
        return None
    versions = frame[["dataset", "version"]].drop_duplicates()
    if len(versions) != 1:
        return None
    name, version = versions.iloc[0].tolist()
    return dataset_row(connection, name, version).id


def published_rows(connection: Connection) -> list[dict[str, Any]]:
    """Every published value with its source key and names, in stored order: the records
    of ``sources.published_records``."""
    names = {
        kind: dict(connection.execute(select(clause.c.id, clause.c.name)).all())
        for kind, clause in (("material", MATERIALS), ("fluid", FLUIDS))
    }
    keys = dict(connection.execute(select(SOURCES.c.id, SOURCES.c.key)).all())
    query = select(*PUBLISHED.c).order_by(PUBLISHED.c.id)
    return [
        {
            "source": keys[row["source_id"]],
            "source_locator": row["source_locator"],
            "label": row["label"],
            "quantity": row["quantity"],
            "value": row["value"],
            "uncertainty": row["uncertainty"],
            "value_as_printed": row["value_as_printed"],
            "particle": names["material"].get(row["particle_id"]),
            "wall": names["material"].get(row["wall_id"]),
            "fluid": names["fluid"].get(row["fluid_id"]),
            "condition": row["condition"],
        }
        for row in connection.execute(query).mappings()
    ]
