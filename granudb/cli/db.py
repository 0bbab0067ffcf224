"""``granudb db upgrade|downgrade|current|history|seed``: the schema and the seed data."""

from __future__ import annotations

from typing import Annotated

import typer

from granudb.cli.common import DbOption, Format, FormatOption
from granudb.cli.confirm import YesOption

app = typer.Typer(
    help="Schema migrations (Alembic) and the shipped seed data.", no_args_is_help=True
)


def _open(db: str | None):
    from granudb.db.engine import open_database

    return open_database(db, migrate=False)


@app.command()
def upgrade(
    revision: Annotated[str, typer.Argument(help="Target revision.")] = "head",
    db: DbOption = None,
) -> None:
    """Migrate the database forward (a new database is created and seeded)."""
    from granudb.api.database import connect
    from granudb.cli.output import say
    from granudb.db import migration

    if revision == "head":
        database = _open(db)
        with database.engine.connect() as connection:
            before = migration.current_revision(connection)
        database.dispose()
        database = connect(db)
        after = migration.head_revision()
    else:
        database = _open(db)
        before, after = migration.upgrade(database, revision)
    say(
        f"schema: {before or 'empty'} → {after}"
        if before != after
        else f"schema: already at {after}"
    )


@app.command()
def downgrade(
    revision: Annotated[str, typer.Argument(help='Target revision, or "base" to drop all.')],
    yes: YesOption = False,
    db: DbOption = None,
) -> None:
    """Migrate the database back to an older revision.

    Says first which tables and columns would lose values (and how many) and asks, or needs
    --yes; a downgrade that loses nothing runs at once.
    """
    from granudb.cli.confirm import confirm
    from granudb.cli.output import say
    from granudb.db import migration

    database = _open(db)
    losses = migration.plan_downgrade(database, revision)
    confirm(f"db downgrade {revision}", losses, yes)
    before, after = migration.downgrade(database, revision, accepted=losses)
    for line in losses:
        say(f"lost {line}")
    say(f"schema: {before or 'empty'} → {after or 'empty'}")


@app.command()
def current(db: DbOption = None, fmt: FormatOption = Format.table) -> None:
    """The database's schema revision and the newest this granudb knows."""
    from granudb.cli.output import emit_one
    from granudb.db import migration

    database = _open(db)
    with database.engine.connect() as connection:
        revision = migration.current_revision(connection)
    head = migration.head_revision()
    emit_one(
        {
            "database": database.display_url,
            "revision": revision,
            "head": head,
            "up_to_date": revision == head,
        },
        fmt,
        title="Schema",
    )


@app.command()
def history(fmt: FormatOption = Format.table) -> None:
    """Every schema revision granudb ships, newest first."""
    from granudb.cli.output import emit
    from granudb.db import migration

    emit(migration.history(), ["revision", "down_revision", "message"], fmt, title="Revisions")


@app.command()
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
    from granudb.api.seeding import reseed, seed_reverts
    from granudb.cli.common import open_db
    from granudb.cli.confirm import confirm
    from granudb.cli.output import say

    database = open_db(db)
    if database.created:
        lines = database.seed_report
    else:
        accepted = None
        if overwrite_edits:
            accepted = seed_reverts(database)
            confirm("db seed --overwrite-edits", accepted, yes)
        lines = reseed(database, overwrite_edits=overwrite_edits, accepted=accepted)
    for line in lines:
        say(line)
