"""``granudb reference list|show|reproduce|dem|import``: the published collision data shipped with
granudb, and how granudb's fits and models reproduce each dataset."""

from __future__ import annotations

from typing import Annotated

import typer

from granudb import api
from granudb.cli.options import DbOption, Format, FormatOption, wraps
from granudb.cli.output import emit, say, to_json

app = typer.Typer(
    help="Published collision data shipped as datasets, and their reproduction by granudb.",
    no_args_is_help=True,
)

ReferenceName = Annotated[
    str, typer.Argument(help="Reference dataset, e.g. kharaz-gorham-salman-2001.")
]


@app.command("list")
@wraps("reference_list")
def list_(fmt: FormatOption = Format.table) -> None:
    """List the reference datasets (name, version, values, title, licences, folder)."""
    columns = api.REFERENCE_NARROW if fmt is Format.table else api.REFERENCE_COLUMNS
    emit(api.reference_list(), columns, fmt, title="Reference datasets")


@app.command()
@wraps("reference_show")
def show(name: ReferenceName, fmt: FormatOption = Format.table) -> None:
    """Show one reference dataset: every reported value with its provenance."""
    shown = api.reference_show(name)
    if fmt is Format.json:
        say(to_json(shown))
        return
    columns = api.REFERENCE_VALUE_COLUMNS if fmt is Format.table else list(shown["values"][0])
    if fmt is Format.table:
        say(f"{shown['name']} {shown['version']}: {shown['title']}")
        for source in shown["sources"]:
            say(f"source: {source}")
        for licence in shown["licences"]:
            say(f"licence: {licence}")
        say(f"package: {shown['path']}")
    emit(shown["values"], columns, fmt)


@app.command()
@wraps("reference_reproduce")
def reproduce(name: ReferenceName, fmt: FormatOption = Format.table) -> None:
    """Run granudb's fits and predictions against a reference dataset: each check's
    reported value, what granudb computes, the residual and the verdict."""
    result = api.reference_reproduce(name)
    if fmt is Format.json:
        say(to_json(result))
        return
    if fmt is Format.csv:
        emit(result["checks"], api.REFERENCE_CHECK_COLUMNS, fmt)
        return
    say(f"{result['name']} {result['version']}: {result['title']}")
    for line in result["summary"]:
        say(line)
    kinds = list(dict.fromkeys(c["check"] for c in result["checks"]))
    for kind in kinds:
        rows = [c for c in result["checks"] if c["check"] == kind]
        emit(rows, api.REFERENCE_CHECK_NARROW, fmt, title=kind)


@app.command()
@wraps("reference_dem")
def dem(
    name: ReferenceName,
    codes: Annotated[
        list[str] | None,
        typer.Option("--code", help="liggghts, lammps or yade (repeat; default: all three)."),
    ] = None,
    points: Annotated[
        list[str] | None,
        typer.Option("--point", help="A figure point to run, e.g. et-05 (repeat; default all)."),
    ] = None,
    fmt: FormatOption = Format.table,
) -> None:
    """Run the dataset's DEM deck in LIGGGHTS, LAMMPS and Yade and compare each code's
    output with the experiment per point (verdict within 2 u_c of the data's u)."""
    result = api.reference_dem(name, codes=codes, points=points)
    if fmt is Format.json:
        say(to_json(result))
        return
    if fmt is Format.table:
        inputs = ", ".join(f"{k} = {v:g}" for k, v in result["inputs"].items())
        say(f"{result['name']}: the deck's inputs {inputs}")
    columns = api.REFERENCE_DEM_NARROW if fmt is Format.table else api.REFERENCE_DEM_COLUMNS
    emit(result["rows"], columns, fmt, title="Each code against the experiment")


@app.command("import")
@wraps("reference_import")
def import_(
    name: Annotated[
        str,
        typer.Argument(
            help="Reference dataset (kharaz-gorham-salman-2001) or the folder of your own "
            "package of reported values."
        ),
    ],
    collection: Annotated[
        str | None, typer.Option("--as", help="Collection to store the runs in (default: NAME).")
    ] = None,
    materials: Annotated[
        list[str] | None,
        typer.Option(
            "--material",
            help="PACKAGE=DATABASE: a particle or wall name of the package and the material "
            "of your database it is (repeat), e.g. 'aluminium oxide=alumina'.",
        ),
    ] = None,
    db: DbOption = None,
) -> None:
    """Import a reference dataset's runs as reported runs, with their provenance; then
    `granudb reported list|fit --collection NAME`."""
    mapping = {}
    for given in materials or []:
        package, sep, ours = given.partition("=")
        if not sep:
            mapping[given] = ""  # refused by the function in one line
        else:
            mapping[package.strip()] = ours.strip()
    done = api.reference_import(name, collection=collection, materials=mapping, db=db)
    say(
        f"stored {done['runs']} runs of {done['name']} {done['version']} in collection "
        f"{done['collection']!r}"
    )
    if done["left_in_package"]:
        say(f"left in the package (not a run's column): {', '.join(done['left_in_package'])}")
