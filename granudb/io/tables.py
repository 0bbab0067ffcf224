"""Tables from outside: headers that carry units, converted to granudb's SI columns.

One rule for every table granudb reads (seed files, collision CSVs, data packages): a header
is either granudb's own column name (``youngs_modulus_pa``, SI already) or the column's base
name with a unit in brackets or parentheses (``youngs_modulus [GPa]``, ``v_n_in (mm/s)``,
``temperature [degC]``, ``density [kg/m3]``), names matched case-insensitively, converted
with Pint once per column (through ``granudb.io.units``' checks) and then vectorized.

Files are read defensively before anything else happens: the header line with a size
limit, at most ``MAX_HEADERS`` columns, every header problem reported in one line, every
row's cell count checked; a semicolon- or tab-delimited file read as comma-delimited is
refused with the options that read it.
"""

from __future__ import annotations

import csv
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from granudb.errors import ValidationError
from granudb.io.units import conversion, round_significant
from granudb.lazy import numpy as np
from granudb.lazy import pandas as pd
from granudb.vocabulary.units import Unit, unit_of_column

#: ``name``, ``name [unit]`` or ``name (unit)``; names are matched case-insensitively.
_HEADER = re.compile(
    r"^\s*(?P<base>[A-Za-z_][A-Za-z0-9_ ]*?)\s*"
    r"(?:\[(?P<unit>[^\]]*)\]|\((?P<paren>.*)\))?\s*$"
)
#: More headers than this is not a granudb table (collisions have 26 columns); refusing
#: early keeps a hostile million-column header from costing minutes and gigabytes.
MAX_HEADERS = 200
#: A header line longer than this is not a granudb table (26 columns fit in 1 kB).
MAX_HEADER_BYTES = 16_384
DELIMITERS = {",": ",", ";": ";", "tab": "\t", "\t": "\t", "\\t": "\t"}
DECIMALS = {".", ","}
#: Problems listed in one refusal before "and N more".
SHOWN_PROBLEMS = 10


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


class _Unknown(Exception):
    """A header that names no known column (listed once, with the known names)."""


def _map_one(
    header: str, numeric: list[str], text: list[str], aliases: dict[str, str]
) -> ColumnMap:
    """One header's mapping, or ``ValidationError``/``_Unknown`` saying what is wrong."""
    by_base = {base_name(c): c for c in numeric}
    match = _HEADER.match(header)
    if not match:
        raise ValidationError("", repr(header), "is not 'name', 'name [unit]' or 'name (unit)'")
    base = re.sub(r"\s+", "_", match["base"].strip()).lower()
    base = aliases.get(base, base)
    unit_text = match["unit"] if match["unit"] is not None else match["paren"]
    if base in text and unit_text is None:
        return ColumnMap(header, base, unit_of_column(""), numeric=False)
    if base in numeric and unit_text is None:
        return ColumnMap(header, base, unit_of_column(base))
    if base not in by_base:
        raise _Unknown(header)
    column = by_base[base]
    unit = unit_of_column(column)
    if unit_text is None:
        if unit.suffix:
            raise ValidationError(
                "", repr(header), f"needs a unit in brackets, e.g. '{base} [{unit.pint}]'"
            )
        return ColumnMap(header, column, unit)
    try:
        scale, offset = conversion(unit_text, unit)
    except ValidationError as exc:
        raise ValidationError("", f"{header!r}: [{unit_text}]", exc.rule) from None
    return ColumnMap(header, column, unit, True, scale, offset)


def _column_named(header: str, numeric: list[str], aliases: dict[str, str]) -> str | None:
    """The column a (refused) header meant, so it is not also reported as missing."""
    match = _HEADER.match(header)
    if not match:
        return None
    base = re.sub(r"\s+", "_", match["base"].strip()).lower()
    base = aliases.get(base, base)
    return {base_name(c): c for c in numeric}.get(base, base)


def map_headers(
    headers: list[str],
    numeric: list[str],
    text: list[str],
    *,
    table: str,
    aliases: dict[str, str] | None = None,
    required: list[str] | None = None,
) -> dict[str, ColumnMap]:
    """Map each header to a known column; refuse unknown, ambiguous or unit-less ones.

    ``numeric`` are unit-suffixed SI column names, ``text`` plain ones. Returns a dict keyed
    by column name. A header for a dimensioned column without a unit is refused: a bare
    ``diameter`` could be metres or millimetres. Every problem of the header (and every
    ``required`` column missing) is reported in one refusal, so a lab file is fixed in one
    pass rather than one error at a time.
    """
    where = f"{table} header"
    if len(headers) > MAX_HEADERS:
        raise ValidationError(where, f"{len(headers):,} columns", f"is more than {MAX_HEADERS}")
    mapped: dict[str, ColumnMap] = {}
    problems: list[str] = []
    unknown: list[str] = []
    attempted: set[str | None] = set()  # columns whose header was there but wrong
    for header in headers:
        try:
            cmap = _map_one(header, numeric, text, aliases or {})
        except _Unknown:
            unknown.append(repr(header))
            continue
        except ValidationError as exc:
            problems.append(f"{exc.value} {exc.rule}")
            attempted.add(_column_named(header, numeric, aliases or {}))
            continue
        if cmap.column in mapped:
            problems.append(f"{header!r} names column {cmap.column} a second time")
            continue
        mapped[cmap.column] = cmap
    if unknown:
        known = sorted({base_name(c) for c in numeric} | set(text))
        verb = "is not a known column" if len(unknown) == 1 else "are not known columns"
        problems.append(f"{', '.join(unknown)} {verb} (known: {', '.join(known)})")
    missing = [base_name(c) for c in required or [] if c not in mapped and c not in attempted]
    if missing:
        verb = "is a required column" if len(missing) == 1 else "are required columns"
        problems.append(f"{', '.join(missing)} {verb} but missing")
    if problems:
        raise _header_error(where, problems)
    return mapped


def _header_error(where: str, problems: list[str]) -> ValidationError:
    if len(problems) == 1:
        value, _, rule = problems[0].partition(" ")
        return ValidationError(where, value, rule)
    shown = problems[:SHOWN_PROBLEMS]
    more = len(problems) - len(shown)
    listed = "; ".join(f"({i}) {p}" for i, p in enumerate(shown, start=1))
    return ValidationError(
        where, f"{len(problems)} problems:", listed + (f"; and {more} more" if more else "")
    )


_DECIMAL_COMMA = r"^[-+]?[0-9]*,[0-9]+(?:[eE][-+]?[0-9]+)?$"


def _numbers(stripped: Any, decimal: str) -> tuple[Any, Any]:
    """Cells as floats (NaN where empty) and a mask of cells that are not numbers.

    With ``decimal=","`` (European spreadsheets) a comma is the decimal separator and a
    point is refused rather than guessed: in "1.234,5" it is a thousands separator, in
    "1.5" a mistake, and either reading could be wrong.
    """
    if decimal == ",":
        has_point = stripped.str.contains(".", regex=False).fillna(False)
        stripped = stripped.str.replace(",", ".", regex=False)
    values = pd.to_numeric(stripped, errors="coerce")
    bad = stripped.notna() & (stripped != "") & values.isna()
    if decimal == ",":
        bad |= has_point
    return values, bad


def _not_a_number(cell: str, decimal: str) -> str:
    if decimal == "," and "." in cell:
        return "has a '.' but the file's decimal separator is ',' (no thousands separators)"
    if decimal == "." and re.match(_DECIMAL_COMMA, cell):
        return "has a decimal comma: use a decimal point, or import with --decimal ','"
    return "is not a number"


def convert_frame(
    frame: Any,
    mapping: dict[str, ColumnMap],
    *,
    table: str,
    first_row: int = 1,
    decimal: str = ".",
) -> Any:
    """A pandas DataFrame with SI columns from a raw one read as strings.

    Numeric cells are parsed vectorized; the first unparseable cell is refused with its
    row number (1-based, counting data rows) and column. ``decimal`` is the file's decimal
    separator ("." or ",").
    """
    out = pd.DataFrame(index=frame.index)
    for column, cmap in mapping.items():
        raw = frame[cmap.header]
        if not cmap.numeric:
            out[column] = raw.where(raw.notna() & (raw.astype("string").str.strip() != ""), None)
            continue
        stripped = raw.astype("string").str.strip()
        values, bad = _numbers(stripped, decimal)
        if bad.any():
            pos = int(np.flatnonzero(bad.to_numpy())[0])
            cell = str(stripped.iloc[pos])
            raise ValidationError(
                cmap.header, repr(cell), _not_a_number(cell, decimal), row=first_row + pos
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


def check_shape(path: Path, delimiter: str) -> None:
    """Every row has as many cells as the header. pandas silently drops the extra cells of
    a long row and pads a short (truncated) one, so rows are counted here first."""
    with path.open(encoding="utf-8-sig", newline="") as handle:
        reader = csv.reader(handle, delimiter=delimiter)
        try:
            header = next(reader, None)
            if not header:
                return
            width = len(header)
            for number, row in enumerate(reader, start=2):
                if len(row) != width and row:  # a blank line pandas skips too
                    what = "more" if len(row) > width else "fewer"
                    hint = "" if what == "more" else " (truncated?)"
                    raise ValidationError(
                        "FILE", f"row {number}", f"has {what} cells than the header{hint}"
                    )
        except csv.Error as exc:
            raise ValidationError(
                "FILE", path.name, f"is not a well-formed CSV (line {reader.line_num}: {exc})"
            ) from None


def csv_options(delimiter: str, decimal: str) -> tuple[str, str]:
    """The file's delimiter and decimal separator, refusing an ambiguous pair."""
    if delimiter not in DELIMITERS:
        raise ValidationError("--delimiter", repr(delimiter), "must be ',', ';' or 'tab'")
    if decimal not in DECIMALS:
        raise ValidationError("--decimal", repr(decimal), "must be '.' or ','")
    delimiter = DELIMITERS[delimiter]
    if delimiter == "," and decimal == ",":
        raise ValidationError(
            "--decimal", "','", "cannot be the delimiter too (decimal commas need --delimiter ';')"
        )
    return delimiter, decimal


def read_header(path: Path, delimiter: str = ",") -> list[str]:
    """The header's cells, read with a size limit (never the whole first line of a huge
    file), or a refusal saying how to read a semicolon-delimited file."""
    with path.open("rb") as handle:
        head = handle.read(MAX_HEADER_BYTES + 1)
    if not head.strip():
        raise ValidationError("FILE", path.name, "is empty")
    end = head.find(b"\n")
    if end < 0 and len(head) > MAX_HEADER_BYTES:
        raise ValidationError(
            "FILE", path.name, f"has a header line longer than {MAX_HEADER_BYTES:,} bytes"
        )
    try:
        line = head[: end if end >= 0 else len(head)].decode("utf-8-sig").rstrip("\r")
    except UnicodeDecodeError:
        raise ValidationError("FILE", path.name, "is not UTF-8 text") from None
    cells = next(csv.reader([line], delimiter=delimiter), [])
    if len(cells) <= 1:
        for other, option in ((";", "';'"), ("\t", "tab")):
            if other != delimiter and other in line:
                raise ValidationError(
                    "FILE",
                    path.name,
                    f"looks {'semicolon' if other == ';' else 'tab'}-delimited (as European "
                    f"spreadsheets write CSV): import it with --delimiter {option}, and "
                    "--decimal ',' if its numbers have decimal commas",
                )
    return cells
