"""``--db`` and ``--format`` before the command mean what they mean after it."""

from __future__ import annotations

import json

import pytest

from granudb.cli.main import options_last


@pytest.mark.parametrize(
    ("given", "parsed"),
    [
        (["--db", "x", "dataset", "list"], ["dataset", "list", "--db", "x"]),
        (["--db=x", "-f", "json", "pair", "a", "b"], ["pair", "a", "b", "--db=x", "-f", "json"]),
        (["materials", "list", "--db", "x"], ["materials", "list", "--db", "x"]),
        (["--version"], ["--version"]),
        (["--db", "x", "--help"], ["--help", "--db", "x"]),
        (["--db", "x", "report", "--", "-odd"], ["report", "--db", "x", "--", "-odd"]),
    ],
)
def test_options_before_the_command_go_after_it(given: list[str], parsed: list[str]) -> None:
    assert options_last(given) == parsed


def test_the_same_listing_either_way(cli, db: str) -> None:
    from typer.testing import CliRunner

    from granudb.cli.main import app

    before = CliRunner().invoke(app, ["--db", db, "--format", "json", "materials", "list"])
    after = cli("materials", "list", "--format", "json", db=db)
    assert before.exit_code == 0, before.output
    assert json.loads(before.stdout) == json.loads(after.stdout)
    assert any(m["name"] == "steel" for m in json.loads(before.stdout))


def test_a_command_without_the_option_still_says_so(cli, tmp_path) -> None:
    from typer.testing import CliRunner

    from granudb.cli.main import app

    result = CliRunner().invoke(app, ["--db", str(tmp_path / "g.sqlite"), "dataset", "validate",
                                      str(tmp_path)])  # fmt: skip
    assert result.exit_code == 2 and "No such option: --db" in result.output
