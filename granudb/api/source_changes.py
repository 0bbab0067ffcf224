"""Changing the sources, for Python users and the command line: ``granudb sources add``
and ``granudb sources update`` are ``add_source`` and ``update_source``.

The same concept as ``granudb.db.source_changes`` seen from the API's side: here the
inputs are checked; there the rows and revisions are written.

A source is a citation (required), with a DOI, URL, year, kind and notes. An update keeps
the source as it was as a revision first (``sources history``), so a released dataset
goes on citing the text it was released with and says when today's text differs. Fields
follow one set of rules (``granudb.vocabulary.catalog.check_source``); a refusal is one
line and changes nothing.
"""

from __future__ import annotations

from typing import Any

from granudb.api import inputs
from granudb.api.catalog import source
from granudb.api.catalog_changes import Update
from granudb.api.database import opened
from granudb.db import source_changes
from granudb.errors import ValidationError
from granudb.vocabulary.catalog import SOURCE_FIELDS

#: The longest reason a correction keeps (a sentence or two, not a document).
MAX_REASON = 1000

#: Fields an update may clear with "" (the citation and kind cannot be empty).
_CLEARABLE = ("doi", "url", "year", "notes")


def _year(value: Any) -> int | None:
    """A year given as a whole number or its digits ("2004")."""
    if isinstance(value, str):
        if not value.strip().isdigit():
            raise ValidationError("year", repr(value), "must be a whole year", parameter=True)
        return int(value)
    number = inputs.number(value, "year")
    if number is None or number != int(number):
        raise ValidationError("year", repr(value), "must be a whole year", parameter=True)
    return int(number)


def _fields(given: dict[str, Any], *, clearing: bool) -> dict[str, Any]:
    """``{column: value}`` of the given fields (None: not given); with ``clearing`` an
    empty text clears a field that may be empty."""
    values: dict[str, Any] = {}
    for column, value in given.items():
        if value is None:
            continue
        if clearing and column in _CLEARABLE and value == "":
            values[column] = None
        elif column == "year":
            values[column] = _year(value)
        else:
            values[column] = inputs.text(value, column)
    return values


#: The fields a user sets, as keywords of both functions (and options of both commands).
_SHOWN = inputs.shows_keywords(dict.fromkeys(SOURCE_FIELDS))


def _given(fields: dict[str, Any]) -> dict[str, Any]:
    return inputs.known_options(fields, SOURCE_FIELDS, "a field of a source")


@_SHOWN
def add_source(key: str, *, db: Any = None, **fields: Any) -> dict[str, Any]:
    """Add a source that materials, fluids, points and datasets can then cite; returns it
    as ``source`` does. ``fields``: ``citation`` (required), ``doi`` (the DOI itself,
    ``10.1017/…``), ``url`` (an http(s) address), ``year`` (a whole year), ``kind``
    ("publication" unless given: "journal-article", "book", "software", …), ``notes``.

    Examples
    --------
    >>> import granudb
    >>> granudb.add_source("gondret-2002", citation="Gondret, P., Lance, M. & Petit, L. "
    ...                    "(2002). Bouncing motion of spherical particles in fluids. "
    ...                    "Phys. Fluids 14, 643-652.", doi="10.1063/1.1427920", year=2002,
    ...                    db=db)["doi"]
    '10.1063/1.1427920'
    """
    key = inputs.text(key, "key")
    given = _given(fields)
    if given.get("citation") is None:
        raise inputs.missing("citation", "is required to add a source")
    values = {"key": key, **_fields(given, clearing=False)}
    with opened(db) as database:
        with database.session(write=True) as session:
            source_changes.add_source(session, values)
        return source(key, db=database)


@_SHOWN
def update_source(key: str, *, reason: str | None = None, db: Any = None, **fields: Any) -> Update:
    """Change the given fields of a source (those of ``add_source``; ``None``: leave as it
    is; ``""`` clears the DOI, URL, year or notes); the source as it was is kept as a
    revision, with ``reason`` (why it changed), so ``source_history`` lists it and a
    release keeps citing what it cited. Returns what changed, field by field.

    Examples
    --------
    >>> import granudb
    >>> print(granudb.update_source("johnson-1985", url="https://doi.org/10.1017/CBO9781139171731",
    ...                             reason="a link to read it", db=db))
    updated source johnson-1985: url (none) → 'https://doi.org/10.1017/CBO9781139171731'
    >>> [r["revision"] for r in granudb.source_history("johnson-1985", db=db)]
    ['current', '1']
    """
    key = inputs.text(key, "key")
    values = _fields(_given(fields), clearing=True)
    if reason:
        reason = inputs.free_text(reason, "reason", max_length=MAX_REASON)
    why = "sources update" + (f": {reason}" if reason else "")
    with opened(db) as database, database.session(write=True) as session:
        change = source_changes.update_source(session, key, values, why)
    return Update(change.action, change.label, change.diffs)
