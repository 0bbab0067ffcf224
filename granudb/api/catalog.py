"""``granudb.materials()`` and ``granudb.fluids()``: the catalogue as DataFrames (SI)."""

from __future__ import annotations

from typing import Any

from granudb.api.database import opened


def _frame(records: list[dict[str, Any]], columns: list[str]) -> Any:
    import pandas as pd

    from granudb.vocabulary import term

    frame = pd.DataFrame.from_records(records, columns=columns)
    frame.attrs["units"] = {c: term(c).unit for c in columns if term(c).unit}
    return frame


def materials(db: Any = None) -> Any:
    """Every material with its properties (SI, units in ``attrs["units"]``) and source.

    >>> import granudb
    >>> frame = granudb.materials(db=db)
    >>> float(frame.set_index("name").loc["glass", "youngs_modulus_pa"])
    60000000000.0
    """
    from granudb.vocabulary import columns

    return _frame(material_records(db), columns.MATERIAL_COLUMNS)


def fluids(db: Any = None) -> Any:
    """Every fluid with its reference values (SI), source and number of viscosity points.

    >>> import granudb
    >>> frame = granudb.fluids(db=db)
    >>> float(frame.set_index("name").loc["glycerol-45", "reference_viscosity_pa_s"])
    0.0045
    """
    from granudb.vocabulary import columns

    return _frame(fluid_records(db), columns.FLUID_COLUMNS)


# The same as plain records (what ``granudb materials|fluids|sources list`` print). They
# read through SQLAlchemy Core without building the ORM's classes (issue 17: start-up).


def material_records(db: Any = None) -> list[dict[str, Any]]:
    """Every material as an SI record, by name."""
    from granudb.db import catalog_rows

    with opened(db) as database, database.reading() as connection:
        return [catalog_rows.material_record(m) for m in catalog_rows.material_rows(connection)]


def fluid_records(db: Any = None) -> list[dict[str, Any]]:
    """Every fluid as an SI record (``points`` counts its viscosity points), by name."""
    from granudb.db import catalog_rows

    with opened(db) as database, database.reading() as connection:
        return [catalog_rows.fluid_record(f) for f in catalog_rows.fluid_rows(connection)]


def source_records(db: Any = None) -> list[dict[str, Any]]:
    """Every source (key, citation, DOI, …), by key."""
    from granudb.db import catalog_rows

    with opened(db) as database, database.reading() as connection:
        return [catalog_rows.source_record(s) for s in catalog_rows.source_rows(connection)]
