"""``granudb reference list|show|reproduce``: the published collision data shipped with
granudb, and how granudb's fits and models reproduce each dataset."""

from __future__ import annotations

from typing import Annotated

import typer

from granudb import api
from granudb.cli.options import Format, FormatOption, wraps
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
