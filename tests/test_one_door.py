"""One door: every command is the face of one public function, named after it.

The command line parses, calls one function of ``granudb.api`` and prints; docs/api.md's
table "command → function" lists them all. These tests walk the Typer app, so a command
added without its function, its row there, or with an option the function does not
take, fails here.
"""

from __future__ import annotations

import ast
import inspect
import re
from pathlib import Path

import pytest
import typer

import granudb
from granudb import api
from granudb.cli.main import COMMANDS, load_command

TABLE_PAGE = Path(__file__).resolve().parents[1] / "docs" / "api.md"  # the table's home
API_DIR = Path(api.__file__).parent

#: Command options that shape only the printing (or the prompt), not the result.
FACE_OPTIONS = {"fmt", "yes", "full_hash", "print_path", "columns", "wide"}
#: Options whose API parameter has another name (the option reads better at a terminal).
RENAMED = {
    ("dataset edit", "author"): "authors",
    ("dataset edit", "authors_json"): "authors",
    ("dataset edit", "keyword"): "keywords",
    ("dem export", "particle"): "particles",
    ("dem export", "wall"): "walls",
    ("dem verify", "particle"): "particles",
    ("dem verify", "wall"): "walls",
    ("report", "fmt"): "format",
}


def _leaves(command, path: tuple[str, ...]):
    children = getattr(command, "commands", None)
    if children is None:
        yield " ".join(path), command
        return
    for name, child in children.items():
        yield from _leaves(child, (*path, name))


def commands() -> dict[str, object]:
    found = {}
    for name in COMMANDS:
        found.update(dict(_leaves(load_command(name), (name,))))
    root = typer.main.get_group(__import__("granudb.cli.main", fromlist=["app"]).app)
    for name, command in root.commands.items():
        if name not in COMMANDS:
            found[name] = command
    return found


ALL = commands()


def readme_table() -> dict[str, str]:
    """The "command → function" table of docs/api.md: ``materials add`` → ``add_material``."""
    rows = {}
    for line in TABLE_PAGE.read_text(encoding="utf-8").splitlines():
        match = re.match(r"^\| `granudb ([^`]+)` \| `granudb\.(\w+)\(", line)
        if match:
            rows[match.group(1)] = match.group(2)
    return rows


def test_every_command_is_the_face_of_a_public_function() -> None:
    assert len(ALL) >= 40
    for path, command in ALL.items():
        function = getattr(command.callback, "api_function", None)
        assert function, f"granudb {path} names no API function (cli.options.wraps)"
        assert function in granudb.__all__, f"granudb {path}: {function} is not public"
        assert callable(getattr(granudb, function)), path
        assert getattr(granudb, function).__doc__, f"{function} has no docstring"


def test_readme_lists_every_command_with_its_function() -> None:
    table = readme_table()
    shown = {path: getattr(c.callback, "api_function", None) for path, c in ALL.items()}
    hidden = {path for path, c in ALL.items() if getattr(c, "hidden", False)}
    assert {p: f for p, f in shown.items() if p not in hidden} == table


def test_each_option_is_a_parameter_of_the_function() -> None:
    for path, command in ALL.items():
        function = getattr(granudb, command.callback.api_function)
        parameters = inspect.signature(function).parameters
        takes_filters = any(p.kind is p.VAR_KEYWORD for p in parameters.values())
        for param in command.params:
            name = RENAMED.get((path, param.name), param.name)
            if name in FACE_OPTIONS or name == "print_path":
                continue
            if takes_filters and name in api.COLLISION_FILTERS:
                continue
            assert name in parameters, f"granudb {path}: {param.name} is not a parameter"


def test_catalogue_options_are_the_functions_keywords() -> None:
    """``materials add`` and friends are generated from the specification, and so are the
    Python functions' keywords (their ``**values``, shown in their signature): both must
    take the same values."""
    for kind, plural in (("material", "materials"), ("fluid", "fluids")):
        for verb in ("add", "update"):
            command = ALL[f"{plural} {verb}"]
            options = {p.name for p in command.params} - {"name", "db"}
            function = getattr(granudb, f"{verb}_{kind}")
            keywords = {
                p.name
                for p in inspect.signature(function).parameters.values()
                if p.kind is p.KEYWORD_ONLY
            } - {"db"}
            assert options == keywords, (plural, verb)


def test_the_command_line_calls_the_function_it_names() -> None:
    for path, command in ALL.items():
        name = command.callback.api_function
        source = inspect.getsource(inspect.unwrap(command.callback))
        if "getattr(api, " in source:  # generated from the catalogue's specification
            continue
        assert f"api.{name}(" in source, f"granudb {path} does not call granudb.{name}"


def test_no_module_of_the_api_hides_a_public_name() -> None:
    """A submodule named like a function would replace it on the package once imported."""
    modules = {p.stem for p in API_DIR.glob("*.py")}
    assert not modules & set(api.__all__)


def test_unknown_names_are_attribute_errors() -> None:
    with pytest.raises(AttributeError):
        granudb.no_such_function  # noqa: B018


def _imports_inside_functions(path: Path) -> list[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            for inner in ast.walk(node):
                if isinstance(inner, ast.Import | ast.ImportFrom):
                    found.append(f"{path.name}:{inner.lineno}")
    return found


def test_the_api_and_the_command_line_import_at_the_top() -> None:
    """Laziness comes from the API's table of names, the command table and
    ``granudb.lazy``; no function imports a module."""
    cli_dir = API_DIR.parent / "cli"
    found = []
    for folder in (API_DIR, cli_dir):
        for path in folder.glob("*.py"):
            found += _imports_inside_functions(path)
    assert found == []
