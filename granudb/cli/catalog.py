"""``granudb materials list|show|add|update|remove`` and ``granudb fluids list|show|add|
update|remove|points``: one face for both kinds of catalogue entry.

The commands are generated from the catalogue's specification
(``granudb.vocabulary.MATERIALS`` / ``FLUIDS``), as the API functions are: ``add`` and
``update`` take one option per value a user may set, named after the API's parameter
(``youngs_modulus`` → ``--youngs-modulus``), with the title and an example from the
vocabulary as help (tests/test_one_door.py holds the options to the functions'
signatures); a value is passed on as typed, for the API to parse.
"""

import inspect
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any

import typer

from granudb import api
from granudb.cli.confirm import asker
from granudb.cli.options import (
    DbOption,
    Format,
    FormatOption,
    YesOption,
    option_name,
    text_option,
    wraps,
)
from granudb.cli.output import emit, emit_one, say

#: The options ``add``/``update`` take besides the properties, with their help.
OTHER_HELP = {
    "source": "Key of a source (granudb sources list).",
    "rename": "New name.",
}


def _option(catalogue: Any, parameter: str, required: bool) -> inspect.Parameter:
    column = catalogue.parameters.get(parameter)
    if column is not None:
        term = api.term(column)
        text = term.title + (f', e.g. "{term.example}"' if term.example else "")
        if required:
            text += " (required)"
    else:
        text = OTHER_HELP[parameter]
    annotation = Annotated[str | None, typer.Option(option_name(parameter), help=text)]
    return inspect.Parameter(
        parameter, inspect.Parameter.KEYWORD_ONLY, default=None, annotation=annotation
    )


def _changing(catalogue: Any, function: str, adding: bool) -> Callable[..., None]:
    """The ``add`` or ``update`` command of ``granudb.<function>``: one option per value
    the catalogue's specification lets a user set, plus ``--source`` (and ``--rename``);
    the API function is loaded only when the command runs."""
    required = {api.parameter_of(c) for c in catalogue.required} if adding else set()
    keywords = [*catalogue.parameters, "source", *([] if adding else ["rename"])]
    name = inspect.Parameter(
        "name",
        inspect.Parameter.POSITIONAL_OR_KEYWORD,
        annotation=Annotated[str, typer.Argument(help=f"The {catalogue.kind}'s name.")],
    )
    db = inspect.Parameter("db", inspect.Parameter.KEYWORD_ONLY, default=None, annotation=DbOption)
    options = [_option(catalogue, k, k in required) for k in keywords]

    def command(**given: Any) -> None:
        result = getattr(api, function)(given.pop("name"), **given)
        say(f"added {catalogue.kind} {result['name']}" if adding else str(result))

    # mypy has no attribute __signature__ on a function; inspect.signature reads it
    command.__signature__ = inspect.Signature([name, *options, db])  # type: ignore[attr-defined]
    if adding:
        needed = ", ".join(option_name(p) for p in keywords if p in required)
        command.__doc__ = f"Add a {catalogue.kind}; {needed} are required."
    else:
        command.__doc__ = f"Change some values of a {catalogue.kind}; prints each change."
    return wraps(function)(command)


def catalogue_app(catalogue: Any, help_text: str) -> typer.Typer:
    """The command group of one kind of entry (``materials`` or ``fluids``)."""
    kind, plural = catalogue.kind, catalogue.plural
    app = typer.Typer(help=help_text, no_args_is_help=True)
    Name = Annotated[str, typer.Argument(help=f"The {kind}'s name (any case).")]

    @app.command("list")
    @wraps(plural)
    def list_(db: DbOption = None, fmt: FormatOption = Format.table) -> None:
        records = getattr(api, plural)(db=db, as_frame=False)
        columns = catalogue.narrow if fmt is Format.table else catalogue.columns
        emit(records, list(columns), fmt, title=plural.capitalize())

    list_.__doc__ = f"List every {kind} with its properties (SI in json/csv)."

    @app.command()
    @wraps(kind)
    def show(name: Name, db: DbOption = None, fmt: FormatOption = Format.table) -> None:
        record = getattr(api, kind)(name, db=db)
        points = record.pop("points", None) if kind == "fluid" else None
        if fmt is Format.json:
            emit_one(record, fmt, extra={"points": points} if points is not None else None)
        elif fmt is Format.csv and points is not None:
            emit(points, api.POINT_COLUMNS, fmt)
        else:
            emit_one(record, fmt, title=f"{kind.capitalize()} {record['name']}")
            if points:
                emit(points, api.POINT_COLUMNS, fmt, title="Viscosity–temperature points")

    show.__doc__ = f"Show one {kind}, with the full citation of its source."

    @app.command()
    @wraps(f"{kind}_history")
    def history(name: Name, db: DbOption = None, fmt: FormatOption = Format.table) -> None:
        records = getattr(api, f"{kind}_history")(name, db=db)
        shown = ("revision", "kept_at", "changes", *catalogue.narrow[1:-1], "used_by")
        columns = shown if fmt is Format.table else ("revision", "kept_at", "changes",
                                                      "used_by", *catalogue.columns)  # fmt: skip
        emit(records, list(columns), fmt, title=f"{kind.capitalize()} {name}: history",
             vertical=True)  # fmt: skip

    history.__doc__ = (
        f"A {kind} as it is and as released datasets keep it (a release never changes)."
    )

    app.command("add")(_changing(catalogue, f"add_{kind}", adding=True))
    app.command("update")(_changing(catalogue, f"update_{kind}", adding=False))

    @app.command()
    @wraps(f"remove_{kind}")
    def remove(name: Name, yes: YesOption = False, db: DbOption = None) -> None:
        removed = getattr(api, f"remove_{kind}")(name, confirm=asker(yes), db=db)
        say(f"removed {kind} {removed}")

    remove.__doc__ = f"Remove a {kind} nothing refers to; says what goes and asks first."
    return app


materials = catalogue_app(api.MATERIALS, "Particle and wall materials (ρ, E, ν, roughness).")
fluids = catalogue_app(api.FLUIDS, "Fluids: density, viscosity and how it varies with temperature.")
points = typer.Typer(
    help="A fluid's viscosity (and density) against temperature.", no_args_is_help=True
)
fluids.add_typer(points, name="points")

FluidName = Annotated[str, typer.Argument(help="The fluid's name (any case).")]
PointSource = Annotated[str | None, typer.Option("--source", help="Key of a source.")]
Replace = Annotated[
    bool, typer.Option("--replace", help="Change a point at a temperature the fluid already has.")
]


@points.command("add")
@wraps("add_fluid_point")
def add_point(
    name: FluidName,
    temperature: Annotated[str | None, text_option('e.g. "30 degC"')] = None,
    viscosity: Annotated[str | None, text_option('At that temperature, "2.1 cP"')] = None,
    density: Annotated[str | None, text_option('At that temperature, "1085 kg/m^3"')] = None,
    source: PointSource = None,
    replace: Replace = False,
    db: DbOption = None,
) -> None:
    """Add one point (temperature, viscosity[, density])."""
    for line in api.add_fluid_point(
        name,
        temperature=temperature,
        viscosity=viscosity,
        density=density,
        source=source,
        replace=replace,
        db=db,
    ):
        say(line)


@points.command("import")
@wraps("import_fluid_points")
def import_points(
    name: FluidName,
    file: Annotated[
        Path, typer.Argument(help="CSV: temperature [degC], viscosity [cP], density [kg/m^3].")
    ],
    source: PointSource = None,
    replace: Replace = False,
    db: DbOption = None,
) -> None:
    """Add every point of a CSV file (units in the headers), all or none."""
    lines = api.import_fluid_points(name, file, source=source, replace=replace, db=db)
    for line in lines:
        say(line)
