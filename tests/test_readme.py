"""Every command of README's "A short tour" runs as written, on a fresh database.

Docs that cannot drift (after sqlite-utils' habit): the tour is parsed from README.md, each
``granudb`` line is split like a shell would and run in-process, in order, against one
database in a temporary folder that holds a copy of ``examples/``.
"""

from __future__ import annotations

import re
import shlex
import shutil
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent


def tour_commands() -> list[list[str]]:
    text = (REPO / "README.md").read_text(encoding="utf-8")
    section = text.split("## A short tour", 1)[1]
    block = re.search(r"```sh\n(.*?)```", section, re.S)
    assert block, "README's tour has no sh block"
    commands = []
    for line in block.group(1).splitlines():
        line = line.strip()
        if not line.startswith("granudb "):
            continue
        words = shlex.split(line, comments=True)
        commands.append(words[1:])
    return commands


def _takes_db(words: list[str]) -> bool:
    from typer.main import get_command

    from granudb.cli.main import app, click

    command = get_command(app)
    for word in words:
        if not hasattr(command, "get_command"):  # a group
            break
        sub = command.get_command(click.Context(command), word)  # loads lazy commands too
        if sub is None:
            break
        command = sub
    return any("--db" in param.opts for param in command.params)


def test_the_tour_lists_every_command_group() -> None:
    groups = {words[0] for words in tour_commands()}
    from typer.main import get_command

    from granudb.cli.main import app, click

    root = get_command(app)
    assert set(root.list_commands(click.Context(root))) - {"datasette-metadata"} <= groups


def test_every_tour_command_runs(cli, db: str, tmp_path: Path, monkeypatch) -> None:
    shutil.copytree(REPO / "examples", tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    for words in tour_commands():
        if words[:2] == ["dem", "verify"] and not shutil.which("liggghts"):
            continue  # needs a DEM code; its own tests say when one is missing
        result = cli(*words, db=db if _takes_db(words) else None)
        assert result.exit_code == 0, f"granudb {' '.join(words)}\n{result.stderr}"


@pytest.mark.parametrize("name", ["connect", "pair", "collisions", "fit_walton", "derive"])
def test_the_python_section_names_real_functions(name: str) -> None:
    import granudb

    assert callable(getattr(granudb, name))
    assert f"granudb.{name}(" in (REPO / "README.md").read_text(encoding="utf-8")
