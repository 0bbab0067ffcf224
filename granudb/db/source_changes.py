"""Adding and correcting sources (``granudb sources add|update``).

The same concept as ``granudb.api.source_changes`` seen from the database's side: there
the inputs are checked; here the rows and revisions are written.

An update first keeps the source as it was as a revision
(``catalog_revisions.keep_source_revision``, as a re-seed does), so ``sources history``
lists it and a release goes on citing the text it was released with
(``catalog_differences.sources_read``). Fields follow one set of rules
(``granudb.vocabulary.catalog.check_source``).
"""

from __future__ import annotations

from typing import Any

from sqlalchemy import select
from sqlalchemy.orm import Session

from granudb.db import catalog_rows
from granudb.db.catalog_revisions import keep_source_revision
from granudb.db.models import Source
from granudb.db.upsert import Change
from granudb.errors import ConflictError
from granudb.vocabulary.catalog import check_source
from granudb.vocabulary.rules import same_value
from granudb.vocabulary.text import name_key, nfc


def add_source(session: Session, values: dict[str, Any]) -> None:
    """Add the source ``values`` (``key`` and ``citation`` required, the other columns
    of ``SOURCE_COLUMNS`` optional, ``kind`` "publication" unless given); refuses a key
    that exists and a field that breaks its rule (``check_source``)."""
    values = {"kind": "publication", **values}  # a copy: the key is stored in NFC
    check_source(values)
    values["key"] = nfc(values["key"])
    keys = session.connection().execute(select(catalog_rows.SOURCES.c.key)).scalars()
    found = next((k for k in keys if name_key(k) == name_key(values["key"])), None)
    if found is not None:
        shown = "" if found == values["key"] else f" as {found!r}"
        raise ConflictError(
            f"source: {values['key']!r} already exists{shown} (keys are compared ignoring "
            "case; use `granudb sources update`); nothing was changed"
        )
    session.add(Source(**values))
    session.flush()


def update_source(session: Session, key: str, values: dict[str, Any], reason: str) -> Change:
    """Change the given fields of the source ``key`` (a value None: cleared; the citation
    cannot be); the source as it was is kept first as a revision, with ``reason``.
    Returns what changed, field by field (nothing kept when nothing changes)."""
    check_source(values)
    row = session.get_one(Source, catalog_rows.source_id(session.connection(), key))
    before = catalog_rows.source_record(row)
    diffs = [(c, before[c], new) for c, new in values.items() if not same_value(before[c], new)]
    label = f"source {key}"
    if not diffs:
        return Change("unchanged", label, diffs)
    keep_source_revision(session, row.id, before, reason)
    for field, _, new in diffs:
        setattr(row, field, new)
    session.flush()
    return Change("updated", label, diffs)
