"""No Python reprs in any output (issue 33): every show, list and history command, as a
table and as CSV, prints lists and mappings in words (``dataset show``'s authors were
``[{'given_names': 'Jane', …}]``); a history says what changed at each revision."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "collisions_example.csv"
REPR = re.compile(r"\[\{'|\{'|\['|\(\['|datetime\.|Decimal\(|np\.float")
COMMANDS = [
    ["materials", "list"], ["materials", "show", "glass"], ["materials", "history", "glass"],
    ["fluids", "list"], ["fluids", "show", "glycerol-37"], ["fluids", "history", "glycerol-37"],
    ["sources", "list"], ["sources", "show", "joseph-hunt-2004"],
    ["sources", "history", "joseph-hunt-2004"], ["pairs", "list"],
    ["dataset", "list"], ["dataset", "show", "ex"], ["dataset", "show", "ex@1.0.0"],
    ["dataset", "diff", "ex@1.0.0", "ex@2.0.0"], ["dataset", "diff", "ex@1.0.0"],
    ["collisions", "list"], ["fit", "walton"], ["fit", "restitution"], ["fit", "gap-viscosity"],
    ["pair", "steel", "Zerodur", "--diameter", "12.7 mm",
     "--velocity", "0.3 m/s"],
]  # fmt: skip


@pytest.fixture
def edited_db(cli, db: str) -> str:
    """A released dataset with authors and keywords, a newer draft, and a source and a
    material changed since the release (so histories and pinned notes have content)."""
    steps = [
        ["collisions", "import", str(EXAMPLE), "--dataset", "ex", "--source",
         "joseph-hunt-2004"],
        ["dataset", "edit", "ex", "--author", "Doe, Jane; orcid=0000-0002-1825-0097; "
         "affiliation=Lab A", "--author", "Roe, Rick", "--keyword", "glass",
         "--keyword", "lubrication"],
        ["dataset", "release", "ex"],
        ["dataset", "new-version", "ex", "--version", "2.0.0"],
        ["sources", "update", "joseph-hunt-2004", "--url", "https://example.org/moved"],
        ["materials", "update", "glass", "--youngs-modulus", "64 GPa"],
    ]  # fmt: skip
    for step in steps:
        done = cli(*step, db=db)
        assert done.exit_code == 0, (step, done.stderr)
    return db


@pytest.mark.parametrize("fmt", ["table", "csv"])
def test_no_output_prints_a_python_repr(cli, edited_db: str, fmt: str) -> None:
    for command in COMMANDS:
        done = cli(*command, "--format", fmt, db=edited_db)
        assert done.exit_code == 0, (command, done.stderr)
        for stream in (done.stdout, done.stderr):
            assert not REPR.search(stream), (command, REPR.search(stream), stream[:3000])


def test_dataset_show_says_authors_and_keywords_in_words(cli, edited_db: str) -> None:
    table = " ".join(cli("dataset", "show", "ex@1.0.0", db=edited_db).stdout.split())
    assert "Jane Doe (ORCID 0000-0002-1825-0097, Lab A); Rick Roe" in table
    assert "glass, lubrication" in table
    record = json.loads(cli("dataset", "show", "ex@1.0.0", "--format", "json",
                            db=edited_db).stdout)  # fmt: skip
    assert record["keywords"] == ["glass", "lubrication"]  # JSON keeps the list


def test_a_history_says_what_changed(cli, edited_db: str, monkeypatch) -> None:
    """Two revisions that differ only in their URL (a column the table did not show) read
    differently: each says its change, old → new, as the JSON records it."""
    records = json.loads(cli("sources", "history", "joseph-hunt-2004", "--format", "json",
                             db=edited_db).stdout)  # fmt: skip
    current, kept = records
    assert current["url"] == "https://example.org/moved" and kept["url"] != current["url"]
    assert current["changes"] == f"url: {kept['url']!r} → 'https://example.org/moved'"
    for columns in ("80", "120"):
        monkeypatch.setenv("COLUMNS", columns)
        table = cli("sources", "history", "joseph-hunt-2004", db=edited_db)
        printed = " ".join(table.stdout.split())
        assert current["changes"] in printed and kept["url"] in printed
    materials = json.loads(cli("materials", "history", "glass", "--format", "json",
                               db=edited_db).stdout)  # fmt: skip
    assert materials[0]["changes"].startswith("youngs_modulus_pa: 60 GPa → 64 GPa")
    assert "youngs_modulus_pa: 60 GPa → 64 GPa" in " ".join(
        cli("materials", "history", "glass", db=edited_db).stdout.split()
    )


@pytest.mark.parametrize("columns", ["80", "120"])
def test_listings_never_cut_a_number(cli, edited_db: str, monkeypatch, columns: str) -> None:
    """``collisions|materials|pairs|fluids list`` at 80 and 120 columns: every number is
    printed whole (text may be shortened with "…", a number never)."""
    monkeypatch.setenv("COLUMNS", columns)
    import granudb
    from granudb import api

    for command, records, column in (
        (["materials", "list"], granudb.materials(db=edited_db, as_frame=False),
         "youngs_modulus_pa"),
        (["fluids", "list"], granudb.fluids(db=edited_db, as_frame=False),
         "reference_viscosity_pa_s"),
    ):  # fmt: skip
        out = cli(*command, db=edited_db).stdout
        assert max(len(line) for line in out.splitlines()) <= int(columns)
        assert not re.search(r"\d…", out), out
        for record in records:
            assert api.display(record[column], column) in out, (record["name"], out)
    for command in (["collisions", "list"], ["pairs", "list"]):
        out = cli(*command, db=edited_db).stdout
        assert max(len(line) for line in out.splitlines()) <= int(columns)
        assert not re.search(r"(?:^|[\s│])[-\d.]+…", out, re.M), (command, out)  # a cut number
    pairs = granudb.pair_values(db=edited_db, as_frame=False)
    out = cli("pairs", "list", db=edited_db).stdout
    for record in pairs:
        assert api.display(record["dry_restitution"], "dry_restitution") in out
