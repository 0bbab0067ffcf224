"""Consent before anything is destroyed: say what will go, then ask or need ``--yes``.

On a terminal the person answers y/N (default no); without a terminal (a script, a pipe,
CI) there is nobody to ask, so the command refuses in one line unless ``--yes`` was given.
Either way a "no" changes nothing.
"""

from __future__ import annotations

import sys
from typing import Annotated

import typer

from granudb.errors import ConfirmationNeeded

YesOption = Annotated[bool, typer.Option("--yes", "-y", help="Do it without asking (for scripts).")]


def interactive() -> bool:
    """Whether someone can answer a prompt (stdin and stderr are terminals)."""
    return sys.stdin.isatty() and sys.stderr.isatty()


def confirm(action: str, losses: list[str], yes: bool) -> None:
    """Return when the person agreed to ``action`` losing ``losses``; else refuse.

    ``losses`` empty means nothing is lost: no question is asked.
    """
    if not losses or yes:
        return
    what = "; ".join(losses)
    if not interactive():
        raise ConfirmationNeeded(
            f"{action}: loses {what}; run again with --yes to confirm (nothing was changed)"
        )
    from granudb.cli.output import note

    note(f"{action} loses:")
    for line in losses:
        note(f"  {line}")
    if not typer.confirm("Proceed?", default=False, err=True):
        raise ConfirmationNeeded(f"{action}: not confirmed; nothing was changed")
