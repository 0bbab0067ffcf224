"""``granudb dem export|verify``: measured pair values as DEM inputs, checked in the codes."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from granudb import api
from granudb.cli.options import DbOption, Format, text_options, wraps
from granudb.cli.output import to_json

app = typer.Typer(
    help="DEM inputs for LIGGGHTS, LAMMPS, Yade and MercuryDPM, checked by running the codes.",
    no_args_is_help=True,
)

Particles = Annotated[
    list[str], typer.Option("--particle", help="Particle material (repeat for several types).")
]
Walls = Annotated[list[str], typer.Option("--wall", help="Wall material (repeat for several).")]
#: The options that choose the DEM model (``granudb.api.dem.MODEL_OPTIONS``), written once
#: for export and verify; they reach a command as its ``model`` keyword.
model_options = text_options(
    "model",
    {
        "diameter": 'Particle diameter, "12.7 mm" (required).',
        "velocity": 'Characteristic impact speed, "0.3 m/s" (required).',
        "fluid": "The fluid, or omit / 'dry'.",
        "values": "Where values come from: published (default), dataset or predicted.",
        "dataset": "The dataset whose fits to use, NAME or NAME@VERSION (--values dataset).",
        "parameter_set": Annotated[
            str | None,
            typer.Option(
                "--set",
                help="central (default), or low / high: every value at that end of its stated "
                "interval (sensitivity runs).",
            ),
        ],
    },
)
Clamp = Annotated[
    bool, typer.Option("--clamp", help="Write a value outside a code's limits at the limit.")
]


@app.command()
@model_options
@wraps("dem_export")
def export(
    code: Annotated[str, typer.Option("--code", help="liggghts, lammps, yade or mercurydpm.")],
    particle: Particles,
    wall: Walls,
    clamp: Clamp = False,
    output: Annotated[
        Path | None, typer.Option("--output", help="Write to this new file (default: stdout).")
    ] = None,
    db: DbOption = None,
    model: dict | None = None,
) -> None:
    """Write a ready-to-include input fragment, every number commented with its source."""
    deck = api.dem_export(code, particle, wall, clamp=clamp, output=output, db=db, **model or {})
    if output is None:
        typer.echo(deck, nl=False)


@app.command()
@model_options
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
    model: dict | None = None,
) -> None:
    """Run the exported values in LIGGGHTS, LAMMPS and Yade (where installed): target
    against achieved e, μ_f on the sliding branch and Ψ_out against Walton's relation with
    a measured β, each judged against its tolerance (e 1 %, μ_f 3 %, Ψ_out 10 %). Exits 1
    when a run fails or nothing could be checked; codes not installed are "not checked"."""
    chosen = tuple(codes) if codes else None
    records = api.dem_verify(particle, wall, codes=chosen, clamp=clamp, db=db, **model or {})
    json_wanted = fmt is Format.json
    typer.echo(to_json(api.verify_document(records)) if json_wanted else api.verify_table(records))
    if not api.verify_passed(records):
        raise typer.Exit(1)
