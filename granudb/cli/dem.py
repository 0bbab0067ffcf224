"""``granudb dem export|verify``: measured pair values as DEM inputs, checked in the codes."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from granudb.cli.options import DbOption

app = typer.Typer(
    help="DEM inputs for LIGGGHTS, LAMMPS, Yade and MercuryDPM, checked by running the codes.",
    no_args_is_help=True,
)

Particles = Annotated[
    list[str], typer.Option("--particle", help="Particle material (repeat for several types).")
]
Walls = Annotated[list[str], typer.Option("--wall", help="Wall material (repeat for several).")]
Fluid = Annotated[str | None, typer.Option("--fluid", help="The fluid, or omit / 'dry'.")]
Diameter = Annotated[str, typer.Option("--diameter", help='Particle diameter, "12.7 mm".')]
Velocity = Annotated[
    str, typer.Option("--velocity", help='Characteristic impact speed, "0.3 m/s".')
]
Values = Annotated[
    str,
    typer.Option("--values", help="Where values come from: published, dataset or predicted."),
]
DatasetName = Annotated[
    str | None, typer.Option("--dataset", help="The dataset whose fits to use (--values dataset).")
]
Clamp = Annotated[
    bool, typer.Option("--clamp", help="Write a value outside a code's limits at the limit.")
]


@app.command()
def export(
    code: Annotated[str, typer.Option("--code", help="liggghts, lammps, yade or mercurydpm.")],
    particle: Particles,
    wall: Walls,
    diameter: Diameter,
    velocity: Velocity,
    fluid: Fluid = None,
    values: Values = "published",
    dataset: DatasetName = None,
    clamp: Clamp = False,
    output: Annotated[
        Path | None, typer.Option("--output", help="Write to this new file (default: stdout).")
    ] = None,
    db: DbOption = None,
) -> None:
    """Write a ready-to-include input fragment, every number commented with its source."""
    from granudb.api.dem import dem_export
    from granudb.cli.common import open_db
    from granudb.errors import ValidationError

    text = dem_export(
        code,
        particle,
        wall,
        clamp=clamp,
        diameter=diameter,
        velocity=velocity,
        fluid=fluid,
        values=values,
        dataset=dataset,
        db=open_db(db),
    )
    if output is None:
        typer.echo(text, nl=False)
        return
    if output.exists():
        raise ValidationError("--output", str(output), "exists already (choose a new file)")
    try:
        output.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise ValidationError(
            "--output", str(output), f"cannot be written ({exc.strerror})"
        ) from None


@app.command()
def verify(
    particle: Particles,
    wall: Walls,
    diameter: Diameter,
    velocity: Velocity,
    fluid: Fluid = None,
    values: Values = "published",
    dataset: DatasetName = None,
    clamp: Clamp = False,
    db: DbOption = None,
) -> None:
    """Run the exported values in LIGGGHTS, LAMMPS and Yade (where installed): target
    against achieved e, and μ_f on oblique impacts. Codes not installed are "not checked"."""
    from granudb.api.dem import dem_verify
    from granudb.cli.common import open_db
    from granudb.dem.verify import table

    records = dem_verify(
        particle,
        wall,
        clamp=clamp,
        diameter=diameter,
        velocity=velocity,
        fluid=fluid,
        values=values,
        dataset=dataset,
        db=open_db(db),
    )
    typer.echo(table(records))
