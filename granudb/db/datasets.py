"""Datasets: finding or creating one, and its lifecycle.

Lifecycle (as Granta MI's record versions, Zenodo's versioned records): a version is a
``draft`` (runs may be imported, removed, metadata edited), then ``released`` (immutable:
nothing imported into it, no run removed, no metadata changed but a DOI set once, not
removed), then ``superseded`` once a newer version of the same name is released (it may
then be removed). Changes go into a new draft version copied from a released one.

The content hash is defined in ``granudb.db.content_hash``.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from sqlalchemy import Integer, delete, func, insert, literal, select
from sqlalchemy.orm import Session

from granudb.db.catalog_revisions import follow_live_rows
from granudb.db.content_hash import update_content_hash
from granudb.db.lookup_rows import dataset_row
from granudb.db.models import Collision, CollisionImport, Dataset, utcnow
from granudb.db.roles import require_curator
from granudb.errors import ConflictError, NotFoundError, ValidationError
from granudb.vocabulary.text import check_name

DEFAULT_VERSION = "1.0.0"


def _versions(session: Session, name: str) -> list[Dataset]:
    return list(session.scalars(select(Dataset).filter_by(name=name).order_by(Dataset.id)))


def get_dataset(session: Session, name: str, version: str | None = None) -> Dataset:
    """The dataset ``name`` at ``version`` (default: the most recently created version);
    found (and refused, with the known names or versions) by ``lookup_rows.dataset_row``."""
    found = dataset_row(session.connection(), name, version)
    dataset = session.get(Dataset, found.id)
    assert dataset is not None  # the same transaction just read it
    return dataset


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
        ensure_editable(found)
        return found, False
    check_dataset_name(name)
    check_version(version)
    dataset = Dataset(name=name, version=version, title=title, license=license, source_id=source_id)
    session.add(dataset)
    session.flush()
    return dataset, True


# --- lifecycle -------------------------------------------------------------------------

DRAFT, RELEASED, SUPERSEDED = "draft", "released", "superseded"


def label(dataset: Dataset) -> str:
    return f"{dataset.name}@{dataset.version}"


def ensure_editable(dataset: Dataset) -> None:
    """Refuse any change to a version that is no longer a draft (released or superseded):
    imports, run removal, metadata edits all call this first."""
    if dataset.state != DRAFT:
        raise ConflictError(
            f"dataset: {label(dataset)} is {dataset.state} and cannot change; make a new "
            f"draft with `granudb dataset new-version {label(dataset)} --version NEW`"
        )


def _counts(session: Session, model: type[Any], dataset: Dataset) -> int:
    query = select(func.count()).select_from(model).where(model.dataset_id == dataset.id)
    return session.scalar(query) or 0


def datasets_to_remove(session: Session, name: str, version: str | None) -> list[Dataset]:
    """The versions ``dataset remove NAME[@VERSION]`` deletes; a released version (one no
    newer release has superseded) is refused."""
    chosen = [get_dataset(session, name, version)] if version else _versions(session, name)
    if not chosen:
        get_dataset(session, name)  # raises NotFoundError naming the known datasets
    for dataset in chosen:
        if dataset.state == RELEASED:
            raise ConflictError(
                f"dataset: {label(dataset)} is released and cannot be removed; release a "
                f"newer version first (`granudb dataset new-version {label(dataset)} "
                "--version NEW`, then `granudb dataset release`)"
            )
        if dataset.state != DRAFT:
            require_curator(session.connection(), f"removing the {dataset.state} {label(dataset)}")
    return chosen


def removal_losses(session: Session, chosen: list[Dataset]) -> list[str]:
    """What removing ``chosen`` deletes, one phrase per version (for the confirmation):
    the id, name and version spelled out (``lab@2024`` version 1 and ``lab`` version
    ``2024@1`` read differently), the state and the run count."""
    return [
        f"dataset {label(d)} (id {d.id}: name {d.name!r}, version {d.version!r}, {d.state}) "
        f"with {_counts(session, Collision, d)} runs and "
        f"{_counts(session, CollisionImport, d)} import records"
        for d in chosen
    ]


def remove_datasets(session: Session, chosen: list[Dataset]) -> None:
    """Delete ``chosen`` with their runs and import records (explicitly, not relying on
    ON DELETE CASCADE, which SQLite honours only with foreign keys on)."""
    for dataset in chosen:
        session.execute(delete(Collision).where(Collision.dataset_id == dataset.id))
        session.execute(delete(CollisionImport).where(CollisionImport.dataset_id == dataset.id))
        session.delete(dataset)
    session.flush()


def runs_to_remove(session: Session, dataset: Dataset, runs: Sequence[str]) -> list[str]:
    """Check that every run label is in the (editable) dataset; returns them deduplicated."""
    ensure_editable(dataset)
    wanted = list(dict.fromkeys(runs))
    if not wanted:
        raise ValidationError("RUN", "(none)", "name at least one run to remove")
    found = set(
        session.scalars(
            select(Collision.run).where(
                Collision.dataset_id == dataset.id, Collision.run.in_(wanted)
            )
        )
    )
    missing = [r for r in wanted if r not in found]
    if missing:
        raise NotFoundError(
            f"run: {missing[0]!r} is not in dataset {label(dataset)}"
            + (f" (nor {len(missing) - 1} more)" if len(missing) > 1 else "")
        )
    return wanted


def remove_runs(session: Session, dataset: Dataset, runs: Sequence[str]) -> int:
    """Delete the runs (all must exist) and refresh the content hash; returns how many."""
    wanted = runs_to_remove(session, dataset, runs)
    session.execute(
        delete(Collision).where(Collision.dataset_id == dataset.id, Collision.run.in_(wanted))
    )
    update_content_hash(session, dataset)
    return len(wanted)


EDITABLE = ("title", "description", "license", "authors", "keywords", "doi")


def edit_dataset(
    session: Session, dataset: Dataset, values: dict[str, str | None]
) -> list[tuple[str, Any, Any]]:
    """Set metadata fields (already checked by the caller); returns (field, old, new) for
    each change. A released version takes only a DOI, and only while it has none (the
    DOI a repository mints when the version is published)."""
    unknown = set(values) - set(EDITABLE)
    if unknown:
        raise ValidationError(sorted(unknown)[0], "", "is not an editable dataset field")
    if dataset.state != DRAFT and not (set(values) == {"doi"} and dataset.doi is None):
        ensure_editable(dataset)
    if dataset.state != DRAFT:
        require_curator(session.connection(), f"setting the DOI of {label(dataset)}")
    diffs = []
    for field, new in values.items():
        old = getattr(dataset, field)
        if old != new:
            diffs.append((field, old, new))
            setattr(dataset, field, new)
    session.flush()
    return diffs


def release_dataset(session: Session, dataset: Dataset) -> list[Dataset]:
    """draft → released (content hash fixed); earlier released versions of the same name
    become superseded. Returns those superseded."""
    ensure_editable(dataset)
    if not _counts(session, Collision, dataset):
        raise ConflictError(f"dataset: {label(dataset)} has no runs; nothing to release")
    require_curator(session.connection(), f"releasing {label(dataset)}")
    superseded = [
        d for d in _versions(session, dataset.name) if d.state == RELEASED and d.id != dataset.id
    ]
    for older in superseded:
        older.state = SUPERSEDED
    dataset.state = RELEASED
    dataset.released_at = utcnow()
    update_content_hash(session, dataset)
    return superseded


_COPIED = [c.name for c in Collision.__table__.columns if c.name not in {"id", "dataset_id"}]
_METADATA = ["title", "description", "license", "source_id", "authors", "keywords"]


def new_version(session: Session, dataset: Dataset, version: str) -> Dataset:
    """A draft copy of ``dataset`` (metadata, runs, import records) as ``version``; the
    DOI is not copied (each version gets its own, as on Zenodo)."""
    check_version(version)
    if session.scalars(select(Dataset).filter_by(name=dataset.name, version=version)).first():
        raise ConflictError(f"dataset: {dataset.name}@{version} already exists")
    copy = Dataset(
        name=dataset.name,
        version=version,
        state=DRAFT,
        **{k: getattr(dataset, k) for k in _METADATA},
    )
    session.add(copy)
    session.flush()
    columns = [Collision.__table__.c[c] for c in _COPIED]
    session.execute(
        insert(Collision).from_select(
            ["dataset_id", *_COPIED],
            select(literal(copy.id, Integer), *columns).where(Collision.dataset_id == dataset.id),
        )
    )
    imports = ["file_sha256", "file_name", "rows", "imported_at"]
    session.execute(
        insert(CollisionImport).from_select(
            ["dataset_id", *imports],
            select(
                literal(copy.id, Integer),
                *(CollisionImport.__table__.c[c] for c in imports),
            ).where(CollisionImport.dataset_id == dataset.id),
        )
    )
    follow_live_rows(session, copy.id)  # a draft follows today's catalogue
    update_content_hash(session, copy)
    return copy


#: Separates a dataset's name from its version in ``NAME@VERSION``; refused inside new
#: names and versions so that every reference splits one way (datasets named before the
#: rule stay reachable with an explicit version).
VERSION_SEPARATOR = "@"


def check_version(version: str) -> str:
    check_name("--version", version, max_length=50)
    _no_separator("--version", version)
    return version


def check_dataset_name(name: str) -> str:
    """A new dataset's name: the shared name rules, and no ``@``."""
    check_name("--dataset", name, max_length=200)
    _no_separator("--dataset", name)
    return name


def _no_separator(field: str, value: str) -> None:
    if VERSION_SEPARATOR in value:
        raise ValidationError(
            field, value, f"must not contain '{VERSION_SEPARATOR}' (it separates NAME@VERSION)"
        )
