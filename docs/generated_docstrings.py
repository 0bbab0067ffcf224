"""Griffe extension for the documentation site: render the docstrings granudb generates.

- The public relations of ``granudb.physics`` get their numpydoc ``Parameters`` section
  from one table (``granudb/physics/arguments.py``) when they are defined, so the source
  text lacks it: each ``granudb.physics`` function gets the docstring Python itself has
  (``inspect.getdoc``), the one ``help()`` and the doctests see.
- Every public function of ``granudb`` is the face of one command, taking the command's
  options under the same names (tests/test_one_door.py). Where its docstring has no
  ``Parameters`` section, one is written from the command's own option help (with its units
  and examples) — the words the command line shows, so the two cannot drift — plus the
  parameters every function shares (``db``, ``as_frame``, ``confirm``, the collision
  filters).

Loaded by ``mkdocs.yml`` (handler option ``extensions``); ``api_parameters`` is what
tests/test_docs_examples.py checks.
"""

from __future__ import annotations

import functools
import inspect
from typing import Any

import griffe

SHARED = {
    "db": "Database: a SQLite file path, a SQLAlchemy URL, or what ``granudb.connect`` "
    "returns. Default: ``GRANUDB_DATABASE_URL``, else ``granudb.sqlite`` in the user data "
    "directory.",
    "as_frame": "True (default): a pandas DataFrame in SI units, the units in "
    '``.attrs["units"]``; False: a list of records (dicts).',
    "confirm": "The consent the command line asks for; from Python the call itself is the consent.",
    "version": "The dataset's version (``NAME@VERSION`` on the command line); default: its latest.",
    "particles": "Particle materials, by name (``--particle``, repeatable).",
    "walls": "Wall materials, by name (``--wall``, repeatable).",
    "frame": "A table (pandas DataFrame or a mapping of columns) of the inputs ``derive`` "
    "takes, in SI under their machine names (Physics functions).",
    "url": "A SQLite file path or a SQLAlchemy URL; default: ``GRANUDB_DATABASE_URL``, else "
    "the user data directory's ``granudb.sqlite``.",
    "folder": "Seed folder to load; default: the shipped ``seed_data``.",
    "progress": "Show a progress bar (the command line does on a terminal).",
    "format": "html (one self-contained file) or md (Markdown, figures beside it).",
    "title": "Title.",
    "description": "Description.",
    "authors": "Authors, e.g. 'Ada Lovelace; Alan Turing'.",
    "keywords": "Keywords, comma-separated.",
    "filters": "The collision filters, the same for every function that selects runs "
    "(``granudb.api.COLLISION_FILTERS``): dataset, version, particle, wall, fluid ('dry' for "
    "dry runs), min_normal_stokes, max_normal_stokes, angle_range, regime, "
    "roughness_exceeds_gap, rebound_expected, critical_stokes.",
}


@functools.cache
def _options() -> dict[str, dict[str, str]]:
    """API function name → {parameter name: the help of its command-line option}."""
    import sys
    from pathlib import Path

    repo = str(Path(__file__).resolve().parent.parent)
    if repo not in sys.path:
        sys.path.insert(0, repo)
    from tools.cli_reference import walk

    found: dict[str, dict[str, str]] = {}
    for _path, command in walk():
        function = getattr(command.callback, "api_function", None)
        if not function:
            continue
        helps = found.setdefault(function, {})
        for param in command.params:
            text = " ".join((getattr(param, "help", None) or "").split())
            if param.name and text and param.name not in helps:
                helps[param.name] = text
    return found


def _type(parameter: inspect.Parameter) -> str:
    """numpydoc's type text: the annotation, or what an unannotated default says."""
    if parameter.annotation is not inspect.Parameter.empty:
        kind = str(parameter.annotation).replace("'", "")
    elif parameter.default is None or parameter.default is inspect.Parameter.empty:
        kind = "str or float"  # a quantity: an SI number or a string with its unit
    else:
        kind = type(parameter.default).__name__
    return kind if parameter.default is inspect.Parameter.empty else f"{kind}, optional"


def api_parameters(name: str, function: Any) -> str:
    """The numpydoc ``Parameters`` section of public function ``name``."""
    helps = _options().get(name, {})
    lines = ["Parameters", "----------"]
    for parameter in inspect.signature(function).parameters.values():
        if parameter.kind is inspect.Parameter.VAR_KEYWORD:
            lines += [f"**{parameter.name}", "    " + SHARED.get(parameter.name, "Options.")]
            continue
        text = helps.get(parameter.name) or SHARED.get(parameter.name)
        if parameter.name in {"db", "as_frame", "confirm"}:
            text = SHARED[parameter.name]
        if text is None:
            text = f"As the command's ``--{parameter.name.replace('_', '-')}``."
        lines += [f"{parameter.name} : {_type(parameter)}", "    " + text]
    return "\n".join(lines)


def documented(name: str, function: Any) -> str:
    """The docstring of public function ``name``, with a ``Parameters`` section."""
    text = inspect.getdoc(function) or ""
    if "\nParameters\n----------" in "\n" + text or not inspect.signature(function).parameters:
        return text
    head, sep, tail = text.partition("\nExamples\n--------")
    section = api_parameters(name, function)
    return f"{head.rstrip()}\n\n{section}\n" + (f"{sep}{tail}" if sep else "")


_KINDS = {
    inspect.Parameter.POSITIONAL_ONLY: griffe.ParameterKind.positional_only,
    inspect.Parameter.POSITIONAL_OR_KEYWORD: griffe.ParameterKind.positional_or_keyword,
    inspect.Parameter.VAR_POSITIONAL: griffe.ParameterKind.var_positional,
    inspect.Parameter.KEYWORD_ONLY: griffe.ParameterKind.keyword_only,
    inspect.Parameter.VAR_KEYWORD: griffe.ParameterKind.var_keyword,
}


def _runtime_signature(func: griffe.Function, function: Any) -> None:
    """Give the page the signature Python reports (a decorator may spell out ``**fields``
    as the named options the function takes), so its Parameters match it."""
    parameters = []
    for parameter in inspect.signature(function).parameters.values():
        annotation = parameter.annotation
        default = parameter.default
        parameters.append(
            griffe.Parameter(
                parameter.name,
                annotation=None if annotation is inspect.Parameter.empty else str(annotation),
                kind=_KINDS[parameter.kind],
                default=None if default is inspect.Parameter.empty else repr(default),
            )
        )
    func.parameters = griffe.Parameters(*parameters)


class GeneratedDocstrings(griffe.Extension):
    """Replace a function's static docstring by the one granudb generates."""

    def on_function_instance(self, *, func: griffe.Function, **kwargs: Any) -> None:
        if func.docstring is None:
            return
        if func.path.startswith("granudb.physics."):
            text = inspect.getdoc(griffe.dynamic_import(func.path))
        elif func.path.startswith("granudb.api.") and not func.name.startswith("_"):
            function = griffe.dynamic_import(func.path)
            text = documented(func.name, function)
            _runtime_signature(func, function)
        else:
            return
        if text and text != func.docstring.value:
            func.docstring = griffe.Docstring(
                text, lineno=func.docstring.lineno, parent=func, parser=func.docstring.parser
            )
