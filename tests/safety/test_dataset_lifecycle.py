"""A dataset's lifecycle: remove a dataset or runs (asking first), edit metadata with
people and ORCID iDs, release (immutable), supersede, new version (issue 14: there was no
way to remove a dataset or a run, and metadata could never be edited)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from support import dump_hash

import granudb
from granudb.errors import ConfirmationNeeded, ConflictError, NotFoundError, ValidationError

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"


@pytest.fixture
def ex(cli, db: str) -> str:
    result = cli("collisions", "import", str(EXAMPLE), "--dataset", "ex", db=db)
    assert result.exit_code == 0, result.stderr
    return db


def _runs(cli, db: str, ref: str = "ex") -> list[str]:
    name, _, version = ref.partition("@")
    args = ["collisions", "list", "--dataset", name, "--format", "json"]
    if version:
        args += ["--version", version]
    return [r["run"] for r in json.loads(cli(*args, db=db).stdout)]


def _one_line_refusal(result, expected: str) -> None:
    assert result.exit_code == 1, (result.stdout, result.stderr)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and expected in lines[0], result.stderr
    assert "internal error" not in lines[0]


def test_dataset_remove_asks_then_removes_everything_of_it(cli, ex: str) -> None:
    before = dump_hash(ex)
    _one_line_refusal(cli("dataset", "remove", "ex", db=ex), "with 12 runs and 1 import records")
    assert dump_hash(ex) == before
    done = cli("dataset", "remove", "ex@1.0.0", "--yes", db=ex)
    assert done.exit_code == 0, done.stderr
    assert "removed dataset ex@1.0.0 (id " in done.stdout
    assert "name 'ex', version '1.0.0', draft) with 12 runs" in done.stdout
    listed = json.loads(cli("dataset", "list", "--format", "json", db=ex).stdout)
    assert listed == []
    # the same file can be imported again: its import record went with the dataset
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "ex", db=ex).exit_code == 0


def test_remove_runs_asks_and_refreshes_the_content_hash(cli, ex: str) -> None:
    runs = _runs(cli, ex)
    before = dump_hash(ex)
    _one_line_refusal(cli("dataset", "remove-runs", "ex", runs[0], db=ex), "--yes")
    _one_line_refusal(cli("dataset", "remove-runs", "ex", "nope", "--yes", db=ex), "'nope'")
    assert dump_hash(ex) == before
    old_hash = json.loads(cli("dataset", "show", "ex", "--format", "json", db=ex).stdout)
    done = cli("dataset", "remove-runs", "ex", runs[0], runs[1], "--yes", db=ex)
    assert done.exit_code == 0, done.stderr
    assert _runs(cli, ex) == runs[2:]
    shown = json.loads(cli("dataset", "show", "ex", "--format", "json", db=ex).stdout)
    assert shown["runs"] == len(runs) - 2
    assert shown["content_hash"] != old_hash["content_hash"]


def test_removal_asks_on_a_terminal(ex: str, monkeypatch) -> None:
    from typer.testing import CliRunner

    from granudb.cli import confirm
    from granudb.cli.main import app

    monkeypatch.setattr(confirm, "interactive", lambda: True)
    runner = CliRunner()
    before = dump_hash(ex)
    no = runner.invoke(app, ["dataset", "remove", "ex", "--db", ex], input="n\n")
    assert no.exit_code == 1 and "not confirmed" in no.stderr
    assert dump_hash(ex) == before
    yes = runner.invoke(app, ["dataset", "remove", "ex", "--db", ex], input="y\n")
    assert yes.exit_code == 0 and "removed dataset ex@1.0.0" in yes.stdout


def test_edit_metadata_with_people_and_orcid(cli, ex: str) -> None:
    result = cli(
        "dataset",
        "edit",
        "ex@1.0.0",
        "--title",
        "Oblique collisions",
        "--license",
        "CC-BY-4.0",
        "--description",
        "Two lines\nof text",
        "--author",
        "Joseph, G. G.; orcid=https://orcid.org/0000-0002-1825-0097; affiliation=Caltech",
        "--author",
        "Hunt, M. L.",
        "--keyword",
        "immersed collisions",
        "--doi",
        "https://doi.org/10.5281/zenodo.42",
        db=ex,
    )
    assert result.exit_code == 0, result.stderr
    shown = json.loads(cli("dataset", "show", "ex", "--format", "json", db=ex).stdout)
    assert shown["title"] == "Oblique collisions" and shown["license"] == "CC-BY-4.0"
    assert shown["doi"] == "10.5281/zenodo.42"
    assert shown["keywords"] == ["immersed collisions"]
    assert shown["authors"][0] == {
        "given_names": "G. G.",
        "family_names": "Joseph",
        "orcid": "0000-0002-1825-0097",
        "affiliation": "Caltech",
    }
    assert shown["authors"][1]["orcid"] is None


@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (["--author", "Hunt; orcid=0000-0002-1825-0098"], "wrong check digit"),
        (["--author", "Hunt; orcid=1234"], "is not an ORCID iD"),
        (["--author", "Hunt; email=x@y"], "must be 'Family, Given"),
        (["--authors-json", '[{"given_names": "M."}]'], "family_names: (missing) is required"),
        (["--authors-json", "{"], "is not JSON"),
        (["--title", "a\u202eb"], "U+202E"),
        (["--doi", "zenodo 42"], "is not a DOI"),
        (["--keyword", " padded "], "must not begin or end with spaces"),
        ([], "needs at least one option"),
    ],
)
def test_bad_metadata_is_refused_in_one_line(cli, ex: str, args: list[str], expected: str) -> None:
    before = dump_hash(ex)
    _one_line_refusal(cli("dataset", "edit", "ex@1.0.0", *args, db=ex), expected)
    assert dump_hash(ex) == before


def test_released_is_immutable_and_a_new_version_holds_changes(cli, ex: str) -> None:
    runs = _runs(cli, ex)
    assert cli("dataset", "release", "ex@1.0.0", db=ex).exit_code == 0
    before = dump_hash(ex)
    for args, expected in [
        (["collisions", "import", str(EXAMPLE), "--dataset", "ex"], "is released"),
        (["dataset", "remove-runs", "ex@1.0.0", runs[0], "--yes"], "is released"),
        (["dataset", "edit", "ex@1.0.0", "--title", "x"], "is released"),
        (["dataset", "remove", "ex@1.0.0", "--yes"], "cannot be removed"),
        (["dataset", "release", "ex@1.0.0"], "is released"),
    ]:
        _one_line_refusal(cli(*args, db=ex), expected)
    assert dump_hash(ex) == before
    # a DOI may be set once on a released version (minted when it is published)
    assert cli("dataset", "edit", "ex@1.0.0", "--doi", "10.5281/zenodo.1", db=ex).exit_code == 0
    _one_line_refusal(
        cli("dataset", "edit", "ex@1.0.0", "--doi", "10.5281/zenodo.2", db=ex), "is released"
    )

    made = cli("dataset", "new-version", "ex@1.0.0", "--version", "1.1.0", db=ex)
    assert made.exit_code == 0, made.stderr
    assert _runs(cli, ex, "ex@1.1.0") == runs
    done = cli("dataset", "remove-runs", "ex@1.1.0", runs[0], "--yes", db=ex)
    assert done.exit_code == 0, done.stderr
    assert cli("dataset", "release", "ex@1.1.0", db=ex).exit_code == 0
    states = {
        d["version"]: d["state"]
        for d in json.loads(cli("dataset", "list", "--format", "json", db=ex).stdout)
    }
    assert states == {"1.0.0": "superseded", "1.1.0": "released"}
    assert _runs(cli, ex, "ex@1.0.0") == runs  # the released version kept every run
    assert cli("dataset", "remove", "ex@1.0.0", "--yes", db=ex).exit_code == 0


def test_python_api(ex: str) -> None:
    diffs = granudb.edit_dataset(
        "ex@1.0.0",
        db=ex,
        authors=[{"family_names": "Hunt", "orcid": "0000-0001-5109-3700"}],
        keywords=["wet"],
    )
    assert [d[0] for d in diffs] == ["authors", "keywords"]
    with pytest.raises(ValidationError, match="check digit"):
        granudb.edit_dataset(
            "ex", db=ex, authors=[{"family_names": "X", "orcid": "0000-0001-5109-3701"}]
        )
    asked: list[list[str]] = []

    def agree(_action: str, losses: list[str]) -> bool:
        asked.append(losses)
        return True

    assert granudb.remove_collisions("ex", ["glass-g45-1"], confirm=agree, db=ex) == 1
    assert asked == [["1 runs of dataset ex@1.0.0 (glass-g45-1)"]]
    with pytest.raises(NotFoundError):
        granudb.remove_collisions("ex", ["glass-g45-1"], db=ex)

    def add_a_version_meanwhile(_action: str, _losses: list[str]) -> bool:
        granudb.new_dataset_version("ex@1.0.0", "2", db=ex)
        return True

    with pytest.raises(ConfirmationNeeded):  # a version was added since the question
        granudb.remove_dataset("ex", confirm=add_a_version_meanwhile, db=ex)
    assert granudb.release_dataset("ex@2", db=ex) == []
    with pytest.raises(ConflictError, match="cannot be removed"):
        granudb.remove_dataset("ex", db=ex)
    assert granudb.remove_dataset("ex@1.0.0", db=ex)
