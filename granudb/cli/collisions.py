"""``granudb collisions import|list|remove``: measured impacts in, derived parameters out."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated, Any

import typer

from granudb import api
from granudb.cli.confirm import asker
from granudb.cli.options import (
    DbOption,
    Format,
    FormatOption,
    YesOption,
    collision_filters,
    wraps,
)
from granudb.cli.output import emit, say
from granudb.lazy import rich_progress

app = typer.Typer(
    help="Measured collisions: import CSV files, list them with e, β, Ψ, μ_f and regime verdicts.",
    no_args_is_help=True,
)

#: A file larger than this (about 5,000 rows) shows a progress bar on a terminal.
PROGRESS_ABOVE_BYTES = 400_000


@app.command("import")
@wraps("import_collisions")
def import_(
    file: Annotated[Path, typer.Argument(help="CSV file, one row per run (see README).")],
    dataset: Annotated[
        str | None, typer.Option("--dataset", help="Dataset to add the runs to (created if new).")
    ] = None,
    version: Annotated[str, typer.Option("--version", help="Dataset version.")] = "1.0.0",
    source: Annotated[
        str | None, typer.Option("--source", help="Source key for a new dataset.")
    ] = None,
    title: Annotated[str | None, typer.Option("--title", help="Title of a new dataset.")] = None,
    license: Annotated[
        str | None, typer.Option("--license", help="License of a new dataset, e.g. CC-BY-4.0.")
    ] = None,
    delimiter: Annotated[
        str | None,
        typer.Option(
            "--delimiter",
            help="Cell separator: ',', ';' or 'tab' (default: ';' or tab if the header has "
            "them and no comma, else ',').",
        ),
    ] = None,
    decimal: Annotated[
        str,
        typer.Option("--decimal", help="Decimal separator: '.' (default) or ',' (with ';')."),
    ] = ".",
    columns: Annotated[
        str | None,
        typer.Option(
            "--columns",
            help="Your headers as granudb's columns: 'shot=run,speed [mm/s]=v_n_in' "
            "(a header's unit is kept), or a file of such lines.",
        ),
    ] = None,
    uncertainty: Annotated[
        str | None,
        typer.Option(
            "--uncertainty",
            help="The dataset's standard uncertainty of measured columns, for runs whose "
            "file has no u(...) cell: 'v_n_in=± 3 %, v_n_out=± 0.5 mm/s'.",
        ),
    ] = None,
    db: DbOption = None,
) -> None:
    """Import a CSV of collisions: all rows or none; a file is never imported twice.
    Every problem of the file is listed at once, in row order."""
    options: dict[str, Any] = {k: v for k, v in locals().items() if k != "file"}
    size = file.stat().st_size if file.is_file() else 0
    if size > PROGRESS_ABOVE_BYTES and sys.stderr.isatty():
        with rich_progress.Progress(
            rich_progress.TextColumn("importing"),
            rich_progress.BarColumn(),
            rich_progress.TextColumn("{task.completed:,} rows"),
            transient=True,
        ) as bar:
            task = bar.add_task("import", total=None)
            progress = lambda n: bar.update(task, completed=n)  # noqa: E731
            result = api.import_collisions(file, progress=progress, **options)
    else:
        result = api.import_collisions(file, **options)
    say(
        f"imported {result.rows:,} runs into dataset {result.dataset} {result.version} "
        f"(file sha256 {result.sha256[:12]}…)"
    )


@app.command("list")
@collision_filters
@wraps("collisions")
def list_(
    wide: Annotated[bool, typer.Option("--wide", help="Every column.")] = False,
    columns: Annotated[
        str | None,
        typer.Option("--columns", help="Comma-separated column names to show (see --wide)."),
    ] = None,
    fmt: FormatOption = Format.table,
    db: DbOption = None,
    filters: dict[str, Any] | None = None,
) -> None:
    """Each run with e, β, Ψ_in, μ_f (2.9), St_n, Λ and Maw's regime (``--wide``: all)."""
    frame = api.collisions(db=db, columns=columns, wide=wide, **(filters or {}))
    shown, records = list(frame.columns), frame.to_dict("records")
    if fmt is Format.table:
        for record in records:
            if not isinstance(record.get("fluid"), str):
                record["fluid"] = "dry"
            if "particle" in record and "wall" in record:
                record["pair"] = f"{record['particle']}/{record['wall']}"
        if shown[1:3] == ["particle", "wall"]:
            shown = ["run", "pair", *shown[3:]]  # one column: the narrow table fits 100
    emit(records, shown, fmt, title=f"Collisions ({len(records)} runs)", symbols=True)


@app.command("remove")
@wraps("remove_collisions")
def remove(
    dataset: Annotated[str, typer.Argument(help="Dataset as NAME@VERSION (or NAME: the newest).")],
    runs: Annotated[list[str], typer.Argument(help="Run labels to delete.")],
    yes: YesOption = False,
    db: DbOption = None,
) -> None:
    """Delete some runs of a draft dataset version (by run label); asks first."""
    count = api.remove_collisions(dataset, runs, confirm=asker(yes), db=db)
    say(f"removed {count} runs from dataset {dataset}")
