"""``granudb report``: an HTML or Markdown lab report for a pair or for stored runs."""

from __future__ import annotations

import shlex
from pathlib import Path
from typing import Annotated

import typer

from granudb.cli.common import DbOption, quantity


def report(
    ctx: typer.Context,
    pair: Annotated[
        tuple[str, str] | None,
        typer.Option("--pair", help="PARTICLE WALL: a scenario report (plus their stored runs)."),
    ] = None,
    fluid: Annotated[
        str | None, typer.Option("--fluid", help="Fluid of the pair, or 'dry' as a filter.")
    ] = None,
    dataset: Annotated[str | None, typer.Option("--dataset")] = None,
    version: Annotated[str | None, typer.Option("--version")] = None,
    particle: Annotated[str | None, typer.Option("--particle")] = None,
    wall: Annotated[str | None, typer.Option("--wall")] = None,
    min_st: Annotated[float | None, typer.Option("--min-st")] = None,
    max_st: Annotated[float | None, typer.Option("--max-st")] = None,
    regime: Annotated[str | None, typer.Option("--regime")] = None,
    angle_range: Annotated[
        str | None, typer.Option("--angle-range", help="Incidence angles, '10..40 deg'.")
    ] = None,
    diameter: Annotated[
        str, typer.Option("--diameter", help="Pair scenario: particle diameter.")
    ] = "12.7 mm",
    velocity: Annotated[
        str, typer.Option("--velocity", help="Pair scenario: impact speed.")
    ] = "0.3 m/s",
    angle: Annotated[
        str, typer.Option("--angle", help="Pair scenario: incidence angle.")
    ] = "0 deg",
    temperature: Annotated[str | None, typer.Option("--temperature")] = None,
    viscosity: Annotated[str | None, typer.Option("--viscosity")] = None,
    critical_stokes: Annotated[float, typer.Option("--critical-stokes")] = 10.0,
    fmt: Annotated[str, typer.Option("--format", "-f", help="html or md.")] = "html",
    output: Annotated[
        Path | None,
        typer.Option(
            "--output", "-o", help="File to write (default: named after the title, here)."
        ),
    ] = None,
    title: Annotated[str | None, typer.Option("--title")] = None,
    db: DbOption = None,
) -> None:
    """Write a lab report: properties with sources, derived quantities, verdicts with the
    roughness flag, fits next to published values, figures and methods."""
    from granudb.analysis.collisions import CollisionQuery
    from granudb.api._inputs import angle as _angle
    from granudb.api._inputs import angle_range as _angle_range
    from granudb.cli.common import open_db
    from granudb.cli.output import say
    from granudb.errors import ValidationError
    from granudb.report.build import dataset_report, pair_report
    from granudb.report.write import write_report

    if fmt not in {"html", "md"}:
        raise ValidationError("--format", fmt, "must be html or md")
    if title is not None and (len(title) > 300 or any(ord(c) < 32 for c in title)):
        raise ValidationError("--title", title[:40], "must be ≤ 300 printable characters")
    asked = _asked(ctx)
    database = open_db(db)
    with database.session() as session:
        if pair is not None:
            report_data = pair_report(
                session,
                title=title,
                query=asked,
                database=database.display_url,
                particle=pair[0],
                wall=pair[1],
                fluid=None if fluid in (None, "dry") else fluid,
                diameter_m=quantity(diameter, "diameter_m", "--diameter"),
                speed_m_s=quantity(velocity, "v_n_in_m_s", "--velocity"),
                angle_rad=_angle(angle),
                temperature_c=quantity(temperature, "temperature_c", "--temperature"),
                viscosity_pa_s=quantity(viscosity, "viscosity_pa_s", "--viscosity"),
                critical_stokes=critical_stokes,
            )
        else:
            query = CollisionQuery(
                dataset=dataset,
                version=version,
                particle=particle,
                wall=wall,
                fluid=fluid,
                min_normal_stokes=min_st,
                max_normal_stokes=max_st,
                angle_range=_angle_range(angle_range),
                regime=None if regime == "rough" else regime,
                roughness_exceeds_gap=True if regime == "rough" else None,
                critical_stokes=critical_stokes,
            )
            report_data = dataset_report(
                session, title=title, query_text=asked, database=database.display_url, query=query
            )
    path = write_report(report_data, fmt, output)
    say(f"wrote {path}")


def _asked(ctx: typer.Context) -> str:
    """The command as asked, rebuilt from the options given (defaults left out)."""
    parts = ["granudb", "report"]
    for param in ctx.command.params:
        value = ctx.params.get(param.name)
        if value is None or value == param.default or param.name == "db":
            continue
        flag = max(param.opts, key=len)
        if isinstance(value, tuple):
            parts += [flag, *map(str, value)]
        else:
            parts += [flag, str(value)]
    return " ".join(shlex.quote(p) for p in parts)
