"""Sources and the numbers printed in them: who published what, and where.

Every stored number that came from a publication points to a ``Source`` plus the table or
figure it was printed in; ``published_records`` lists the numbers as printed.
"""

from __future__ import annotations

from typing import Any

from sqlalchemy import func, select
from sqlalchemy.orm import Session

# The record builders live with the Core reads (``catalog_rows``); re-exported here.
from granudb.db.catalog_rows import SOURCE_COLUMNS as SOURCE_COLUMNS
from granudb.db.catalog_rows import source_record as source_record
from granudb.db.models import Dataset, Fluid, Material, PublishedValue, Source
from granudb.errors import NotFoundError


def get_source(session: Session, key: str) -> Source:
    found = session.scalars(select(Source).filter_by(key=key)).one_or_none()
    if found is None:
        known = ", ".join(s.key for s in list_sources(session)) or "none yet"
        raise NotFoundError(f"source: {key!r} is not in the database (known: {known})")
    return found


def list_sources(session: Session) -> list[Source]:
    return list(session.scalars(select(Source).order_by(Source.key)))


def source_usage(session: Session, source: Source) -> dict[str, int]:
    """How many rows of each kind cite ``source``."""
    counts = {}
    for label, model in (
        ("materials", Material),
        ("fluids", Fluid),
        ("published_values", PublishedValue),
        ("datasets", Dataset),
    ):
        counts[label] = (
            session.scalar(
                select(func.count()).select_from(model).where(model.source_id == source.id)
            )
            or 0
        )
    return counts


def published_records(session: Session, source: Source | None = None) -> list[dict[str, Any]]:
    query = select(PublishedValue).order_by(PublishedValue.id)
    if source is not None:
        query = query.where(PublishedValue.source_id == source.id)
    return [
        {
            "source": pv.source.key,
            "source_locator": pv.source_locator,
            "label": pv.label,
            "quantity": pv.quantity,
            "value": pv.value,
            "uncertainty": pv.uncertainty,
            "value_as_printed": pv.value_as_printed,
            "particle": pv.particle.name if pv.particle else None,
            "wall": pv.wall.name if pv.wall else None,
            "fluid": pv.fluid.name if pv.fluid else None,
            "condition": pv.condition,
        }
        for pv in session.scalars(query)
    ]
