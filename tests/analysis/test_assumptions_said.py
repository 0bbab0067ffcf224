"""Every assumption visible (issue 24): a wet run without a temperature is derived at its
fluid's reference temperature, and its ``derivation_note`` says so with the values used,
in the Python listing, JSON and CSV alike; a run with a temperature says nothing."""

from __future__ import annotations

import csv
import io
import json

from paper_runs import HEADER, write_csv

import granudb

ROW = ["w-{}", "steel", "Zerodur", "water", "12.7", "20", "300", "109.2", "0", "250", "20", "0"]


def test_a_run_without_temperature_says_what_was_assumed(cli, db, tmp_path) -> None:
    rows = [[f"w-{i}", *ROW[1:], t, ""] for i, t in enumerate(["", "21.3"], start=1)]
    assert len(rows[0]) == len(HEADER)
    source = write_csv(tmp_path / "w.csv", rows)
    assert cli("collisions", "import", str(source), "--dataset", "w", db=db).exit_code == 0
    database = granudb.connect(db)
    try:
        runs = granudb.collisions(dataset="w", db=database, as_frame=False, wide=True)
    finally:
        database.dispose()
    notes = {r["run"]: r["derivation_note"] for r in runs}
    assert notes["w-1"].startswith("assumed: no temperature given, so water at its reference")
    assert not isinstance(notes["w-2"], str)  # nothing assumed: no note
    args = ["collisions", "list", "--dataset", "w", "--columns", "run,derivation_note"]
    as_json = json.loads(cli(*args, "--format", "json", db=db).stdout)
    assert {r["run"]: r["derivation_note"] for r in as_json}["w-1"] == notes["w-1"]
    as_csv = list(csv.DictReader(io.StringIO(cli(*args, "--format", "csv", db=db).stdout)))
    assert {r["run"]: r["derivation_note"] for r in as_csv}["w-1"] == notes["w-1"]
    for fmt in ("html", "md"):
        out = tmp_path / f"r.{fmt}"
        report = cli("report", "--dataset", "w", "--format", fmt, "--output", str(out), db=db)
        assert report.exit_code == 0, report.stderr
        text = out.read_text("utf-8").replace("\\", "")
        assert "1 run: assumed: no temperature given, so water at its reference" in text
