"""Datasets for Python users and the command line: the catalogue of datasets (list, show,
diff) and each version's lifecycle (edit its metadata, release it, start a new version,
remove it). ``granudb dataset list|show|diff|edit|release|new-version|remove`` are
``datasets``, ``dataset``, ``diff_datasets``, ``edit_dataset``, ``release_dataset``,
``new_dataset_version`` and ``remove_dataset``.

A version is a draft until released; a released version is immutable (no import, no run
removed, no metadata changed except a DOI set once) and can be removed only after a newer
version has been released (it is then superseded), as with Granta MI record versions and
Zenodo's versioned records. Every function takes ``db=`` like the rest of the API
(an opened database, a URL, a SQLite path or nothing for the default) and runs in one
transaction: it happens whole or not at all.

A dataset is named ``NAME`` (its newest version) or ``NAME@VERSION`` (``dataset_ref``
reads both, and ``version=`` names a version explicitly). Removal asks
``confirm(action, losses)`` first (``granudb.api.consent``); from Python without it the
call itself is the consent.
"""

from __future__ import annotations

import json
import re
from typing import Any

from granudb.api import inputs
from granudb.api.consent import Confirm, agreed, unchanged
from granudb.api.database import opened
from granudb.api.frames import records_frame
from granudb.db import catalog_differences, dataset_catalog
from granudb.db import datasets as store
from granudb.db.content_hash import hash_problem
from granudb.errors import ValidationError
from granudb.reporting.format import difference_line
from granudb.reporting.pinned import pinned_notes
from granudb.vocabulary.listings import DATASET_COLUMNS
from granudb.vocabulary.people import check_author, check_keyword
from granudb.vocabulary.text import check_name, check_text

_DOI = re.compile(r"^10\.\d{4,9}/\S+$")


def parse_author(text: str) -> dict[str, str | None]:
    """``"Family, Given; orcid=0000-…; affiliation=Lab"`` (the command line's
    ``--author``) as an author record."""
    first, *rest = [part.strip() for part in text.split(";")]
    family, _, given = (p.strip() for p in first.partition(","))
    person: dict[str, str | None] = {"family_names": family, "given_names": given or None}
    for part in rest:
        key, eq, value = (p.strip() for p in part.partition("="))
        if not eq or key not in ("orcid", "affiliation"):
            raise ValidationError(
                "--author", text, "must be 'Family, Given; orcid=…; affiliation=…'"
            )
        person[key] = value
    return check_author(person, "--author")


def check_metadata(values: dict[str, Any]) -> dict[str, str | None]:
    """Check and normalise dataset metadata: title, description, license, doi as text;
    authors as a list of author records; keywords as a list of names. Returns the values
    as stored (authors and keywords as JSON text; ``""`` clears a field)."""
    out: dict[str, str | None] = {}
    for field, value in values.items():
        if value == "" or value == []:
            out[field] = None
        elif field == "title":
            out[field] = check_name("--title", value, max_length=500)
        elif field == "license":
            out[field] = check_name("--license", value)
        elif field == "description":
            out[field] = check_text("--description", value)
        elif field == "doi":
            value = re.sub(r"^https://doi\.org/", "", check_name("--doi", value))
            if not _DOI.match(value):
                raise ValidationError("--doi", value, "is not a DOI (10.NNNN/…)")
            out[field] = value
        elif field == "authors":
            people = [check_author(p, f"author {i + 1}") for i, p in enumerate(value)]
            out[field] = json.dumps(people, ensure_ascii=False)
        elif field == "keywords":
            words = [check_keyword(w) for w in value]
            out[field] = json.dumps(list(dict.fromkeys(words)), ensure_ascii=False)
        else:
            raise ValidationError(field, value, "is not an editable dataset field")
    return out


def datasets(db: Any = None, *, as_frame: bool = True) -> Any:
    """Every dataset version with its state, title, run count, content hash, licence and
    source: a DataFrame, or a list of records with ``as_frame=False``, where each record
    also has ``pinned_changes`` (what a release pins that today's
    catalogue has changed).

    Examples
    --------
    >>> import granudb
    >>> list(granudb.datasets(db=db).columns)[:3]
    ['name', 'version', 'state']
    """
    with opened(db) as database, database.session() as session:
        records = dataset_catalog.dataset_records(session)
        for record in records:
            record["pinned_changes"] = pinned_notes(session.connection(), record.pop("id"))
    return records_frame(records, DATASET_COLUMNS) if as_frame else records


def dataset(name: str, *, version: str | None = None, db: Any = None) -> dict[str, Any]:
    """One dataset version (``name`` as NAME or NAME@VERSION): its metadata,
    ``pinned_changes`` (what a release pins that today's catalogue has
    changed) and ``groups``, its runs counted by particle, wall and fluid.

    Examples
    --------
    >>> import granudb
    >>> _ = granudb.import_collisions(example_csv, dataset="shown", db=db)
    >>> granudb.dataset("shown@1.0.0", db=db)["runs"]
    12
    """
    name, version = inputs.dataset_ref(name, version)
    with opened(db) as database, database.session() as session:
        chosen = store.get_dataset(session, name, version)
        record = dataset_catalog.dataset_record(session, chosen)
        record["pinned_changes"] = pinned_notes(session.connection(), chosen.id)
        problem = hash_problem(session, chosen)  # e.g. values a downgrade dropped
        if problem is not None:
            record["pinned_changes"].append(f"content hash: {problem}")
        record["groups"] = dataset_catalog.group_counts(session, chosen)
    return record


def diff_datasets(a: str, b: str | None = None, *, db: Any = None) -> list[dict[str, Any]]:
    """The differences from dataset ``a`` to ``b`` (each NAME or NAME@VERSION): the runs
    added, removed and changed, matched by run label, one record (change, run, fields)
    per run; then the catalogue values the two read differently (a release's pinned
    revisions and pair values against the other's: materials, fluids, fluid points, dry
    values), one record per value with change "catalogue" and the value in ``fields``.
    Without ``b``: what ``a`` pins that today's catalogue has changed (change "pinned").

    Examples
    --------
    >>> import granudb
    >>> _ = granudb.import_collisions(example_csv, dataset="diffed", db=db)
    >>> granudb.diff_datasets("diffed", "diffed@1.0.0", db=db)
    []
    >>> granudb.diff_datasets("diffed", db=db)
    []
    """
    with opened(db) as database, database.session() as session:
        first = store.get_dataset(session, *inputs.dataset_ref(a))
        if b is None:
            lines = pinned_notes(session.connection(), first.id)
            return [{"change": "pinned", "run": None, "fields": line} for line in lines]
        second = store.get_dataset(session, *inputs.dataset_ref(b))
        runs = dataset_catalog.diff_datasets(session, first, second)
        changes = catalog_differences.catalogue_diff(session.connection(), first.id, second.id)
    catalogue = [{"change": "catalogue", "run": None, "fields": difference_line(c)}
                 for c in changes]  # fmt: skip
    return runs + catalogue


def remove_dataset(
    dataset: str,
    *,
    version: str | None = None,
    confirm: Confirm | None = None,
    db: Any = None,
) -> list[str]:
    """Delete a dataset version (``NAME@VERSION``), or every version of ``NAME``, with its
    runs and import records; returns what was deleted. A released version cannot be
    removed until a newer version is released. ``confirm`` as ``remove_material``.

    Examples
    --------
    >>> import granudb
    >>> _ = granudb.import_collisions(example_csv, dataset="removed", db=db)
    >>> granudb.remove_dataset("removed@1.0.0", db=db)
    ["dataset removed@1.0.0 (id ...: name 'removed', version '1.0.0', draft) with 12 runs
    and 1 import records"]
    """
    name, version = inputs.dataset_ref(dataset, version)
    action = f"dataset remove {dataset}"
    with opened(db) as database:
        with database.session() as session:
            losses = store.removal_losses(session, store.datasets_to_remove(session, name, version))
        agreed(confirm, action, losses)
        with database.session(write=True) as session:
            chosen = store.datasets_to_remove(session, name, version)
            unchanged(action, losses, store.removal_losses(session, chosen))
            store.remove_datasets(session, chosen)
    return losses


def edit_dataset(
    dataset: str,
    *,
    version: str | None = None,
    title: str | None = None,
    description: str | None = None,
    license: str | None = None,
    doi: str | None = None,
    authors: Any = None,
    keywords: Any = None,
    db: Any = None,
) -> list[tuple[str, Any, Any]]:
    """Change the metadata of a draft version: ``title``, ``description``, ``license``,
    ``doi`` (text; "" clears), ``authors`` (a list of {"given_names", "family_names",
    "orcid", "affiliation"} or of "Family, Given; orcid=…; affiliation=…", or that list as
    JSON text; ORCID check digits verified), ``keywords`` (a list of text). Returns
    (field, old, new) for each change.

    Examples
    --------
    >>> import granudb
    >>> _ = granudb.import_collisions(example_csv, dataset="edited", db=db)
    >>> granudb.edit_dataset("edited", title="Example runs", db=db)
    [('title', None, 'Example runs')]
    """
    given = {
        "title": title,
        "description": description,
        "license": license,
        "doi": doi,
        "authors": _authors(authors) if authors is not None else None,
        "keywords": inputs.sequence(keywords, "keywords") if keywords is not None else None,
    }
    values = {k: v for k, v in given.items() if v is not None}
    if not values:
        raise ValidationError("edit", dataset, "needs at least one option to change")
    checked = check_metadata(values)
    name, version = inputs.dataset_ref(dataset, version)
    with opened(db) as database, database.session(write=True) as session:
        return store.edit_dataset(session, store.get_dataset(session, name, version), checked)


def _authors(value: Any) -> list[Any]:
    """Authors as records: JSON text, or a list of records or of ``--author`` texts."""
    if isinstance(value, str):
        try:
            value = json.loads(value)
        except json.JSONDecodeError as exc:
            raise ValidationError("authors", value[:40], f"is not JSON ({exc.msg})") from None
        except RecursionError:
            raise ValidationError("authors", value[:40], "is nested too deeply") from None
        if not isinstance(value, list):
            raise ValidationError("authors", "(JSON)", "must be a JSON list of people")
    people = inputs.sequence(value, "authors")
    return [parse_author(p) if isinstance(p, str) else p for p in people]


def release_dataset(dataset: str, *, version: str | None = None, db: Any = None) -> list[str]:
    """Release a draft version: from now on it cannot change (a new version holds
    changes). Returns the versions it supersedes.

    Examples
    --------
    >>> import granudb
    >>> _ = granudb.import_collisions(example_csv, dataset="released", db=db)
    >>> granudb.release_dataset("released@1.0.0", db=db)
    []
    """
    name, version = inputs.dataset_ref(dataset, version)
    with opened(db) as database, database.session(write=True) as session:
        chosen = store.get_dataset(session, name, version)
        return [d.version for d in store.release_dataset(session, chosen)]


def new_dataset_version(dataset: str, version: str | None = None, *, db: Any = None) -> str:
    """Copy a dataset version (``NAME@VERSION``, or ``NAME``: the newest) — metadata, runs
    and import records — as a new draft ``version``; returns its content hash (the same
    as the copied version's).

    Examples
    --------
    >>> import granudb
    >>> _ = granudb.import_collisions(example_csv, dataset="versioned", db=db)
    >>> len(granudb.new_dataset_version("versioned@1.0.0", "1.1.0", db=db))
    64
    """
    if version is None:
        raise inputs.missing("version", "is required: the new version, e.g. 1.1.0")
    new = inputs.name(version, "version")
    name, old = inputs.dataset_ref(dataset)
    with opened(db) as database, database.session(write=True) as session:
        chosen = store.get_dataset(session, name, old)
        return store.new_version(session, chosen, new).content_hash or ""
