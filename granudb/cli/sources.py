"""``granudb sources list|show|history|add|update``: where every published number comes
from, and how a user adds or corrects a source (each correction kept as a revision)."""

from __future__ import annotations

from typing import Annotated, Any

import typer

from granudb import api
from granudb.cli.options import (
    DbOption,
    Format,
    FormatOption,
    keyword_option,
    option_group,
    wraps,
)
from granudb.cli.output import emit, emit_one, say

app = typer.Typer(
    help="Sources (papers, correlations) cited by stored values.", no_args_is_help=True
)


@app.command("list")
@wraps("sources")
def list_(db: DbOption = None, fmt: FormatOption = Format.table) -> None:
    """List every source."""
    records = api.sources(db=db, as_frame=False)
    columns = api.SOURCE_NARROW if fmt is Format.table else api.SOURCE_COLUMNS
    emit(records, columns, fmt, title="Sources")


SourceKey = Annotated[str, typer.Argument(help="Source key, e.g. joseph-hunt-2004.")]


@app.command()
@wraps("source")
def show(key: SourceKey, db: DbOption = None, fmt: FormatOption = Format.table) -> None:
    """Show a source, what cites it, and the published values it holds."""
    record = api.source(key, db=db)
    usage = record.pop("cited_by")
    published = record.pop("published_values")
    if fmt is Format.json:
        emit_one(record, fmt, extra={"cited_by": usage, "published_values": published})
    elif fmt is Format.csv:
        emit(published, list(published[0]) if published else ["label"], fmt)
    else:
        cited = {f"cited by {k}": v for k, v in usage.items()}
        emit_one({**record, **cited}, fmt, title=f"Source {key}")
        if published:
            emit(published, api.PUBLISHED_NARROW, fmt, title="Published values")


@app.command()
@wraps("source_history")
def history(key: SourceKey, db: DbOption = None, fmt: FormatOption = Format.table) -> None:
    """Show a source as it is and as it was before each change (when and why)."""
    records = api.source_history(key, db=db)
    columns = ["revision", "kept_at", "reason", "changes", *api.SOURCE_FIELDS]
    emit(records, columns if fmt is Format.table else list(records[0]), fmt,
         title=f"Source {key}: history", vertical=True)  # fmt: skip


def _field(column: str, *aliases: str) -> Any:
    """A text option of one source field, its help the field's term (the vocabulary)."""
    term = api.term(column)
    help_text = f"{term.title}: {term.description}"
    return Annotated[str | None, typer.Option(f"--{column}", *aliases, help=help_text)]


#: One option per field a user sets (``--notes`` also as ``--note``), for both commands.
source_fields = option_group(
    "fields",
    [
        keyword_option(c, _field(c, *(["--note"] if c == "notes" else [])))
        for c in api.SOURCE_FIELDS
    ],
)


@app.command()
@wraps("add_source")
@source_fields
def add(key: SourceKey, fields: Any = None, db: DbOption = None) -> None:
    """Add a source; --citation is required."""
    say(f"added source {api.add_source(key, db=db, **fields)['key']}")


@app.command()
@wraps("update_source")
@source_fields
def update(
    key: SourceKey,
    fields: Any = None,
    reason: Annotated[
        str | None, typer.Option(help="Why it changed (kept with the old revision).")
    ] = None,
    db: DbOption = None,
) -> None:
    """Change some fields of a source ("" clears one); the old is kept as a revision."""
    say(str(api.update_source(key, reason=reason, db=db, **fields)))
