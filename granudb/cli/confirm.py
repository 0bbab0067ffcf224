"""Consent before anything is destroyed, at the terminal: the ``confirm`` the command line
passes to the API's destructive functions (``granudb.api.consent``).

On a terminal the person answers y/N (default no); without a terminal (a script, a pipe,
CI) there is nobody to ask, so the command refuses in one line unless ``--yes`` was given.
Either way a "no" changes nothing.
"""

from __future__ import annotations

import sys
from collections.abc import Callable

import typer

from granudb import api
from granudb.cli.output import note


def interactive() -> bool:
    """Whether someone can answer a prompt (stdin and stderr are terminals)."""
    return sys.stdin.isatty() and sys.stderr.isatty()


def asker(yes: bool) -> Callable[[str, list[str]], bool]:
    """The ``confirm(action, losses)`` for a command run with or without ``--yes``."""

    def confirm(action: str, losses: list[str]) -> bool:
        if yes:
            return True
        what = "; ".join(losses)
        if not interactive():
            raise api.ConfirmationNeeded(
                f"{action}: loses {what}; run again with --yes to confirm (nothing was changed)"
            )
        note(f"{action} loses:")
        for line in losses:
            note(f"  {line}")
        return typer.confirm("Proceed?", default=False, err=True)

    return confirm
