"""A dataset's content hash: the one definition.

The content hash identifies a dataset's measurements independently of database ids,
insertion order and backend: sha256 over the collisions sorted by run label (UTF-8 byte
order), each written as its run, its particle, wall and fluid names in canonical form
(``name_key``: case and runs of spaces do not count, as they do not when names are
matched, so 'GLASS' in a package and 'glass' here hash alike), its SI values in
``ALWAYS_HASHED`` order (``repr`` of the float, empty for none) and its notes, then the
target sphere's values (``TARGET_HASHED``) only when the row has any or has stated
uncertainties, then those uncertainties (``UNCERTAINTY_HASHED``) only when the row has
any (so datasets hashed before these columns existed keep their hash); fields separated by
``FIELD_SEPARATOR`` (U+001F), each row ended by ``ROW_SEPARATOR`` (U+001E). Two
databases (or a database and a Data Package) with the same hash hold the same runs with
the same values.

Hashes stored before names were canonical (granudb's first definition, names as spelled)
still identify their rows: ``recorded_hash_holds`` accepts a recorded hash under either
definition, so a release keeps the hash it was released (and perhaps cited) with.

Here it is computed from rows (read back from the database, or a package's table);
``granudb.db.bulk_hash`` computes the same bytes columnar from the arrays an import
inserts, from the constants below (tests hold the two equal).
"""

from __future__ import annotations

import hashlib
from collections.abc import Iterable, Iterator, Sequence
from typing import Any

from sqlalchemy import ColumnElement, select
from sqlalchemy.orm import Session, aliased

from granudb.db.models import Collision, Dataset, Fluid, Material
from granudb.errors import ConflictError
from granudb.vocabulary import COLLISION_MEASURED, COLLISION_TARGET, COLLISION_UNCERTAINTIES
from granudb.vocabulary.text import name_key

FIELD_SEPARATOR = "\x1f"
ROW_SEPARATOR = "\x1e"
#: The names that open every row, after the run label.
NAMES = ("particle", "wall", "fluid")
#: The SI columns every row carries, in order, before its notes.
ALWAYS_HASHED = tuple(
    c for c in COLLISION_MEASURED if c not in (*COLLISION_TARGET, *COLLISION_UNCERTAINTIES)
)
#: The target sphere's columns, after the notes, only in a row that has any of them (or
#: any stated uncertainty).
TARGET_HASHED = tuple(COLLISION_TARGET)
#: The stated uncertainties, last, only in a row that has any of them.
UNCERTAINTY_HASHED = tuple(COLLISION_UNCERTAINTIES)
_OPTIONAL = (*TARGET_HASHED, *UNCERTAINTY_HASHED)
_ROW = ("run", *NAMES, *ALWAYS_HASHED, "notes", *_OPTIONAL)


def content_hash(
    session: Session,
    dataset: Dataset,
    renamed: tuple[dict, dict] | None = None,
    *,
    spelled: bool = False,
) -> str:
    """The dataset's content hash (see the module docstring); with ``renamed`` (material
    and fluid names: {stored name: name to hash instead}), the hash of the same rows under
    other names (a package's own, before its names were matched here). ``spelled``: the
    first definition, names as spelled (hashes recorded before names were canonical)."""
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
            *(getattr(Collision, c) for c in ALWAYS_HASHED),
            Collision.notes,
            *(getattr(Collision, c) for c in _OPTIONAL),
        )
        .join(particle, Collision.particle_id == particle.id)
        .join(wall, Collision.wall_id == wall.id)
        .outerjoin(Fluid, Collision.fluid_id == Fluid.id)
        .where(Collision.dataset_id == dataset.id)
        .order_by(Collision.run.collate(collation)),
        execution_options={"yield_per": 20_000},
    )
    batches: Iterator[Sequence[Sequence[Any]]] = result.partitions()
    if renamed:
        materials, fluids = renamed
        batches = (
            [(r[0], materials.get(r[1], r[1]), materials.get(r[2], r[2]),
              fluids.get(r[3], r[3]), *r[4:]) for r in rows]
            for rows in batches
        )  # fmt: skip
    if not spelled:
        keys: dict[str, str] = {}  # a handful of names, a key each

        def key(name: str | None) -> str | None:
            if name is None:
                return None
            if name not in keys:
                keys[name] = name_key(name)
            return keys[name]

        batches = (
            [(r[0], key(r[1]), key(r[2]), key(r[3]), *r[4:]) for r in rows] for rows in batches
        )
    return hash_rows(batches)


def recorded_hash_holds(
    session: Session, dataset: Dataset, renamed: tuple[dict, dict] | None = None
) -> bool:
    """Do the dataset's rows still give its recorded ``content_hash`` (under today's
    definition, or the first one for a hash recorded before names were canonical)?"""
    recorded = dataset.content_hash
    if recorded is None:
        return False
    if content_hash(session, dataset, renamed) == recorded:
        return True
    return content_hash(session, dataset, renamed, spelled=True) == recorded


def hash_rows(batches: Iterable[Iterable[Sequence[object]]]) -> str:
    """sha256 of rows already in canonical order, each (run, particle, wall, fluid,
    *ALWAYS_HASHED, notes, *TARGET_HASHED, *UNCERTAINTY_HASHED), given in batches."""
    digest = hashlib.sha256()
    for rows in batches:
        text = "".join(FIELD_SEPARATOR.join(_canonical(row)) + ROW_SEPARATOR for row in rows)
        digest.update(text.encode("utf-8"))
    return digest.hexdigest()


def _canonical(row: Sequence[object]) -> list[str]:
    cells = ["" if v is None else repr(v) if type(v) is float else str(v) for v in row]
    stated = len(cells) - len(UNCERTAINTY_HASHED)
    if any(cells[stated:]):
        return cells
    kept = stated - len(TARGET_HASHED)
    return cells[:stated] if any(cells[kept:stated]) else cells[:kept]


def update_content_hash(session: Session, dataset: Dataset) -> str:
    dataset.content_hash = content_hash(session, dataset)
    session.flush()
    return dataset.content_hash


def rehash_drafts_naming(session: Session, kind: str, entry_id: int) -> list[str]:
    """Hash again every draft whose runs name the material or fluid ``entry_id`` (``kind``
    "material" or "fluid"), after its name changed: a draft's hash is over the names it
    reads today, so ``dataset show`` and its export agree. A released version keeps the
    name it was released with (``keep_for_releases``) and its hash. Returns the drafts'
    labels (NAME@VERSION)."""
    naming: ColumnElement[bool]
    if kind == "material":
        naming = (Collision.particle_id == entry_id) | (Collision.wall_id == entry_id)
    else:
        naming = Collision.fluid_id == entry_id
    drafts = session.scalars(
        select(Dataset)
        .where(Dataset.state == "draft")
        .where(Dataset.id.in_(select(Collision.dataset_id).where(naming)))
        .order_by(Dataset.id)
    ).all()
    for dataset in drafts:
        update_content_hash(session, dataset)
    return [f"{d.name}@{d.version}" for d in drafts]


def hash_problem(session: Session, dataset: Dataset) -> str | None:
    """Why a released (or superseded) version's rows no longer give its recorded content
    hash, in words; None when they do, and for a draft (a draft's hash follows its
    rows). Said by ``dataset show`` and by the export, which refuses such a release."""
    if dataset.state == "draft" or recorded_hash_holds(session, dataset):
        return None
    return _no_longer(dataset, content_hash(session, dataset))


def _no_longer(dataset: Dataset, now: str) -> str:
    recorded = str(dataset.content_hash or "none")
    return (
        f"its runs no longer give the content hash it was released with ({recorded[:16]}…; "
        f"now {now[:16]}…): stored values were dropped by a consented schema downgrade or "
        "changed outside granudb, so it can no longer be exported as that release"
    )


def export_hash(session: Session, dataset: Dataset) -> str:
    """The hash an export of ``dataset`` declares: the recorded one when its rows still
    give it (a release keeps the hash it was released with), else a draft's from its
    rows; a release whose rows no longer give it is refused (``hash_problem``)."""
    if dataset.content_hash is not None and recorded_hash_holds(session, dataset):
        return dataset.content_hash
    now = content_hash(session, dataset)
    if dataset.state != "draft":
        raise ConflictError(
            f"dataset {dataset.name}@{dataset.version}: {_no_longer(dataset, now)}; copy it "
            "to a new version (`granudb dataset new-version`) to export what it holds now; "
            "nothing was written"
        )
    return now
