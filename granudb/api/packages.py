"""Sharing datasets as Frictionless Data Packages: ``granudb dataset export|validate|import``
are ``export_dataset``, ``validate_dataset`` and ``import_dataset``.

A package holds ``datapackage.json``, ``data/*.csv`` (collisions, materials, fluids,
fluid_points, sources) with Table Schemas, a README and a CITATION.cff; README "Sharing
datasets" says what is checked on the way in. A round trip is lossless (docs/sharing.md):
the descriptor carries the dataset as stored (``granudb:status``, ``granudb:title``,
``granudb:description``, ``granudb:authors``, ``granudb:keywords``, ``granudb:source``),
so export → import → export gives the same bytes, and a release imported stays a release.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from granudb.api import inputs
from granudb.api.database import opened
from granudb.db import datasets as store
from granudb.db.package_queries import export_data
from granudb.db.package_store import PackageImport
from granudb.io.package_export import build_package, write_package
from granudb.io.package_import import import_package, validate_package
from granudb.reporting.pinned import pinned_notes

#: Problems a validation prints before it counts the rest.
SHOWN_PROBLEMS = 20


@dataclass(frozen=True)
class Exported:
    """What ``export_dataset`` wrote: the dataset, its version and content hash, where."""

    dataset: str
    version: str
    content_hash: str
    path: Path
    #: What the release pins that today's catalogue has changed (``pinned_notes`` of
    #: ``granudb.reporting.pinned``); the package holds the pinned values, its bytes
    #: never change.
    pinned_changes: list[str] = field(default_factory=list)


@dataclass(frozen=True)
class Validation:
    """What ``validate_dataset`` found: every problem (none: valid) and the row counts."""

    path: Path
    problems: list[str]
    counts: dict[str, int]

    @property
    def valid(self) -> bool:
        return not self.problems

    @property
    def shown(self) -> list[str]:
        """What the command line prints: the first ``SHOWN_PROBLEMS`` problems, then one
        line "… and N more" (a descriptor of 50,000 junk resources is 21 lines)."""
        if len(self.problems) <= SHOWN_PROBLEMS:
            return list(self.problems)
        rest = len(self.problems) - SHOWN_PROBLEMS
        return [*self.problems[:SHOWN_PROBLEMS], f"… and {rest} more problems"]


def export_dataset(
    dataset: str, output: str | Path, *, version: str | None = None, db: Any = None
) -> Exported:
    """Write a dataset version (``NAME`` or ``NAME@VERSION``) as a Data Package to
    ``output``: an empty or new folder, or a file ending in ``.zip``.

    Examples
    --------
    >>> import granudb
    >>> _ = granudb.import_collisions(example_csv, dataset="shared", db=db)
    >>> granudb.export_dataset("shared", tmp / "shared.zip", db=db).path.name
    'shared.zip'
    """
    name, version = inputs.dataset_ref(dataset, version)
    target = Path(inputs.path(output, "output"))
    with opened(db) as database, database.session() as session:
        data = export_data(session, name, version)
        pinned = pinned_notes(session.connection(), store.get_dataset(session, name, version).id)
    written = write_package(build_package(data), target)
    return Exported(
        data.dataset["name"], data.dataset["version"], data.content_hash, written, pinned
    )


def validate_dataset(path: str | Path) -> Validation:
    """Check a package (folder, ``datapackage.json`` or ``.zip``) without importing it;
    every problem found is listed (``valid`` when there is none; ``shown``: the first 20
    and a count). The collisions are read in blocks and not kept: memory does not grow
    with their number (README "Sharing datasets").

    Examples
    --------
    >>> import granudb
    >>> _ = granudb.import_collisions(example_csv, dataset="checked", db=db)
    >>> exported = granudb.export_dataset("checked", tmp / "checked.zip", db=db)
    >>> granudb.validate_dataset(exported.path).counts["collisions"]
    12
    """
    target = Path(inputs.path(path, "path"))
    result = validate_package(target, keep_collisions=False)
    return Validation(target, list(result.problems), dict(result.counts))


def import_dataset(
    path: str | Path,
    *,
    as_name: str | None = None,
    rename_conflicts: bool = False,
    db: Any = None,
) -> PackageImport:
    """Validate and import a package in one transaction (all or nothing), under its own
    name or ``as_name``. A material or fluid whose name exists here with other values is a
    conflict, unless ``rename_conflicts`` brings it in as ``NAME (package)``.

    Examples
    --------
    >>> import granudb
    >>> _ = granudb.import_collisions(example_csv, dataset="ours", db=db)
    >>> exported = granudb.export_dataset("ours", tmp / "ours.zip", db=db)
    >>> granudb.import_dataset(exported.path, as_name="theirs", db=db).rows
    12
    """
    target = Path(inputs.path(path, "path"))
    if as_name is not None:
        as_name = inputs.text(as_name, "as_name")
    with opened(db) as database:
        imported: PackageImport = import_package(
            database, target, as_name=as_name, rename_conflicts=rename_conflicts
        )
        return imported
