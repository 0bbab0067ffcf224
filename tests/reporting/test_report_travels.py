"""Reports that travel (issue 24): the header names the database by its file name only,
never the folder it sits in on the author's machine; fit texts pluralise ("1 value",
"1 dry run"); the gap-viscosity listing says a reason once."""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd

from granudb.analysis import fits
from granudb.reporting.build import database_name


def test_header_names_the_database_by_its_file_name(cli, example_db, tmp_path) -> None:
    for fmt in ("html", "md"):
        out = tmp_path / f"r.{fmt}"
        result = cli("report", "--dataset", "example", "--format", fmt, "--output", str(out),
                     db=example_db)  # fmt: skip
        assert result.exit_code == 0, result.stderr
        text = out.read_text("utf-8")
        folder = str(tmp_path)
        assert folder not in text and folder.replace("/", "\\/") not in text
        # a file by its name; a server database by its name and backend, never its URL
        name = database_name(example_db) if "://" in example_db else Path(example_db).name
        assert f"Database: <code>{name}</code>" in text or f"Database: ` {name} `" in text


def test_one_stokes_number_says_one_value() -> None:
    frame = pd.DataFrame(
        {"dataset": "d", "version": "1", "particle": "steel", "wall": "Zerodur",
         "fluid": "oil", "normal_stokes_number": [40.0] * 4, "normal_restitution": 0.5}
    )  # fmt: skip
    [fit] = fits.restitution(frame, "threshold")
    assert "(1 value, 40)" in fit["reason"] and "1 values" not in fit["reason"]


def test_gap_listing_gives_the_reason_once(cli, example_db) -> None:
    table = cli("fit", "gap-viscosity", db=example_db)
    assert table.exit_code == 0, table.stderr
    assert "Note" not in table.stdout
    wide = json.loads(cli("fit", "gap-viscosity", "--format", "json", db=example_db).stdout)
    assert wide and all(r["note"] == r["reason"] for r in wide)  # the older name, kept
