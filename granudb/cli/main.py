"""The ``granudb`` command: sub-commands are thin wrappers over the library.

A ``GranudbError`` anywhere becomes one line on stderr (``Error: field: value rule``) and
exit code 1; nothing else is printed, and the transaction it happened in was rolled back.
"""

from __future__ import annotations

import os
import sys
from typing import Any, NoReturn

import click
import typer
from typer.core import TyperGroup

from granudb.cli import (
    collisions,
    dataset,
    db,
    dem,
    fit,
    fluids,
    materials,
    pair,
    report,
    sources,
)
from granudb.cli.common import DbOption
from granudb.version import __version__


class GranudbGroup(TyperGroup):
    """Turns granudb's refusals into a one-line error and a non-zero exit.

    Three kinds of refusal, none of them a bug: a usage error (missing option or argument,
    unknown option or command, a value outside a choice) is one line with the usage hint
    and exit 2, click's usage code; a ``GranudbError`` is one line and its exit code (1);
    a file-system error (unreadable, a folder for a file, not a folder, exists) is one line
    naming the path and exit 1. Only what is left is reported as an internal error.
    """

    def make_context(self, *args: Any, **kwargs: Any) -> Any:
        # The top-level options are parsed here, outside ``invoke``.
        try:
            return super().make_context(*args, **kwargs)
        except _NO_ARGS:
            raise
        except _USAGE as exc:
            _usage_error(exc)

    def invoke(self, ctx: typer.Context) -> Any:
        from granudb.errors import GranudbError, ValidationError

        try:
            return super().invoke(ctx)
        except GranudbError as exc:
            shown = exc.as_option() if isinstance(exc, ValidationError) else str(exc)
            message = shown.replace("\n", " ")
            typer.echo(f"Error: {message}", err=True)
            raise typer.Exit(exc.exit_code) from None
        except _NO_ARGS:
            raise
        except _USAGE as exc:
            _usage_error(exc)
        except (typer.Exit, typer.Abort, KeyboardInterrupt, BrokenPipeError):
            raise
        except OSError as exc:
            if os.environ.get("GRANUDB_DEBUG") or exc.filename is None:
                raise
            _file_error(exc)
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


def _click_classes(name: str) -> tuple[type[Exception], ...]:
    """click's exception class ``name``, and Typer's vendored copy of it (Typer ≥ 0.20
    ships its own click, whose exceptions are not click's)."""
    classes: list[type[Exception]] = [getattr(click.exceptions, name)]
    try:
        from typer._click import exceptions as vendored
    except ImportError:  # a Typer that uses click itself
        return tuple(classes)
    classes.append(getattr(vendored, name))
    return tuple(classes)


_USAGE = _click_classes("UsageError")
_NO_ARGS = _click_classes("NoArgsIsHelpError")


def _usage_error(exc: Any) -> NoReturn:
    """One line: what is wrong, then the command's usage and where to read more."""
    message = " ".join(exc.format_message().split())
    hint = ""
    if exc.ctx is not None:
        usage = " ".join(exc.ctx.get_usage().split())
        hint = f" ({usage}; '{exc.ctx.command_path} --help' explains every option)"
    typer.echo(f"Error: {message}{hint}", err=True)
    raise typer.Exit(exc.exit_code)


_FILE_PROBLEMS = {
    FileNotFoundError: "does not exist",
    IsADirectoryError: "is a folder, not a file",
    NotADirectoryError: "is not a folder (or lies inside a file)",
    FileExistsError: "already exists",
    PermissionError: "cannot be read or written (permission denied)",
}


def _file_error(exc: OSError) -> NoReturn:
    """A file-system refusal (bad path from outside) as one line naming the path."""
    rule = next(
        (text for kind, text in _FILE_PROBLEMS.items() if isinstance(exc, kind)),
        exc.strerror or "cannot be used",
    )
    typer.echo(f"Error: {exc.filename}: {rule}; nothing was changed", err=True)
    raise typer.Exit(1)


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
app.add_typer(dem.app, name="dem")


@app.command("datasette-metadata")
def datasette_metadata(
    db: DbOption = None,
) -> None:
    """Print Datasette metadata (titles, descriptions, units) for the database as JSON.

    Browse the database with: granudb datasette-metadata > metadata.json &&
    datasette PATH/TO/granudb.sqlite -m metadata.json
    """
    from pathlib import Path

    from sqlalchemy.engine import make_url

    from granudb.cli.output import to_json
    from granudb.config import resolve_database_url
    from granudb.io.datasette import datasette_metadata as metadata

    url = make_url(resolve_database_url(db))
    name = (
        Path(url.database).stem
        if url.get_backend_name() == "sqlite" and url.database
        else "granudb"
    )
    typer.echo(to_json(metadata(name)))


def main() -> None:
    """Console-script entry point."""
    sys.exit(app())
