"""The dataset catalogue: what each dataset holds, and how two versions differ."""

from __future__ import annotations

import json
from typing import Any

from sqlalchemy import func, select
from sqlalchemy.orm import Session, aliased

from granudb.db.catalog_differences import sources_read
from granudb.db.models import Collision, Dataset, Fluid, Material
from granudb.vocabulary import COLLISION_MEASURED as COLUMNS
from granudb.vocabulary.listings import DATASET_DESCRIPTION
from granudb.vocabulary.rules import same_value

COMPARED = ["particle_id", "wall_id", "fluid_id", *COLUMNS, "notes"]


def _runs(session: Session) -> dict[int, int]:
    rows = session.execute(
        select(Collision.dataset_id, func.count()).group_by(Collision.dataset_id)
    ).all()
    return dict(rows)


def dataset_records(session: Session) -> list[dict[str, Any]]:
    runs = _runs(session)
    return [
        {
            "id": d.id,
            "name": d.name,
            "version": d.version,
            "state": d.state,
            "title": d.title,
            "runs": runs.get(d.id, 0),
            "content_hash": d.content_hash,
            "license": d.license,
            "source": d.source.key if d.source else None,
        }
        for d in session.scalars(select(Dataset).order_by(Dataset.name, Dataset.version))
    ]


def dataset_record(session: Session, dataset: Dataset) -> dict[str, Any]:
    runs = (
        session.scalar(
            select(func.count()).select_from(Collision).where(Collision.dataset_id == dataset.id)
        )
        or 0
    )
    return {
        **{field: getattr(dataset, field) for field in DATASET_DESCRIPTION},
        "state": dataset.state,
        "released_at": dataset.released_at,
        "doi": dataset.doi,
        "authors": json.loads(dataset.authors) if dataset.authors else [],
        "keywords": json.loads(dataset.keywords) if dataset.keywords else [],
        "source": dataset.source.key if dataset.source else None,
        # a release cites its source as it was when released
        "citation": (
            sources_read(session.connection(), dataset.id)[dataset.source.key].citation
            if dataset.source
            else None
        ),
        "content_hash": dataset.content_hash,
        "runs": runs,
        "created_at": dataset.created_at,
        "updated_at": dataset.updated_at,
    }


def group_counts(session: Session, dataset: Dataset) -> list[dict[str, Any]]:
    """Runs by (particle, wall, fluid) — "dry" where there is no fluid."""
    particle, wall = aliased(Material), aliased(Material)
    rows = session.execute(
        select(particle.name, wall.name, Fluid.name, func.count())
        .select_from(Collision)
        .join(particle, Collision.particle_id == particle.id)
        .join(wall, Collision.wall_id == wall.id)
        .outerjoin(Fluid, Collision.fluid_id == Fluid.id)
        .where(Collision.dataset_id == dataset.id)
        .group_by(particle.name, wall.name, Fluid.name)
        .order_by(particle.name, wall.name, Fluid.name)
    ).all()
    return [{"particle": p, "wall": w, "fluid": f or "dry", "runs": n} for p, w, f, n in rows]


def _live_ids(session: Session, model: Any) -> dict[int, int]:
    """{revision id: its live row's id} of a catalogue table."""
    query = select(model.id, model.revision_of).where(model.revision_of.is_not(None))
    return {row_id: live for row_id, live in session.execute(query)}


def diff_datasets(session: Session, first: Dataset, second: Dataset) -> list[dict[str, Any]]:
    """Runs added in ``second``, removed from ``first``, and changed (field by field)."""

    # A release's runs point at the revisions it keeps: runs are compared by the live
    # rows, the catalogue values themselves by ``catalog_differences.catalogue_diff``.
    live = {
        "particle_id": _live_ids(session, Material),
        "wall_id": _live_ids(session, Material),
        "fluid_id": _live_ids(session, Fluid),
    }

    def load(dataset: Dataset) -> dict[str, dict[str, Any]]:
        rows = session.execute(
            select(Collision.run, *(getattr(Collision, c) for c in COMPARED)).where(
                Collision.dataset_id == dataset.id
            )
        ).all()
        found = {}
        for row in rows:
            values = dict(zip(COMPARED, row[1:], strict=True))
            for column, ids in live.items():
                values[column] = ids.get(values[column], values[column])
            found[row[0]] = values
        return found

    before, after = load(first), load(second)
    changes: list[dict[str, Any]] = []
    for run in sorted(after.keys() - before.keys()):
        changes.append({"change": "added", "run": run, "fields": ""})
    for run in sorted(before.keys() - after.keys()):
        changes.append({"change": "removed", "run": run, "fields": ""})
    for run in sorted(before.keys() & after.keys()):
        differing = [c for c in COMPARED if not same_value(before[run][c], after[run][c])]
        if differing:
            changes.append({"change": "changed", "run": run, "fields": ", ".join(differing)})
    order = {"added": 0, "removed": 1, "changed": 2}
    return sorted(changes, key=lambda c: (order[c["change"]], c["run"]))
