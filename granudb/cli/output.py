"""One way to print records: a Rich table for people, JSON or CSV for scripts.

JSON is a plain array of objects (or one object for ``show``) with SI values under the
public column names; NaN becomes ``null``. CSV has the same names as headers. Tables show
values with units in engineering notation (``60 GPa``, ``130.5 nm``).
"""

from __future__ import annotations

import csv
import json
import logging
import math
import sys
from collections.abc import Sequence
from typing import Any

from granudb import api
from granudb.cli.options import Format
from granudb.lazy import rich_box, rich_console, rich_markup, rich_table, rich_text


def _clean(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if hasattr(value, "isoformat"):
        return value.isoformat()
    if hasattr(value, "item"):  # numpy scalar
        return _clean(value.item())
    return value


def to_json(data: Any) -> str:
    if isinstance(data, dict):
        data = {k: to_json_value(v) for k, v in data.items()}
    elif isinstance(data, list):
        data = [to_json_value(v) for v in data]
    return json.dumps(data, indent=2, ensure_ascii=False, allow_nan=False)


def to_json_value(value: Any) -> Any:
    if isinstance(value, dict):
        return {k: to_json_value(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [to_json_value(v) for v in value]
    return _clean(value)


def console(stderr: bool = False, soft_wrap: bool = False) -> Any:
    return rich_console.Console(stderr=stderr, highlight=False, soft_wrap=soft_wrap)


def note(message: str) -> None:
    """A remark for the person at the terminal (stderr, so pipes stay clean); dimmed on a
    terminal, plain text otherwise."""
    if not sys.stderr.isatty():
        print(message, file=sys.stderr)
        return
    escaped = rich_markup.escape(message)
    console(stderr=True, soft_wrap=True).print(f"[dim]{escaped}[/dim]", emoji=False)


def say(message: str) -> None:
    """A result line on stdout, as plain text: names from the database are never markup
    or emoji codes, and one line does not need rich (0.1 s to import)."""
    print(message)


def label(column: str) -> str:
    """A table header for a column: its title in the vocabulary (``youngs_modulus_pa`` →
    ``Young's modulus``), else the name in words."""
    return api.term(column).title


def header(column: str, symbols: bool) -> str:
    """A table header: the symbol people read (``St_n``) when asked for and known, else
    the column name in words."""
    if symbols:
        # the cells carry their units (``300 mm/s``); a column without a symbol is named
        return api.term(column).symbol or column.replace("_", " ")
    return label(column)


#: How Maw's regimes read in a narrow table (JSON and CSV keep the machine values).
SHORT_WORDS = {"slip_then_stick": "slip→stick", "gross_slip": "gross slip"}


def emit(
    records: Sequence[dict[str, Any]],
    columns: Sequence[str],
    fmt: Format,
    title: str | None = None,
    *,
    symbols: bool = False,
) -> None:
    """Print ``records`` (SI dicts) in ``fmt``, keeping ``columns`` in order; a table uses
    symbols for its headers when ``symbols``, JSON and CSV always the machine names."""
    rows = [{c: r.get(c) for c in columns} for r in records]
    if fmt is Format.json:
        sys.stdout.write(to_json(rows) + "\n")
    elif fmt is Format.csv:
        writer = csv.DictWriter(sys.stdout, fieldnames=list(columns), lineterminator="\n")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: api.spreadsheet_cell(_clean(v)) for k, v in row.items()})
    else:
        narrow = {"box": rich_box.SIMPLE_HEAD, "padding": (0, 0), "show_edge": False}
        narrow = narrow if symbols else {}
        table = rich_table.Table(
            title=rich_text.Text(title) if title else None, title_justify="left", **narrow
        )
        for column in columns:
            table.add_column(header(column, symbols), overflow="ellipsis", no_wrap=symbols)
        digits = 3 if symbols else 4
        for record, row in zip(records, rows, strict=True):
            cells = (
                SHORT_WORDS.get(v, v) if symbols and isinstance(v, str) else v
                for v in (row[c] for c in columns)
            )
            table.add_row(*(rich_text.Text(_cell(record, v, c, digits))
                            for v, c in zip(cells, columns, strict=True)))  # fmt: skip
        console().print(table)


def _cell(record: dict[str, Any], value: Any, column: str, digits: int) -> str:
    """A table cell: the value, with its standard uncertainty where the record has one
    (``u_<column>``: "46 ± 5 nm")."""
    u = record.get(f"u_{column}")
    if isinstance(u, int | float) and not isinstance(u, bool) and u > 0:
        return api.display_uncertain(value, u, column)
    return api.display(value, column, digits)


def emit_one(
    record: dict[str, Any],
    fmt: Format,
    title: str | None = None,
    extra: dict[str, Any] | None = None,
) -> None:
    """Print one record: a two-column property table, or a JSON object / one-row CSV."""
    if fmt is Format.json:
        sys.stdout.write(to_json({**record, **(extra or {})}) + "\n")
        return
    if fmt is Format.csv:
        emit([record], list(record), fmt)
        return
    table = rich_table.Table(
        title=rich_text.Text(title) if title else None, title_justify="left", show_header=False
    )
    table.add_column("property", style="bold")
    table.add_column("value", overflow="fold")
    for column, value in record.items():
        table.add_row(label(column), rich_text.Text(api.display(value, column)))
    console().print(table)


class NoteHandler(logging.Handler):
    """Prints the library's remarks (the ``granudb`` logger: "created … and loaded the seed
    data") as notes on stderr."""

    def emit(self, record: logging.LogRecord) -> None:
        note(record.getMessage())


def show_notes() -> None:
    """Print the library's INFO remarks on stderr (once, however often it is called)."""
    logger = logging.getLogger("granudb")
    logger.setLevel(logging.INFO)
    if not any(isinstance(h, NoteHandler) for h in logger.handlers):
        logger.addHandler(NoteHandler())
