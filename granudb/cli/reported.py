"""``granudb reported import|list|fit``: runs as papers report them (e, e_t, ω_out, θ),
stored as stated, listed with what follows by stated relations, and fitted."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from granudb import api
from granudb.cli.options import DbOption, Format, FormatOption, wraps
from granudb.cli.output import emit, say

app = typer.Typer(
    help="Runs as papers report them (e, e_t, ω_out, angle): import, list, fit.",
    no_args_is_help=True,
)

Collection = Annotated[
    str | None, typer.Option("--collection", help="The collection (a paper, a figure).")
]


@app.command("import")
@wraps("import_reported_runs")
def import_(
    file: Annotated[Path, typer.Argument(help="CSV file, one row per run as reported.")],
    collection: Annotated[str, typer.Option("--collection", help="Collection to add the runs to.")],
    source: Annotated[str | None, typer.Option("--source", help="Source key of every run.")] = None,
    no_spin_in: Annotated[
        bool,
        typer.Option("--no-spin-in", help="The paper states the spheres arrive without spin."),
    ] = False,
    db: DbOption = None,
) -> None:
    """Import runs as a paper reports them; no velocity is made."""
    result = api.import_reported_runs(
        file, collection=collection, source=source, no_spin_in=no_spin_in, db=db
    )
    say(f"stored {result['runs']} runs in collection {result['collection']!r}")


@app.command("list")
@wraps("reported_runs")
def list_(collection: Collection = None, db: DbOption = None,
          fmt: FormatOption = Format.table) -> None:  # fmt: skip
    """List runs as reported, with Ψ where the exact no-spin-in relation gives it."""
    records = api.reported_runs(collection, db=db)
    columns = api.REPORTED_NARROW if fmt is Format.table else api.REPORTED_COLUMNS
    emit(records, columns, fmt, title="Runs as reported")
    if fmt is Format.table:  # the provenance a table has no room for (JSON, CSV: per run)
        kept = ("collection", "reference_package", "source", "digitiser", "licence")
        for said in dict.fromkeys(tuple(r.get(k) for k in kept) for r in records):
            named = [
                f"{k.replace('_', ' ')} {v}" for k, v in zip(kept[1:], said[1:], strict=True) if v
            ]
            if named:
                say(f"{said[0]}: {'; '.join(named)}")


@app.command()
@wraps("fit_reported")
def fit(
    collection: Collection = None,
    model: Annotated[
        str, typer.Option("--model", help="walton (θ, e_t, e, no spin in) or restitution (e).")
    ] = "walton",
    db: DbOption = None,
    fmt: FormatOption = Format.table,
) -> None:
    """Fit runs as reported: Walton's β, μ_f from e_t(θ), or ē from e."""
    rows = api.fit_reported(collection, model=model, db=db)
    if not rows:
        say("no runs to fit")
        return
    columns = list(rows[0])
    if fmt is Format.table:
        keep = ("collection", "particle", "wall", "fluid", "n_runs", "model",
                "sliding_friction", "rotational_restitution", "normal_restitution_mean",
                "normal_restitution_low", "normal_restitution_high", "reason")  # fmt: skip
        columns = [c for c in keep if c in rows[0]]
    emit(rows, columns, fmt, title=f"Fit of runs as reported: {model}")
