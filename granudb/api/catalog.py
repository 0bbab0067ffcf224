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
    from granudb.db import catalog
    from granudb.vocabulary import columns

    with opened(db) as database, database.session() as session:
        records = [catalog.material_record(m) for m in catalog.list_materials(session)]
    return _frame(records, columns.MATERIAL_COLUMNS)


def fluids(db: Any = None) -> Any:
    """Every fluid with its reference values (SI), source and number of viscosity points.

    >>> import granudb
    >>> frame = granudb.fluids(db=db)
    >>> float(frame.set_index("name").loc["glycerol-45", "reference_viscosity_pa_s"])
    0.0045
    """
    from granudb.db import catalog
    from granudb.vocabulary import columns

    with opened(db) as database, database.session() as session:
        records = [catalog.fluid_record(f) for f in catalog.list_fluids(session)]
    return _frame(records, columns.FLUID_COLUMNS)
