"""Datasets: finding or creating one, and its content hash.

The content hash identifies a dataset's measurements independently of database ids,
insertion order and backend: sha256 over the collisions sorted by run label (UTF-8 byte
order), each written as its run, particle, wall and fluid names and its SI values in
``COLUMNS`` order (``repr`` of the float, empty for none), fields separated by U+001F and
rows by U+001E. Two databases (or a database and a Data Package) with the same hash hold
the same runs with the same values.
"""

from __future__ import annotations

import hashlib
from collections.abc import Iterable, Sequence
from typing import Any

from sqlalchemy import select
from sqlalchemy.orm import Session, aliased

from granudb.db.models import Collision, Dataset, Fluid, Material
from granudb.errors import NotFoundError, ValidationError
from granudb.vocabulary import COLLISION_MEASURED as COLUMNS
from granudb.vocabulary import COLLISION_TARGET

#: How many of ``COLUMNS`` every hashed row carries; the target sphere's velocities follow
#: only when a row has any, so datasets hashed before they existed keep their hash.
_ALWAYS_HASHED = len(COLUMNS) - len(COLLISION_TARGET)
DEFAULT_VERSION = "1.0.0"


def _versions(session: Session, name: str) -> list[Dataset]:
    return list(session.scalars(select(Dataset).filter_by(name=name).order_by(Dataset.id)))


def get_dataset(session: Session, name: str, version: str | None = None) -> Dataset:
    """The dataset ``name`` at ``version`` (default: the most recently created version)."""
    versions = _versions(session, name)
    if not versions:
        known = ", ".join(sorted({d.name for d in session.scalars(select(Dataset))})) or "none yet"
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


def get_or_create_dataset(
    session: Session,
    name: str,
    version: str = DEFAULT_VERSION,
    *,
    title: str | None = None,
    license: str | None = None,
    source_id: int | None = None,
) -> tuple[Dataset, bool]:
    """The dataset (name, version), created if new; returns (dataset, created)."""
    if not name or not name.strip() or len(name) > 200 or any(ord(c) < 32 for c in name):
        raise ValidationError("--dataset", repr(name), "must be 1–200 printable characters")
    if not version or len(version) > 50 or any(ord(c) < 32 for c in version):
        raise ValidationError("--version", repr(version), "must be 1–50 printable characters")
    found = session.scalars(select(Dataset).filter_by(name=name, version=version)).first()
    if found is not None:
        return found, False
    dataset = Dataset(name=name, version=version, title=title, license=license, source_id=source_id)
    session.add(dataset)
    session.flush()
    return dataset, True


def content_hash(session: Session, dataset: Dataset) -> str:
    """The dataset's content hash (see the module docstring)."""
    particle, wall = aliased(Material), aliased(Material)
    # Byte order of the UTF-8 run labels, on every backend (SQLite's BINARY collation,
    # PostgreSQL's "C"), streamed so a million runs hash in bounded memory.
    collation = "C" if session.get_bind().dialect.name == "postgresql" else "BINARY"
    result = session.connection().execute(
        select(
            Collision.run,
            particle.name,
            wall.name,
            Fluid.name,
            *(getattr(Collision, c) for c in COLUMNS),
            Collision.notes,
        )
        .join(particle, Collision.particle_id == particle.id)
        .join(wall, Collision.wall_id == wall.id)
        .outerjoin(Fluid, Collision.fluid_id == Fluid.id)
        .where(Collision.dataset_id == dataset.id)
        .order_by(Collision.run.collate(collation)),
        execution_options={"yield_per": 20_000},
    )
    return hash_rows(result.partitions())


def hash_rows(batches: Iterable[Iterable[Sequence[object]]]) -> str:
    """sha256 of rows already in canonical order, (run, particle, wall, fluid, *COLUMNS,
    notes), given in batches."""
    digest = hashlib.sha256()
    for rows in batches:
        text = "".join("\x1f".join(_canonical(row)) + "\x1e" for row in rows)
        digest.update(text.encode("utf-8"))
    return digest.hexdigest()


def _canonical(row: Sequence[object]) -> list[str]:
    cells = ["" if v is None else repr(v) if type(v) is float else str(v) for v in row]
    first_target = 4 + _ALWAYS_HASHED
    target = cells[first_target : first_target + len(COLLISION_TARGET)]
    kept = cells[:first_target] + [cells[-1]]
    return kept + target if any(target) else kept


def hash_frame(frame: Any) -> str:
    """The content hash of collisions given by name in a DataFrame (a package's table)."""
    import math

    columns = ["run", "particle", "wall", "fluid", *COLUMNS, "notes"]
    values = [frame[c].tolist() if c in frame else [None] * len(frame) for c in columns]
    order = sorted(range(len(frame)), key=lambda i: str(values[0][i]).encode("utf-8"))
    rows = (
        [None if isinstance(v, float) and math.isnan(v) else v for v in (c[i] for c in values)]
        for i in order
    )
    return hash_rows([rows])


def update_content_hash(session: Session, dataset: Dataset) -> str:
    dataset.content_hash = content_hash(session, dataset)
    session.flush()
    return dataset.content_hash
