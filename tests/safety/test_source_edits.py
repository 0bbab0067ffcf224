"""A user adds and corrects sources (``sources add|update``, ``add_source`` /
``update_source``): each correction is a new revision, the old text kept with its reason;
an unknown key (with "did you mean"), an empty citation, a malformed DOI, URL or year is
refused in one line from the command line and Python alike, nothing changed; a re-seed
keeps a user's correction unless told to revert it, and then keeps the correction as a
revision."""

from __future__ import annotations

import pytest
from support import dump_hash

import granudb
from granudb.vocabulary.catalog import check_source

KEY = "joseph-hunt-2004"
CITATION = "Gondret, P., Lance, M. & Petit, L. (2002). Bouncing motion. Phys. Fluids 14."


def _refused(result, expected: str) -> None:
    assert result.exit_code == 1, (result.stdout, result.stderr)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and expected in lines[0], result.stderr
    assert "Traceback" not in result.stderr and "internal error" not in result.stderr


def test_add_then_update_keeps_each_revision(cli, db: str) -> None:
    added = cli("sources", "add", "gondret-2002", "--citation", CITATION, "--doi",
                "10.1063/1.1427920", "--year", "2002", "--note", "figure 4", db=db)  # fmt: skip
    assert added.exit_code == 0, added.stderr
    assert added.stdout.strip() == "added source gondret-2002"
    record = granudb.source("gondret-2002", db=db)
    assert (record["citation"], record["doi"], record["year"], record["kind"], record["notes"]) == (
        CITATION, "10.1063/1.1427920", 2002, "publication", "figure 4"
    )  # fmt: skip

    first = cli("sources", "update", "gondret-2002", "--citation", CITATION + " (corrected)",
                "--reason", "page numbers", db=db)  # fmt: skip
    assert first.exit_code == 0, first.stderr
    assert first.stdout.strip() == (
        f"updated source gondret-2002: citation {CITATION!r} → {CITATION + ' (corrected)'!r}"
    )
    second = granudb.update_source("gondret-2002", doi="", url="https://example.org/g", db=db)
    assert second.action == "updated"
    assert [c[0] for c in second.changes] == ["doi", "url"]
    history = granudb.source_history("gondret-2002", db=db)
    assert [r["revision"] for r in history] == ["current", "2", "1"]
    assert history[0]["doi"] is None and history[0]["url"] == "https://example.org/g"
    assert history[1]["citation"] == CITATION + " (corrected)" and history[1]["doi"]
    assert history[2]["citation"] == CITATION
    assert history[2]["reason"] == "sources update: page numbers"
    assert history[1]["reason"] == "sources update"
    shown = cli("sources", "history", "gondret-2002", db=db)
    assert "page numbers" in shown.stdout

    same = granudb.update_source("gondret-2002", year=2002, db=db)
    assert str(same) == "unchanged source gondret-2002"
    assert len(granudb.source_history("gondret-2002", db=db)) == 3


@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (["update", "joseph-hunt-2005", "--citation", "x"],
         "source: 'joseph-hunt-2005' is not in the database; did you mean 'joseph-hunt-2004'?"),
        (["update", KEY, "--citation", "  "], "citation: '  ' must not be empty"),
        (["update", KEY, "--citation", ""], "citation: '' must not be empty"),
        (["update", KEY, "--doi", "doi:10.1017/S0022"], "doi: 'doi:10.1017/S0022' must look like"),
        (["update", KEY, "--doi", "10.1017 S0022"], "must look like 10.NNNN/suffix"),
        (["update", KEY, "--url", "www.example.org"], "url: 'www.example.org' must be an http"),
        (["update", KEY, "--url", "javascript:alert(1)"], "must be an http:// or https://"),
        (["update", KEY, "--year", "1066"], "year: 1066 must be a whole year from 1600 to 3000"),
        (["update", KEY, "--year", "2004a"], "year: '2004a' must be a whole year"),
        (["update", KEY, "--kind", "a\tb"], "kind: 'a\\tb' must not contain U+0009"),
        (["add", KEY, "--citation", "again"], f"source: '{KEY}' already exists"),
        (["add", "new source\n", "--citation", "x"], "key: 'new source\\n' must not"),
        (["add", "new-source", "--citation", "x", "--doi", "10.12/x"], "doi: '10.12/x'"),
    ],
)  # fmt: skip
def test_bad_edits_are_refused_in_one_line(cli, db: str, args: list[str], expected: str) -> None:
    before = dump_hash(db)
    _refused(cli("sources", *args, db=db), expected)
    assert dump_hash(db) == before


def test_python_refuses_with_the_same_line(cli, db: str) -> None:
    before = dump_hash(db)
    with pytest.raises(granudb.MissingInput, match="citation"):
        granudb.add_source("new-source", db=db)
    missing = cli("sources", "add", "new-source", db=db)  # a usage error, as for materials
    assert missing.exit_code == 2 and "Missing option '--citation'" in missing.stderr
    for call, args in (
        (granudb.update_source, ("joseph-hunt-2005",)),
        (granudb.update_source, (KEY,)),
        (granudb.add_source, (KEY,)),
    ):
        keywords = {"citation": "" if call is granudb.update_source and args == (KEY,) else "x"}
        with pytest.raises(granudb.GranudbError) as raised:
            call(*args, db=db, **keywords)
        command = "update" if call is granudb.update_source else "add"
        shown = cli("sources", command, *args, "--citation", keywords["citation"], db=db)
        assert shown.stderr.strip() == f"Error: {raised.value}"
    with pytest.raises(granudb.ValidationError, match="year: 2004.5 must be a whole year"):
        granudb.update_source(KEY, year=2004.5, db=db)
    with pytest.raises(granudb.ValidationError, match="doi: '10.1/x'"):  # None: left as is
        granudb.update_source(KEY, citation=None, doi="10.1/x", db=db)
    assert dump_hash(db) == before


def test_every_seeded_source_meets_the_rules(db: str) -> None:
    records = granudb.sources(db=db, as_frame=False)
    assert len(records) >= 8
    for record in records:
        check_source(record)


def test_a_reseed_keeps_a_users_correction_and_a_revert_is_a_revision(db: str) -> None:
    granudb.update_source(KEY, notes="read again 2026", db=db)
    granudb.db_seed(db=db)
    assert granudb.source(KEY, db=db)["notes"] == "read again 2026"
    assert [r["revision"] for r in granudb.source_history(KEY, db=db)] == ["current", "1"]
    granudb.db_seed(overwrite_edits=True, db=db)
    history = granudb.source_history(KEY, db=db)
    assert [r["revision"] for r in history] == ["current", "2", "1"]
    assert history[0]["notes"] != "read again 2026" and history[1]["notes"] == "read again 2026"
    assert "overwrite-edits" in history[1]["reason"]
