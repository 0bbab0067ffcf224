"""``granudb fluids points add|import``: a fluid's viscosity against temperature.

With two or more points a fluid has a viscosity at any temperature between them (the
points, Andrade-interpolated and scaled through the printed reference value); without,
only at its reference temperature.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from granudb.cli.common import DbOption, open_db, quantities

app = typer.Typer(
    help="A fluid's viscosity (and density) against temperature.", no_args_is_help=True
)

Name = Annotated[str, typer.Argument(help="Fluid name (matched case-insensitively).")]
SourceKey = Annotated[str | None, typer.Option("--source", help="Key of a source.")]
Replace = Annotated[
    bool, typer.Option("--replace", help="Change a point at a temperature the fluid already has.")
]


@app.command()
def add(
    name: Name,
    temperature: Annotated[str, typer.Option("--temperature", help='e.g. "30 degC"')],
    viscosity: Annotated[str, typer.Option("--viscosity", help='At that temperature, "2.1 cP"')],
    density: Annotated[
        str | None, typer.Option("--density", help='At that temperature, "1085 kg/m^3"')
    ] = None,
    source: SourceKey = None,
    replace: Replace = False,
    db: DbOption = None,
) -> None:
    """Add one point (temperature, viscosity[, density])."""
    from granudb.cli.output import say
    from granudb.db import catalog

    point = quantities(
        {
            "temperature_c": (temperature, "--temperature"),
            "viscosity_pa_s": (viscosity, "--viscosity"),
            "density_kg_m3": (density, "--density"),
        }
    )
    with open_db(db).session(write=True) as session:
        lines = catalog.add_fluid_points(session, name, [point], source, replace=replace)
    for line in lines:
        say(line)


@app.command("import")
def import_(
    name: Name,
    file: Annotated[
        Path, typer.Argument(help="CSV: temperature [degC], viscosity [cP], density [kg/m^3].")
    ],
    source: SourceKey = None,
    replace: Replace = False,
    db: DbOption = None,
) -> None:
    """Add every point of a CSV file (units in the headers), all or none."""
    from granudb.cli.output import say
    from granudb.db import catalog
    from granudb.io.seed import POINT_NUMERIC, read_table

    points = read_table(file, POINT_NUMERIC, [])
    with open_db(db).session(write=True) as session:
        lines = catalog.add_fluid_points(session, name, points, source, replace=replace)
    for line in lines:
        say(line)
