"""A package's dataset as stored, read back: what ``package_export.dataset_record`` wrote
(``granudb:status``, ``granudb:title``, ``granudb:description``, ``granudb:authors``,
``granudb:keywords``, ``granudb:source``) and the descriptor's ``created``, checked by the
rules of ``dataset edit`` (one door for people and packages alike).

So a package exported, imported into another database and exported again gives the same
bytes: the authors with their ORCID and affiliation, the keywords, the dataset's own
source, its licence and DOI, a release as a release, its creation time, and a
placeholder title or description (``null`` here) kept a placeholder. A package without
these fields (an older granudb's, or another tool's) reads as before: the descriptor's
``title`` and ``description`` (an older granudb's placeholders — the name, "granudb
dataset NAME" — read as none), a draft, no authors or keywords.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from datetime import UTC, datetime
from typing import Any

from granudb.errors import ValidationError
from granudb.vocabulary.people import check_author, check_keyword
from granudb.vocabulary.text import check_text

STATUSES = ("draft", "released")
_WHERE = "datapackage.json: "


@dataclass(frozen=True)
class DatasetRecord:
    """A package's dataset metadata as it is to be stored (authors and keywords as the
    JSON text ``dataset edit`` stores, None when there are none)."""

    title: str | None
    description: str | None
    authors: str | None
    keywords: str | None
    source: str | None
    status: str
    created: datetime | None


def _text(descriptor: dict[str, Any], key: str, fallback: str, problems: list[str]) -> Any:
    """The stored title or description: ``granudb:<key>`` when the package says it (even
    null), else the descriptor's standard field."""
    own = f"granudb:{key}"
    value = descriptor[own] if own in descriptor else descriptor.get(fallback)
    if value is None or (own not in descriptor and value in _placeholders(descriptor)):
        return None
    if not isinstance(value, str):
        problems.append(f"{_WHERE}{own}: must be text or null, not {type(value).__name__}")
        return None
    if own in descriptor:  # the standard field is checked with the descriptor's names
        try:
            check_text(f"{_WHERE}{own}", value)
        except ValidationError as exc:
            problems.append(str(exc))
    return value


def _placeholders(descriptor: dict[str, Any]) -> set[str]:
    """What an older granudb wrote for a dataset without a title or description (its name;
    "granudb dataset NAME"): placeholders, not metadata."""
    name = descriptor.get("granudb:dataset")
    return {name, f"granudb dataset {name}"} if isinstance(name, str) else set()


def _listed(descriptor: dict[str, Any], key: str, check: Any, problems: list[str]) -> Any:
    value = descriptor.get(key)
    if value is None:
        return None
    if not isinstance(value, list):
        problems.append(f"{_WHERE}{key}: must be a list, not {type(value).__name__}")
        return None
    checked = []
    for number, item in enumerate(value, start=1):
        try:
            checked.append(check(item, f"{_WHERE}{key} {number}"))
        except ValidationError as exc:
            problems.append(str(exc))
    return checked or None


def _created(value: Any, problems: list[str]) -> datetime | None:
    if value is None:
        return None
    try:
        stamp = datetime.fromisoformat(str(value))
    except ValueError:
        problems.append(f"{_WHERE}created: {str(value)[:40]!r} is not an ISO 8601 date-time")
        return None
    return (stamp if stamp.tzinfo else stamp.replace(tzinfo=UTC)).astimezone(UTC)


def dataset_record(
    descriptor: dict[str, Any], source_keys: set[str], problems: list[str]
) -> DatasetRecord:
    """The dataset metadata ``descriptor`` brings; each problem is added to ``problems``
    (``source_keys``: the keys of the package's ``sources.csv``)."""
    title = _text(descriptor, "title", "title", problems)
    description = _text(descriptor, "description", "description", problems)
    people = _listed(descriptor, "granudb:authors", check_author, problems)
    words = _listed(descriptor, "granudb:keywords", check_keyword, problems)
    status = descriptor.get("granudb:status", "draft")
    if status not in STATUSES:
        problems.append(f"{_WHERE}granudb:status: {str(status)[:40]!r} is not one of {STATUSES}")
    source = descriptor.get("granudb:source")
    if source is not None and (not isinstance(source, str) or source not in source_keys):
        problems.append(f"{_WHERE}granudb:source: {str(source)[:100]!r} is not in sources.csv")
        source = None
    return DatasetRecord(
        title=title,
        description=description,
        authors=None if not people else json.dumps(people, ensure_ascii=False),
        keywords=None if not words else json.dumps(list(dict.fromkeys(words)), ensure_ascii=False),
        source=source,
        status=status if status in STATUSES else "draft",
        created=_created(descriptor.get("created"), problems),
    )
