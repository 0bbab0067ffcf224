"""The options several commands share, defined once: the database, the output format and
the collision filters. Option names are the Python API's parameter names with dashes
(``--angle-range`` ↔ ``angle_range``), so an error from the library names the option.
"""

from __future__ import annotations

from enum import StrEnum
from typing import Annotated

import typer

from granudb.config import ENV_VAR


class Format(StrEnum):
    table = "table"
    json = "json"
    csv = "csv"


DbOption = Annotated[
    str | None,
    typer.Option(
        "--db",
        envvar=ENV_VAR,
        show_envvar=True,
        help="Database: a SQLAlchemy URL or a SQLite file path "
        "(default: granudb.sqlite in the user data directory).",
    ),
]
FormatOption = Annotated[
    Format, typer.Option("--format", "-f", help="table for people; json or csv (SI) for scripts.")
]

Dataset = Annotated[str | None, typer.Option("--dataset", help="Dataset name.")]
Version = Annotated[
    str | None, typer.Option("--version", help="Dataset version (default: newest).")
]
Particle = Annotated[str | None, typer.Option("--particle", help="Particle material.")]
Wall = Annotated[str | None, typer.Option("--wall", help="Wall (or target sphere) material.")]
Fluid = Annotated[str | None, typer.Option("--fluid", help="A fluid name, or 'dry'.")]
MinNormalStokes = Annotated[
    float | None, typer.Option("--min-normal-stokes", help="Lowest normal Stokes number St_n.")
]
MaxNormalStokes = Annotated[
    float | None, typer.Option("--max-normal-stokes", help="Highest normal Stokes number St_n.")
]
AngleRange = Annotated[
    str | None,
    typer.Option(
        "--angle-range",
        help="Incidence angles ζ_in of the contact point's path, '10..40 deg'.",
    ),
]
Regime = Annotated[
    str | None,
    typer.Option("--regime", help="Maw's tangential regime: stick, slip_then_stick, gross_slip."),
]
RoughnessExceedsGap = Annotated[
    bool | None,
    typer.Option(
        "--roughness-exceeds-gap/--roughness-within-gap",
        help="Only runs whose roughness exceeds (or is within) the EHD gap h_m.",
        show_default=False,
    ),
]
ReboundExpected = Annotated[
    bool | None,
    typer.Option(
        "--rebound-expected/--no-rebound-expected",
        help="Only runs with St_n above (or not above) St_c.",
        show_default=False,
    ),
]
CriticalStokes = Annotated[
    float, typer.Option("--critical-stokes", help="No rebound below this normal Stokes number.")
]
