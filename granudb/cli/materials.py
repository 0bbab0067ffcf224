"""``granudb materials list|show|add|update|remove``."""

from __future__ import annotations

from typing import Annotated

import typer

from granudb.cli.common import DbOption, Format, FormatOption, given, open_db, quantities
from granudb.cli.confirm import YesOption

app = typer.Typer(help="Particle and wall materials (ρ, E, ν, roughness).", no_args_is_help=True)

Name = Annotated[str, typer.Argument(help="Material name (matched case-insensitively).")]
Density = Annotated[str | None, typer.Option("--density", help='e.g. "7780 kg/m^3"')]
Youngs = Annotated[str | None, typer.Option("--youngs-modulus", help='e.g. "190 GPa"')]
Poisson = Annotated[str | None, typer.Option("--poisson-ratio", help="e.g. 0.27")]
Roughness = Annotated[str | None, typer.Option("--roughness", help='RMS roughness, "23.6 nm"')]
Correlation = Annotated[
    str | None, typer.Option("--correlation-length", help='Roughness correlation length, "48 um"')
]
Shear = Annotated[
    str | None,
    typer.Option("--shear-modulus", help='e.g. "75 GPa" (default: derived, E / (2(1 + ν)))'),
]
Description = Annotated[str | None, typer.Option("--description")]
SourceKey = Annotated[str | None, typer.Option("--source", help="Key of a source (sources list).")]
Locator = Annotated[
    str | None, typer.Option("--source-locator", help='Where in the source, e.g. "table 1".')
]


YieldStress = Annotated[
    str | None,
    typer.Option(
        "--yield-stress",
        help='Yield stress in tension, "1.7 GPa" (with a --source: yield starts at 1.6 Y).',
    ),
]


def _values(
    density, youngs, poisson, roughness, correlation, shear, yield_stress=None
) -> dict[str, float]:
    return quantities(
        {
            "density_kg_m3": (density, "--density"),
            "youngs_modulus_pa": (youngs, "--youngs-modulus"),
            "poisson_ratio": (poisson, "--poisson-ratio"),
            "roughness_rms_m": (roughness, "--roughness"),
            "correlation_length_m": (correlation, "--correlation-length"),
            "shear_modulus_pa": (shear, "--shear-modulus"),
            "yield_stress_pa": (yield_stress, "--yield-stress"),
        }
    )


@app.command("list")
def list_(db: DbOption = None, fmt: FormatOption = Format.table) -> None:
    """List every material with its properties (SI in json/csv)."""
    from granudb.api.catalog import material_records
    from granudb.cli.output import emit
    from granudb.vocabulary import columns

    records = material_records(db=open_db(db))
    emit(
        records,
        columns.MATERIAL_TABLE_COLUMNS if fmt is Format.table else columns.MATERIAL_COLUMNS,
        fmt,
        title="Materials",
    )


@app.command()
def show(name: Name, db: DbOption = None, fmt: FormatOption = Format.table) -> None:
    """Show one material, with the full citation of its source."""
    from granudb.cli.output import emit_one
    from granudb.db import catalog

    database = open_db(db)
    with database.session() as session:
        material = catalog.get_material(session, name)
        record = catalog.material_record(material)
        record["citation"] = material.source.citation if material.source else None
        record["created_at"] = material.created_at
        record["updated_at"] = material.updated_at
    emit_one(record, fmt, title=f"Material {record['name']}")


@app.command()
def add(
    name: Name,
    density: Density = None,
    youngs_modulus: Youngs = None,
    poisson_ratio: Poisson = None,
    roughness: Roughness = None,
    correlation_length: Correlation = None,
    shear_modulus: Shear = None,
    yield_stress: YieldStress = None,
    description: Description = None,
    source: SourceKey = None,
    source_locator: Locator = None,
    db: DbOption = None,
) -> None:
    """Add a material. Density, Young's modulus, Poisson ratio and roughness are required."""
    from granudb.cli.output import say
    from granudb.db import catalog
    from granudb.errors import ValidationError

    required = {
        "--density": density,
        "--youngs-modulus": youngs_modulus,
        "--poisson-ratio": poisson_ratio,
        "--roughness": roughness,
    }
    for option, value in required.items():
        if value is None:
            raise ValidationError(option, "(missing)", "is required to add a material")
    values: dict[str, object] = _values(
        density,
        youngs_modulus,
        poisson_ratio,
        roughness,
        correlation_length,
        shear_modulus,
        yield_stress,
    )
    values.update(given(description=description, source_locator=source_locator))
    database = open_db(db)
    with database.session(write=True) as session:
        catalog.add_material(session, name, values, source=source)
    say(f"added material {name}")


@app.command()
def update(
    name: Name,
    density: Density = None,
    youngs_modulus: Youngs = None,
    poisson_ratio: Poisson = None,
    roughness: Roughness = None,
    correlation_length: Correlation = None,
    shear_modulus: Shear = None,
    yield_stress: YieldStress = None,
    description: Description = None,
    source: SourceKey = None,
    source_locator: Locator = None,
    rename: Annotated[str | None, typer.Option("--rename", help="New name.")] = None,
    db: DbOption = None,
) -> None:
    """Change some properties of a material; prints each change (old → new)."""
    from granudb.cli.output import say_change
    from granudb.db import catalog

    values: dict[str, object] = _values(
        density,
        youngs_modulus,
        poisson_ratio,
        roughness,
        correlation_length,
        shear_modulus,
        yield_stress,
    )
    values.update(given(description=description, source_locator=source_locator))
    database = open_db(db)
    with database.session(write=True) as session:
        change = catalog.update_material(session, name, values, source=source, new_name=rename)
    say_change(change)


@app.command()
def remove(name: Name, yes: YesOption = False, db: DbOption = None) -> None:
    """Remove a material no collision or published value refers to; asks first."""
    from granudb.cli.confirm import confirm
    from granudb.cli.output import say
    from granudb.db import catalog

    database = open_db(db)
    with database.session() as session:
        losses = catalog.material_removal(session, name)
    confirm(f"materials remove {name}", losses, yes)
    with database.session(write=True) as session:
        material = catalog.remove_material(session, name)
    say(f"removed material {material.name}")
