"""``granudb dataset list|show|diff|export|validate|import``: share curated datasets as
Frictionless Data Packages."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from granudb.cli.common import DbOption, Format, FormatOption, open_db

app = typer.Typer(
    help="Curated collision datasets: catalogue, export and import as Frictionless Data Packages.",
    no_args_is_help=True,
)

Name = Annotated[str, typer.Argument(help="Dataset name.")]
Version = Annotated[
    str | None, typer.Option("--version", help="Dataset version (default: newest).")
]


FullHash = Annotated[
    bool, typer.Option("--full-hash", help="Show the whole 64-digit content hash in a table.")
]
#: Hex digits of a content hash a table shows (as git shows commits); JSON and CSV keep all.
SHORT_HASH = 12


@app.command("list")
def list_(
    full_hash: FullHash = False, db: DbOption = None, fmt: FormatOption = Format.table
) -> None:
    """Every dataset with its version, content hash, run count and source."""
    from granudb.cli.output import emit
    from granudb.db import dataset_catalog

    database = open_db(db)
    with database.session() as session:
        records = dataset_catalog.dataset_records(session)
    if fmt is Format.table and not full_hash:
        for record in records:
            digest = record.get("content_hash")
            record["content_hash"] = f"{digest[:SHORT_HASH]}…" if digest else digest
    emit(records, dataset_catalog.DATASET_COLUMNS, fmt, title="Datasets")


@app.command()
def show(
    name: Name, version: Version = None, db: DbOption = None, fmt: FormatOption = Format.table
) -> None:
    """One dataset: metadata and run counts by particle, wall and fluid."""
    from granudb.cli.output import emit, emit_one
    from granudb.db import dataset_catalog, datasets

    database = open_db(db)
    with database.session() as session:
        dataset = datasets.get_dataset(session, name, version)
        record = dataset_catalog.dataset_record(session, dataset)
        groups = dataset_catalog.group_counts(session, dataset)
    if fmt is Format.json:
        emit_one(record, fmt, extra={"groups": groups})
    elif fmt is Format.csv:
        emit(groups, ["particle", "wall", "fluid", "runs"], fmt)
    else:
        emit_one(record, fmt, title=f"Dataset {name}")
        emit(groups, ["particle", "wall", "fluid", "runs"], fmt, title="Runs by pair and fluid")


@app.command()
def diff(
    a: Annotated[str, typer.Argument(help="Dataset A as NAME or NAME@VERSION.")],
    b: Annotated[str, typer.Argument(help="Dataset B as NAME or NAME@VERSION.")],
    db: DbOption = None,
    fmt: FormatOption = Format.table,
) -> None:
    """Runs added, removed and changed from A to B (matched by run label)."""
    from granudb.cli.output import emit, say
    from granudb.db import dataset_catalog, datasets

    database = open_db(db)
    with database.session() as session:
        first = datasets.get_dataset(session, *_split(a))
        second = datasets.get_dataset(session, *_split(b))
        changes = dataset_catalog.diff_datasets(session, first, second)
    if fmt is Format.table:
        counts = {
            k: sum(1 for c in changes if c["change"] == k) for k in ("added", "removed", "changed")
        }
        say(
            f"{a} → {b}: {counts['added']} added, {counts['removed']} removed, "
            f"{counts['changed']} changed"
        )
    emit(changes, ["change", "run", "fields"], fmt, title="Differences")


def _split(text: str) -> tuple[str, str | None]:
    name, _, version = text.partition("@")
    return name, version or None


@app.command()
def export(
    name: Name,
    output: Annotated[
        Path, typer.Option("--output", "-o", help="An empty folder, or a file ending in .zip.")
    ],
    version: Version = None,
    db: DbOption = None,
) -> None:
    """Write the dataset as a Data Package (datapackage.json, CSVs, README, CITATION.cff)."""
    from granudb.cli.output import say
    from granudb.db.package_queries import export_data
    from granudb.io.package_export import build_package, write_package

    database = open_db(db)
    with database.session() as session:
        data = export_data(session, name, version)
    write_package(build_package(data), output)
    say(
        f"exported dataset {data.dataset['name']} {data.dataset['version']} to {output} "
        f"(content hash {data.content_hash[:16]}…)"
    )


@app.command()
def validate(
    path: Annotated[Path, typer.Argument(help="Package folder, datapackage.json or .zip.")],
) -> None:
    """Check a package without importing it; lists every problem found."""
    from granudb.cli.output import note, say
    from granudb.io.package_import import PackageError, validate_package

    result = validate_package(path)
    if result.problems:
        for problem in result.problems:
            note(f"problem: {problem}")
        raise PackageError(result.problems)
    rows = len(result.tables["collisions"])
    say(
        f"valid: {path} holds {rows} collisions, "
        f"{len(result.tables['materials'])} materials, {len(result.tables['fluids'])} fluids"
    )


@app.command("import")
def import_(
    path: Annotated[Path, typer.Argument(help="Package folder, datapackage.json or .zip.")],
    as_name: Annotated[
        str | None, typer.Option("--as", help="Import under this dataset name.")
    ] = None,
    rename_conflicts: Annotated[
        bool,
        typer.Option(
            "--rename-conflicts",
            help="Import a material or fluid whose name exists with other values under a new "
            "name ('NAME (package)') instead of refusing.",
        ),
    ] = False,
    db: DbOption = None,
) -> None:
    """Validate and import a package in one transaction (all or nothing)."""
    from granudb.cli.output import say
    from granudb.io.package_import import import_package

    database = open_db(db)
    result = import_package(database, path, as_name=as_name, rename_conflicts=rename_conflicts)
    for line in result.renamed:
        say(f"renamed {line}")
    say(
        f"imported dataset {result.dataset} {result.version}: {result.rows} collisions "
        f"(content hash {result.content_hash[:16]}…); reused {len(result.reused)}, added "
        f"{len(result.added)} materials/fluids/sources"
    )
    if result.declared_hash and result.declared_hash != result.content_hash:
        say(
            f"content hash: the package's {result.declared_hash[:16]}… was verified; stored "
            f"as {result.content_hash[:16]}… because names were matched or renamed "
            f"({', '.join(result.renamed + result.reused) or 'case differences'})"
        )


from granudb.cli import dataset_lifecycle  # noqa: E402, F401 - registers remove, edit, release, …
