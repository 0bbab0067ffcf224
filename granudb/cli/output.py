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
    vertical: bool = False,
) -> None:
    """Print ``records`` (SI dicts) in ``fmt``, keeping ``columns`` in order; a table uses
    symbols for its headers when ``symbols``, JSON and CSV always the machine names. With
    ``vertical`` (a history: few records of long text) a table shows each record as name
    and value lines."""
    rows = [{c: r.get(c) for c in columns} for r in records]
    if fmt is Format.json:
        sys.stdout.write(to_json(rows) + "\n")
    elif fmt is Format.csv:
        writer = csv.DictWriter(sys.stdout, fieldnames=list(columns), lineterminator="\n")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: api.spreadsheet_cell(_csv_value(v)) for k, v in row.items()})
    else:
        _table(records, rows, columns, title, symbols, vertical)


def _csv_value(value: Any) -> Any:
    """A CSV cell: a list or mapping (a dataset's authors) as JSON text, never as Python
    writes it."""
    if isinstance(value, dict | list | tuple):
        return json.dumps(to_json_value(value), ensure_ascii=False)
    return _clean(value)


def _is_value(value: Any) -> bool:
    """A number or a time: a cell that is never cut (text may be)."""
    if isinstance(value, bool):
        return False
    return isinstance(value, int | float) or hasattr(value, "isoformat") or hasattr(value, "item")


#: The narrowest a text column is squeezed to before a table is shown record by record.
TEXT_MIN_WIDTH = 6


def _table(
    records: Sequence[dict[str, Any]],
    rows: list[dict[str, Any]],
    columns: Sequence[str],
    title: str | None,
    symbols: bool,
    vertical: bool = False,
) -> None:
    """A Rich table in which no number is cut: each column holding numbers (or times) is
    at least as wide as its widest value, text columns give way (wrapped or shortened with
    "…"); when even that does not fit the terminal, each record is shown vertically
    (name and value on a line)."""
    digits = 3 if symbols else 4
    cells = [
        [
            _cell(record, SHORT_WORDS.get(v, v) if symbols and isinstance(v, str) else v, c,
                  digits)
            for v, c in ((row[c], c) for c in columns)
        ]
        for record, row in zip(records, rows, strict=True)
    ]  # fmt: skip
    valued = [any(_is_value(row[c]) for row in rows) for c in columns]
    heads = [header(column, symbols) for column in columns]
    # a header wraps at spaces (not in symbols mode); a value column is never narrower
    # than its widest value nor its header's longest word
    words = [len(h) if symbols else max(len(w) for w in h.split() or [""]) for h in heads]
    natural = [max([len(r[i]) for r in cells] + [words[i]]) for i in range(len(columns))]
    out = console()
    overhead = len(columns) - 1 if symbols else 3 * len(columns) + 1
    fixed = sum(w for w, is_value in zip(natural, valued, strict=True) if is_value)
    texts = [w for w, is_value in zip(natural, valued, strict=True) if not is_value]
    room = out.width - overhead - fixed
    if vertical or room < sum(min(w, TEXT_MIN_WIDTH) for w in texts):
        _vertical(cells, columns, title, symbols)
        return
    cap = max(texts, default=0)
    while cap > TEXT_MIN_WIDTH and sum(min(w, cap) for w in texts) > room:
        cap -= 1  # text columns give way evenly, the widest first
    narrow = {"box": rich_box.SIMPLE_HEAD, "padding": (0, 0), "show_edge": False}
    narrow = narrow if symbols else {}
    table = rich_table.Table(
        title=rich_text.Text(title) if title else None, title_justify="left", **narrow
    )
    for head, is_value, width in zip(heads, valued, natural, strict=True):
        if is_value:  # never cut: as wide as its widest value
            table.add_column(head, width=width, overflow="fold", no_wrap=symbols)
        else:
            table.add_column(head, width=min(width, cap), overflow="ellipsis", no_wrap=symbols)
    for row in cells:
        table.add_row(*(rich_text.Text(c) for c in row))
    out.print(table)


def _vertical(
    cells: list[list[str]], columns: Sequence[str], title: str | None, symbols: bool
) -> None:
    """Each record as a two-column table (name, value): nothing is cut at any width."""
    out = console()
    if title:
        out.print(rich_text.Text(title, style="bold"))
    for row in cells:
        table = rich_table.Table(show_header=False, box=rich_box.SIMPLE, padding=(0, 1))
        table.add_column("property", style="bold", overflow="fold", ratio=1)
        table.add_column("value", overflow="fold", ratio=2)
        for column, text in zip(columns, row, strict=True):
            table.add_row(rich_text.Text(header(column, symbols)), rich_text.Text(text))
        out.print(table)


def _cell(record: dict[str, Any], value: Any, column: str, digits: int) -> str:
    """A table cell: the value, with its standard uncertainty where the record has one
    (``u_<column>``: "46 ± 5 nm")."""
    u = record.get(f"u_{column}")
    if isinstance(u, int | float) and not isinstance(u, bool) and u > 0:
        return api.display_uncertain(value, u, column)
    return api.display(value, column, digits)


def emit_records(
    views: Sequence[tuple[str, Sequence[tuple[str, str]]]], title: str | None = None
) -> None:
    """Records for people, each shown vertically (its heading, then one line per
    quantity: name and what it reads), so that no value is ever cut whatever the
    terminal's width: long words wrap at spaces, never inside a number."""
    out = console()
    if title:
        out.print(rich_text.Text(title, style="bold"))
    for heading, lines in views:
        table = rich_table.Table(
            title=rich_text.Text(heading), title_justify="left", show_header=False,
            box=rich_box.SIMPLE, padding=(0, 1),
        )  # fmt: skip
        table.add_column("quantity", style="bold", overflow="fold", ratio=1)
        table.add_column("value", overflow="fold", ratio=2)
        for name, text in lines:
            table.add_row(rich_text.Text(name), rich_text.Text(text))
        out.print(table)


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
