"""Storing a validated Data Package: merge its sources, materials and fluids, add its runs.

``granudb.io.package_import`` parses and validates; everything that reads or writes the
database happens here, in one write transaction, so a refusal at any step (a conflict, a
dataset that exists) leaves the database exactly as it was.

Merging is by name (case-insensitive, as everywhere in granudb): an identical row is
reused; a row with the same name and different values is a conflict, reported field by
field, and only resolved by ``rename_conflicts`` (the package's row comes in under
``NAME (package)``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from datetime import datetime
from typing import Any

import numpy as np
from sqlalchemy import select
from sqlalchemy.orm import Session

from granudb.db.bulk_insert import CollisionChunk, NameColumn
from granudb.db.catalog_rows import source_record
from granudb.db.collision_store import FirstProblem, FluidRanges, insert_collisions
from granudb.db.content_hash import content_hash, update_content_hash
from granudb.db.datasets import RELEASED, SUPERSEDED, check_dataset_name, check_version
from granudb.db.models import Dataset, Fluid, FluidPoint, Material, Source, name_key, utcnow
from granudb.db.roles import require_curator
from granudb.errors import ConflictError
from granudb.vocabulary.rules import same_value
from granudb.vocabulary.terms import stored as declared
from granudb.vocabulary.text import MAX_NAME

#: Every column a fluid point stores (its key, values and their uncertainties).
_POINT_STORED = [s.column for s in declared("fluid_points", uncertainties=True)]

FLUID_SOURCES = {
    "source": "source_id",
    "density_source": "density_source_id",
    "pressure_viscosity_source": "pressure_viscosity_source_id",
}


@dataclass(frozen=True)
class PackageContent:
    """What a validated package brings: dataset metadata and its SI tables (frames)."""

    dataset: str
    version: str
    package: str
    title: str | None
    description: str | None
    license: str | None
    doi: str | None
    tables: dict[str, Any]
    #: The dataset's authors and keywords as stored (JSON text), its own source's key,
    #: "draft" or "released", and its creation time (None: now).
    authors: str | None = None
    keywords: str | None = None
    source: str | None = None
    status: str = "draft"
    created: datetime | None = None


@dataclass
class PackageImport:
    """What an import did: the dataset, its rows and hash, and what was merged how."""

    dataset: str
    version: str
    rows: int
    content_hash: str
    reused: list[str] = field(default_factory=list)
    added: list[str] = field(default_factory=list)
    renamed: list[str] = field(default_factory=list)
    declared_hash: str | None = None


class HashMismatch(ConflictError):
    """The collisions as stored do not give the content hash the package declares."""


class MergeConflict(ConflictError):
    """Names in the package that exist here with other values; ``conflicts`` lists them."""

    def __init__(self, conflicts: list[str]) -> None:
        self.conflicts = conflicts
        super().__init__("; ".join(conflicts))


def records(frame: Any) -> list[dict[str, Any]]:
    """Rows of a validated frame as dicts with None for missing values."""
    return [
        {k: (None if isinstance(v, float) and math.isnan(v) else v) for k, v in r.items()}
        for r in frame.to_dict("records")
    ]


def _differences(existing: dict[str, Any], incoming: dict[str, Any]) -> list[str]:
    return [
        f"{k}: {existing.get(k)!r} here, {v!r} in the package"
        for k, v in incoming.items()
        if not same_value(existing.get(k), v)
    ]


def _point_differences(existing: Fluid, points: list[dict[str, Any]]) -> list[str]:
    names = _POINT_STORED
    here = sorted(tuple(getattr(p, n) for n in names) for p in existing.points)
    there = sorted(tuple(p.get(n) for n in names) for p in points)
    if len(here) == len(there) and not any(
        _differences(dict(zip(names, a, strict=True)), dict(zip(names, b, strict=True)))
        for a, b in zip(here, there, strict=True)
    ):
        return []
    return [
        f"viscosity points: {len(here)} here, {len(there)} in the package, with different values"
    ]


def renamed(name: str, tag: str, number: int | None = None, limit: int = MAX_NAME) -> str:
    """``NAME (tag)`` or ``NAME (tag number)`` within the name rule's ``limit`` characters:
    a long tag and then a long name are shortened with "…" (the number never is, so each
    candidate differs), and granudb never builds a name it would refuse.

    >>> len(renamed("m" * 200, "p" * 200, 12))
    200
    >>> renamed("steel", "lab", 2)
    'steel (lab 2)'
    """
    count = f" {number}" if number is not None else ""
    suffix = f" ({tag}{count})"
    if len(name) + len(suffix) <= limit:
        return name + suffix
    if len(suffix) > limit // 2:
        suffix = f" ({tag[: limit // 2 - 5 - len(count)].rstrip()}…{count})"
    return name[: limit - len(suffix) - 1].rstrip() + "…" + suffix


class Merger:
    """Matches the package's sources, materials and fluids against the database."""

    def __init__(self, session: Session, package: str, rename_conflicts: bool) -> None:
        self.session = session
        self.package = package
        self.rename = rename_conflicts
        self.conflicts: list[str] = []
        self.result = PackageImport("", "", 0, "")
        self.source_ids: dict[str, int] = {}

    def _renamed(self, model: type[Any], name: str) -> str:
        candidate = renamed(name, self.package)
        number = 2
        while self.session.scalars(
            select(model.id).filter_by(name_key=name_key(candidate))
        ).first():
            candidate = renamed(name, self.package, number)
            number += 1
        return candidate

    def sources(self, rows: list[dict[str, Any]]) -> None:
        for row in rows:
            existing = self.session.scalars(select(Source).filter_by(key=row["key"])).first()
            values = {**row, "year": None if row["year"] is None else int(row["year"])}
            if existing is None:
                source = Source(**values)
                self.session.add(source)
                self.session.flush()
                self.source_ids[row["key"]] = source.id
                self.result.added.append(f"source {row['key']}")
                continue
            diffs = _differences(source_record(existing), values)
            if diffs:
                self.conflicts.append(f"source {row['key']}: " + "; ".join(diffs))
            self.source_ids[row["key"]] = existing.id

    def _source(self, key: str | None) -> int | None:
        return None if key is None else self.source_ids[key]

    def _match(
        self, kind: str, model: type[Any], name: str, values: dict[str, Any], points: Any
    ) -> tuple[int | None, str | None]:
        """(id of an identical row, None) or (None, the name to add the row under)."""
        existing = self.session.scalars(select(model).filter_by(name_key=name_key(name))).first()
        if existing is None:
            self.result.added.append(f"{kind} {name}")
            return None, name
        diffs = _differences({k: getattr(existing, k) for k in values}, values)
        if points is not None:
            diffs += _point_differences(existing, points)
        if not diffs:
            self.result.reused.append(f"{kind} {existing.name}")
            return existing.id, None
        if not self.rename:
            self.conflicts.append(f"{kind} {name}: " + "; ".join(diffs))
            return None, None
        new_name = self._renamed(model, name)
        self.result.renamed.append(f"{kind} {name} → {new_name}")
        return None, new_name

    def named(
        self,
        kind: str,
        model: type[Any],
        rows: list[dict[str, Any]],
        references: dict[str, str],
        points: dict[str, list[dict[str, Any]]] | None,
    ) -> dict[str, int]:
        """Ids by the package's names; new rows (and their viscosity points) added."""
        ids: dict[str, int] = {}
        for row in rows:
            name = row["name"]
            values = {k: v for k, v in row.items() if k not in references and k != "name"}
            for column, id_column in references.items():
                values[id_column] = self._source(row[column])
            own_points = None if points is None else points.get(name, [])
            found, new_name = self._match(kind, model, name, values, own_points)
            if found is not None:
                ids[name] = found
            if new_name is None:
                continue
            added = model(name=new_name, name_key=name_key(new_name), **values)
            self.session.add(added)
            self.session.flush()
            for point in own_points or []:
                self.session.add(
                    FluidPoint(
                        fluid_id=added.id,
                        **{c: point.get(c) for c in _POINT_STORED},
                        source_id=self._source(point["source"]),
                        source_locator=point["source_locator"],
                    )
                )
            ids[name] = added.id
        return ids


def _merge(merger: Merger, tables: dict[str, Any]) -> tuple[dict[str, int], dict[str, int]]:
    merger.sources(records(tables["sources"]))
    materials = merger.named(
        "material", Material, records(tables["materials"]), {"source": "source_id"}, None
    )
    points: dict[str, list[dict[str, Any]]] = {}
    for point in records(tables["fluid_points"]):
        points.setdefault(point["fluid"], []).append(point)
    fluids = merger.named("fluid", Fluid, records(tables["fluids"]), FLUID_SOURCES, points)
    if merger.conflicts:
        raise MergeConflict(merger.conflicts)
    return materials, fluids


def store_package(
    database: Any,
    content: PackageContent,
    *,
    rename_conflicts: bool = False,
    declared_hash: str | None = None,
    problems: Any = None,
) -> PackageImport:
    """Merge and insert ``content`` in one write transaction; all or nothing. Its
    collisions are a frame or an iterable of frames (blocks, inserted one at a time, so
    memory is bounded by a block). With ``declared_hash``, the stored rows under the
    package's own names must give it (``HashMismatch`` otherwise, nothing stored).

    A run whose temperature its fluid's data does not cover is refused by the rule of
    the CSV import (``collision_store.FluidRanges``, one rule for both doors): every
    such row goes to ``problems`` (``granudb.io.tables.Problems``; without one the first
    is refused at once) and nothing is stored."""
    problems = problems if problems is not None else FirstProblem()
    with database.session(write=True) as session:
        if session.scalars(
            select(Dataset).filter_by(name=content.dataset, version=content.version)
        ).first():
            raise ConflictError(
                f"package: dataset {content.dataset} {content.version} already exists (use "
                "--as NAME, or export a new version); nothing was imported"
            )
        check_dataset_name(content.dataset)
        check_version(content.version)
        merger = Merger(session, content.package, rename_conflicts)
        materials, fluids = _merge(merger, content.tables)
        dataset = Dataset(
            name=content.dataset,
            version=content.version,
            title=content.title,
            description=content.description,
            license=content.license,
            doi=content.doi,
            authors=content.authors,
            keywords=content.keywords,
            source_id=merger.source_ids.get(content.source) if content.source else None,
            **({"created_at": content.created} if content.created else {}),
        )
        session.add(dataset)
        session.flush()
        blocks = content.tables["collisions"]
        rows = 0
        ranges = FluidRanges(session)
        stored = _stored_names(session, fluids)
        for block in [blocks] if hasattr(blocks, "columns") else blocks:
            frame = block.copy()
            ranges.check(_temperatures(frame, stored), content.dataset, problems)
            if problems:
                continue  # checked to the end, nothing more written
            frame["particle_id"] = frame.pop("particle").map(materials)
            frame["wall_id"] = frame.pop("wall").map(materials)
            frame["fluid_id"] = frame.pop("fluid").map(fluids)
            rows += insert_collisions(session, dataset.id, frame)
        problems.raise_any()  # rolls the transaction back
        result = merger.result
        result.dataset, result.version = content.dataset, content.version
        result.rows, result.content_hash = rows, update_content_hash(session, dataset)
        if declared_hash is not None:
            result.content_hash = _check_declared(session, dataset, result.content_hash,
                                                  declared_hash, (materials, fluids))  # fmt: skip
        if content.status == RELEASED:
            _released(session, dataset)
        return result


def _released(session: Session, dataset: Dataset) -> None:
    """A release imported stays a release (a curator's act, as releasing is), released
    here now: it reads its sources and pair values as this database holds them at import,
    which are the package's (a source or row that differs is a conflict). When this
    database already has a released version of the name, that one stays current and the
    imported one comes in superseded."""
    require_curator(session.connection(), f"importing the release {dataset.name}")
    current = session.scalars(
        select(Dataset.id).filter_by(name=dataset.name, state=RELEASED)
        .where(Dataset.id != dataset.id)
    ).first()  # fmt: skip
    dataset.state = SUPERSEDED if current is not None else RELEASED
    dataset.released_at = utcnow()
    session.flush()


def _temperatures(frame: Any, stored: dict[str, str]) -> CollisionChunk:
    """What ``FluidRanges.check`` reads of a block of the package's runs: their fluids
    under the stored names (matched in another case, or renamed) and temperatures, the
    names coded at numpy speed (a package may hold millions of runs)."""
    codes, names = frame["fluid"].map(stored).factorize()  # no fluid: code -1
    nobody = NameColumn(np.full(len(frame), -1), [])
    return CollisionChunk(
        first_row=int(frame.attrs.get("first_row", 2)),
        headers={},
        runs=frame["run"].tolist(),
        particle=nobody,
        wall=nobody,
        fluid=NameColumn(codes, list(names)),
        values={"temperature_c": frame["temperature_c"].to_numpy(float, na_value=np.nan)},
        notes=None,
    )


def _stored_names(session: Session, fluids: dict[str, int]) -> dict[str, str]:
    """{the package's fluid name: the stored fluid's name} of ``fluids`` (ids by name)."""
    query = select(Fluid.id, Fluid.name).where(Fluid.id.in_(sorted(set(fluids.values()))))
    names = dict(session.execute(query).all())
    return {name: names[i] for name, i in fluids.items()}


def _check_declared(
    session: Session, dataset: Dataset, stored: str, declared: str, ids: tuple[dict, dict]
) -> str:
    """Refuse a package whose collisions, under the package's own names, do not give the
    hash it declares; return the hash to record. They give the stored hash unless a name
    was renamed (a name matched in another case hashes alike: names are hashed in
    canonical form); then the stored rows are hashed again with the package's names. A
    package hashed under the first definition (names as spelled, before they were
    canonical) is checked under it, and its hash is kept when the names are this
    database's: a release keeps the hash it was published with."""
    own: list[dict[str, str]] = []
    models: tuple[type[Material] | type[Fluid], ...] = (Material, Fluid)
    for model, by_name in zip(models, ids, strict=True):
        here = dict(session.execute(select(model.id, model.name).where(
            model.id.in_(sorted(set(by_name.values()))))).all())  # fmt: skip
        own.append({here[i]: name for name, i in by_name.items() if here[i] != name})
    renamed = (own[0], own[1]) if any(own) else None
    computed = stored if renamed is None else content_hash(session, dataset, renamed)
    if computed == declared:
        return stored
    if content_hash(session, dataset, renamed, spelled=True) == declared:
        if renamed is None:
            dataset.content_hash = declared
            session.flush()
            return declared
        return stored
    raise HashMismatch(
        f"content hash: computed {computed[:16]}…, the package declares "
        f"{str(declared)[:16]}…; the collisions changed"
    )
