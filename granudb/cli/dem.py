"""``granudb dem export|verify``: measured pair values as DEM inputs, checked in the codes."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from granudb import api
from granudb.cli.options import DbOption, Format, wraps
from granudb.cli.output import to_json

app = typer.Typer(
    help="DEM inputs for LIGGGHTS, LAMMPS, Yade and MercuryDPM, checked by running the codes.",
    no_args_is_help=True,
)

Particles = Annotated[
    list[str], typer.Option("--particle", help="Particle material (repeat for several types).")
]
Walls = Annotated[list[str], typer.Option("--wall", help="Wall material (repeat for several).")]
Fluid = Annotated[str | None, typer.Option("--fluid", help="The fluid, or omit / 'dry'.")]
Diameter = Annotated[
    str | None, typer.Option("--diameter", help='Particle diameter, "12.7 mm" (required).')
]
Velocity = Annotated[
    str | None,
    typer.Option("--velocity", help='Characteristic impact speed, "0.3 m/s" (required).'),
]
Values = Annotated[
    str,
    typer.Option("--values", help="Where values come from: published, dataset or predicted."),
]
DatasetName = Annotated[
    str | None, typer.Option("--dataset", help="The dataset whose fits to use (--values dataset).")
]
ParameterSet = Annotated[
    str,
    typer.Option(
        "--set",
        help="central, or low / high: every value at that end of its stated interval "
        "(sensitivity runs).",
    ),
]
Clamp = Annotated[
    bool, typer.Option("--clamp", help="Write a value outside a code's limits at the limit.")
]


@app.command()
@wraps("dem_export")
def export(
    code: Annotated[str, typer.Option("--code", help="liggghts, lammps, yade or mercurydpm.")],
    particle: Particles,
    wall: Walls,
    diameter: Diameter = None,
    velocity: Velocity = None,
    fluid: Fluid = None,
    values: Values = "published",
    dataset: DatasetName = None,
    parameter_set: ParameterSet = "central",
    clamp: Clamp = False,
    output: Annotated[
        Path | None, typer.Option("--output", help="Write to this new file (default: stdout).")
    ] = None,
    db: DbOption = None,
) -> None:
    """Write a ready-to-include input fragment, every number commented with its source."""
    text = api.dem_export(
        code,
        particle,
        wall,
        diameter=diameter,
        velocity=velocity,
        fluid=fluid,
        values=values,
        dataset=dataset,
        parameter_set=parameter_set,
        clamp=clamp,
        output=output,
        db=db,
    )
    if output is None:
        typer.echo(text, nl=False)


@app.command()
@wraps("dem_verify")
def verify(
    particle: Particles,
    wall: Walls,
    codes: Annotated[
        list[str] | None,
        typer.Option("--code", help="Run only this code (repeat): liggghts, lammps, yade."),
    ] = None,
    clamp: Clamp = False,
    fmt: Annotated[
        Format, typer.Option("--format", "-f", help="table for people; json for scripts.")
    ] = Format.table,
    db: DbOption = None,
    diameter: Diameter = None,
    velocity: Velocity = None,
    fluid: Fluid = None,
    values: Values = "published",
    dataset: DatasetName = None,
    parameter_set: ParameterSet = "central",
) -> None:
    """Run the exported values in LIGGGHTS, LAMMPS and Yade (where installed): target
    against achieved e, μ_f on the sliding branch and Ψ_out against Walton's relation with
    a measured β, each judged against its tolerance (e 1 %, μ_f 3 %, Ψ_out 10 %). Exits 1
    when a run fails or nothing could be checked; codes not installed are "not checked"."""
    records = api.dem_verify(
        particle, wall, codes=tuple(codes) if codes else None, clamp=clamp, db=db,
        diameter=diameter, velocity=velocity, fluid=fluid, values=values, dataset=dataset,
        parameter_set=parameter_set,
    )  # fmt: skip
    json_wanted = fmt is Format.json
    typer.echo(to_json(api.verify_document(records)) if json_wanted else api.verify_table(records))
    if not api.verify_passed(records):
        raise typer.Exit(1)
