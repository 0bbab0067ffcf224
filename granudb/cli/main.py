"""The ``granudb`` command: sub-commands are thin wrappers over the library.

A ``GranudbError`` anywhere becomes one line on stderr (``Error: field: value rule``) and
exit code 1; nothing else is printed, and the transaction it happened in was rolled back.
"""

from __future__ import annotations

import os
import sys
from typing import Any

import typer
from typer.core import TyperGroup

from granudb.cli import collisions, dataset, db, fit, fluids, materials, pair, report, sources
from granudb.cli.common import DbOption
from granudb.version import __version__


class GranudbGroup(TyperGroup):
    """Turns granudb's refusals into a one-line error and a non-zero exit."""

    def invoke(self, ctx: typer.Context) -> Any:
        from granudb.errors import GranudbError

        try:
            return super().invoke(ctx)
        except GranudbError as exc:
            message = str(exc).replace("\n", " ")
            typer.echo(f"Error: {message}", err=True)
            raise typer.Exit(exc.exit_code) from None
        except (typer.Exit, typer.Abort, KeyboardInterrupt, BrokenPipeError):
            raise
        except Exception as exc:
            if os.environ.get("GRANUDB_DEBUG"):
                raise
            # A bug, not bad input: still one line, and the transaction was rolled back.
            first = str(exc).splitlines()[0] if str(exc) else ""
            typer.echo(
                f"Error: internal error ({type(exc).__name__}: {first}); nothing was "
                "changed. Set GRANUDB_DEBUG=1 for the traceback and please report it.",
                err=True,
            )
            raise typer.Exit(2) from None


app = typer.Typer(
    cls=GranudbGroup,
    name="granudb",
    help="Materials-and-regime database for particle–wall collisions in liquids.",
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    context_settings={"help_option_names": ["-h", "--help"]},
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"granudb {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: bool = typer.Option(
        False, "--version", callback=_version, is_eager=True, help="Print the version and exit."
    ),
) -> None:
    """Materials-and-regime database for particle–wall collisions in liquids.

    Values go in with units ("190 GPa", "4.5 cP") and are stored in SI.
    """


app.add_typer(materials.app, name="materials")
app.add_typer(fluids.app, name="fluids")
app.add_typer(sources.app, name="sources")
app.add_typer(collisions.app, name="collisions")
app.add_typer(fit.app, name="fit")
app.add_typer(dataset.app, name="dataset")
app.command("pair")(pair.pair)
app.command("report")(report.report)
app.add_typer(db.app, name="db")


@app.command("datasette-metadata")
def datasette_metadata(
    db: DbOption = None,
    print_path: bool = typer.Option(
        False,
        "--print-path",
        help="Print the SQLite file's path instead (for: datasette \"$(granudb "
        'datasette-metadata --print-path)" -m metadata.json).',
    ),
) -> None:
    """Print Datasette metadata (titles, descriptions, units) for the database as JSON.

    Browse the database with: granudb datasette-metadata > metadata.json &&
    datasette "$(granudb datasette-metadata --print-path)" -m metadata.json
    """
    from pathlib import Path

    from sqlalchemy.engine import make_url

    from granudb.cli.output import to_json
    from granudb.config import resolve_database_url
    from granudb.errors import ValidationError
    from granudb.io.datasette import datasette_metadata as metadata

    url = make_url(resolve_database_url(db))
    path = url.database if url.get_backend_name() == "sqlite" and url.database else None
    if print_path:
        if path is None or path == ":memory:":
            raise ValidationError(
                "--db", url.render_as_string(), "is not a SQLite file (Datasette reads SQLite)"
            )
        typer.echo(str(Path(path).resolve()))
        return
    typer.echo(to_json(metadata(Path(path).stem if path else "granudb")))


def main() -> None:
    """Console-script entry point."""
    sys.exit(app())
