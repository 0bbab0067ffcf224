"""``granudb dataset remove|remove-runs|edit|release|new-version``: a dataset's lifecycle.

Registered on ``granudb.cli.dataset.app``. Each command parses, calls the public API
(``granudb.api.datasets``) and prints; removals first say what they delete and ask (or
need ``--yes``).
"""

from __future__ import annotations

from typing import Annotated

import typer

from granudb.cli.common import DbOption
from granudb.cli.confirm import YesOption
from granudb.cli.dataset import app

Ref = Annotated[str, typer.Argument(help="Dataset as NAME@VERSION (or NAME: the newest).")]


@app.command()
def remove(
    ref: Annotated[str, typer.Argument(help="NAME@VERSION, or NAME for every version of it.")],
    yes: YesOption = False,
    db: DbOption = None,
) -> None:
    """Delete a dataset version (or all versions) with its runs; asks first.

    A released version cannot be removed until a newer version is released.
    """
    from granudb.api import datasets
    from granudb.cli.common import open_db
    from granudb.cli.confirm import confirm
    from granudb.cli.output import say

    name, version = datasets.split_ref(ref)
    database = open_db(db)
    losses = datasets.removal_plan(name, version, db=database)
    confirm(f"dataset remove {ref}", losses, yes)
    for line in datasets.remove_dataset(name, version, db=database, accepted=losses):
        say(f"removed {line}")


@app.command("remove-runs")
def remove_runs(
    ref: Ref,
    runs: Annotated[list[str], typer.Argument(help="Run labels to delete.")],
    yes: YesOption = False,
    db: DbOption = None,
) -> None:
    """Delete some runs of a draft dataset version (by run label); asks first."""
    from granudb.api import datasets
    from granudb.cli.common import open_db
    from granudb.cli.confirm import confirm
    from granudb.cli.output import say

    name, version = datasets.split_ref(ref)
    database = open_db(db)
    losses = datasets.run_removal_plan(name, runs, version, db=database)
    confirm(f"dataset remove-runs {ref}", losses, yes)
    count = datasets.remove_runs(name, runs, version, db=database, accepted=losses)
    say(f"removed {count} runs from dataset {ref}")


@app.command()
def edit(
    ref: Ref,
    title: Annotated[str | None, typer.Option("--title")] = None,
    description: Annotated[str | None, typer.Option("--description")] = None,
    license: Annotated[
        str | None, typer.Option("--license", help='SPDX id, e.g. "CC-BY-4.0".')
    ] = None,
    doi: Annotated[str | None, typer.Option("--doi", help="The dataset's own DOI.")] = None,
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
        typer.Option(
            "--authors-json",
            help='JSON list of {"given_names","family_names","orcid","affiliation"}.',
        ),
    ] = None,
    keyword: Annotated[
        list[str] | None, typer.Option("--keyword", help="Repeat for each; replaces the list.")
    ] = None,
    db: DbOption = None,
) -> None:
    """Edit a draft version's metadata; prints each change (old → new). "" clears a field."""
    from granudb.api import datasets
    from granudb.cli.output import say

    values: dict[str, object] = {
        k: v
        for k, v in {
            "title": title,
            "description": description,
            "license": license,
            "doi": doi,
            "keywords": keyword,
        }.items()
        if v is not None
    }
    if author:
        values["authors"] = [datasets.parse_author(a) for a in author]
    if authors_json is not None:
        values["authors"] = _authors(authors_json)
    if not values:
        raise datasets.ValidationError("edit", ref, "needs at least one option to change")
    name, version = datasets.split_ref(ref)
    diffs = datasets.edit_dataset(name, version, db=db, **values)
    for field, old, new in diffs:
        say(f"{field}: {old!r} → {new!r}")
    if not diffs:
        say(f"dataset {ref}: unchanged")


def _authors(text: str) -> list:
    import json

    from granudb.errors import ValidationError

    try:
        people = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ValidationError("--authors-json", text[:40], f"is not JSON ({exc.msg})") from None
    if not isinstance(people, list):
        raise ValidationError("--authors-json", text[:40], "must be a JSON list of people")
    return people


@app.command()
def release(ref: Ref, db: DbOption = None) -> None:
    """Release a draft version: from now on it cannot change (a new version holds changes)."""
    from granudb.api import datasets
    from granudb.cli.output import say

    name, version = datasets.split_ref(ref)
    superseded = datasets.release_dataset(name, version, db=db)
    say(f"released dataset {ref}")
    for old in superseded:
        say(f"superseded {name}@{old}")


@app.command("new-version")
def new_version(
    ref: Ref,
    version: Annotated[str, typer.Option("--version", help="The new version, e.g. 1.1.0.")],
    db: DbOption = None,
) -> None:
    """Copy a version (metadata and runs) as a new draft version to change."""
    from granudb.api import datasets
    from granudb.cli.output import say

    name, old = datasets.split_ref(ref)
    content_hash = datasets.new_version(name, old, version, db=db)
    say(f"created draft {name}@{version} from {ref} (content hash {content_hash[:16]}…)")
