"""``granudb sources list|show``: where every published number comes from."""

from __future__ import annotations

from typing import Annotated

import typer

from granudb.cli.common import DbOption, Format, FormatOption, open_db

app = typer.Typer(
    help="Sources (papers, correlations) cited by stored values.", no_args_is_help=True
)


@app.command("list")
def list_(db: DbOption = None, fmt: FormatOption = Format.table) -> None:
    """List every source."""
    from granudb.api.catalog import source_records
    from granudb.cli.output import emit
    from granudb.db.catalog_rows import SOURCE_COLUMNS

    records = source_records(db=open_db(db))
    emit(
        records,
        ["key", "year", "kind", "citation", "doi"] if fmt is Format.table else SOURCE_COLUMNS,
        fmt,
        title="Sources",
    )


@app.command()
def show(
    key: Annotated[str, typer.Argument(help="Source key, e.g. joseph-hunt-2004.")],
    db: DbOption = None,
    fmt: FormatOption = Format.table,
) -> None:
    """Show a source, what cites it, and the published values it holds."""
    from granudb.cli.output import emit, emit_one
    from granudb.db import sources

    database = open_db(db)
    with database.session() as session:
        source = sources.get_source(session, key)
        record = sources.source_record(source)
        usage = sources.source_usage(session, source)
        published = sources.published_records(session, source)
    if fmt is Format.json:
        emit_one(record, fmt, extra={"cited_by": usage, "published_values": published})
    elif fmt is Format.csv:
        emit(published, list(published[0]) if published else ["label"], fmt)
    else:
        emit_one(
            {**record, **{f"cited by {k}": v for k, v in usage.items()}}, fmt, title=f"Source {key}"
        )
        if published:
            emit(
                published,
                ["source_locator", "label", "quantity", "value_as_printed"],
                fmt,
                title="Published values",
            )
