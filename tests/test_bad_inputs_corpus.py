"""The corpus in tests/bad_inputs/: every entry point refuses bad input in one line, with
a non-zero exit, no traceback, and the database exactly as it was."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from support import dump_hash

CORPUS = Path(__file__).resolve().parent / "bad_inputs"
CLI_CASES = json.loads((CORPUS / "cli_cases.json").read_text(encoding="utf-8"))
CSV_CASES = json.loads((CORPUS / "csv" / "expected.json").read_text(encoding="utf-8"))


EXAMPLES = CORPUS.parent.parent / "examples"


def _refused(result, expected: str, exit_code: int = 1) -> None:
    """One line on stderr, the exit code (1 for a refusal, 2 for a usage error), never an
    internal error or a traceback."""
    assert result.exit_code == exit_code, (result.stdout, result.stderr)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("Error: ") and expected in lines[0], lines[0]
    assert "internal error" not in lines[0]
    assert "Traceback" not in result.stdout + result.stderr


def _argv(args: list[str]) -> list[str]:
    return [a.replace("{examples}", str(EXAMPLES)) for a in args]


@pytest.mark.parametrize(
    "case", CLI_CASES, ids=[f"{i}-{' '.join(c['argv'][:3])}" for i, c in enumerate(CLI_CASES)]
)
def test_cli_values(cli, db: str, tmp_path: Path, monkeypatch, case: dict) -> None:
    monkeypatch.chdir(tmp_path)
    for step in case.get("setup", []):  # state the case needs (a dataset, a released one)
        done = cli(*_argv(step), db=db)
        assert done.exit_code == 0, (step, done.stderr)
    before = dump_hash(db)
    _refused(cli(*_argv(case["argv"]), db=db), case["expect"], case.get("exit", 1))
    assert dump_hash(db) == before


@pytest.mark.parametrize("name", sorted(CSV_CASES))
def test_csv_files(cli, db: str, name: str) -> None:
    before = dump_hash(db)
    result = cli("collisions", "import", str(CORPUS / "csv" / name), "--dataset", "bad", db=db)
    _refused(result, CSV_CASES[name])
    assert dump_hash(db) == before


def test_the_corpus_is_large_enough() -> None:
    assert len(CLI_CASES) + len(CSV_CASES) >= 40
    # issue 14: at least 40 more command-line cases (usage, files, consent, lifecycle)
    assert len(CLI_CASES) >= 30 + 40
    assert sum(c.get("exit") == 2 for c in CLI_CASES) >= 15


@pytest.mark.parametrize(
    "name",
    [
        "'; DROP TABLE materials; --",
        "<img src=x onerror=alert(1)>",
        "**bold** _x_ `code` | a",
        "Robert'); DELETE FROM collisions;--",
        "ümlaut ß 材料",
    ],
)
def test_hostile_strings_are_stored_and_shown_verbatim(cli, db: str, name: str) -> None:
    added = cli(
        "materials",
        "add",
        name,
        "--density",
        "1 g/cm^3",
        "--youngs-modulus",
        "1 GPa",
        "--poisson-ratio",
        "0.3",
        "--roughness",
        "1 nm",
        "--description",
        name,
        db=db,
    )
    assert added.exit_code == 0, added.stderr
    shown = json.loads(cli("materials", "show", name, "--format", "json", db=db).stdout)
    assert shown["name"] == name and shown["description"] == name
    assert {"glass", "steel", "Zerodur"} <= {
        m["name"] for m in json.loads(cli("materials", "list", "--format", "json", db=db).stdout)
    }
