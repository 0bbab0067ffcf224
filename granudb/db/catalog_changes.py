"""Changing the catalogue: add, update and remove materials and fluids, add fluid points.

The same concept as ``granudb.api.catalog_changes`` seen from the database's side: there
the inputs are parsed and consent asked; here the rows are written.

One implementation serves both kinds of entry; what differs between a material and a
fluid is its specification (``granudb.vocabulary.MATERIALS`` / ``FLUIDS``) and which
stored rows refer to it (``REFERENCES`` below). Reads go through Core
(``granudb.db.catalog_rows``, the one read path of these tables): an entry is found by
name there, and only the row being changed is loaded as an ORM object, by its id.

Every function takes a ``Session`` (the caller owns the transaction) and SI values keyed
by column name; names match case-insensitively; a missing name is an error listing the
names that exist.
"""

from __future__ import annotations

from typing import Any

from sqlalchemy import func, or_, select
from sqlalchemy.orm import Session

from granudb.db import catalog_rows
from granudb.db.catalog_revisions import keep_for_releases, revisions
from granudb.db.content_hash import rehash_drafts_naming
from granudb.db.models import (
    Collision,
    Dataset,
    Fluid,
    FluidPoint,
    Material,
    PublishedValue,
    ReportedRun,
)
from granudb.db.upsert import Change
from granudb.errors import ConflictError, ValidationError
from granudb.vocabulary import Catalogue, check_record
from granudb.vocabulary.catalog import check_entry, check_words
from granudb.vocabulary.rules import same_value
from granudb.vocabulary.terms import stored
from granudb.vocabulary.text import check_name, name_key

#: What a fluid point stores besides its key (the temperature): its declared values and
#: their uncertainties.
_POINT_VALUES = [s.column for s in stored("fluid_points", uncertainties=True) if not s.keyed]

MODELS: dict[str, type] = {"material": Material, "fluid": Fluid}

#: The stored rows that refer to an entry of each kind: (column, the role it plays).
REFERENCES: dict[str, tuple[tuple[Any, str], ...]] = {
    "material": ((Collision.particle_id, "particle"), (Collision.wall_id, "wall")),
    "fluid": ((Collision.fluid_id, "fluid"),),
}
PUBLISHED_REFERENCES: dict[str, tuple[Any, ...]] = {
    "material": (PublishedValue.particle_id, PublishedValue.wall_id),
    "fluid": (PublishedValue.fluid_id,),
}


def check_entry_name(catalogue: Catalogue, name: str) -> str:
    """``name`` in NFC if it follows the shared name rules (``granudb.vocabulary.text``)
    and is not one of the kind's reserved names."""
    name = check_name(f"{catalogue.kind} name", name)
    reason = catalogue.reserved.get(name.casefold())
    if reason is not None:
        raise ValidationError(f"{catalogue.kind} name", name, reason)
    return name


def _entry(session: Session, catalogue: Catalogue, name: str) -> Any:
    """The ORM row of the entry called ``name`` (found through the Core read path)."""
    entry_id = catalog_rows.entry_id(session.connection(), catalogue.kind, name)
    return session.get(MODELS[catalogue.kind], entry_id)


def _check_fields(catalogue: Catalogue, values: dict[str, Any]) -> None:
    unknown = sorted(set(values) - catalogue.fields)
    if unknown:
        raise ValidationError(unknown[0], values[unknown[0]], f"is not a {catalogue.kind} field")
    check_record(values)
    check_words(catalogue, values)


def add_entry(
    session: Session, catalogue: Catalogue, name: str, values: dict[str, Any], source: str | None
) -> Any:
    """Add a material or fluid; refuses a name that exists (compared case-insensitively),
    a missing required property, and values that break a rule."""
    name = check_entry_name(catalogue, name)
    values = {**catalogue.defaults, **values}
    _check_fields(catalogue, values)
    for column in catalogue.required:
        if values.get(column) is None:
            raise ValidationError(column, "(missing)", f"is required to add a {catalogue.kind}")
    check_entry(catalogue, values)
    clash = catalog_rows.entry_name(session.connection(), catalogue.kind, name)
    if clash is not None:
        raise ConflictError(
            f"{catalogue.kind}: {name!r} already exists as {clash!r} "
            f"(use `granudb {catalogue.plural} update`)"
        )
    row = MODELS[catalogue.kind](name=name, name_key=name_key(name), **values)
    if source is not None:
        row.source_id = catalog_rows.source_id(session.connection(), source)
    session.add(row)
    session.flush()
    return row


def update_entry(
    session: Session,
    catalogue: Catalogue,
    name: str,
    values: dict[str, Any],
    source: str | None = None,
    new_name: str | None = None,
) -> Change:
    """Change the given fields of an entry (and its source or name); returns what changed,
    field by field."""
    _check_fields(catalogue, values)
    row = _entry(session, catalogue, name)
    label = f"{catalogue.kind} {row.name}"
    changed = {c: new for c, new in values.items() if not same_value(getattr(row, c), new)}
    diffs = [(column, getattr(row, column), new) for column, new in changed.items()]
    check_entry(catalogue, {c: changed.get(c, getattr(row, c)) for c in catalogue.properties})
    source_id = None if source is None else catalog_rows.source_id(session.connection(), source)
    if source_id is not None and row.source_id != source_id:
        diffs.append(("source", row.source.key if row.source else None, source))
    if new_name is not None and new_name != row.name:
        new_name = check_entry_name(catalogue, new_name)
        clash = catalog_rows.entry_name(session.connection(), catalogue.kind, new_name)
        if clash is not None and name_key(clash) != row.name_key:
            raise ConflictError(f"{catalogue.kind}: {new_name!r} already exists")
        diffs.append(("name", row.name, new_name))
    if not diffs:
        return Change("unchanged", label, diffs)
    keep_for_releases(session, catalogue.kind, row)  # a release keeps what it used
    for column, new in changed.items():
        setattr(row, column, new)
    if source_id is not None:
        row.source_id = source_id
    if new_name is not None and new_name != row.name:
        row.name, row.name_key = new_name, name_key(new_name)
        session.flush()
        rehash_drafts_naming(session, catalogue.kind, row.id)  # their runs read the new name
    session.flush()
    return Change("updated" if diffs else "unchanged", label, diffs)


def removal(session: Session, catalogue: Catalogue, name: str) -> list[str]:
    """What removing the entry deletes (for the confirmation); refuses one in use."""
    row = _unused(session, catalogue, name)
    if catalogue.kind == "fluid":
        points = session.scalar(
            select(func.count()).select_from(FluidPoint).where(FluidPoint.fluid_id == row.id)
        )
        return [f"fluid {row.name} with its {points} viscosity points"]
    return [f"{catalogue.kind} {row.name}"]


def remove_entry(session: Session, catalogue: Catalogue, name: str) -> str:
    """Delete an entry nothing refers to (a fluid with its points); returns its name."""
    row = _unused(session, catalogue, name)
    session.delete(row)
    session.flush()
    return row.name


def _unused(session: Session, catalogue: Catalogue, name: str) -> Any:
    row = _entry(session, catalogue, name)
    uses = []
    for column, role in REFERENCES[catalogue.kind]:
        counts = session.execute(
            select(Dataset.name, Dataset.version, func.count())
            .join(Collision, Collision.dataset_id == Dataset.id)
            .where(column == row.id)
            .group_by(Dataset.name, Dataset.version)
            .order_by(Dataset.name, Dataset.version)
        ).all()
        uses += [f"{n} collisions in dataset {d} {v} (as {role})" for d, v, n in counts]
    references = PUBLISHED_REFERENCES[catalogue.kind]
    published = session.scalar(
        select(func.count())
        .select_from(PublishedValue)
        .where(or_(*(column == row.id for column in references)))
    )
    if published:
        uses.append(f"{published} published values")
    reported = (
        (ReportedRun.particle_id, ReportedRun.wall_id)
        if catalogue.kind == "material"
        else (ReportedRun.fluid_id,)
    )
    runs = session.scalar(
        select(func.count()).select_from(ReportedRun).where(or_(*(c == row.id for c in reported)))
    )
    if runs:
        uses.append(f"{runs} runs as reported (granudb reported list)")
    if uses:
        raise ConflictError(
            f"{catalogue.kind}: {row.name!r} is still used by {'; '.join(uses)}; remove those first"
        )
    kept = len(revisions(session, catalogue.kind, row.id))
    if kept:
        raise ConflictError(
            f"{catalogue.kind}: {row.name!r} has {kept} revisions that released datasets "
            "keep (a release never changes); it cannot be removed"
        )
    return row


def add_fluid_points(
    session: Session,
    name: str,
    points: list[dict[str, Any]],
    source: str | None = None,
    *,
    replace: bool = False,
) -> list[str]:
    """Add measured (temperature, viscosity[, density]) points to a fluid; one line per
    point. A point at a temperature the fluid already has is refused, naming the stored
    value, unless ``replace`` (then the line says what it replaced): a stored number is
    never changed silently."""
    connection = session.connection()
    fluid = catalog_rows.get_fluid_row(connection, name)
    fluid_id = catalog_rows.entry_id(connection, "fluid", name)
    kept = False
    source_id = catalog_rows.source_id(connection, source) if source is not None else None
    stored = {
        p.temperature_c: p
        for p in session.scalars(select(FluidPoint).where(FluidPoint.fluid_id == fluid_id))
    }
    seen: set[float] = set()
    lines = []
    for index, point in enumerate(points, start=1):
        check_record(point, row=index)
        t = point["temperature_c"]
        if t in seen:
            raise ValidationError("temperature_c", f"{t:g} °C", "appears twice", row=index)
        seen.add(t)
        existing = stored.get(t)
        new = point["viscosity_pa_s"] * 1e3
        if not kept:
            keep_for_releases(session, "fluid", session.get(Fluid, fluid_id))
            kept = True
        if existing is not None and not replace:
            raise ConflictError(
                f"fluid {fluid.name}: a point at {t:g} °C exists already "
                f"({existing.viscosity_pa_s * 1e3:.4g} mPa·s); give --replace to change it"
            )
        if existing is None:
            existing = FluidPoint(fluid_id=fluid_id, temperature_c=t)
            session.add(existing)
            lines.append(f"added {fluid.name} at {t:g} °C: {new:.4g} mPa·s")
        else:
            old = existing.viscosity_pa_s * 1e3
            lines.append(f"replaced {fluid.name} at {t:g} °C: {old:.4g} → {new:.4g} mPa·s")
        for column in _POINT_VALUES:  # every declared value of a point but its key
            setattr(existing, column, point.get(column))
        existing.source_id = source_id
    session.flush()
    return lines
