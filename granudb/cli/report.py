"""``granudb report``: an HTML or Markdown lab report for a pair or for stored runs.

``--pair`` takes the scenario options of ``granudb pair`` (diameter, velocity, angle,
temperature, viscosity, second-sphere diameter); a diameter or velocity not given is
assumed and the report says so at the top. The collision filters are those of
``collisions list``.
"""

from __future__ import annotations

import shlex
from pathlib import Path
from typing import Annotated

import typer

from granudb.cli import options
from granudb.cli.common import DbOption, quantity

PairOption = Annotated[
    tuple[str, str] | None,
    typer.Option("--pair", help="PARTICLE WALL: a scenario report (plus their stored runs)."),
]
FluidOption = Annotated[
    str | None, typer.Option("--fluid", help="Fluid of the pair, or 'dry' as a filter.")
]
DiameterOption = Annotated[
    str | None,
    typer.Option("--diameter", help='Pair: particle diameter, "12.7 mm" (assumed if omitted).'),
]
VelocityOption = Annotated[
    str | None,
    typer.Option("--velocity", help='Pair: impact speed, "0.3 m/s" (assumed if omitted).'),
]
AngleOption = Annotated[
    str | None, typer.Option("--angle", help='Pair: incidence angle, "30 deg" (default 0°).')
]
TemperatureOption = Annotated[
    str | None, typer.Option("--temperature", help="Pair: fluid temperature.")
]
ViscosityOption = Annotated[
    str | None, typer.Option("--viscosity", help="Pair: override the fluid viscosity.")
]
WallDiameterOption = Annotated[
    str | None,
    typer.Option("--wall-diameter", help="Pair: diameter of a second sphere (default: wall)."),
]
FormatOption = Annotated[str, typer.Option("--format", "-f", help="html or md.")]
OutputOption = Annotated[
    Path | None,
    typer.Option("--output", "-o", help="File to write (default: named after the title, here)."),
]
ForceOption = Annotated[
    bool, typer.Option("--force", help="Overwrite the --output file if it exists.")
]
TitleOption = Annotated[str | None, typer.Option("--title")]


def report(
    ctx: typer.Context,
    pair: PairOption = None,
    fluid: FluidOption = None,
    dataset: options.Dataset = None,
    version: options.Version = None,
    particle: options.Particle = None,
    wall: options.Wall = None,
    min_normal_stokes: options.MinNormalStokes = None,
    max_normal_stokes: options.MaxNormalStokes = None,
    regime: options.Regime = None,
    roughness_exceeds_gap: options.RoughnessExceedsGap = None,
    rebound_expected: options.ReboundExpected = None,
    angle_range: options.AngleRange = None,
    diameter: DiameterOption = None,
    velocity: VelocityOption = None,
    angle: AngleOption = None,
    temperature: TemperatureOption = None,
    viscosity: ViscosityOption = None,
    wall_diameter: WallDiameterOption = None,
    critical_stokes: options.CriticalStokes = 10.0,
    fmt: FormatOption = "html",
    output: OutputOption = None,
    force: ForceOption = False,
    title: TitleOption = None,
    db: DbOption = None,
) -> None:
    """Write a lab report: properties with sources, derived quantities, verdicts with the
    roughness flag, fits next to published values, figures and methods."""
    from granudb.api.collisions import collision_query
    from granudb.cli.common import open_db
    from granudb.cli.output import say
    from granudb.errors import ValidationError
    from granudb.report.build import dataset_report, pair_report
    from granudb.report.write import check_output, write_report

    if fmt not in {"html", "md"}:
        raise ValidationError("--format", fmt, "must be html or md")
    if title is not None and (len(title) > 300 or any(ord(c) < 32 for c in title)):
        raise ValidationError("--title", title[:40], "must be ≤ 300 printable characters")
    if not critical_stokes > 0:
        raise ValidationError("--critical-stokes", f"{critical_stokes:g}", "must be > 0")
    check_output(output, force=force)
    asked = _asked(ctx)
    database = open_db(db)
    with database.reading() as session:  # Core only: a report reads, no ORM needed
        if pair is not None:
            scenario = _scenario(fluid, diameter, velocity, angle, temperature, viscosity)
            report_data = pair_report(
                session,
                title=title,
                query=asked,
                database=database.display_url,
                particle=pair[0],
                wall=pair[1],
                wall_diameter_m=quantity(wall_diameter, "wall_diameter_m", "--wall-diameter"),
                critical_stokes=critical_stokes,
                **scenario,
            )
        else:
            query = collision_query(
                dataset=dataset,
                version=version,
                particle=particle,
                wall=wall,
                fluid=fluid,
                min_normal_stokes=min_normal_stokes,
                max_normal_stokes=max_normal_stokes,
                angle_range=angle_range,
                regime=regime,
                roughness_exceeds_gap=roughness_exceeds_gap,
                rebound_expected=rebound_expected,
                critical_stokes=critical_stokes,
            )
            report_data = dataset_report(
                session, title=title, query_text=asked, database=database.display_url, query=query
            )
    path = write_report(report_data, fmt, output, force=force)
    say(f"wrote {path}")


def _scenario(
    fluid: str | None,
    diameter: str | None,
    velocity: str | None,
    angle: str | None,
    temperature: str | None,
    viscosity: str | None,
) -> dict[str, object]:
    """The pair scenario's inputs in SI, as ``granudb pair`` reads them; an angle not
    given is 0° and said to be assumed."""
    from granudb.api import inputs

    return {
        "fluid": None if fluid in (None, "dry") else fluid,
        "diameter_m": quantity(diameter, "diameter_m", "--diameter"),
        "speed_m_s": quantity(velocity, "impact_speed_m_s", "--velocity"),
        "angle_rad": inputs.angle(angle or "0 deg"),
        "temperature_c": quantity(temperature, "temperature_c", "--temperature"),
        "viscosity_pa_s": quantity(viscosity, "viscosity_pa_s", "--viscosity"),
        "assumed": set() if angle is not None else {"incidence_angle_rad"},
    }


def _asked(ctx: typer.Context) -> str:
    """The command as asked, rebuilt from the options given (defaults left out)."""
    parts = ["granudb", "report"]
    for param in ctx.command.params:
        value = ctx.params.get(param.name)
        if value is None or value == param.default or param.name in {"db", "force"}:
            continue
        flag = max(param.opts, key=len)
        if isinstance(value, tuple):
            parts += [flag, *map(str, value)]
        else:
            parts += [flag, str(value)]
    return " ".join(shlex.quote(p) for p in parts)
