"""``granudb report``: an HTML or Markdown lab report for a pair or for stored runs.

``--pair`` takes the scenario options of ``granudb pair`` (diameter, velocity, angle,
temperature, viscosity, second-sphere diameter); a diameter or velocity not given is
assumed and the report says so at the top. The collision filters are those of
``collisions list``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

from granudb import api
from granudb.cli.options import DbOption, collision_filters, wraps
from granudb.cli.output import say

PairOption = Annotated[
    tuple[str, str] | None,
    typer.Option("--pair", help="PARTICLE WALL: a scenario report (plus their stored runs)."),
]


def _scenario(option: str, text: str) -> Any:
    """The metadata of a scenario option: ``Annotated[str | None, _scenario(...)]``."""
    return typer.Option(option, help=f"Pair: {text}")


@collision_filters
@wraps("report")
def report(
    pair: PairOption = None,
    diameter: Annotated[
        str | None, _scenario("--diameter", 'particle diameter, "12.7 mm" (assumed if omitted).')
    ] = None,
    velocity: Annotated[
        str | None, _scenario("--velocity", 'impact speed, "0.3 m/s" (assumed if omitted).')
    ] = None,
    angle: Annotated[
        str | None, _scenario("--angle", 'incidence angle, "30 deg" (default 0°).')
    ] = None,
    temperature: Annotated[str | None, _scenario("--temperature", "fluid temperature.")] = None,
    viscosity: Annotated[
        str | None, _scenario("--viscosity", "override the fluid viscosity.")
    ] = None,
    wall_diameter: Annotated[
        str | None,
        _scenario("--wall-diameter", "diameter of a second sphere, free unless --target fixed."),
    ] = None,
    target: Annotated[
        str | None, _scenario("--target", "wall, fixed or free (a second sphere's default).")
    ] = None,
    fmt: Annotated[str, typer.Option("--format", "-f", help="html or md.")] = "html",
    output: Annotated[
        Path | None,
        typer.Option(
            "--output", "-o", help="File to write (default: named after the title, here)."
        ),
    ] = None,
    force: Annotated[
        bool, typer.Option("--force", help="Overwrite the --output file if it exists.")
    ] = False,
    title: Annotated[str | None, typer.Option("--title")] = None,
    db: DbOption = None,
    filters: dict[str, Any] | None = None,
) -> None:
    """Write a lab report: properties with sources, derived quantities, verdicts with the
    roughness flag, fits next to published values, figures and methods."""
    path = api.report(
        pair,
        format=fmt,
        output=output if output is not None else Path.cwd(),
        force=force,
        title=title,
        diameter=diameter,
        velocity=velocity,
        angle=angle,
        temperature=temperature,
        viscosity=viscosity,
        wall_diameter=wall_diameter,
        target=target,
        db=db,
        **(filters or {}),
    )
    say(f"wrote {path}")
