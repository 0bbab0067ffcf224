"""README is short and gets a newcomer to their own data fast; its links lead somewhere.

Its examples are run, their output compared, by tests/test_docs_examples.py; here: its
length, where "import your own CSV" comes, the install commands CI runs (.ci/run installs
"exactly as README says"), and that every function and file it names exists.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
README = (REPO / "README.md").read_text(encoding="utf-8")


def test_readme_is_at_most_200_lines() -> None:
    assert len(README.splitlines()) <= 200


def test_a_newcomer_reaches_importing_their_own_csv_within_60_lines() -> None:
    lines = README.splitlines()
    first = next(i for i, line in enumerate(lines) if "granudb collisions import" in line)
    assert first < 60, first
    assert "own CSV" in "\n".join(lines[:first])
    assert "--columns" in lines[first]  # with its own headers


@pytest.mark.parametrize(
    ("command", "in_ci"),
    [
        (
            "python3 -m venv .venv && . .venv/bin/activate && pip install . && "
            "granudb materials list",
            ["pip install --quiet .\n", "granudb materials list"],
        ),
        ("pip install '.[test]' && pytest", ["pip install --quiet '.[test]'", "\npytest\n"]),
        (
            "pip install '.[docs]' && mkdocs build --strict",
            ["pip install --quiet '.[docs]'", "mkdocs build --strict"],
        ),
    ],
)
def test_the_commands_ci_runs_are_the_readme_s(command: str, in_ci: list[str]) -> None:
    assert command in README
    ci = (REPO / ".ci" / "run").read_text(encoding="utf-8")
    for words in in_ci:
        assert words in ci


def test_readme_says_sudo_may_be_absent_for_root() -> None:
    assert re.search(r"`sudo`[^.]*unless you are root", README)


def test_every_relative_link_of_readme_exists() -> None:
    links = re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", README)
    local = [link for link in links if not re.match(r"[a-z]+://", link)]
    assert local
    missing = [link for link in local if not (REPO / link).exists()]
    assert missing == []


@pytest.mark.parametrize(
    "name", ["connect", "pair", "import_collisions", "collisions", "fit_walton", "report"]
)
def test_the_python_section_names_real_functions(name: str) -> None:
    import granudb

    assert callable(getattr(granudb, name))
    assert f"granudb.{name}(" in README
