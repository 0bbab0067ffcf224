"""Consent before anything is destroyed, the same for Python and the command line.

A function that deletes stored data (``remove_material``, ``remove_dataset``,
``db_downgrade``, ``db_seed(overwrite_edits=True)`` …) first works out what would be
lost, in a read-only transaction, then asks ``confirm(action, losses)`` — the command
line passes its prompt (or ``--yes``) — and only then deletes, in a write transaction
that works the losses out again and refuses if they changed meanwhile. Called from
Python without ``confirm``, the call itself is the consent.
"""

from __future__ import annotations

from collections.abc import Callable

from granudb.errors import ConfirmationNeeded

#: ``confirm(action, losses)`` returns True to go ahead; it may also raise
#: ``ConfirmationNeeded`` itself (a script without ``--yes``).
Confirm = Callable[[str, list[str]], bool]


def agreed(confirm: Confirm | None, action: str, losses: list[str]) -> None:
    """Return when ``action`` losing ``losses`` may go ahead; nothing lost needs no
    question."""
    if confirm is None or not losses:
        return
    if not confirm(action, losses):
        raise ConfirmationNeeded(f"{action}: not confirmed; nothing was changed")


def unchanged(action: str, confirmed: list[str], now: list[str]) -> None:
    """Refuse when what an action loses changed between the question and the change."""
    if confirmed != now:
        raise ConfirmationNeeded(
            f"{action}: what it loses changed since you confirmed; nothing was changed"
        )
