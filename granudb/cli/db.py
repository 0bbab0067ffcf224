"""``granudb db upgrade|downgrade|current|history|seed|grant``: the schema, the seed data
and the accounts of a shared PostgreSQL server."""

from __future__ import annotations

from enum import StrEnum
from typing import Annotated

import typer

from granudb import api
from granudb.cli.confirm import asker
from granudb.cli.options import DbOption, Format, FormatOption, YesOption, wraps
from granudb.cli.output import emit, emit_one, say

app = typer.Typer(
    help="Schema migrations (Alembic) and the shipped seed data.", no_args_is_help=True
)


@app.command()
@wraps("db_upgrade")
def upgrade(
    revision: Annotated[str, typer.Argument(help="Target revision.")] = "head",
    db: DbOption = None,
) -> None:
    """Migrate the database forward (a new database is created and seeded)."""
    before, after = api.db_upgrade(revision, db=db)
    say(
        f"schema: {before or 'empty'} → {after}"
        if before != after
        else f"schema: already at {after}"
    )


@app.command()
@wraps("db_downgrade")
def downgrade(
    revision: Annotated[str, typer.Argument(help='Target revision, or "base" to drop all.')],
    yes: YesOption = False,
    drop_released_values: Annotated[
        bool,
        typer.Option(
            "--drop-released-values",
            help="Accept that released versions lose values they hold (their exports "
            "then no longer match their content hashes); --yes alone does not.",
        ),
    ] = False,
    db: DbOption = None,
) -> None:
    """Migrate the database back to an older revision.

    Says first which tables and columns would lose values (and how many, and which
    released versions that changes) and asks, or needs --yes; a downgrade that would
    change a released version also needs --drop-released-values. A downgrade that loses
    nothing runs at once.
    """
    before, after, losses = api.db_downgrade(
        revision, confirm=asker(yes), drop_released_values=drop_released_values, db=db
    )
    for line in losses:
        say(f"lost {line}")
    say(f"schema: {before or 'empty'} → {after or 'empty'}")


@app.command()
@wraps("db_current")
def current(db: DbOption = None, fmt: FormatOption = Format.table) -> None:
    """The database's schema revision and the newest this granudb knows."""
    emit_one(api.db_current(db=db), fmt, title="Schema")


@app.command()
@wraps("db_history")
def history(fmt: FormatOption = Format.table) -> None:
    """Every schema revision granudb ships, newest first."""
    emit(api.db_history(), ["revision", "down_revision", "message"], fmt, title="Revisions")


@app.command()
@wraps("db_seed")
def seed(
    overwrite_edits: Annotated[
        bool,
        typer.Option(
            "--overwrite-edits",
            help="Revert values you changed to the seed's (says which, and asks first).",
        ),
    ] = False,
    yes: YesOption = False,
    db: DbOption = None,
) -> None:
    """Reload the shipped seed data: adds what is missing, updates what the seed changed,
    keeps (and reports) every value you changed, unless --overwrite-edits."""
    lines = api.db_seed(overwrite_edits=overwrite_edits, confirm=asker(yes), db=db)
    for line in lines:
        say(line)


class Role(StrEnum):
    reader = "reader"
    contributor = "contributor"
    curator = "curator"


@app.command()
@wraps("grant_role")
def grant(
    account: Annotated[str, typer.Argument(metavar="ROLE", help="PostgreSQL login role.")],
    role: Annotated[Role, typer.Option("--as", help="What the account may do.")],
    db: DbOption = None,
) -> None:
    """Give a PostgreSQL account (created if new) the reader, contributor or curator role.

    reader: reads everything. contributor: also imports into, edits and removes drafts.
    curator: also the catalogue, releases and removals. SQLite has no accounts: refused.
    """
    for line in api.grant_role(account, role=role.value, db=db):
        say(line)
