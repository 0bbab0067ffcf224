"""What every command shares: the ``--db`` and ``--format`` options, opening the
database, and turning a typed quantity (``"190 GPa"``) into a checked SI value.

Kept free of heavy imports so ``granudb --help`` stays fast: SQLAlchemy, pandas and Pint
load only when a command runs.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from granudb.cli.options import DbOption, Format, FormatOption

if TYPE_CHECKING:
    from granudb.db.engine import Database

__all__ = ["DbOption", "Format", "FormatOption", "given", "open_db", "quantities", "quantity"]


def open_db(url: str | None) -> Database:
    """Open the database, creating, migrating and seeding it on first use."""
    from granudb.api.database import connect

    database = connect(url)
    if database.created:
        from granudb.cli.output import note

        note(f"created {database.display_url} and loaded the seed data")
    return database


def quantity(text: str | None, column: str, option: str) -> float | None:
    """Parse an option's text into SI for ``column`` and check its physical rule."""
    if text is None:
        return None
    from granudb.io.units import parse_quantity
    from granudb.vocabulary.rules import check_value
    from granudb.vocabulary.units import unit_of_column

    value = parse_quantity(text, unit_of_column(column), option)
    check_value(column, value, field=option, shown=text)
    return value


def quantities(pairs: dict[str, tuple[str | None, str]]) -> dict[str, float]:
    """``{column: (text, option)}`` → ``{column: SI value}`` for the options given."""
    values = {}
    for column, (text, option) in pairs.items():
        value = quantity(text, column, option)
        if value is not None:
            values[column] = value
    return values


def given(**options: str | None) -> dict[str, str]:
    """The text options the user gave (``None`` means "not given", not "clear it")."""
    return {name: value for name, value in options.items() if value is not None}
