"""``granudb dataset list|show|diff|export|validate|import|edit|release|new-version|remove|
remove-runs``: curated datasets, shared as Frictionless Data Packages."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from granudb import api
from granudb.cli import collisions
from granudb.cli.confirm import asker
from granudb.cli.options import DbOption, Format, FormatOption, YesOption, text_option, wraps
from granudb.cli.output import emit, emit_one, note, say

app = typer.Typer(
    help="Curated collision datasets: catalogue, export and import as Frictionless Data Packages.",
    no_args_is_help=True,
)

Ref = Annotated[str, typer.Argument(help="Dataset as NAME@VERSION (or NAME: the newest).")]
PackagePath = Annotated[Path, typer.Argument(help="Package folder, datapackage.json or .zip.")]
FullHash = Annotated[
    bool, typer.Option("--full-hash", help="Show the whole 64-digit content hash in a table.")
]
#: Hex digits of a content hash a table shows (as git shows commits); JSON and CSV keep all.
SHORT_HASH = 12


@app.command("list")
@wraps("datasets")
def list_(
    full_hash: FullHash = False, db: DbOption = None, fmt: FormatOption = Format.table
) -> None:
    """Every dataset with its version, content hash, run count and source."""
    records = api.datasets(db=db, as_frame=False)
    if fmt is Format.table and not full_hash:
        for record in records:
            digest = record.get("content_hash")
            record["content_hash"] = f"{digest[:SHORT_HASH]}…" if digest else digest
    if fmt is Format.json:
        emit(records, [*api.DATASET_COLUMNS, "pinned_changes"], fmt)
        return
    emit(records, api.DATASET_COLUMNS, fmt, title="Datasets")
    for record in records:
        for line in record["pinned_changes"]:
            note(f"{record['name']}@{record['version']} {line}")


@app.command()
@wraps("dataset")
def show(name: Ref, db: DbOption = None, fmt: FormatOption = Format.table) -> None:
    """One dataset: metadata and run counts by particle, wall and fluid."""
    record = api.dataset(name, db=db)
    groups = record.pop("groups")
    pinned = record.pop("pinned_changes")
    if fmt is Format.json:
        emit_one(record, fmt, extra={"pinned_changes": pinned, "groups": groups})
        return
    if fmt is Format.csv:
        emit(groups, api.DATASET_GROUP_COLUMNS, fmt)
    else:
        emit_one(record, fmt, title=f"Dataset {record['name']}")
        emit(groups, api.DATASET_GROUP_COLUMNS, fmt, title="Runs by pair and fluid")
    for line in pinned:
        note(line)


@app.command()
@wraps("diff_datasets")
def diff(
    a: Annotated[str, typer.Argument(help="Dataset A as NAME or NAME@VERSION.")],
    b: Annotated[
        str | None,
        typer.Argument(help="Dataset B as NAME or NAME@VERSION (none: today's catalogue)."),
    ] = None,
    db: DbOption = None,
    fmt: FormatOption = Format.table,
) -> None:
    """Runs added, removed and changed from A to B (matched by run label), and the
    catalogue values they read differently; without B, what A pins that today's
    catalogue has changed."""
    changes = api.diff_datasets(a, b, db=db)
    if fmt is Format.table:
        kinds = ("added", "removed", "changed", "catalogue", "pinned")
        counts = {k: sum(c["change"] == k for c in changes) for k in kinds}
        if b is None:
            say(f"{a} → today's catalogue: {counts['pinned']} pinned values differ")
        else:
            say(
                f"{a} → {b}: {counts['added']} added, {counts['removed']} removed, "
                f"{counts['changed']} changed; {counts['catalogue']} catalogue values differ"
            )
    emit(changes, api.DIFF_COLUMNS, fmt, title="Differences")


@app.command()
@wraps("export_dataset")
def export(
    dataset: Ref,
    output: Annotated[
        Path, typer.Option("--output", "-o", help="An empty folder, or a file ending in .zip.")
    ],
    db: DbOption = None,
) -> None:
    """Write the dataset as a Data Package (datapackage.json, CSVs, README, CITATION.cff)."""
    done = api.export_dataset(dataset, output, db=db)
    say(
        f"exported dataset {done.dataset} {done.version} to {done.path} "
        f"(content hash {done.content_hash[:16]}…)"
    )
    for line in done.pinned_changes:
        note(line)


@app.command()
@wraps("validate_dataset")
def validate(path: PackagePath) -> None:
    """Check a package without importing it; lists every problem found."""
    result = api.validate_dataset(path)
    if result.problems:
        for problem in result.shown:
            note(f"problem: {problem}")
        raise api.PackageError(result.problems)
    say(
        f"valid: {path} holds {result.counts['collisions']} collisions, "
        f"{result.counts['materials']} materials, {result.counts['fluids']} fluids"
    )


@app.command("import")
@wraps("import_dataset")
def import_(
    path: PackagePath,
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
    result = api.import_dataset(path, as_name=as_name, rename_conflicts=rename_conflicts, db=db)
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


@app.command()
@wraps("remove_dataset")
def remove(
    dataset: Annotated[str, typer.Argument(help="NAME@VERSION, or NAME for every version of it.")],
    yes: YesOption = False,
    db: DbOption = None,
) -> None:
    """Delete a dataset version (or all versions) with its runs; asks first.

    A released version cannot be removed until a newer version is released.
    """
    for line in api.remove_dataset(dataset, confirm=asker(yes), db=db):
        say(f"removed {line}")


#: The same command as ``collisions remove``, kept under its older name.
app.command("remove-runs", hidden=True)(collisions.remove)


@app.command()
@wraps("edit_dataset")
def edit(
    dataset: Ref,
    title: Annotated[str | None, typer.Option("--title")] = None,
    description: Annotated[str | None, typer.Option("--description")] = None,
    license: Annotated[str | None, text_option('SPDX id, e.g. "CC-BY-4.0".')] = None,
    doi: Annotated[str | None, text_option("The dataset's own DOI.")] = None,
    author: Annotated[
        list[str] | None,
        typer.Option(
            "--author",
            help="'Family, Given; orcid=0000-0002-1825-0097; affiliation=Lab' (repeat for "
            "each; replaces the list).",
        ),
    ] = None,
    authors_json: Annotated[
        str | None,
        text_option('JSON list of {"given_names","family_names","orcid","affiliation"}.'),
    ] = None,
    keyword: Annotated[
        list[str] | None, typer.Option("--keyword", help="Repeat for each; replaces the list.")
    ] = None,
    db: DbOption = None,
) -> None:
    """Edit a draft version's metadata; prints each change (old → new). "" clears a field."""
    diffs = api.edit_dataset(
        dataset,
        title=title,
        description=description,
        license=license,
        doi=doi,
        authors=authors_json if authors_json is not None else author or None,
        keywords=keyword or None,
        db=db,
    )
    for field, old, new in diffs:
        say(f"{field}: {old!r} → {new!r}")
    if not diffs:
        say(f"dataset {dataset}: unchanged")


@app.command()
@wraps("release_dataset")
def release(dataset: Ref, db: DbOption = None) -> None:
    """Release a draft version: from now on it cannot change (a new version holds changes)."""
    superseded = api.release_dataset(dataset, db=db)
    say(f"released dataset {dataset}")
    name, _ = api.dataset_ref(dataset)
    for old in superseded:
        say(f"superseded {name}@{old}")


@app.command("new-version")
@wraps("new_dataset_version")
def new_version(
    dataset: Ref,
    version: Annotated[str | None, text_option("The new version, e.g. 1.1.0.")] = None,
    db: DbOption = None,
) -> None:
    """Copy a version (metadata and runs) as a new draft version to change."""
    content_hash = api.new_dataset_version(dataset, version, db=db)
    name, _ = api.dataset_ref(dataset)
    say(f"created draft {name}@{version} from {dataset} (content hash {content_hash[:16]}…)")
