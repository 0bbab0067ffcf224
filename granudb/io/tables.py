"""Tables from outside: headers that carry units, converted to granudb's SI columns.

One rule for every table granudb reads (seed files, collision CSVs, data packages): a header
is either granudb's own column name (``youngs_modulus_pa``, SI already) or the column's base
name with a unit in brackets (``youngs_modulus [GPa]``, ``v_n_in [mm/s]``,
``temperature [degC]``), converted with Pint once per column and then vectorized.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

from granudb.errors import ValidationError
from granudb.io.units import conversion
from granudb.vocabulary.units import Unit, unit_of_column

_HEADER = re.compile(r"^\s*(?P<base>[A-Za-z_][A-Za-z0-9_ ]*?)\s*(\[(?P<unit>[^\]]*)\])?\s*$")


def base_name(column: str) -> str:
    """``youngs_modulus_pa`` → ``youngs_modulus``; a unitless column is its own base."""
    unit = unit_of_column(column)
    return column[: -len(unit.suffix) - 1] if unit.suffix else column


@dataclass(frozen=True)
class ColumnMap:
    """How one header of a file becomes one SI column: ``si = scale * raw + offset``."""

    header: str
    column: str
    unit: Unit
    numeric: bool = True
    scale: float = 1.0
    offset: float = 0.0


def map_headers(
    headers: list[str],
    numeric: list[str],
    text: list[str],
    *,
    table: str,
    aliases: dict[str, str] | None = None,
) -> dict[str, ColumnMap]:
    """Map each header to a known column; refuse unknown, ambiguous or unit-less ones.

    ``numeric`` are unit-suffixed SI column names, ``text`` plain ones. Returns a dict keyed
    by column name. A header for a dimensioned column without a unit is refused: a bare
    ``diameter`` could be metres or millimetres.
    """
    by_base = {base_name(c): c for c in numeric}
    mapped: dict[str, ColumnMap] = {}
    for header in headers:
        match = _HEADER.match(header)
        if not match:
            raise ValidationError(f"{table} header", repr(header), "is not 'name' or 'name [unit]'")
        base, unit_text = match["base"].strip().replace(" ", "_"), match["unit"]
        base = (aliases or {}).get(base, base)
        if base in text and unit_text is None:
            column, cmap = base, ColumnMap(header, base, unit_of_column(""), numeric=False)
        elif base in numeric and unit_text is None:
            column, cmap = base, ColumnMap(header, base, unit_of_column(base))
        elif base in by_base:
            column = by_base[base]
            unit = unit_of_column(column)
            if unit_text is None:
                if unit.suffix:
                    raise ValidationError(
                        f"{table} header",
                        repr(header),
                        f"needs a unit in brackets, e.g. '{base} [{unit.pint}]'",
                    )
                cmap = ColumnMap(header, column, unit)
            else:
                try:
                    scale, offset = conversion(unit_text, unit)
                except ValidationError as exc:
                    raise ValidationError(
                        f"{table} header {header!r}", f"[{unit_text}]", exc.rule
                    ) from None
                cmap = ColumnMap(header, column, unit, True, scale, offset)
        else:
            known = sorted({*by_base, *text})
            raise ValidationError(
                f"{table} header",
                repr(header),
                f"is not a known column (known: {', '.join(known)})",
            )
        if column in mapped:
            raise ValidationError(
                f"{table} header", repr(header), f"names column {column} a second time"
            )
        mapped[column] = cmap
    return mapped


def convert_frame(
    frame: Any, mapping: dict[str, ColumnMap], *, table: str, first_row: int = 1
) -> Any:
    """A pandas DataFrame with SI columns from a raw one read as strings.

    Numeric cells are parsed vectorized; the first unparseable cell is refused with its
    row number (1-based, counting data rows) and column.
    """
    import numpy as np
    import pandas as pd

    from granudb.io.units import round_significant

    out = pd.DataFrame(index=frame.index)
    for column, cmap in mapping.items():
        raw = frame[cmap.header]
        if not cmap.numeric:
            out[column] = raw.where(raw.notna() & (raw.astype("string").str.strip() != ""), None)
            continue
        stripped = raw.astype("string").str.strip()
        values = pd.to_numeric(stripped, errors="coerce")
        bad = stripped.notna() & (stripped != "") & values.isna()
        if bad.any():
            pos = int(np.flatnonzero(bad.to_numpy())[0])
            raise ValidationError(
                cmap.header, repr(str(stripped.iloc[pos])), "is not a number", row=first_row + pos
            )
        arr = values.to_numpy(dtype=float, na_value=np.nan)
        inf = np.isinf(arr)
        if inf.any():
            pos = int(np.flatnonzero(inf)[0])
            raise ValidationError(
                cmap.header,
                repr(str(stripped.iloc[pos])),
                "must be a finite number",
                row=first_row + pos,
            )
        if cmap.scale != 1.0 or cmap.offset != 0.0:
            arr = round_significant(arr * cmap.scale + cmap.offset)
        out[column] = arr
    return out
