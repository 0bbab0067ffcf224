"""``granudb collisions import|list``: measured impacts in, derived parameters out."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from granudb.cli.common import DbOption, Format, FormatOption, open_db

app = typer.Typer(
    help="Measured collisions: import CSV files, list them with e, β, Ψ, μ_f and regime verdicts.",
    no_args_is_help=True,
)

TABLE_COLUMNS = [
    "run",
    "particle",
    "wall",
    "fluid",
    "incidence_angle_rad",
    "v_n_in_m_s",
    "normal_restitution",
    "rotational_restitution",
    "effective_incidence",
    "effective_rebound",
    "sliding_friction",
    "normal_stokes_number",
    "roughness_exceeds_gap",
    "tangential_regime",
]
PROGRESS_ABOVE_BYTES = 400_000  # about 5,000 rows


@app.command("import")
def import_(
    file: Annotated[Path, typer.Argument(help="CSV file, one row per run (see README).")],
    dataset: Annotated[
        str, typer.Option("--dataset", help="Dataset to add the runs to (created if new).")
    ],
    version: Annotated[str, typer.Option("--version", help="Dataset version.")] = "1.0.0",
    source: Annotated[
        str | None, typer.Option("--source", help="Source key for a new dataset.")
    ] = None,
    title: Annotated[str | None, typer.Option("--title", help="Title of a new dataset.")] = None,
    license: Annotated[
        str | None, typer.Option("--license", help="License of a new dataset, e.g. CC-BY-4.0.")
    ] = None,
    delimiter: Annotated[
        str, typer.Option("--delimiter", help="Cell separator: ',' (default), ';' or 'tab'.")
    ] = ",",
    decimal: Annotated[
        str,
        typer.Option("--decimal", help="Decimal separator: '.' (default) or ',' (with ';')."),
    ] = ".",
    db: DbOption = None,
) -> None:
    """Import a CSV of collisions: all rows or none; a file is never imported twice."""
    import sys

    from granudb.cli.output import say
    from granudb.io.collisions_csv import import_collisions
    from granudb.vocabulary.text import check_name

    check_name("--dataset", dataset)
    check_name("--version", version)
    database = open_db(db)
    options = dict(
        dataset=dataset,
        version=version,
        source=source,
        title=title,
        license=license,
        delimiter=delimiter,
        decimal=decimal,
    )
    size = file.stat().st_size if file.is_file() else 0
    if size > PROGRESS_ABOVE_BYTES and sys.stderr.isatty():
        from rich.progress import BarColumn, Progress, TextColumn

        with Progress(
            TextColumn("importing"),
            BarColumn(),
            TextColumn("{task.completed:,} rows"),
            transient=True,
        ) as bar:
            task = bar.add_task("import", total=None)
            result = import_collisions(
                database, file, progress=lambda n: bar.update(task, completed=n), **options
            )
    else:
        result = import_collisions(database, file, **options)
    say(
        f"imported {result.rows:,} runs into dataset {result.dataset} {result.version} "
        f"(file sha256 {result.sha256[:12]}…)"
    )


def _angle_range(text: str) -> tuple[float, float]:
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


@app.command("list")
def list_(
    dataset: Annotated[str | None, typer.Option("--dataset")] = None,
    version: Annotated[str | None, typer.Option("--version")] = None,
    particle: Annotated[str | None, typer.Option("--particle")] = None,
    wall: Annotated[str | None, typer.Option("--wall")] = None,
    fluid: Annotated[str | None, typer.Option("--fluid", help="A fluid name, or 'dry'.")] = None,
    min_st: Annotated[
        float | None, typer.Option("--min-st", help="Minimum normal Stokes number.")
    ] = None,
    max_st: Annotated[
        float | None, typer.Option("--max-st", help="Maximum normal Stokes number.")
    ] = None,
    angle_range: Annotated[
        str | None, typer.Option("--angle-range", help="Incidence angles, '10..40 deg'.")
    ] = None,
    regime: Annotated[
        str | None,
        typer.Option(
            "--regime", help="stick, slip_then_stick, gross_slip, rough (σ > h_m) or no_rebound."
        ),
    ] = None,
    critical_stokes: Annotated[float, typer.Option("--critical-stokes")] = 10.0,
    db: DbOption = None,
    fmt: FormatOption = Format.table,
) -> None:
    """Each run with e, β, Ψ_in, Ψ_out, μ_f (2.9), St_n, Re and the regime verdicts."""
    from granudb.analysis.derivation import LISTED_COLUMNS
    from granudb.analysis.query import CollisionQuery, select_collisions
    from granudb.cli.output import emit

    database = open_db(db)
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
    with database.session() as session:
        frame = select_collisions(session, query)
    records = frame.to_dict("records")
    emit(
        records,
        TABLE_COLUMNS if fmt is Format.table else LISTED_COLUMNS,
        fmt,
        title=f"Collisions ({len(records)} runs)",
    )
