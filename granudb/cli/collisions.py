"""``granudb collisions import|list``: measured impacts in, derived parameters out."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from granudb.cli import options
from granudb.cli.common import DbOption, Format, FormatOption, open_db

app = typer.Typer(
    help="Measured collisions: import CSV files, list them with e, β, Ψ, μ_f and regime verdicts.",
    no_args_is_help=True,
)

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


def natural_key(label: object) -> tuple:
    """Sort run labels as people count: run-2 before run-10."""
    import re

    parts = re.split(r"(\d+)", str(label))
    return tuple((0, int(p), "") if p.isdigit() else (1, 0, p.casefold()) for p in parts)


def choose_columns(columns: str | None, wide: bool, available: list[str]) -> list[str]:
    """The columns to show, the same in every format: the narrow default, ``--wide`` for
    all, or ``--columns a,b,c`` (machine names, as in JSON and CSV)."""
    from granudb.analysis.collisions import DEFAULT_COLUMNS
    from granudb.errors import ValidationError

    if columns is None:
        return available if wide else DEFAULT_COLUMNS
    chosen = [c.strip() for c in columns.split(",") if c.strip()]
    unknown = [c for c in chosen if c not in available]
    if unknown or not chosen:
        raise ValidationError(
            "--columns",
            ", ".join(unknown) or columns,
            f"are not columns of the listing (known: {', '.join(available)})",
        )
    return chosen


@app.command("list")
def list_(
    dataset: options.Dataset = None,
    version: options.Version = None,
    particle: options.Particle = None,
    wall: options.Wall = None,
    fluid: options.Fluid = None,
    min_normal_stokes: options.MinNormalStokes = None,
    max_normal_stokes: options.MaxNormalStokes = None,
    angle_range: options.AngleRange = None,
    regime: options.Regime = None,
    roughness_exceeds_gap: options.RoughnessExceedsGap = None,
    rebound_expected: options.ReboundExpected = None,
    critical_stokes: options.CriticalStokes = 10.0,
    columns: Annotated[
        str | None,
        typer.Option("--columns", help="Comma-separated column names to show (see --wide)."),
    ] = None,
    wide: Annotated[bool, typer.Option("--wide", help="Every column.")] = False,
    db: DbOption = None,
    fmt: FormatOption = Format.table,
) -> None:
    """Each run with e, β, Ψ_in, μ_f (2.9), St_n, Λ and Maw's regime (``--wide``: all)."""
    from granudb.api.collisions import collisions
    from granudb.cli.output import emit

    frame = collisions(
        db=open_db(db),
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
    shown = choose_columns(columns, wide, list(frame.columns))
    if not frame.empty:
        order = sorted(
            range(len(frame)),
            key=lambda i: (
                frame["dataset"].iat[i],
                frame["version"].iat[i],
                natural_key(frame["run"].iat[i]),
            ),
        )
        frame = frame.iloc[order]
    records = frame.to_dict("records")
    if fmt is Format.table:
        for record in records:
            if not isinstance(record.get("fluid"), str):
                record["fluid"] = "dry"
            record["pair"] = f"{record['particle']}/{record['wall']}"
        if shown[1:3] == ["particle", "wall"]:
            shown = ["run", "pair", *shown[3:]]  # one column: the narrow table fits 100
    emit(records, shown, fmt, title=f"Collisions ({len(records)} runs)", symbols=True)
