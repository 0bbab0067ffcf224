"""``granudb fluids list|show|add|update|remove``."""

from __future__ import annotations

from typing import Annotated

import typer

from granudb.cli import fluid_points
from granudb.cli.common import DbOption, Format, FormatOption, given, open_db, quantities
from granudb.cli.confirm import YesOption

app = typer.Typer(
    help="Fluids: density, viscosity and how it varies with temperature.", no_args_is_help=True
)

Name = Annotated[str, typer.Argument(help="Fluid name (matched case-insensitively).")]
Viscosity = Annotated[
    str | None,
    typer.Option("--reference-viscosity", help='At the reference temperature, e.g. "4.5 cP"'),
]
Density = Annotated[
    str | None,
    typer.Option("--reference-density", help='At the reference temperature, e.g. "1112 kg/m^3"'),
]
Temperature = Annotated[
    str | None,
    typer.Option(
        "--reference-temperature",
        help='Temperature of the reference viscosity and density, "20 degC" (default 20 °C).',
    ),
]
Pressure = Annotated[
    str | None,
    typer.Option("--pressure-viscosity", help='Barus pressure-viscosity coefficient, "6e-9 1/Pa".'),
]
Glycerol = Annotated[
    str | None, typer.Option("--glycerol-fraction", help='Glycerol mass fraction, "45 %" or 0.45.')
]
Description = Annotated[str | None, typer.Option("--description")]
SourceKey = Annotated[str | None, typer.Option("--source", help="Key of a source (sources list).")]
Locator = Annotated[
    str | None, typer.Option("--source-locator", help='Where in the source, e.g. "table 2".')
]


def _values(viscosity, density, temperature, pressure, glycerol) -> dict[str, float]:
    return quantities(
        {
            "reference_viscosity_pa_s": (viscosity, "--reference-viscosity"),
            "reference_density_kg_m3": (density, "--reference-density"),
            "reference_temperature_c": (temperature, "--reference-temperature"),
            "pressure_viscosity_pa_inv": (pressure, "--pressure-viscosity"),
            "glycerol_mass_fraction": (glycerol, "--glycerol-fraction"),
        }
    )


@app.command("list")
def list_(db: DbOption = None, fmt: FormatOption = Format.table) -> None:
    """List every fluid (``points`` counts its viscosity–temperature points)."""
    from granudb.api.catalog import fluid_records
    from granudb.cli.output import emit
    from granudb.vocabulary import columns

    records = fluid_records(db=open_db(db))
    emit(
        records,
        columns.FLUID_TABLE_COLUMNS if fmt is Format.table else columns.FLUID_COLUMNS,
        fmt,
        title="Fluids",
    )


@app.command()
def show(name: Name, db: DbOption = None, fmt: FormatOption = Format.table) -> None:
    """Show one fluid with its sources and its viscosity–temperature points."""
    from granudb.cli.output import emit, emit_one
    from granudb.db import catalog
    from granudb.vocabulary import columns

    database = open_db(db)
    with database.session() as session:
        fluid = catalog.get_fluid(session, name)
        record = catalog.fluid_record(fluid)
        record["citation"] = fluid.source.citation if fluid.source else None
        points = catalog.point_records(fluid)
    if fmt is Format.table:
        emit_one(record, fmt, title=f"Fluid {record['name']}")
        if points:
            emit(points, columns.POINT_COLUMNS, fmt, title="Viscosity–temperature points")
    elif fmt is Format.json:
        emit_one(record, fmt, extra={"points": points})
    else:
        emit(points, columns.POINT_COLUMNS, fmt)


@app.command()
def add(
    name: Name,
    viscosity: Viscosity = None,
    density: Density = None,
    temperature: Temperature = None,
    pressure_coefficient: Pressure = None,
    glycerol_fraction: Glycerol = None,
    description: Description = None,
    source: SourceKey = None,
    source_locator: Locator = None,
    db: DbOption = None,
) -> None:
    """Add a fluid. Viscosity and density are required."""
    from granudb.cli.output import say
    from granudb.db import catalog
    from granudb.errors import ValidationError

    required = {"--reference-viscosity": viscosity, "--reference-density": density}
    for option, value in required.items():
        if value is None:
            raise ValidationError(option, "(missing)", "is required to add a fluid")
    values: dict[str, object] = _values(
        viscosity, density, temperature or "20 degC", pressure_coefficient, glycerol_fraction
    )
    values.update(given(description=description, source_locator=source_locator))
    database = open_db(db)
    with database.session(write=True) as session:
        catalog.add_fluid(session, name, values, source=source)
    say(f"added fluid {name}")


@app.command()
def update(
    name: Name,
    viscosity: Viscosity = None,
    density: Density = None,
    temperature: Temperature = None,
    pressure_coefficient: Pressure = None,
    glycerol_fraction: Glycerol = None,
    description: Description = None,
    source: SourceKey = None,
    source_locator: Locator = None,
    rename: Annotated[str | None, typer.Option("--rename", help="New name.")] = None,
    db: DbOption = None,
) -> None:
    """Change some properties of a fluid; prints each change (old → new)."""
    from granudb.cli.output import say_change
    from granudb.db import catalog

    values: dict[str, object] = _values(
        viscosity, density, temperature, pressure_coefficient, glycerol_fraction
    )
    values.update(given(description=description, source_locator=source_locator))
    database = open_db(db)
    with database.session(write=True) as session:
        change = catalog.update_fluid(session, name, values, source=source, new_name=rename)
    say_change(change)


@app.command()
def remove(name: Name, yes: YesOption = False, db: DbOption = None) -> None:
    """Remove a fluid (with its points) that no collision or published value uses; asks first."""
    from granudb.cli.confirm import confirm
    from granudb.cli.output import say
    from granudb.db import catalog

    database = open_db(db)
    with database.session() as session:
        losses = catalog.fluid_removal(session, name)
    confirm(f"fluids remove {name}", losses, yes)
    with database.session(write=True) as session:
        fluid = catalog.remove_fluid(session, name)
    say(f"removed fluid {fluid.name}")


app.add_typer(fluid_points.app, name="points")
