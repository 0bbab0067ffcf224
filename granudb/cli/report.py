"""``granudb report``: an HTML or Markdown lab report for a pair or for stored runs.

``--pair`` takes the scenario options of ``granudb pair`` (diameter, velocity, angle,
temperature, viscosity, second-sphere diameter); a diameter or velocity not given is
assumed and the report says so at the top. The collision filters are those of
``collisions list``.
"""

from __future__ import annotations

import math
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
        str | None,
        typer.Option("--diameter", help='Pair: particle diameter, "12.7 mm" (assumed if omitted).'),
    ] = None,
    velocity: Annotated[
        str | None,
        typer.Option("--velocity", help='Pair: impact speed, "0.3 m/s" (assumed if omitted).'),
    ] = None,
    angle: Annotated[
        str | None, typer.Option("--angle", help='Pair: incidence angle, "30 deg" (default 0°).')
    ] = None,
    temperature: Annotated[
        str | None, typer.Option("--temperature", help="Pair: fluid temperature.")
    ] = None,
    viscosity: Annotated[
        str | None, typer.Option("--viscosity", help="Pair: override the fluid viscosity.")
    ] = None,
    wall_diameter: Annotated[
        str | None,
        typer.Option("--wall-diameter", help="Pair: diameter of a second sphere (default: wall)."),
    ] = None,
    critical_stokes: Annotated[float, typer.Option("--critical-stokes")] = 10.0,
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
) -> None:
    """Write a lab report: properties with sources, derived quantities, verdicts with the
    roughness flag, fits next to published values, figures and methods."""
    from granudb.analysis.query import CollisionQuery
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
                angle_rad=_angle(angle or "0 deg"),
                temperature_c=quantity(temperature, "temperature_c", "--temperature"),
                viscosity_pa_s=quantity(viscosity, "viscosity_pa_s", "--viscosity"),
                wall_diameter_m=quantity(wall_diameter, "wall_diameter_m", "--wall-diameter"),
                critical_stokes=critical_stokes,
                assumed=set() if angle is not None else {"incidence_angle_rad"},
            )
        else:
            query = CollisionQuery(
                dataset=dataset,
                version=version,
                particle=particle,
                wall=wall,
                fluid=fluid,
                min_st=min_st,
                max_st=max_st,
                angle_range=_angle_range(angle_range) if angle_range else None,
                regime=regime,
                critical_stokes=critical_stokes,
            )
            report_data = dataset_report(
                session, title=title, query_text=asked, database=database.display_url, query=query
            )
    path = write_report(report_data, fmt, output, force=force)
    say(f"wrote {path}")


def _angle(text: str) -> float:
    """An incidence angle from the normal, 0 ≤ ζ < 90°, as ``granudb pair`` takes it."""
    from granudb.errors import ValidationError
    from granudb.io.units import parse_quantity

    value = parse_quantity(text, "rad", "--angle")
    if not 0.0 <= value < math.pi / 2:
        raise ValidationError("--angle", text, "must be ≥ 0° and < 90°")
    return value


def _angle_range(text: str) -> tuple[float, float]:
    """``LOW..HIGH`` with one unit for both ("20..60 deg"), as ``collisions list`` takes it."""
    from granudb.errors import ValidationError
    from granudb.io.units import parse_quantity

    low, sep, high = text.partition("..")
    if not sep:
        raise ValidationError("--angle-range", text, "must be LOW..HIGH, e.g. '10..40 deg'")
    high = high.strip()
    unit = high.lstrip("0123456789.eE+- ").strip()
    low = low.strip()
    if unit and low and low.replace(".", "", 1).isdigit():
        low = f"{low} {unit}"
    return (
        parse_quantity(low, "rad", "--angle-range"),
        parse_quantity(high, "rad", "--angle-range"),
    )


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
