"""A release never changes: the catalogue values a released dataset used are kept.

When a material or fluid that a released or superseded dataset's runs use is about to
change (``materials update``, ``fluids update``, a fluid point added or removed, ``db
seed``), ``keep_for_releases`` first copies the row as it is into a *revision* — the same
name, ``revision_of`` the live row, a name key no lookup matches — with a fluid's points,
and points those runs at the revision. Everything computed or exported for the release
reads its runs' rows by id, so its package, report numbers, DEM deck and content hash stay
what they were; drafts keep following the live row. Listings show live rows only;
``revisions`` lists a row's history.
"""

from __future__ import annotations

from typing import Any

from sqlalchemy import func, or_, select, update
from sqlalchemy.orm import Session

from granudb.db.models import (
    Collision,
    Dataset,
    Fluid,
    FluidPoint,
    Material,
    SourceRevision,
    utcnow,
)

#: Separates a revision's name key from its number: a control character, which no name
#: may contain, so no lookup by name ever finds a revision.
REVISION_MARK = "\x1f"
_MODELS: dict[str, type[Material] | type[Fluid]] = {"material": Material, "fluid": Fluid}
_RUN_COLUMNS = {
    "material": (Collision.particle_id, Collision.wall_id),
    "fluid": (Collision.fluid_id,),
}
_NOT_COPIED = {"id", "name_key", "revision_of", "updated_at"}


def _frozen_runs(kind: str, row_id: int) -> Any:
    frozen = select(Dataset.id).where(Dataset.state != "draft")
    uses = or_(*(column == row_id for column in _RUN_COLUMNS[kind]))
    return uses & Collision.dataset_id.in_(frozen)


def keep_for_releases(session: Session, kind: str, row: Any) -> Any | None:
    """Before ``row`` (a live material or fluid) changes: if released runs use it, keep
    its values as a revision and point those runs at it; returns the revision (or None
    when no release uses the row)."""
    used = session.scalar(
        select(func.count()).select_from(Collision).where(_frozen_runs(kind, row.id))
    )
    if not used:
        return None
    model = _MODELS[kind]
    number = 1 + (
        session.scalar(select(func.count()).select_from(model).where(model.revision_of == row.id))
        or 0
    )
    values = {
        c.key: getattr(row, c.key) for c in model.__table__.columns if c.key not in _NOT_COPIED
    }
    revision = model(
        **values,
        name_key=f"{row.name_key}{REVISION_MARK}revision {number}",
        revision_of=row.id,
        updated_at=utcnow(),
    )
    session.add(revision)
    session.flush()
    if kind == "fluid":
        for point in session.scalars(select(FluidPoint).where(FluidPoint.fluid_id == row.id)):
            copied = {
                c.key: getattr(point, c.key)
                for c in FluidPoint.__table__.columns
                if c.key not in {"id", "fluid_id"}
            }
            session.add(FluidPoint(**copied, fluid_id=revision.id))
    for column in _RUN_COLUMNS[kind]:
        session.execute(
            update(Collision)
            .where(column == row.id, Collision.dataset_id.in_(
                select(Dataset.id).where(Dataset.state != "draft")))
            .values({column.key: revision.id})
        )  # fmt: skip
    session.flush()
    return revision


def follow_live_rows(session: Session, dataset_id: int) -> None:
    """Point a draft's runs at the live rows of the revisions they use (a new version
    copied from a release follows today's catalogue)."""
    for kind, columns in _RUN_COLUMNS.items():
        model = _MODELS[kind]
        for column in columns:
            live = select(model.revision_of).where(model.id == column).scalar_subquery()
            revised = select(model.id).where(model.revision_of.is_not(None))
            session.execute(
                update(Collision)
                .where(Collision.dataset_id == dataset_id, column.in_(revised))
                .values({column.key: live})
            )
    session.flush()


def revisions(session: Session, kind: str, row_id: int) -> list[Any]:
    """The revisions of a live row, oldest first."""
    model = _MODELS[kind]
    return list(
        session.scalars(select(model).where(model.revision_of == row_id).order_by(model.id))
    )


def keep_source_revision(
    session: Session, source_id: int, before: dict[str, Any], reason: str
) -> SourceRevision:
    """Keep a source's values ``before`` one change (its ``source_record``), with the time
    and ``reason``: a release reads its sources as they were when it was released
    (``catalog_rows.sources_as_of``), and ``sources history`` lists the changes."""
    revision = SourceRevision(source_id=source_id, **before, kept_at=utcnow(), reason=reason)
    session.add(revision)
    session.flush()
    return revision
