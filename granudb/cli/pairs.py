"""``granudb pairs list|show|add``: the dry values a source measured for a pair, and
the values every prediction uses with where each came from (docs/physics.md §18)."""

from __future__ import annotations

from typing import Annotated

import typer

from granudb import api
from granudb.cli.options import DbOption, Format, FormatOption, text_option, wraps
from granudb.cli.output import emit, emit_one, say

app = typer.Typer(
    help="Dry restitution and friction of pairs of materials, with their sources.",
    no_args_is_help=True,
)
Particle = Annotated[str, typer.Argument(help="The particle's material.")]
Wall = Annotated[str, typer.Argument(help="The wall's (or second sphere's) material.")]


@app.command("list")
@wraps("pair_values")
def list_(db: DbOption = None, fmt: FormatOption = Format.table) -> None:
    """List every pair's measured dry values with their source."""
    records = api.pair_values(db=db, as_frame=False)
    emit(records, list(api.PAIR_VALUE_COLUMNS), fmt, title="Pair values")


@app.command()
@wraps("dry_values")
def show(
    particle: Particle,
    wall: Wall,
    dataset: Annotated[
        str | None, text_option("NAME or NAME@VERSION: as that dataset uses them.")
    ] = None,
    db: DbOption = None,
    fmt: FormatOption = Format.table,
) -> None:
    """The dry e and μ every prediction uses for a pair, and where each came from."""
    record = api.dry_values(particle, wall, dataset=dataset, db=db)
    emit_one(record, fmt, title=f"Dry values: {particle} on {wall}")


@app.command()
@wraps("add_pair_value")
def add(
    particle: Particle,
    wall: Wall,
    dry_restitution: Annotated[str | None, text_option('Dry restitution, e.g. "0.97".')] = None,
    dry_friction: Annotated[str | None, text_option('Dry friction, e.g. "0.11".')] = None,
    immersed_friction: Annotated[
        str | None, text_option('Friction with asperities in a liquid, "0.15".')
    ] = None,
    source: Annotated[
        str | None, text_option("Key of a source (granudb sources list), or use --notes.")
    ] = None,
    source_locator: Annotated[str | None, text_option('Where in the source, e.g. "§3".')] = None,
    notes: Annotated[str | None, text_option("Free text.")] = None,
    db: DbOption = None,
) -> None:
    """Store the dry values a source measured for a pair (never changed once stored)."""
    record = api.add_pair_value(
        particle,
        wall,
        dry_restitution=dry_restitution,
        dry_friction=dry_friction,
        immersed_friction=immersed_friction,
        source=source,
        source_locator=source_locator,
        notes=notes,
        db=db,
    )
    say(f"added dry values for {particle} on {wall}: e_dry = {record['dry_restitution']:g} "
        f"({record['dry_restitution_basis']}), μ_dry = {record['dry_friction']:g} "
        f"({record['dry_friction_basis']})")  # fmt: skip
