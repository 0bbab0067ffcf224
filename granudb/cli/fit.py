"""``granudb fit walton|restitution|gap-viscosity``: the paper's fits on stored runs."""

from __future__ import annotations

from typing import Annotated

import typer

from granudb.cli.common import DbOption, Format, FormatOption, open_db

app = typer.Typer(
    help="Fit measured collisions: Walton β and μ_f, e(St), gap viscosity.", no_args_is_help=True
)

Dataset = Annotated[str | None, typer.Option("--dataset")]
Version = Annotated[str | None, typer.Option("--version")]
Particle = Annotated[str | None, typer.Option("--particle")]
Wall = Annotated[str | None, typer.Option("--wall")]
Fluid = Annotated[str | None, typer.Option("--fluid", help="A fluid name, or 'dry'.")]


def _frame(db, dataset, version, particle, wall, fluid):
    from granudb.analysis.query import CollisionQuery, select_collisions

    database = open_db(db)
    query = CollisionQuery(
        dataset=dataset, version=version, particle=particle, wall=wall, fluid=fluid
    )
    with database.session() as session:
        return database, select_collisions(session, query)


@app.command()
def walton(
    dataset: Dataset = None,
    version: Version = None,
    particle: Particle = None,
    wall: Wall = None,
    fluid: Fluid = None,
    db: DbOption = None,
    fmt: FormatOption = Format.table,
) -> None:
    """β (sticking runs) and μ_f (sliding runs) per dataset × pair × fluid, with ē."""
    from granudb.analysis import fits
    from granudb.cli.output import emit

    _, frame = _frame(db, dataset, version, particle, wall, fluid)
    emit(fits.walton(frame), fits.WALTON_COLUMNS, fmt, title="Walton fits")


@app.command()
def restitution(
    model: Annotated[str, typer.Option("--model", help="threshold or exponential.")] = "threshold",
    dataset: Dataset = None,
    version: Version = None,
    particle: Particle = None,
    wall: Wall = None,
    db: DbOption = None,
    fmt: FormatOption = Format.table,
) -> None:
    """e against the normal Stokes number for immersed runs: e_dry and St_c (or k)."""
    from granudb.analysis import fits
    from granudb.cli.output import emit

    _, frame = _frame(db, dataset, version, particle, wall, None)
    results = fits.restitution(frame, model)
    emit(
        results,
        [
            "dataset",
            "particle",
            "wall",
            "model",
            "e_dry",
            "e_dry_stderr",
            "parameter_name",
            "parameter",
            "parameter_stderr",
            "n_runs",
            "formula",
            "citation",
        ]
        if fmt is not Format.table
        else [
            "dataset",
            "particle",
            "wall",
            "model",
            "e_dry",
            "parameter_name",
            "parameter",
            "n_runs",
        ],
        fmt,
        title="Restitution against Stokes number",
    )


@app.command("gap-viscosity")
def gap_viscosity(
    dataset: Dataset = None,
    version: Version = None,
    particle: Particle = None,
    wall: Wall = None,
    fluid: Fluid = None,
    db: DbOption = None,
    fmt: FormatOption = Format.table,
) -> None:
    """Gap viscosity μ₀ fitting (5.10) to smooth sliding runs, and the gap temperature."""
    from granudb.analysis import fits
    from granudb.analysis.derivation import fluid_model
    from granudb.cli.output import emit
    from granudb.db import catalog

    database, frame = _frame(db, dataset, version, particle, wall, fluid)
    with database.session() as session:
        models = {f.name: fluid_model(f) for f in catalog.list_fluids(session)}
    emit(
        fits.gap_viscosity(frame, models),
        [
            "dataset",
            "particle",
            "wall",
            "fluid",
            "gap_viscosity_pa_s",
            "gap_viscosity_std_pa_s",
            "ambient_viscosity_pa_s",
            "gap_temperature_c",
            "n_runs",
            "note",
        ],
        fmt,
        title="Gap viscosity (figure 14, table 2)",
    )
