"""``granudb pair``: what happens when this particle hits that wall in this fluid."""

from __future__ import annotations

from typing import Annotated, Any

import typer

from granudb.cli.options import CriticalStokes, DbOption, Format, FormatOption


def pair(
    particle: Annotated[str, typer.Argument(help="Particle material, e.g. steel.")],
    wall: Annotated[str, typer.Argument(help="Wall (or second particle) material, e.g. Zerodur.")],
    diameter: Annotated[str, typer.Option("--diameter", help='Particle diameter, "12.7 mm".')],
    velocity: Annotated[
        str, typer.Option("--velocity", help='Impact speed V of the centre, "0.3 m/s".')
    ],
    fluid: Annotated[
        str | None, typer.Option("--fluid", help="Fluid; omit (or 'dry') for a dry collision.")
    ] = None,
    angle: Annotated[
        str, typer.Option("--angle", help='Incidence angle from the normal, "30 deg" (0 to < 90°).')
    ] = "0 deg",
    temperature: Annotated[
        str | None,
        typer.Option(
            "--temperature", help='Fluid temperature, "20 degC" (default: the fluid\'s reference).'
        ),
    ] = None,
    viscosity: Annotated[
        str | None,
        typer.Option("--viscosity", help='Override the fluid viscosity, "0.8 cP" (what-if).'),
    ] = None,
    wall_diameter: Annotated[
        str | None,
        typer.Option("--wall-diameter", help="Diameter of a second sphere (default: a flat wall)."),
    ] = None,
    critical_stokes: CriticalStokes = 10.0,
    db: DbOption = None,
    fmt: FormatOption = Format.table,
) -> None:
    """Properties, every derived quantity and the regime verdicts for one collision."""
    from granudb.api.pair import pair as derive_pair
    from granudb.cli.common import open_db

    document = derive_pair(
        particle,
        wall,
        diameter=diameter,
        velocity=velocity,
        angle=angle,
        fluid=fluid,
        temperature=temperature,
        viscosity=viscosity,
        wall_diameter=wall_diameter,
        critical_stokes=critical_stokes,
        db=open_db(db),
    )
    if fmt is Format.json:
        import sys

        from granudb.cli.output import to_json

        sys.stdout.write(to_json(document) + "\n")
    elif fmt is Format.csv:
        from granudb.cli.output import emit

        row = flatten(document)
        emit([row], list(row), fmt)
    else:
        from granudb.cli.pair_table import print_pair

        print_pair(document, critical_stokes)


def flatten(document: dict[str, Any]) -> dict[str, Any]:
    """One CSV row of a pair document: nested records as ``particle_<column>``,
    ``fluid_<column>``, ``inputs`` under their own names, derived values as they are."""
    row: dict[str, Any] = {}
    for key, value in document.items():
        if key == "inputs":
            row.update(value)
        elif key == "sources":
            row["sources"] = "; ".join(value)
        elif isinstance(value, dict):
            row.update({f"{key}_{k}": v for k, v in value.items()})
        elif value is None and key == "fluid":
            row["fluid_name"] = "dry"
        else:
            row[key] = value
    return row
