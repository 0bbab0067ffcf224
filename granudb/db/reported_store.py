"""Runs as papers report them (table ``reported_runs``, migration 0012): store and read.

Rows come in as dicts of granudb's names (particle, wall, fluid and source by name or
key, quantities in SI); names are resolved case-insensitively, an unknown one is refused
naming the known ones, and a run label already in the collection is refused. Nothing here
makes a velocity.
"""

from __future__ import annotations

from typing import Any

from sqlalchemy import select
from sqlalchemy.orm import Session, aliased

from granudb.db import catalog_rows
from granudb.db.models import Fluid, Material, ReportedRun, Source
from granudb.errors import ValidationError
from granudb.vocabulary.terms import stored

#: The stored columns a row may set, besides the names.
STORED = (
    *(s.column for s in stored("reported_runs", uncertainties=True)),
    "source_locator",
    "notes",
)


def store(session: Session, collection: str, rows: list[dict[str, Any]]) -> int:
    """Insert ``rows`` into ``collection`` in the session's transaction; the count."""
    connection = session.connection()
    taken = set(
        session.scalars(select(ReportedRun.run).where(ReportedRun.collection == collection))
    )
    ids: dict[tuple[str, str], int] = {}

    def entry(kind: str, name: str) -> int:
        if (kind, name) not in ids:
            ids[(kind, name)] = catalog_rows.entry_id(connection, kind, name)
        return ids[(kind, name)]

    for number, row in enumerate(rows, start=2):
        if row["run"] in taken:
            raise ValidationError(
                "run", row["run"], f"is already in collection {collection!r}", row=number
            )
        taken.add(row["run"])
        fluid = row.get("fluid")
        source = row.get("source")
        session.add(
            ReportedRun(
                collection=collection,
                run=row["run"],
                particle_id=entry("material", row["particle"]),
                wall_id=entry("material", row["wall"]),
                fluid_id=entry("fluid", fluid) if fluid else None,
                source_id=catalog_rows.source_id(connection, source) if source else None,
                **{c: row.get(c) for c in STORED if c in row},
            )
        )
    session.flush()
    return len(rows)


def read(session: Session, collection: str | None = None) -> list[dict[str, Any]]:
    """Every reported run (of ``collection``), with material, fluid and source names."""
    particle, wall = aliased(Material), aliased(Material)
    query = (
        select(ReportedRun, particle.name, wall.name, Fluid.name, Source.key)
        .join(particle, ReportedRun.particle_id == particle.id)
        .join(wall, ReportedRun.wall_id == wall.id)
        .outerjoin(Fluid, ReportedRun.fluid_id == Fluid.id)
        .outerjoin(Source, ReportedRun.source_id == Source.id)
        .order_by(ReportedRun.collection, ReportedRun.id)
    )
    if collection is not None:
        query = query.where(ReportedRun.collection == collection)
    out = []
    for run, particle_name, wall_name, fluid_name, source_key in session.execute(query):
        record = {"collection": run.collection, "run": run.run}
        record.update(particle=particle_name, wall=wall_name, fluid=fluid_name)
        record.update({c: getattr(run, c) for c in STORED})
        record["source"] = source_key
        out.append(record)
    return out


def packages(session: Session) -> dict[str, str]:
    """The reference packages ("NAME VERSION") imported, each with its collection."""
    package = ReportedRun.__table__.c.reference_package
    query = select(package, ReportedRun.collection).where(package.is_not(None))
    return {str(package): collection for package, collection in session.execute(query)}


def collections(session: Session) -> list[str]:
    """The collections that hold reported runs."""
    query = select(ReportedRun.collection).distinct().order_by(ReportedRun.collection)
    return list(session.scalars(query))
