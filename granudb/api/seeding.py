"""Re-loading the shipped seed data without reverting what the user changed.

``reseed`` keeps every value the user edited (reporting the difference) unless
``overwrite_edits``; ``seed_reverts`` says beforehand which edits an overwrite would
revert, so the command line can ask first.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from granudb.api.database import opened


class _DryRun(Exception):
    """Raised inside the transaction to roll a trial load back."""


def reseed(
    db: Any = None,
    *,
    folder: Path | None = None,
    overwrite_edits: bool = False,
    accepted: list[str] | None = None,
) -> list[str]:
    """Load the seed files (default: the shipped ``seed_data``) in one transaction; returns
    one line per change plus a summary. With ``overwrite_edits`` the user's edits are
    reverted to the seed's values; given ``accepted`` (from ``seed_reverts``) it refuses
    if the reverts differ from those the person agreed to."""
    from granudb.db.seed_store import apply_seed
    from granudb.errors import ConfirmationNeeded
    from granudb.io.seed import read_seed

    data = read_seed(folder)
    with opened(db) as database, database.session(write=True) as session:
        lines = apply_seed(session, data, overwrite_edits=overwrite_edits)
        reverts = _reverts(lines)
        if accepted is not None and reverts != accepted:
            raise ConfirmationNeeded(
                "db seed --overwrite-edits: the edits to revert changed since you "
                "confirmed; nothing was changed"
            )
    return lines


def seed_reverts(db: Any = None, *, folder: Path | None = None) -> list[str]:
    """The user's edits ``reseed(overwrite_edits=True)`` would revert (nothing changes)."""
    from granudb.db.seed_store import apply_seed
    from granudb.io.seed import read_seed

    data = read_seed(folder)
    lines: list[str] = []
    try:
        with opened(db) as database, database.session(write=True) as session:
            lines = apply_seed(session, data, overwrite_edits=True)
            raise _DryRun
    except _DryRun:
        pass
    return _reverts(lines)


def _reverts(lines: list[str]) -> list[str]:
    prefix = "reverted "
    return [line.removeprefix(prefix) for line in lines if line.startswith(prefix)]
