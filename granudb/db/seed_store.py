"""Writing the seed data: idempotent upserts by natural key, every change reported.

A second load changes nothing; a changed value updates its row and is reported field by
field. Rows are never deleted by a load, so nothing a user added is lost, and a value the
user changed is never reverted: each seeded row's values are recorded in
``seed_records``, and a value that differs from what the seed last wrote (or from a row
with no record, as in a database seeded before records existed) is the user's. It is
kept and the difference reported, unless ``overwrite_edits`` is set; a seeded row the
user removed or renamed is not added back either. The records come
from ``granudb.io.seed.read_seed`` (the files people edit); the caller decides when to
load them (first use, ``granudb db seed``).
"""

from __future__ import annotations

import json
from collections import Counter
from typing import Any

from sqlalchemy import select
from sqlalchemy.orm import Session

from granudb.db.catalog_revisions import keep_for_releases, keep_source_revision
from granudb.db.catalog_rows import source_record
from granudb.db.models import (
    Fluid,
    FluidPoint,
    Material,
    PairValue,
    PublishedValue,
    SeedRecord,
    Source,
    name_key,
)
from granudb.db.upsert import Change
from granudb.errors import ValidationError
from granudb.vocabulary.rules import same_value
from granudb.vocabulary.terms import keyed

#: What keys a fluid point within its fluid (its temperature).
_POINT_KEYS = keyed("fluid_points")


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

    def named(self, model: type[Any], name: str | None, where: str) -> int | None:
        if name is None:
            return None
        found = self.session.scalars(select(model.id).filter_by(name_key=name_key(name)))
        row = found.one_or_none()
        if row is None:
            row = self._renamed(model, name)
        if row is None:
            raise ValidationError(where, name, f"names no {model.__tablename__[:-1]}")
        return row

    def _renamed(self, model: type[Any], name: str) -> int | None:
        """The id of a seeded row the user renamed since (its seed record remembers it)."""
        record = self.session.scalars(
            select(SeedRecord).filter_by(
                table_name=model.__tablename__, seed_key=_seed_key(model, {"k": name_key(name)})
            )
        ).one_or_none()
        row_id = json.loads(record.seeded_values).get("_id") if record is not None else None
        return row_id if row_id is not None and self.session.get(model, row_id) else None


def apply_seed(session: Session, data: Any, *, overwrite_edits: bool = False) -> list[str]:
    """Write the seed records (``granudb.io.seed.SeedData``) by natural key.

    Returns one line per change (and per user edit kept or reverted) plus a summary line;
    raises ``ValidationError`` (and the caller's transaction rolls back) if a record
    refers to something missing.
    """
    resolve = _Resolver(session)
    changes: list[Change] = []

    def upsert(
        session: Session, model: type[Any], key: dict[str, Any], values: dict[str, Any], label: str
    ) -> tuple[None, Change]:
        return None, _seed_row(session, model, key, values, label, overwrite_edits)

    for entry in data.sources:
        values = {k: entry.get(k) for k in ("citation", "doi", "url", "year", "notes")}
        values["kind"] = entry.get("kind", "publication")
        existing = session.scalars(select(Source).filter_by(key=entry["key"])).one_or_none()
        before = None if existing is None else source_record(existing)
        change = upsert(session, Source, {"key": entry["key"]}, values, f"source {entry['key']}")[1]
        if existing is not None and before is not None and change.action in ("updated", "reverted"):
            reason = {"updated": "db seed: the seed's sources changed",
                      "reverted": "db seed --overwrite-edits: a user's edit reverted to the "
                                  "seed"}[change.action]  # fmt: skip
            keep_source_revision(session, existing.id, before, reason)
        changes.append(change)

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
            key = {"fluid_id": fluid_id, **{c: row.pop(c) for c in _POINT_KEYS}}
            label = f"fluid point {fluid} at {key[_POINT_KEYS[0]]:g} °C"
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

    for row in (dict(r) for r in data.pairs):
        pair = f"{row['particle']} on {row['wall']}"
        where = f"pair_values.csv {pair}"
        key = {
            "particle_id": resolve.named(Material, row.pop("particle"), where),
            "wall_id": resolve.named(Material, row.pop("wall"), where),
        }
        row["source_id"] = resolve.source(row.pop("source"), where)
        changes.append(upsert(session, PairValue, key, row, f"pair values {pair}")[1])

    session.flush()
    return summarize(changes)


def _seed_key(model: type[Any], key: dict[str, Any]) -> str:
    return json.dumps([key[k] for k in sorted(key)], ensure_ascii=False)


def _seed_row(
    session: Session,
    model: type[Any],
    key: dict[str, Any],
    values: dict[str, Any],
    label: str,
    overwrite_edits: bool,
) -> Change:
    """Insert or update one seeded row, keeping every value the user changed."""
    table = model.__tablename__
    record = session.scalars(
        select(SeedRecord).filter_by(table_name=table, seed_key=_seed_key(model, key))
    ).one_or_none()
    row = session.scalars(select(model).filter_by(**key)).one_or_none()
    change: Change
    if row is None and record is not None and not overwrite_edits:
        return Change("kept", label, [("(row)", "removed or renamed by you", "seeded")])
    if row is None:
        _keep_for_releases(session, model, key, None)
        row = model(**key, **values)
        session.add(row)
        session.flush()
        change = Change("reverted" if record is not None else "added", label)
        if record is not None:
            change.diffs.append(("(row)", "removed or renamed by you", "added again"))
    else:
        recorded = json.loads(record.seeded_values) if record is not None else {}
        applied, kept = [], []
        for name, new in values.items():
            old = getattr(row, name)
            if same_value(old, new):
                continue
            edited = name not in recorded or not same_value(old, recorded[name])
            if edited and not overwrite_edits:
                kept.append((name, old, new))
                continue
            applied.append((name, old, new, edited))
        if applied:
            _keep_for_releases(session, model, key, row)
        for name, _, new, _ in applied:
            setattr(row, name, new)
        if any(edited for *_, edited in applied):
            change = Change("reverted", label, [a[:3] for a in applied])
        elif applied:
            change = Change("updated", label, [a[:3] for a in applied])
        else:
            change = Change("kept" if kept else "unchanged", label, kept)
        if kept and change.action != "kept":
            change.diffs += [(f"{n} (kept)", o, v) for n, o, v in kept]
    seeded = json.dumps({**values, "_id": row.id}, ensure_ascii=False, default=str)
    if record is None:
        session.add(
            SeedRecord(table_name=table, seed_key=_seed_key(model, key), seeded_values=seeded)
        )
    else:
        record.seeded_values = seeded
    session.flush()
    return change


def _describe(change: Change) -> str:
    parts = ", ".join(f"{name} {old!r} → {new!r}" for name, old, new in change.diffs)
    if change.action == "kept":
        shown = ", ".join(f"{n} {o!r} (seed: {v!r})" for n, o, v in change.diffs)
        return (
            f"kept your edit of {change.label}: {shown}; `granudb db seed "
            "--overwrite-edits` takes the seed's"
        )
    if change.action == "reverted":
        return f"reverted your edit of {change.label}: {parts}"
    return f"updated {change.label}: {parts}"


def summarize(changes: list[Change]) -> list[str]:
    """One line per update, kept edit and reverted edit, then the counts."""
    lines = [_describe(c) for c in changes if c.action in {"updated", "kept", "reverted"}]
    counts = Counter(c.action for c in changes)
    extra = "".join(f", {counts[a]} of your edits {a}" for a in ("kept", "reverted") if counts[a])
    lines.append(
        f"seed: {counts['added']} added, {counts['updated']} updated, "
        f"{counts['unchanged']} unchanged{extra}"
    )
    return lines


def _keep_for_releases(session: Session, model: type[Any], key: dict[str, Any], row: Any) -> None:
    """Before the seed changes a material, a fluid or a fluid's points, keep what a
    release used (``granudb.db.catalog_revisions``)."""
    if model is Material and row is not None:
        keep_for_releases(session, "material", row)
    elif model is Fluid and row is not None:
        keep_for_releases(session, "fluid", row)
    elif model is FluidPoint:
        keep_for_releases(session, "fluid", session.get(Fluid, key["fluid_id"]))
