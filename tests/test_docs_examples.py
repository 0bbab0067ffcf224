"""Every example of README.md and the manual runs, and prints what the page shows.

After sqlite-utils' cog habit: ``tools/docs_examples.py`` runs each ``console`` block's
commands (and each ``sh`` and ``python`` block) on a documented fixture — a fresh folder
with ``examples/`` and a freshly seeded database — and compares what they print with the
page. A change of output fails here until the page changes with it:
``python -m tools.docs_examples --update`` rewrites the pages (and docs/cli.md).
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
if str(REPO) not in sys.path:
    sys.path.insert(0, str(REPO))

from tools import cli_reference, docs_examples  # noqa: E402

PAGES = docs_examples.pages()


@pytest.mark.parametrize("page", PAGES, ids=[str(p.relative_to(REPO)) for p in PAGES])
def test_every_example_prints_what_the_page_shows(page: Path) -> None:
    result = docs_examples.check_page(page)
    assert not result.differences and not result.errors, (
        docs_examples.report([result]) + "\n(python -m tools.docs_examples --update rewrites it)"
    )


def test_the_manual_runs_examples_on_every_guide_page() -> None:
    for page in PAGES:
        if page.parent.name == "guide" or page.name in {"README.md", "getting-started.md"}:
            runnable = docs_examples.blocks(page.read_text(encoding="utf-8"))
            assert runnable, f"{page.relative_to(REPO)} has no example that runs"


def test_one_changed_output_string_fails(tmp_path: Path) -> None:
    """The comparison has teeth: a page whose shown output differs by one word fails."""
    text = (REPO / "README.md").read_text(encoding="utf-8")
    assert "imported 4 runs into dataset my-lab" in text
    page = tmp_path / "README.md"
    page.write_text(text.replace("imported 4 runs", "imported four runs"), encoding="utf-8")
    result = docs_examples.check_page(page)
    assert [d.command.split()[:3] for d in result.differences] == [
        ["granudb", "collisions", "import"]
    ]
    assert "imported 4 runs" in result.differences[0].printed


def test_the_command_line_reference_is_generated_from_the_code() -> None:
    shown = (REPO / "docs" / "cli.md").read_text(encoding="utf-8")
    assert shown == cli_reference.render(), "python -m tools.docs_examples --update"


def test_the_reference_names_every_command_and_option_of_the_app() -> None:
    from typer.main import get_command

    from granudb.cli.main import app, click

    shown = (REPO / "docs" / "cli.md").read_text(encoding="utf-8")
    root = get_command(app)
    for name in root.list_commands(click.Context(root)):
        assert f"## granudb {name}" in shown, name
    leaves = cli_reference.walk()
    assert len(leaves) >= 45
    for path, command in leaves:
        section = shown.split(f"## granudb {' '.join(path)} {{#", 1)[1].split("\n## ", 1)[0]
        for param in command.params:
            if param.name == "help":
                continue
            if param.param_type_name == "argument":
                assert f"`{param.name.upper()}`" in section, (path, param.name)
            else:
                assert f"`{param.opts[0]}" in section, (path, param.opts)
            if getattr(param, "envvar", None):
                assert f"`{param.envvar}`" in section, (path, param.name)


def test_the_tour_uses_every_command_group() -> None:
    from typer.main import get_command

    from granudb.cli.main import app, click

    tour = (REPO / "docs" / "tour.md").read_text(encoding="utf-8")
    root = get_command(app)
    for name in root.list_commands(click.Context(root)):
        if name != "datasette-metadata":  # its own guide: guide/datasette.md
            assert f"granudb {name} " in tour, name


def test_every_public_function_has_parameters_on_the_api_page() -> None:
    """numpydoc Parameters for every public function: its own, or written from its
    command's option help (docs/generated_docstrings.py), naming every parameter."""
    import importlib
    import inspect

    from granudb import api

    sys.path.insert(0, str(REPO / "docs"))
    try:
        from generated_docstrings import documented
    finally:
        sys.path.remove(str(REPO / "docs"))
    generic = []
    for name, module in api.NAMES.items():
        function = getattr(importlib.import_module(f"granudb.api.{module}"), name, None)
        if not inspect.isfunction(function):
            continue
        parameters = inspect.signature(function).parameters
        if not parameters:
            continue
        text = documented(name, function)
        section = text.split("Parameters\n----------", 1)[1].split("\n\n", 1)[0]
        for parameter in parameters.values():
            shown = ("**" if parameter.kind is parameter.VAR_KEYWORD else "") + parameter.name
            assert f"\n{shown} : " in "\n" + section or f"\n{shown}\n" in "\n" + section, (
                name,
                parameter.name,
            )
        if "As the command's" in section:
            generic.append(name)
    assert len(generic) <= 10, generic  # nearly every parameter has its own words
