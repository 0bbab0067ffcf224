"""What several commands share, defined once: the database and format options, ``--yes``,
the collision filters, and the marker that names the API function a command wraps.

Option names are the Python API's parameter names with dashes (``--angle-range`` ↔
``angle_range``), so an error from the library names the option; a command passes what
the user typed to the API unchanged (text with units, ``None`` for "not given") and the
API's one gate checks it and applies the defaults, the same for Python and the command
line.
"""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable
from enum import StrEnum
from typing import Annotated, Any

import typer

from granudb import api


class Format(StrEnum):
    table = "table"
    json = "json"
    csv = "csv"


DbOption = Annotated[
    str | None,
    typer.Option(
        "--db",
        envvar=api.DATABASE_ENV_VAR,
        show_envvar=True,
        help="Database: a SQLAlchemy URL or a SQLite file path "
        "(default: granudb.sqlite in the user data directory).",
    ),
]
FormatOption = Annotated[
    Format, typer.Option("--format", "-f", help="table for people; json or csv (SI) for scripts.")
]
YesOption = Annotated[bool, typer.Option("--yes", "-y", help="Do it without asking (for scripts).")]


def text_option(help: str) -> Any:
    """The metadata of an optional option taking text (a number with its unit, a name),
    ``None`` when not given; its flag is the parameter's name with dashes, as Typer makes it
    (``wall_diameter`` → ``--wall-diameter``). Use:
    ``diameter: Annotated[str | None, text_option('Particle diameter, "12.7 mm".')] = None``
    (the type is written out so a type checker reads it)."""
    return typer.Option(help=help)


def text(help: str) -> Any:
    """``Annotated[str | None, text_option(help)]`` as a value, for the option tables that
    build a command's signature (``text_options``, ``keyword_option``); in a ``def`` write
    the ``Annotated`` out (``text_option``)."""
    return Annotated[str | None, text_option(help)]


#: The collision filters (``granudb.api.COLLISION_FILTERS``) as options, with their help.
FILTER_HELP: dict[str, str] = {
    "dataset": "Dataset name (NAME or NAME@VERSION).",
    "version": "Dataset version (default: newest).",
    "particle": "Particle material.",
    "wall": "Wall (or target sphere) material.",
    "fluid": "A fluid name, or 'dry'.",
    "min_normal_stokes": "Lowest normal Stokes number St_n.",
    "max_normal_stokes": "Highest normal Stokes number St_n.",
    "angle_range": "Incidence angles ζ_in of the contact point's path, '10..40 deg'.",
    "regime": "Maw's tangential regime: stick, slip_then_stick, gross_slip.",
    "roughness_exceeds_gap": "Only runs whose roughness exceeds (or, with --no-, is within) "
    "the EHD gap h_m.",
    "rebound_expected": "Only runs with St_n above (or, with --no-, not above) St_c.",
    "critical_stokes": "No rebound below this normal Stokes number (default 10).",
}
_FLAGS = ("roughness_exceeds_gap", "rebound_expected")
CriticalStokes = text(FILTER_HELP["critical_stokes"])


def option_name(parameter: str) -> str:
    """The option of an API parameter: ``angle_range`` → ``--angle-range``."""
    return "--" + parameter.replace("_", "-")


def _filter_parameter(name: str) -> inspect.Parameter:
    if name in _FLAGS:
        flag = option_name(name)
        info = typer.Option(f"{flag}/--no-{flag[2:]}", help=FILTER_HELP[name], show_default=False)
        annotation: Any = Annotated[bool | None, info]
    else:
        annotation = Annotated[str | None, typer.Option(option_name(name), help=FILTER_HELP[name])]
    return keyword_option(name, annotation)


def keyword_option(name: str, annotation: Any) -> inspect.Parameter:
    """An optional keyword option ``name`` (``None`` when not given) for ``option_group``."""
    return inspect.Parameter(
        name, inspect.Parameter.KEYWORD_ONLY, default=None, annotation=annotation
    )


def option_group(
    keyword: str, parameters: list[inspect.Parameter]
) -> Callable[[Callable[..., None]], Callable[..., None]]:
    """Give a command the options ``parameters``, written once for every command that
    takes them; they reach it as one keyword ``keyword``, a dict of the ones given (the
    API applies its defaults to the others, the same for Python and the command line)."""

    def decorate(command: Callable[..., None]) -> Callable[..., None]:
        signature = inspect.signature(command, eval_str=True)
        own = [p for p in signature.parameters.values() if p.name != keyword]
        taken = {p.name for p in own}
        added = [p for p in parameters if p.name not in taken]

        @functools.wraps(command)
        def grouped(**given: Any) -> None:
            group = {p.name: given.pop(p.name) for p in added}
            command(**given, **{keyword: {k: v for k, v in group.items() if v is not None}})

        # mypy has no attribute __signature__ on a function; inspect.signature reads it
        grouped.__signature__ = signature.replace(parameters=[*own, *added])  # type: ignore[attr-defined]
        grouped.__annotations__ = {}
        return grouped

    return decorate


def text_options(
    keyword: str, helps: dict[str, Any]
) -> Callable[[Callable[..., None]], Callable[..., None]]:
    """``option_group`` of the options ``helps`` names, each text (``text``) with its help,
    or of the annotation given in place of a help (a flag, a renamed option)."""
    return option_group(
        keyword,
        [keyword_option(n, text(h) if isinstance(h, str) else h) for n, h in helps.items()],
    )


def collision_filters(command: Callable[..., None]) -> Callable[..., None]:
    """Give a command that selects runs every collision filter option, as the one keyword
    ``filters``. Built when a command module uses it, so ``granudb --help`` does not load
    the filters' vocabulary."""
    parameters = [_filter_parameter(n) for n in api.COLLISION_FILTERS]
    return option_group("filters", parameters)(command)


def wraps(function: str) -> Callable[[Callable[..., None]], Callable[..., None]]:
    """Mark a command as the face of the public function ``granudb.<function>``
    (tests/test_one_door.py walks the commands and checks every one names one)."""

    def mark(command: Callable[..., None]) -> Callable[..., None]:
        # a mark on the function object, read by tests/test_one_door.py
        command.api_function = function  # type: ignore[attr-defined]
        return command

    return mark
