"""Reading a collision CSV in one pass: hashed while Arrow parses it, checked in columns.

``HashingFile`` updates the sha256 with every byte read, and the file is read once (not
once to hash, once to count cells, once to parse), ``READ_BYTES`` at a time cut at the
last whole record; ``pyarrow.csv.read_csv`` parses each piece on its threads, every cell as
text. Pieces are cut into chunks of ``chunk_rows`` rows (memory stays bounded whatever the
file's size) and each chunk is converted and checked with vectorized rules:

* numbers: ASCII spaces trimmed, cast to float64 by Arrow (the correctly rounded double,
  as pandas parses it), converted to SI as ``granudb.io.tables.convert_frame`` does;
* names: checked once per distinct name (a million rows name a handful of materials) with
  the vocabulary's own ``check_name`` rules, run labels and notes vectorized;
* rules: ``collision_file.check_values``, the same function the pandas path runs.

Anything the fast path does not accept outright (a cell Arrow cannot cast, an empty
required name, a label with spaces or control characters...) sends the chunk through the
earlier pandas path (``convert_frame``, ``_check_chunk``), which gives exactly the message
it always gave, or accepts the chunk where Arrow was stricter. A file Arrow cannot parse is
re-read with Python's csv module for the row and the reason (``check_shape``).
"""

from __future__ import annotations

import io
import re
from collections.abc import Iterator
from typing import Any

import numpy as np

from granudb.db.bulk_insert import CollisionChunk, NameColumn, block_from_frame
from granudb.errors import ValidationError
from granudb.io import collision_file
from granudb.io.reading import HashingFile, Prefetched, arrow_memory
from granudb.io.tables import CSV_FIELD_LIMIT, Problems, check_shape, convert_frame, underflows
from granudb.io.units import round_significant
from granudb.lazy import pyarrow as pa
from granudb.lazy import pyarrow_compute as pc
from granudb.lazy import pyarrow_csv as pacsv
from granudb.vocabulary.text import (
    MAX_NAME,
    MAX_TEXT,
    name_forbidden_pattern,
    text_forbidden_pattern,
)

__all__ = ["HashingFile", "Prefetched", "arrow_memory", "read_chunks"]

#: Bytes read and parsed at a time (about 45,000 rows, one chunk: 8 MB held about 20 MB
#: more at the million-row import's peak, benchmarks/import_speed.py), and the block each
#: of Arrow's parser threads takes of them.
READ_BYTES = 4 << 20
BLOCK_BYTES = 1 << 20


def read_chunks(
    source: Any, stream: HashingFile, chunk_rows: int = collision_file.CHUNK_ROWS
) -> Iterator[CollisionChunk]:
    """The file's rows as checked ``CollisionChunk``s of ``chunk_rows`` rows.

    From the first chunk with a problem on, blocks come ``faulty`` (with what could be
    read of them: names, and numbers with the unreadable cells empty) so the catalogue
    checks still see every row, and nothing is written; the rest of the file is read and
    checked, and then every problem is refused at once, in row order (``FileProblems``,
    capped)."""
    headers = {column: cmap.header for column, cmap in source.mapping.items()}
    problems = Problems(source.path.name)
    rows = 0
    try:
        for table in _chunks(_tables(source, stream), chunk_rows):
            if rows == 0 and table.schema.names != list(headers.values()):
                raise ValidationError(
                    "FILE", source.path.name, "has a header that is not one line of cells"
                )
            block = _block(table, source, headers, rows + 2, problems)
            block.faulty = bool(problems)  # after a problem the rest is only checked
            yield block
            rows += table.num_rows
    except pa.ArrowInvalid as exc:
        _refuse_unparsable(source, exc)
    problems.raise_any()
    if rows == 0:
        raise ValidationError("FILE", source.path.name, "holds no rows")


def _record_end(data: bytes) -> int:
    """Where the last whole record of ``data`` ends (after its line feed), or 0.

    A line feed inside a quoted cell (notes may hold line breaks) has an odd number of
    quote characters before it (an escaped quote is two), so it is skipped.
    """
    cut = data.rfind(b"\n")
    while cut >= 0 and data.count(b'"', 0, cut) % 2:
        cut = data.rfind(b"\n", 0, cut)
    return cut + 1


def _tables(source: Any, stream: HashingFile) -> Iterator[Any]:
    """The file as Arrow tables of whole records, every cell text, parsed ``READ_BYTES``
    at a time. (Arrow's own streaming reader reads many blocks ahead of the consumer:
    about 100 MB more peak memory on a million rows.)"""
    headers = [cmap.header for cmap in source.mapping.values()]
    parse = pacsv.ParseOptions(delimiter=source.delimiter, newlines_in_values=True)
    convert = pacsv.ConvertOptions(
        column_types={h: pa.string() for h in headers},
        strings_can_be_null=False,
        quoted_strings_can_be_null=False,
    )
    first, pending = True, b""
    while True:
        data = stream.read(READ_BYTES)
        pending += data
        cut = len(pending) if not data else _record_end(pending)
        if cut == 0 and data:
            continue  # one record longer than READ_BYTES: read on
        piece, pending = pending[:cut], pending[cut:]
        if piece.strip():
            options = pacsv.ReadOptions(
                block_size=BLOCK_BYTES, column_names=None if first else headers
            )
            yield pacsv.read_csv(
                io.BytesIO(piece),
                read_options=options,
                parse_options=parse,
                convert_options=convert,
            )
        elif first:
            return
        first = False
        if not data:
            return


def _chunks(tables: Iterator[Any], chunk_rows: int) -> Iterator[Any]:
    """Tables re-cut into tables of exactly ``chunk_rows`` rows (the last shorter), so
    checks and messages go chunk by chunk as they always did."""
    pending: list[Any] = []
    size = 0
    schema = None
    for batch in (b for table in tables for b in table.to_batches()):
        schema = batch.schema
        pending.append(batch)
        size += batch.num_rows
        while size >= chunk_rows:
            table = pa.Table.from_batches(pending)
            yield table.slice(0, chunk_rows)
            rest = table.slice(chunk_rows)
            pending, size = rest.to_batches(), rest.num_rows
    if size:
        yield pa.Table.from_batches(pending, schema=schema)


def _refuse_unparsable(source: Any, exc: Exception) -> None:
    """Arrow refused the file: find the row and reason with Python's csv module."""
    message = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
    if "utf8" in message.lower() or "utf-8" in message.lower():
        raise ValidationError("FILE", source.path.name, "is not UTF-8 text") from None
    try:
        check_shape(source.path, source.delimiter)
    except UnicodeDecodeError:
        raise ValidationError("FILE", source.path.name, "is not UTF-8 text") from None
    raise ValidationError(
        "FILE", source.path.name, f"is not a well-formed CSV ({message})"
    ) from None


def _refuse_huge_cells(table: Any, source: Any) -> None:
    """A cell longer than Python's csv field limit was always refused by ``check_shape``
    (the file is not a table granudb reads); it still is, with the same message."""
    limit = CSV_FIELD_LIMIT
    for column in table.columns:
        if (pc.max(pc.utf8_length(column)).as_py() or 0) > limit:
            check_shape(source.path, source.delimiter)


def _block(
    table: Any, source: Any, headers: dict[str, str], first_row: int, problems: Problems
) -> CollisionChunk:
    """One chunk's checked block; its problems are added to ``problems``."""
    _refuse_huge_cells(table, source)
    values = _numbers(table, source)
    texts = _texts(table, source.mapping) if values is not None else None
    if values is None or texts is None:
        return _pandas_block(table, source, headers, first_row, problems)
    runs, particle, wall, fluid, notes = texts
    columns = {c: values.get(c, np.full(table.num_rows, np.nan)) for c in collision_file.NUMERIC}
    cell = lambda header, pos: str(table.column(header)[pos].as_py()).strip()  # noqa: E731
    found = problems.count
    rows = collision_file.Rows(columns, cell, source.mapping, first_row, problems)
    collision_file.check_values(rows)
    block = CollisionChunk(first_row, headers, runs, particle, wall, fluid, values, notes)
    block.faulty = problems.count > found
    return block


def _pandas_block(
    table: Any, source: Any, headers: dict[str, str], first_row: int, problems: Problems
) -> CollisionChunk:
    """The earlier pandas path for one chunk: its problems (to ``problems``) and its rows,
    checked, or as far as they could be read (a name that breaks a rule is left out: it
    was refused already)."""
    raw = table.to_pandas()
    found = problems.count
    frame = convert_frame(
        raw,
        source.mapping,
        table=source.path.name,
        first_row=first_row,
        decimal=source.decimal,
        problems=problems,
    )
    for column in collision_file.NUMERIC + collision_file.TEXT:
        if column not in frame:
            frame[column] = np.nan if column in collision_file.NUMERIC else None
    collision_file.check_chunk(frame, raw, source.mapping, first_row, problems)
    faulty = problems.count > found
    if faulty:
        for column in ("run", "particle", "wall", "fluid"):
            names = frame[column].astype(object)
            readable = names.map(lambda n: isinstance(n, str) and _name_ok(n))
            frame[column] = names.where(readable, None)
        frame["run"] = frame["run"].where(frame["run"].notna(), "")
    frame.attrs["first_row"] = first_row
    frame.attrs["headers"] = headers
    block = block_from_frame(frame)
    block.faulty = faulty
    return block


def _numbers(table: Any, source: Any) -> dict[str, Any] | None:
    """Every numeric column in SI (NaN = empty), or None if any cell needs the pandas path."""
    out: dict[str, Any] = {}
    for column, cmap in source.mapping.items():
        if not cmap.numeric:
            continue
        text = pc.ascii_trim_whitespace(table.column(cmap.header))
        empty = pc.equal(text, "")
        if source.decimal == ",":
            if pc.any(pc.match_substring(text, ".")).as_py():
                return None
            text = pc.replace_substring(text, ",", ".")
        try:
            numbers = pc.cast(pc.if_else(empty, pa.scalar(None, pa.string()), text), pa.float64())
        except (pa.ArrowInvalid, pa.ArrowNotImplementedError):
            return None
        values = np.asarray(pc.fill_null(numbers, np.nan).combine_chunks(), dtype=np.float64)
        if (np.isinf(values) | (np.isnan(values) & ~_numpy(empty))).any():
            return None  # "inf", "nan": the pandas path says what is wrong
        if cmap.scale != 1.0 or cmap.offset != 0.0:
            with np.errstate(over="ignore"):  # beyond float range: inf, refused by its rule
                si = round_significant(values * cmap.scale + cmap.offset)
        else:
            si = values
        if underflows(values, si).any():
            return None  # the pandas path says which cell
        out[column] = si
    return out


def _numpy(array: Any) -> Any:
    return np.asarray(array.combine_chunks() if hasattr(array, "combine_chunks") else array)


_NAME_FORBIDDEN = re.compile(name_forbidden_pattern())
_TEXT_FORBIDDEN = re.compile(text_forbidden_pattern())
#: A label starting or ending with a character Python's ``str.strip`` removes (every one
#: of them: ``str.isspace``), found by Arrow's regex without a Python loop over the
#: labels (which held the GIL the insert waits for); such a label goes the pandas way.
_SPACE = r"[\t\n\v\f\r \x1c-\x1f\x85\p{Z}]"
_EDGE_SPACE = f"^{_SPACE}|{_SPACE}$"


def _names(table: Any, mapping: dict[str, Any], column: str, required: bool) -> Any:
    """A name column dictionary-encoded, or None if a name breaks a rule (or a required one
    is empty): the pandas path then says which."""
    n = table.num_rows
    if column not in mapping:
        return NameColumn(np.full(n, -1, dtype=np.int64), [])
    encoded = table.column(mapping[column].header).combine_chunks().dictionary_encode()
    distinct = encoded.dictionary.to_pylist()
    keep: list[str] = []
    recode = np.full(len(distinct) + 1, -1, dtype=np.int64)
    for code, name in enumerate(distinct):
        if not name.strip():
            continue
        if not _name_ok(name):
            return None
        recode[code] = len(keep)
        keep.append(name)
    codes = recode[np.asarray(encoded.indices)]
    if required and (codes < 0).any():
        return None
    return NameColumn(codes, keep)


def _name_ok(name: str) -> bool:
    return name == name.strip() and len(name) <= MAX_NAME and not _NAME_FORBIDDEN.search(name)


def _texts(table: Any, mapping: dict[str, Any]) -> tuple[Any, ...] | None:
    """(runs, particle, wall, fluid, notes), or None if the pandas path must look."""
    column = table.column(mapping["run"].header)
    if pc.any(pc.equal(column, "")).as_py():
        return None
    if pc.any(pc.match_substring_regex(column, _EDGE_SPACE)).as_py():
        return None
    runs = column.to_pylist()
    if _NAME_FORBIDDEN.search("".join(runs)) or max(map(len, runs)) > MAX_NAME:
        return None
    names = [
        _names(table, mapping, c, c in collision_file.REQUIRED)
        for c in ("particle", "wall", "fluid")
    ]
    if any(n is None for n in names):
        return None
    notes = None
    if "notes" in mapping:
        column = table.column(mapping["notes"].header)
        if pc.max(pc.utf8_length(column)).as_py():
            listed = [note if note.strip() else None for note in column.to_pylist()]
            present = [note for note in listed if note is not None]
            if _TEXT_FORBIDDEN.search("".join(present)) or max(map(len, present)) > MAX_TEXT:
                return None
            notes = listed
    return runs, *names, notes
