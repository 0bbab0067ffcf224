"""Datasette ``metadata.json`` for a granudb SQLite file, generated from the vocabulary.

Datasette shows a column description as a tooltip and a ``units`` entry beside values;
foreign keys display the referenced row's ``name`` (or ``key`` for sources). Temperatures
(°C, an offset unit) get no ``units`` entry; the description says °C.
"""

from __future__ import annotations

from typing import Any

from granudb.db.models import Base
from granudb.version import __version__
from granudb.vocabulary import TABLES, term

#: Units Datasette cannot show: it multiplies values by their unit with Pint, and an
#: offset unit (°C) cannot be multiplied, so a table with one answers HTTP 500. Such
#: columns keep the unit in their name (``temperature_c``) and their description.
OFFSET_UNITS = {"degC", "degF", "celsius", "fahrenheit"}


def datasette_metadata(database_name: str = "granudb") -> dict[str, Any]:
    """Datasette ``metadata.json`` for a granudb SQLite file: titles, descriptions, units.

    Datasette shows a column description as a tooltip and a ``units`` entry beside values;
    foreign keys display the referenced row's ``name`` (or ``key`` for sources).
    ``database_name`` is what Datasette calls the file: its name without ``.sqlite``.
    """
    tables: dict[str, Any] = {}
    for table in Base.metadata.sorted_tables:
        columns = {
            c.name: term(c.name).description or term(c.name).title
            for c in table.columns
            if c.name != "id"
        }
        units = {
            c.name: term(c.name).unit
            for c in table.columns
            if term(c.name).unit is not None and term(c.name).unit not in OFFSET_UNITS
        }
        entry: dict[str, Any] = {"description": TABLES.get(table.name, ""), "columns": columns}
        if units:
            entry["units"] = units
        if "name" in table.columns:
            entry["label_column"] = "name"
        elif table.name == "sources":
            entry["label_column"] = "key"
        tables[table.name] = entry
    return {
        "title": "granudb",
        "description": "Materials, fluids and measured particle–wall collisions in liquids "
        f"(granudb {__version__}). Values are SI; column names carry the unit.",
        "source": "Joseph & Hunt (2004), J. Fluid Mech. 510, 71–93 (seed data)",
        "source_url": "https://doi.org/10.1017/S002211200400919X",
        "databases": {database_name: {"tables": tables}},
    }
