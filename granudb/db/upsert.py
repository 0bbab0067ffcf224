"""Insert-or-update by a natural key, saying exactly what changed.

Used to load the seed files idempotently: loading twice changes nothing, and a value edited
in a seed file updates its row and is reported field by field, never silently.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from sqlalchemy import select
from sqlalchemy.orm import Session

from granudb.vocabulary.rules import same_value


@dataclass
class Change:
    """What one upsert did: ``action`` is "added", "updated" or "unchanged"."""

    action: str
    label: str
    diffs: list[tuple[str, Any, Any]] = field(default_factory=list)

    def describe(self, shown: Callable[[str, Any], str] | None = None) -> str:
        """One line; ``shown(column, value)`` formats a value for people (default: the SI
        value as Python writes it), e.g. ``granudb.cli.output.human``."""
        if self.action != "updated":
            return f"{self.action} {self.label}"
        show = shown or (lambda _column, value: repr(value))
        parts = ", ".join(
            f"{name} {show(name, old)} → {show(name, new)}" for name, old, new in self.diffs
        )
        return f"updated {self.label}: {parts}"


def upsert(
    session: Session, model: type, key: dict[str, Any], values: dict[str, Any], label: str
) -> tuple[Any, Change]:
    """Find the ``model`` row matching ``key``; insert it or update the fields that differ."""
    row = session.scalars(select(model).filter_by(**key)).one_or_none()
    if row is None:
        row = model(**key, **values)
        session.add(row)
        session.flush()
        return row, Change("added", label)
    diffs = []
    for name, new in values.items():
        old = getattr(row, name)
        if not same_value(old, new):
            diffs.append((name, old, new))
            setattr(row, name, new)
    if diffs:
        session.flush()
    return row, Change("updated" if diffs else "unchanged", label, diffs)
