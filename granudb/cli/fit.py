"""``granudb fit walton|restitution|gap-viscosity``: the paper's fits on stored runs.

Each command takes the collision filters of ``collisions list`` and prints one row per
group (dataset × particle × wall × fluid). A table shows the main columns; JSON and CSV
every key the fit returns (``granudb.analysis.fits`` documents them).
"""

from __future__ import annotations

from typing import Annotated, Any

import typer

from granudb.cli import options
from granudb.cli.common import DbOption, Format, FormatOption, open_db

app = typer.Typer(
    help="Fit measured collisions: Walton β and μ_f, e(St), gap viscosity.", no_args_is_help=True
)

GROUP = ["dataset", "particle", "wall", "fluid"]
TABLE_COLUMNS = {
    "walton": [
        *GROUP,
        "model",
        "rotational_restitution",
        "sliding_friction",
        "normal_restitution_mean",
        "n_sticking",
        "n_sliding",
    ],
    "restitution": [
        *GROUP[:3],
        "model",
        "e_dry",
        "parameter_name",
        "parameter",
        "n_runs",
        "reason",
    ],
    "gap_viscosity": [
        *GROUP,
        "gap_viscosity_pa_s",
        "ambient_viscosity_pa_s",
        "gap_temperature_c",
        "n_runs",
        "reason",
        "note",
    ],
}


def _show(frame: Any, kind: str, fmt: Format, title: str) -> None:
    from granudb.cli.output import emit

    records = frame.to_dict("records")
    every = list(frame.columns)
    shown = [c for c in TABLE_COLUMNS[kind] if c in every] if fmt is Format.table else every
    emit(records, shown or every, fmt, title=title)


@app.command()
def walton(
    dataset: options.Dataset = None,
    version: options.Version = None,
    particle: options.Particle = None,
    wall: options.Wall = None,
    fluid: options.Fluid = None,
    angle_range: options.AngleRange = None,
    db: DbOption = None,
    fmt: FormatOption = Format.table,
) -> None:
    """β (sticking runs) and μ_f (sliding runs) per dataset × pair × fluid, with ē."""
    from granudb.api.fits import fit_walton

    frame = fit_walton(
        db=open_db(db),
        dataset=dataset,
        version=version,
        particle=particle,
        wall=wall,
        fluid=fluid,
        angle_range=angle_range,
    )
    _show(frame, "walton", fmt, "Walton fits")


@app.command()
def restitution(
    model: Annotated[str, typer.Option("--model", help="threshold or exponential.")] = "threshold",
    dataset: options.Dataset = None,
    version: options.Version = None,
    particle: options.Particle = None,
    wall: options.Wall = None,
    db: DbOption = None,
    fmt: FormatOption = Format.table,
) -> None:
    """e against the normal Stokes number for immersed runs: e_dry and St_c (or k)."""
    from granudb.api.fits import fit_restitution

    frame = fit_restitution(
        model, db=open_db(db), dataset=dataset, version=version, particle=particle, wall=wall
    )
    _show(frame, "restitution", fmt, "Restitution against Stokes number")


@app.command("gap-viscosity")
def gap_viscosity(
    dataset: options.Dataset = None,
    version: options.Version = None,
    particle: options.Particle = None,
    wall: options.Wall = None,
    fluid: options.Fluid = None,
    db: DbOption = None,
    fmt: FormatOption = Format.table,
) -> None:
    """Gap viscosity μ₀ fitting (5.8) to sliding runs, and the gap temperature."""
    from granudb.api.fits import fit_gap_viscosity

    frame = fit_gap_viscosity(
        db=open_db(db), dataset=dataset, version=version, particle=particle, wall=wall, fluid=fluid
    )
    _show(frame, "gap_viscosity", fmt, "Gap viscosity (figure 14, table 2)")
