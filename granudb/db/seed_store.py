"""Writing the seed data: idempotent upserts by natural key, every change reported.

A second load changes nothing; a changed value updates its row and is reported field by
field. Rows are never deleted by a load, so nothing a user added is lost. The records come
from ``granudb.io.seed.read_seed`` (the files people edit); the caller decides when to
load them (first use, ``granudb db seed``).
"""

from __future__ import annotations

from collections import Counter
from typing import Any

from sqlalchemy import select
from sqlalchemy.orm import Session

from granudb.db.models import Fluid, FluidPoint, Material, PublishedValue, Source, name_key
from granudb.db.upsert import Change, upsert
from granudb.errors import ValidationError


class _Resolver:
    """Looks up referenced rows by key or name while loading."""

    def __init__(self, session: Session) -> None:
        self.session = session

    def source(self, key: str | None, where: str) -> int | None:
        if key is None:
            return None
        found = self.session.scalars(select(Source.id).filter_by(key=key)).one_or_none()
        if found is None:
            raise ValidationError(where, key, "names no source in sources.toml")
        return found

    def named(self, model: type, name: str | None, where: str) -> int | None:
        if name is None:
            return None
        found = self.session.scalars(select(model.id).filter_by(name_key=name_key(name)))
        row = found.one_or_none()
        if row is None:
            raise ValidationError(where, name, f"names no {model.__tablename__[:-1]}")
        return row


def apply_seed(session: Session, data: Any) -> list[str]:
    """Write the seed records (``granudb.io.seed.SeedData``) by natural key.

    Returns one line per change plus a summary line; raises ``ValidationError`` (and the
    caller's transaction rolls back) if a record refers to something missing.
    """
    resolve = _Resolver(session)
    changes: list[Change] = []

    for entry in data.sources:
        values = {k: entry.get(k) for k in ("citation", "doi", "url", "year", "notes")}
        values["kind"] = entry.get("kind", "publication")
        changes.append(
            upsert(session, Source, {"key": entry["key"]}, values, f"source {entry['key']}")[1]
        )

    for row in (dict(r) for r in data.materials):
        name = row.pop("name")
        row["source_id"] = resolve.source(row.pop("source"), f"materials.csv {name}")
        changes.append(
            upsert(
                session,
                Material,
                {"name_key": name_key(name)},
                {"name": name, **row},
                f"material {name}",
            )[1]
        )

    for row in (dict(r) for r in data.fluids):
        name = row.pop("name")
        for prefix in ("", "density_", "pressure_viscosity_"):
            row[f"{prefix}source_id"] = resolve.source(
                row.pop(f"{prefix}source"), f"fluids.csv {name}"
            )
        changes.append(
            upsert(
                session, Fluid, {"name_key": name_key(name)}, {"name": name, **row}, f"fluid {name}"
            )[1]
        )

    if data.points:
        for row in (dict(r) for r in data.points):
            fluid = row.pop("fluid")
            fluid_id = resolve.named(Fluid, fluid, "fluid_points.csv fluid")
            row["source_id"] = resolve.source(row.pop("source"), "fluid_points.csv")
            key = {"fluid_id": fluid_id, "temperature_c": row.pop("temperature_c")}
            label = f"fluid point {fluid} at {key['temperature_c']:g} °C"
            changes.append(upsert(session, FluidPoint, key, row, label)[1])

    for row in (dict(r) for r in data.published):
        where = f"published_values.csv {row['label']}"
        key = {
            "source_id": resolve.source(row.pop("source"), where),
            "label": row.pop("label"),
            "quantity": row.pop("quantity"),
        }
        row["particle_id"] = resolve.named(Material, row.pop("particle"), where)
        row["wall_id"] = resolve.named(Material, row.pop("wall"), where)
        row["fluid_id"] = resolve.named(Fluid, row.pop("fluid"), where)
        label = f"published value {key['label']} / {key['quantity']}"
        changes.append(upsert(session, PublishedValue, key, row, label)[1])

    session.flush()
    return summarize(changes)


def summarize(changes: list[Change]) -> list[str]:
    """One line per update, then a count of what was added, updated and left alone."""
    lines = [c.describe() for c in changes if c.action == "updated"]
    counts = Counter(c.action for c in changes)
    lines.append(
        f"seed: {counts['added']} added, {counts['updated']} updated, "
        f"{counts['unchanged']} unchanged"
    )
    return lines
