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
import difflib
import re
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from granudb.errors import ValidationError
from granudb.io.units import TINY_RULE, conversion, round_significant
from granudb.lazy import numpy as np
from granudb.lazy import pandas as pd
from granudb.vocabulary.terms import UNCERTAINTY_PREFIX, plain_uncertainty_header
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
#: Row problems of one file listed in one refusal before "… and N more problems": enough
#: to fix a systematic mistake in one pass, few enough to read in a terminal.
SHOWN_ROW_PROBLEMS = 20


class FileProblems(ValidationError):
    """Every problem of one file's rows in one refusal, in row order, named by the file.

    ``problems`` are the first ``SHOWN_ROW_PROBLEMS`` (each a ``ValidationError`` with its
    row), ``count`` all of them; ``field``, ``value``, ``rule`` and ``row`` are the first
    problem's, for callers that look at one.
    """

    def __init__(self, file: str, problems: list[ValidationError], count: int) -> None:
        self.file, self.problems, self.count = file, problems, count
        first = problems[0]
        super().__init__(first.field, first.value, first.rule, row=first.row)

    def render(self, field: str) -> str:
        listed = "; ".join(str(p) for p in self.problems)
        if self.count == 1:
            return f"{self.file}: {listed}"
        more = self.count - len(self.problems)
        tail = f"; … and {more:,} more problems" if more else ""
        return f"{self.file}: {self.count:,} problems: {listed}{tail}"


class Problems:
    """Collects a file's row problems as they are found, chunk by chunk, keeping the first
    ``shown`` in row order (memory bounded whatever the file) and counting all."""

    def __init__(self, file: str, shown: int = SHOWN_ROW_PROBLEMS) -> None:
        self.file, self.shown = file, shown
        self.found: list[ValidationError] = []
        self.count = 0

    def __bool__(self) -> bool:
        return self.count > 0

    def add(self, positions: Any, problem: Any) -> None:
        """``problem(position)`` for each position in ``positions`` (ascending) breaking
        one rule; only the first ``shown`` are built, all are counted."""
        positions = np.asarray(positions)
        self.count += len(positions)
        self.found.extend(problem(int(p)) for p in positions[: self.shown])
        self.found.sort(key=lambda p: p.row or 0)  # stable: a row's rules in check order
        del self.found[self.shown :]

    def add_one(self, problem: ValidationError) -> None:
        self.add([0], lambda _: problem)

    def refusal(self) -> FileProblems:
        return FileProblems(self.file, self.found, self.count)

    def merged(self, refusal: FileProblems) -> FileProblems:
        """``refusal`` (another collector's) with these problems merged in, row order kept
        (each list holds its first ``shown`` in row order, so the first ``shown`` of both
        are among them); ``refusal`` itself when it is this collector's own."""
        if refusal.problems is self.found or not self.count:
            return refusal
        found = sorted([*refusal.problems, *self.found], key=lambda p: p.row or 0)
        return FileProblems(refusal.file, found[: self.shown], refusal.count + self.count)

    def raise_any(self) -> None:
        if self.count:
            raise self.refusal()


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
    match = _HEADER.match(plain_uncertainty_header(header))
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
    if column.startswith(UNCERTAINTY_PREFIX):
        offset = 0.0  # an uncertainty is a difference: u(T) [K] is u(T) [degC]
    return ColumnMap(header, column, unit, True, scale, offset)


def _column_named(header: str, numeric: list[str], aliases: dict[str, str]) -> str | None:
    """The column a (refused) header meant, so it is not also reported as missing."""
    match = _HEADER.match(plain_uncertainty_header(header))
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
    columns: dict[str, str] | None = None,
) -> dict[str, ColumnMap]:
    """Map each header to a known column; refuse unknown, ambiguous or unit-less ones.

    ``numeric`` are unit-suffixed SI column names, ``text`` plain ones. Returns a dict keyed
    by column name. A header for a dimensioned column without a unit is refused: a bare
    ``diameter`` could be metres or millimetres. Every problem of the header (and every
    ``required`` column missing) is reported in one refusal, so a lab file is fixed in one
    pass rather than one error at a time. ``columns`` maps a file's own headers to
    granudb's columns (``check_column_mapping``).
    """
    where = f"{table} header"
    renamed = check_column_mapping(columns, headers, numeric, text, table, aliases or {})
    if len(headers) > MAX_HEADERS:
        raise ValidationError(where, f"{len(headers):,} columns", f"is more than {MAX_HEADERS}")
    mapped: dict[str, ColumnMap] = {}
    problems: list[str] = []
    unknown: list[str] = []
    attempted: set[str | None] = set()  # columns whose header was there but wrong
    for header in headers:
        try:
            cmap = _map_one(renamed.get(header, header), numeric, text, aliases or {})
            cmap = replace(cmap, header=header)
        except _Unknown:
            unknown.append(repr(header))
            continue
        except ValidationError as exc:
            if header in renamed:
                problems.append(f"{header!r} (mapped to {renamed[header]!r}) {exc.rule}")
            else:
                problems.append(f"{exc.value} {exc.rule}")
            attempted.add(_column_named(renamed.get(header, header), numeric, aliases or {}))
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


#: A header's unit at its end: ``speed [mm/s]`` or ``speed (mm/s)``.
_UNIT_AT_END = re.compile(r"\s*(\[[^\]]*\]|\([^()]*(?:\([^()]*\)[^()]*)*\))\s*$")


def parse_column_mapping(text: str) -> dict[str, str]:
    """``"my name=run, speed [mm/s]=v_n_in"`` (the command line's ``--columns``; a
    mapping file holds the same pairs one a line, ``#`` starting a comment) as a dict:
    pairs separated by commas or line breaks, each split at its last ``=``."""
    mapping: dict[str, str] = {}
    for pair in re.split(r"[,\n]", text):
        pair = pair.split("#", 1)[0] if pair.lstrip().startswith("#") else pair
        if not pair.strip():
            continue
        header, equals, column = pair.rpartition("=")
        if header.strip() in mapping:  # exactly twice (differing in case: refused below)
            raise ValidationError(
                "columns", repr(header.strip()), "is mapped twice", parameter=True
            )
        if not equals or not header.strip() or not column.strip():
            raise ValidationError(
                "columns", repr(pair.strip()), "must be 'your header=granudb column'",
                parameter=True,
            )  # fmt: skip
        mapping[header.strip()] = column.strip()  # a header named twice: refused below
    return mapping


#: A mapping file is a few lines; anything larger is not one.
MAX_MAPPING_BYTES = 65_536


def column_mapping(value: Any) -> dict[str, str] | None:
    """A column mapping as given: a dict, ``"header=column, …"`` pairs, or the path of
    a mapping file (text without ``=`` is a path) holding such pairs one a line."""
    if value is None or isinstance(value, dict):
        return value
    if isinstance(value, str) and "=" in value:
        return parse_column_mapping(value)
    if not isinstance(value, str) and not hasattr(value, "__fspath__"):
        raise ValidationError(
            "columns", repr(value)[:60], "must be a dict, 'header=column' pairs or a file",
            parameter=True,
        )  # fmt: skip
    path = Path(value)
    if not path.is_file():
        raise ValidationError(
            "columns", str(path), "is neither 'header=column' pairs nor a mapping file",
            parameter=True,
        )  # fmt: skip
    with path.open("rb") as handle:
        data = handle.read(MAX_MAPPING_BYTES + 1)
    if len(data) > MAX_MAPPING_BYTES:
        raise ValidationError(
            "columns", path.name, f"is larger than {MAX_MAPPING_BYTES:,} bytes", parameter=True
        )
    try:
        return parse_column_mapping(data.decode("utf-8-sig"))
    except UnicodeDecodeError:
        raise ValidationError("columns", path.name, "is not UTF-8 text", parameter=True) from None


def check_column_mapping(
    columns: dict[str, str] | None,
    headers: list[str],
    numeric: list[str],
    text: list[str],
    table: str,
    aliases: dict[str, str],
) -> dict[str, str]:
    """Each of the file's headers that ``columns`` maps, with the header it is read as.

    A key names one of the file's headers (spaces around it and case ignored); a value
    names a granudb column (``v_n_in``, ``v_n_in_m_s``, ``run``), with or without a unit.
    The unit is the value's, else the header's own (``speed [mm/s]=v_n_in`` reads mm/s).
    An unknown column is refused with the nearest known one.
    """
    if not columns:
        return {}
    bases = {base_name(c): c for c in numeric}
    known = sorted(set(bases) | set(numeric) | set(text))
    by_key = {h.strip().casefold(): h for h in headers}
    renamed: dict[str, str] = {}
    for key, target in columns.items():
        if not isinstance(key, str) or not isinstance(target, str):
            raise ValidationError("columns", repr(key), "must map text to text", parameter=True)
        header = by_key.get(key.strip().casefold())
        if header is None:
            shown = ", ".join(repr(h) for h in headers[:12]) + (", …" if len(headers) > 12 else "")
            raise ValidationError(
                "columns", repr(key), f"is not a header of {table} (its headers: {shown})",
                parameter=True,
            )  # fmt: skip
        if header in renamed:
            raise ValidationError("columns", repr(key), "is mapped twice", parameter=True)
        unit = _UNIT_AT_END.search(target)
        name = target[: unit.start()] if unit else target
        column = re.sub(r"\s+", "_", name.strip()).lower()
        if aliases.get(column, column) not in known:
            near = difflib.get_close_matches(column, known, n=1, cutoff=0.6)
            hint = f"; did you mean {near[0]}?" if near else f" (known: {', '.join(known)})"
            raise ValidationError(
                "columns", repr(target), f"is not a granudb column{hint}", parameter=True
            )
        if unit is None and column in bases and column not in numeric:
            own = _UNIT_AT_END.search(header)
            target = f"{column} {own.group(1)}" if own else column
        renamed[header] = target
    return renamed


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


def underflows(raw: Any, si: Any) -> Any:
    """Cells that are not 0 as written but are 0 or subnormal in SI (``TINY_RULE``)."""
    with np.errstate(invalid="ignore"):
        return (raw != 0) & np.isfinite(raw) & (np.abs(si) < np.finfo(float).tiny)


def _unreadable(
    cells: Any, header: str, why: str | None, decimal: str, first_row: int
) -> Callable[[int], ValidationError]:
    """The problem of the cell at a position of ``cells``: not a number (and why), or
    ``why``."""

    def problem(pos: int) -> ValidationError:
        cell = str(cells.iloc[pos])
        rule = why or _not_a_number(cell, decimal)
        return ValidationError(header, repr(cell), rule, row=first_row + pos)

    return problem


def convert_frame(
    frame: Any,
    mapping: dict[str, ColumnMap],
    *,
    table: str,
    first_row: int = 1,
    decimal: str = ".",
    problems: Problems | None = None,
) -> Any:
    """A pandas DataFrame with SI columns from a raw one read as strings.

    Numeric cells are parsed vectorized; an unparseable or infinite cell is refused with
    its row number (the header is row 1 when ``first_row`` is 2) and column: the first
    one, or with ``problems`` every one (collected there, the cell left empty and listed
    in ``out.attrs["unreadable"]`` by column, so no later rule reports it again).
    ``decimal`` is the file's decimal separator ("." or ",").
    """
    out = pd.DataFrame(index=frame.index)
    unreadable: dict[str, Any] = {}
    for column, cmap in mapping.items():
        raw = frame[cmap.header]
        if not cmap.numeric:
            out[column] = raw.where(raw.notna() & (raw.astype("string").str.strip() != ""), None)
            continue
        stripped = raw.astype("string").str.strip()
        values, bad = _numbers(stripped, decimal)
        arr = values.to_numpy(dtype=float, na_value=np.nan)
        inf = np.isinf(arr)
        bad = bad.to_numpy(dtype=bool)
        if cmap.scale != 1.0 or cmap.offset != 0.0:
            si = round_significant(arr * cmap.scale + cmap.offset)
        else:
            si = arr
        tiny = underflows(arr, si) & ~bad & ~inf
        checks = ((bad, None), (inf & ~bad, "must be a finite number"), (tiny, TINY_RULE))
        for mask, why in checks:
            if not mask.any():
                continue
            problem = _unreadable(stripped, cmap.header, why, decimal, first_row)
            if problems is None:
                raise problem(int(np.flatnonzero(mask)[0]))
            problems.add(np.flatnonzero(mask), problem)
        refused = bad | inf | tiny
        if refused.any():
            unreadable[column] = refused
            si = np.where(refused, np.nan, si)
        out[column] = si
    out.attrs["unreadable"] = unreadable
    return out


#: The longest CSV cell granudb reads (Python's csv default). granudb's own, not the
#: process-wide ``csv.field_size_limit()``: a library that raises that limit when it is
#: imported (frictionless does) must not change which files granudb refuses.
CSV_FIELD_LIMIT = 131_072


@contextmanager
def _field_limit() -> Iterator[None]:
    """Python's csv reader at granudb's own cell limit, the process's limit restored after."""
    before = csv.field_size_limit(CSV_FIELD_LIMIT)
    try:
        yield
    finally:
        csv.field_size_limit(before)


def check_shape(path: Path, delimiter: str) -> None:
    """Every row has as many cells as the header; every row that does not is listed (in
    one ``FileProblems``, capped). pandas silently drops the extra cells of a long row and
    pads a short (truncated) one, so rows are counted here first."""
    problems = Problems(path.name)
    with _field_limit(), path.open(encoding="utf-8-sig", newline="") as handle:
        reader = csv.reader(handle, delimiter=delimiter)
        try:
            header = next(reader, None)
            if not header:
                return
            width = len(header)
            for number, row in enumerate(reader, start=2):
                if len(row) != width and row:  # a blank line pandas skips too
                    hint = " (truncated?)" if len(row) < width else ""
                    rule = f"where the header has {width}{hint}"
                    problems.add_one(ValidationError("cells", str(len(row)), rule, row=number))
        except csv.Error as exc:
            raise ValidationError(
                "FILE", path.name, f"is not a well-formed CSV (line {reader.line_num}: {exc})"
            ) from None
    if problems:
        _refuse_bare_carriage_return(path)
    problems.raise_any()


def _refuse_bare_carriage_return(path: Path) -> None:
    """A carriage return not followed by a line feed ends a row for CSV readers (old Mac
    line ends) but not for people, who meant a line break in a cell: when rows are ragged
    and the file has one, that is the problem to name."""
    line, tail = 1, b""
    with path.open("rb") as handle:
        while block := handle.read(1 << 20):
            data = tail + block
            found = re.search(rb"\r(?!\n)", data[:-1] if len(block) == 1 << 20 else data)
            if found:
                at = line + data.count(b"\n", 0, found.start())
                raise ValidationError(
                    "FILE",
                    path.name,
                    f"has a bare carriage return (U+000D) on line {at}: it splits the row "
                    "there; a line break inside a cell must be a line feed, in quotes",
                )
            line += data[:-1].count(b"\n")
            tail = data[-1:]


def csv_options(delimiter: str | None, decimal: str) -> tuple[str | None, str]:
    """The file's delimiter (None: detected from its header) and decimal separator,
    refusing an ambiguous pair."""
    if delimiter is not None and delimiter not in DELIMITERS:
        raise ValidationError("--delimiter", repr(delimiter), "must be ',', ';' or 'tab'")
    if decimal not in DECIMALS:
        raise ValidationError("--decimal", repr(decimal), "must be '.' or ','")
    delimiter = DELIMITERS.get(delimiter) if delimiter is not None else None
    if delimiter == "," and decimal == ",":
        raise ValidationError(
            "--decimal", "','", "cannot be the delimiter too (decimal commas need --delimiter ';')"
        )
    return delimiter, decimal


def read_header(path: Path, delimiter: str | None = ",") -> tuple[list[str], str]:
    """The header's cells and the file's delimiter, read with a size limit (never the
    whole first line of a huge file).

    With ``delimiter=None`` it is detected: a header with semicolons (or tabs) and no
    comma is semicolon- (or tab-) delimited, as European spreadsheets write CSV; any
    other header is comma-delimited. A stated delimiter the header does not use is
    refused with the option that reads the file.
    """
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
    if delimiter is None:
        found = [d for d in (";", "\t") if d in line]
        delimiter = found[0] if len(found) == 1 and "," not in line else ","
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
    return cells, delimiter
