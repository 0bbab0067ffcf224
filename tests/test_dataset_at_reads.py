"""``--dataset NAME@VERSION`` reads that version's runs in every command that reads runs
(issue 35): ``collisions list``, ``fit``, ``report`` and ``dem export`` promised it in
their help and refused it. A released version and a newer draft with fewer runs tell the
versions apart: ``lab@2024`` answers as ``--dataset lab --version 2024`` does and unlike
``lab`` (the newest)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

import granudb
from granudb.errors import NotFoundError

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "collisions_example.csv"
DRY = [f"steel-dry-{i}" for i in (1, 2, 3)]


@pytest.fixture
def two_versions(opened) -> str:
    """lab@2024 released with the 12 example runs; lab@2025 a draft without three dry runs."""
    granudb.import_collisions(EXAMPLE, dataset="lab", version="2024", db=opened)
    granudb.release_dataset("lab", db=opened)
    granudb.new_dataset_version("lab@2024", "2025", db=opened)
    assert granudb.remove_collisions("lab@2025", DRY, db=opened) == 3
    return opened.url


def _runs(cli, db: str, *dataset: str) -> list[str]:
    result = cli("collisions", "list", "--format", "json", "--dataset", *dataset, db=db)
    assert result.exit_code == 0, result.stderr
    return sorted(row["run"] for row in json.loads(result.stdout))


def test_collisions_list_reads_the_named_version(cli, two_versions: str) -> None:
    released = _runs(cli, two_versions, "lab@2024")
    assert len(released) == 12 and set(DRY) <= set(released)
    assert released == _runs(cli, two_versions, "lab", "--version", "2024")
    assert _runs(cli, two_versions, "lab@2025") == _runs(cli, two_versions, "lab")
    assert len(_runs(cli, two_versions, "lab")) == 9


def test_fit_reads_the_named_version(cli, two_versions: str) -> None:
    def fit(*dataset: str) -> str:
        result = cli("fit", "walton", "--format", "json", "--dataset", *dataset, db=two_versions)
        assert result.exit_code == 0, result.stderr
        return result.stdout

    assert fit("lab@2024") == fit("lab", "--version", "2024")
    assert fit("lab@2024") != fit("lab")  # the newest lacks three dry runs
    assert fit("lab@2025") == fit("lab")


def test_report_reads_the_named_version(cli, two_versions: str, tmp_path: Path) -> None:
    def report(name: str, *dataset: str) -> str:
        out = tmp_path / f"{name}.md"
        result = cli(
            "report", "--format", "md", "-o", str(out), "--dataset", *dataset, db=two_versions
        )
        assert result.exit_code == 0, result.stderr
        text = out.read_text(encoding="utf-8").replace(f"{name}_figures", "FIGURES")
        # the report quotes the command that wrote it and when: the lines that may differ
        text = re.sub(r"\d{4}-\d\d-\d\dT[\d:]+\+00:00", "WHEN", text)
        return "\n".join(line for line in text.splitlines() if "--format md" not in line)

    at = report("at", "lab@2024")
    assert "lab" in at and "2024" in at
    assert at == report("flag", "lab", "--version", "2024")
    assert at != report("newest", "lab")


def test_dem_export_reads_the_named_version(cli, two_versions: str) -> None:
    def deck(dataset: str) -> str:
        result = cli(
            "dem", "export", "--code", "liggghts", "--particle", "steel", "--wall", "Zerodur",
            "--diameter", "12.7 mm", "--velocity", "0.3 m/s", "--values", "dataset",
            "--dataset", dataset, db=two_versions,
        )  # fmt: skip
        assert result.exit_code == 0, result.stderr
        return result.stdout

    at, newest = deck("lab@2024"), deck("lab")
    assert "lab@2024" in at
    assert at != newest

    def unwrapped(deck: str) -> str:  # comments are wrapped at a width: compare the words
        return re.sub(r"\s*\n#?\s*", " ", deck)

    assert unwrapped(deck("lab@2025").replace("lab@2025", "lab")) == unwrapped(newest)


@pytest.mark.parametrize(
    "command",
    [
        ("collisions", "list"),
        ("fit", "walton"),
        ("report", "--format", "md"),
        ("dem", "export", "--code", "yade", "--particle", "steel", "--wall", "Zerodur",
         "--diameter", "12.7 mm", "--velocity", "0.3 m/s", "--values", "dataset"),
    ],
)  # fmt: skip
def test_a_version_that_does_not_exist_is_one_line(
    cli, two_versions: str, command, tmp_path: Path, monkeypatch
) -> None:
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    result = cli(*command, "--dataset", "lab@1999", db=two_versions)
    assert result.exit_code == 1
    assert result.stderr.strip() == (
        "Error: dataset: 'lab' has no version '1999' (versions: 2024, 2025)"
    )
    assert list(work.iterdir()) == []  # no report, no figures


def test_python_api_takes_name_at_version_too(two_versions: str) -> None:
    frame = granudb.collisions(dataset="lab@2024", db=two_versions)
    assert len(frame) == 12
    with pytest.raises(NotFoundError, match="has no version '1999'"):
        granudb.fit_walton(dataset="lab@1999", db=two_versions)
