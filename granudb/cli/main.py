"""The ``granudb`` command: sub-commands are thin wrappers over the library.

A ``GranudbError`` anywhere becomes one line on stderr (``Error: field: value rule``) and
exit code 1; nothing else is printed, and the transaction it happened in was rolled back.

Sub-commands load lazily: ``granudb --help`` lists every command from the one-line help in
``COMMANDS`` below without importing any of their modules, and ``granudb materials list``
imports ``granudb.cli.materials`` only (tests/test_startup.py checks the one-line help here
matches each module's own). The root help is plain Click text rather than Rich, because
importing Rich costs several times Python's own start-up; sub-command help keeps Rich.

Why ``typer._click`` and a replaced ``invoke`` (issue 34, measured with typer 0.28): since
0.26 Typer ships its own copy of Click under ``typer._click`` and exposes publicly only
``Context``, ``BadParameter``, ``Exit`` and ``Abort``. The refusals Typer's parser raises
(``UsageError``, ``NoArgsIsHelpError``, ``MissingParameter``) and the ``Command`` and
``HelpFormatter`` types exist only there; the separate ``click`` package is a different
copy (``click.UsageError is typer._click.exceptions.UsageError`` is False), so catching
its classes would miss every usage error. pyproject pins ``typer>=0.26,<0.29`` so a
release that moves them fails the tests, not a user. ``invoke`` is replaced on each leaf
command (``_missing_as_usage``) because Typer builds the leaf commands of a sub-app
itself, with no app-wide command class; the alternative, ``cls=`` on every
``@app.command()``, repeats the same wiring in every command module.
"""

from __future__ import annotations

import os
import sys
from importlib import import_module
from typing import Any, NoReturn

import typer
from typer import _click as click  # Typer ≥ 0.26 ships its own click
from typer.core import TyperGroup

from granudb import api
from granudb.cli.options import DbOption, wraps
from granudb.cli.output import show_notes, to_json

# name → (module, attribute, one-line help). A Typer app attribute is a command group; a
# function is a single command. The help must match the module's (tests/test_startup.py).
COMMANDS: dict[str, tuple[str, str, str]] = {
    "materials": (
        "granudb.cli.catalog",
        "materials",
        "Particle and wall materials (ρ, E, ν, roughness).",
    ),
    "fluids": (
        "granudb.cli.catalog",
        "fluids",
        "Fluids: density, viscosity and how it varies with temperature.",
    ),
    "sources": (
        "granudb.cli.sources",
        "app",
        "Sources (papers, correlations) cited by stored values.",
    ),
    "pairs": (
        "granudb.cli.pairs",
        "app",
        "Dry restitution and friction of pairs of materials, with their sources.",
    ),
    "collisions": (
        "granudb.cli.collisions",
        "app",
        "Measured collisions: import CSV files, list them with e, β, Ψ, μ_f and regime verdicts.",
    ),
    "fit": (
        "granudb.cli.fit",
        "app",
        "Fit measured collisions: Walton β and μ_f, e(St), gap viscosity.",
    ),
    "dataset": (
        "granudb.cli.dataset",
        "app",
        "Curated collision datasets: catalogue, export and import as Frictionless Data Packages.",
    ),
    "pair": (
        "granudb.cli.pair",
        "pair",
        "Properties, every derived quantity and the regime verdicts for one collision.",
    ),
    "report": (
        "granudb.cli.report",
        "report",
        "Write a lab report: properties with sources, derived quantities, verdicts with the "
        "roughness flag, fits next to published values, figures and methods.",
    ),
    "db": (
        "granudb.cli.db",
        "app",
        "Schema migrations (Alembic) and the shipped seed data.",
    ),
    "reported": (
        "granudb.cli.reported",
        "app",
        "Runs as papers report them (e, e_t, ω_out, angle): import, list, fit.",
    ),
    "reference": (
        "granudb.cli.reference",
        "app",
        "Published collision data shipped as datasets, and their reproduction by granudb.",
    ),
    "dem": (
        "granudb.cli.dem",
        "app",
        "DEM inputs for LIGGGHTS, LAMMPS, Yade and MercuryDPM, checked by running the codes.",
    ),
}


def load_command(name: str) -> click.Command:
    """Import the module of sub-command ``name`` and build its Click command."""
    module, attribute, _ = COMMANDS[name]
    target = getattr(import_module(module), attribute)
    if isinstance(target, typer.Typer):
        command: click.Command = typer.main.get_group(target)
    else:
        single = typer.Typer(add_completion=False)
        single.command(name)(target)
        command = typer.main.get_command(single)
    command.name = name
    _missing_as_usage(command)
    return command


def _missing_as_usage(command: click.Command) -> None:
    """Make each leaf command say a required value the API found missing as click says a
    missing option (with the command's usage, exit 2): "required" is decided once, by the
    API, for Python and the command line alike."""
    if isinstance(command, TyperGroup):
        for child in command.commands.values():
            _missing_as_usage(child)
        return
    original = command.invoke

    def invoke(ctx: click.Context) -> Any:
        try:
            return original(ctx)
        except api.MissingInput as exc:
            param = next((p for p in command.params if p.name == exc.field), None)
            if param is None:
                raise
            raise click.exceptions.MissingParameter(ctx=ctx, param=param) from None

    # replaced on this one command object (module docstring: why not a subclass)
    command.invoke = invoke  # type: ignore[method-assign]


class GranudbGroup(TyperGroup):
    """Turns granudb's refusals into a one-line error and a non-zero exit.

    Three kinds of refusal, none of them a bug: a usage error (missing option or argument,
    unknown option or command, a value outside a choice) is one line with the usage hint
    and exit 2, click's usage code; a ``GranudbError`` is one line and its exit code (1);
    a file-system error (unreadable, a folder for a file, not a folder, exists) is one line
    naming the path and exit 1. Only what is left is reported as an internal error.
    """

    def main(self, args: Any = None, *rest: Any, **kwargs: Any) -> Any:
        """``--db`` and ``--format`` before the command mean the same as after it."""
        given = list(sys.argv[1:] if args is None else args)
        return super().main(options_last(given), *rest, **kwargs)

    def make_context(self, *args: Any, **kwargs: Any) -> Any:
        # The top-level options are parsed here, outside ``invoke``.
        try:
            return super().make_context(*args, **kwargs)
        except _NO_ARGS:
            raise
        except _USAGE as exc:
            _usage_error(exc)

    def list_commands(self, ctx: click.Context) -> list[str]:
        return [*COMMANDS, *super().list_commands(ctx)]

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name in COMMANDS:
            if cmd_name not in self.commands:
                self.commands[cmd_name] = load_command(cmd_name)
            return self.commands[cmd_name]
        return super().get_command(ctx, cmd_name)

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """List every command from ``COMMANDS`` without importing its module."""
        rows = [(name, help_text) for name, (_, _, help_text) in COMMANDS.items()]
        rows += [
            (name, command.get_short_help_str(limit=formatter.width))
            for name, command in sorted(self.commands.items())
            if name not in COMMANDS and not command.hidden
        ]
        width = formatter.width - 6 - max(len(name) for name, _ in rows)
        with formatter.section("Commands"):
            formatter.write_dl([(name, _shorten(text, width)) for name, text in rows])

    def _as_option(self, exc: Any) -> str:
        """A refusal naming its parameter as the option spells it: the option's flag when
        it differs from the parameter's name (``parameter_set`` is ``--set``)."""
        spelled: dict[str, str] = {}
        groups = list(self.commands.values())
        while groups:
            command = groups.pop()
            groups.extend(getattr(command, "commands", {}).values())
            for param in command.params:
                flags = [o for o in param.opts if o.startswith("--")]
                if param.name and flags and flags[0][2:].replace("-", "_") != param.name:
                    spelled[param.name] = flags[0]
        if exc.parameter and exc.field in spelled:
            return exc.render(spelled[exc.field])
        return exc.as_option()

    def invoke(self, ctx: click.Context) -> Any:
        try:
            return super().invoke(ctx)
        except api.GranudbError as exc:
            shown = self._as_option(exc) if isinstance(exc, api.ValidationError) else str(exc)
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


#: Options every command that reads a database (``--db``) or prints a listing
#: (``--format``) takes, accepted before the command name too: ``granudb --db x.sqlite
#: dataset list`` is ``granudb dataset list --db x.sqlite``.
EVERYWHERE = {"--db", "--format", "-f"}


def options_last(args: list[str]) -> list[str]:
    """``args`` with the ``EVERYWHERE`` options that come before the command name moved
    after the command's own arguments (where the command parses them).

    >>> options_last(["--db", "x.sqlite", "dataset", "list"])
    ['dataset', 'list', '--db', 'x.sqlite']
    >>> options_last(["-f", "json", "materials", "list", "--db=y"])
    ['materials', 'list', '--db=y', '-f', 'json']
    """
    moved: list[str] = []
    index = 0
    while index < len(args) and args[index].startswith("-") and args[index] != "--":
        name = args[index].split("=", 1)[0]
        if name not in EVERYWHERE:
            return args if not moved else [*args[index:], *moved]
        if "=" in args[index] or index + 1 >= len(args):
            moved.append(args[index])
            index += 1
        else:
            moved += args[index : index + 2]
            index += 2
    if not moved:
        return args
    rest = args[index:]
    if "--" in rest:
        cut = rest.index("--")
        return [*rest[:cut], *moved, *rest[cut:]]
    return [*rest, *moved]


# Typer's own click raises these; the click package (installed for other tools) is not
# imported: no granudb command runs code that raises its copies.
_USAGE = click.exceptions.UsageError
_NO_ARGS = click.exceptions.NoArgsIsHelpError


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
    rich_markup_mode=None,
    context_settings={"help_option_names": ["-h", "--help"]},
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"granudb {api.__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: bool = typer.Option(
        False, "--version", callback=_version, is_eager=True, help="Print the version and exit."
    ),
) -> None:
    """Materials-and-regime database for particle–wall collisions in liquids.

    Values go in with units ("190 GPa", "4.5 cP") and are stored in SI. --db and
    --format may come before the command or after it.
    """
    show_notes()


def _shorten(text: str, width: int) -> str:
    """The first sentence of ``text``, cut to ``width`` like Click's short help."""
    first = text.split(". ")[0].rstrip(".") + "."
    return first if len(first) <= width else first[: max(width - 3, 10)].rsplit(" ", 1)[0] + "..."


@app.command("datasette-metadata")
@wraps("datasette_metadata")
def datasette_metadata(
    db: DbOption = None,
    print_path: bool = typer.Option(
        False,
        "--print-path",
        help="Print the SQLite file's path instead (for: datasette \"$(granudb "
        'datasette-metadata --print-path)" -m metadata.json); granudb.database_file.',
    ),
) -> None:
    """Print Datasette metadata (titles, descriptions, units) for the database as JSON.

    Browse the database with: granudb datasette-metadata > metadata.json &&
    datasette "$(granudb datasette-metadata --print-path)" -m metadata.json
    """
    if print_path:
        typer.echo(str(api.database_file(db)))
        return
    typer.echo(to_json(api.datasette_metadata(db)))


def main() -> None:
    """Console-script entry point."""
    sys.exit(app())
