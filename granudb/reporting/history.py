"""What changed between one revision of a catalogue row (a material, a fluid, a source)
and the next: ``sources history``, ``materials history`` and ``fluids history`` show it
beside each revision, so two revisions that differ in a field the table does not show
(a source's URL) never look identical.

Each change reads as ``difference_line`` reads a difference between two datasets'
catalogues (``url: 'https://a' → 'https://b'``): one renderer for "old → new".
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from granudb.reporting.format import difference_line

#: Keys of a history record that are about the revision, not values of the row.
NOT_VALUES = {"revision", "kept_at", "reason", "used_by", "changes", "id", "name_key",
              "revision_of", "updated_at", "created_at"}  # fmt: skip


def _plain(value: Any) -> bool:
    return value is None or isinstance(value, str | int | float)


def change_words(older: dict[str, Any], newer: dict[str, Any]) -> str:
    """``field: old → new`` for each value that differs, joined by "; " ("" when none).
    A value that is a list or table (a fluid's points) is named, not printed."""
    said = []
    for field in newer:
        if field in NOT_VALUES or field not in older:
            continue
        old, new = older[field], newer[field]
        if old == new or (old != old and new != new):  # equal, or both NaN
            continue
        if _plain(old) and _plain(new):
            change = {"kind": "", "name": "", "field": field, "temperature_c": None,
                      "first": old, "second": new}  # fmt: skip
            said.append(difference_line(change).strip())
        else:
            said.append(f"{field} changed")
    return "; ".join(said)


def with_changes(records: Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    """``records`` (newest first: the current row, then each kept revision) each with
    ``changes``: what the change made at that revision did, from the revision before it
    (the oldest says "(the oldest kept)")."""
    found = []
    for index, record in enumerate(records):
        older = records[index + 1] if index + 1 < len(records) else None
        words = "(the oldest kept)" if older is None else change_words(older, record)
        found.append({**record, "changes": words if older is None or words else "(none)"})
    if len(found) == 1:
        found[0]["changes"] = "(no change kept)"
    return found
