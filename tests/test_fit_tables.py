"""Fit tables a person can read (issue 33): ``fit walton|restitution|gap-viscosity`` as
tables show every value with its interval, or — where either is missing — the reason in
the fit's own words, at 80 and 120 columns, and never cut a number (no "…")."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from paper_runs import paper_rows, write_csv

from granudb import api

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "collisions_example.csv"
KINDS = {"walton": "walton", "restitution": "restitution", "gap-viscosity": "gap_viscosity"}
VALUES = {
    "β (rotational restitution)", "μ_f (sliding friction)", "ē (mean normal restitution)",
    "e_dry (dry restitution)", "μ₀ (gap viscosity)", "gap temperature", "k", "St_c",
}  # fmt: skip


@pytest.fixture
def fitted_db(cli, db: str, tmp_path: Path) -> str:
    """The example's runs (too few for intervals: the reasons) and the paper's runs, 12 a
    group (intervals given)."""
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "few", db=db).exit_code == 0
    runs = write_csv(tmp_path / "runs.csv", paper_rows(runs_per_group=12))
    assert cli("collisions", "import", str(runs), "--dataset", "paper", db=db).exit_code == 0
    return db


def _words(text: str) -> str:
    return " ".join(text.split())


@pytest.mark.parametrize("columns", ["80", "120"])
@pytest.mark.parametrize("command", list(KINDS))
def test_every_value_has_its_interval_or_reason_uncut(
    cli, fitted_db: str, monkeypatch, command: str, columns: str
) -> None:
    monkeypatch.setenv("COLUMNS", columns)
    table = cli("fit", command, db=fitted_db)
    assert table.exit_code == 0, table.stderr
    assert "…" not in table.stdout
    assert max(len(line) for line in table.stdout.splitlines()) <= int(columns)
    records = json.loads(cli("fit", command, "--format", "json", db=fitted_db).stdout)
    printed = _words(table.stdout)
    said = 0
    for record in records:
        heading, lines = api.fit_people_view(KINDS[command], record)
        assert heading in printed
        for name, text in lines:
            assert _words(f"{name} {text}") in printed  # whole, nothing cut
            if name in VALUES:
                said += 1
                assert re.search(r"\[[-\d.]+, [-\d.]+\]", text) or "not determined" in text, text
    assert said >= 2 * len(records)


def test_the_words_are_the_records(cli, fitted_db: str) -> None:
    """A value without an interval reads the fit's own reason; a value with one reads its
    bounds; the method, resamples and seed are the record's."""
    [steel] = [r for r in json.loads(cli("fit", "walton", "--format", "json",
                                         db=fitted_db).stdout)
               if r["dataset"] == "few" and r["fluid"] == "dry"]  # fmt: skip
    [part] = [p for p in steel["reason"].split("; ") if p.startswith("interval of β")]
    why = part.split("not determined: ", 1)[1]  # the fit's words, e.g. "4 runs, at least …"
    lines = dict(api.fit_people_view("walton", steel)[1])
    beta = lines["β (rotational restitution)"]
    assert beta.startswith("0.3399") and "± 0.00003 (standard error" in beta  # its se
    assert beta.endswith(f"; interval not determined: {why})")
    assert beta.count("not determined") == 1
    assert lines["μ_f (sliding friction)"] == (
        "not determined by these runs: 2 sliding runs (< 3): no μ_f"
    )
    assert steel["model_reason"] in lines["model"]
    if "bootstrap" in steel["interval_method"]:
        assert f"{steel['bootstrap_resamples']} resamples" in lines["intervals"]
    assert steel["interval_method"] in lines["intervals"]
    every = json.loads(cli("fit", "walton", "--format", "json", db=fitted_db).stdout)
    paper = [r for r in every if r["dataset"] == "paper"]
    shown = 0
    for record in paper:
        lines = dict(api.fit_people_view("walton", record)[1])
        for key, name in (("rotational_restitution", "β (rotational restitution)"),
                          ("sliding_friction", "μ_f (sliding friction)")):  # fmt: skip
            if record[f"{key}_low"] is not None:
                low, high = re.search(r"\[([-\d.]+), ([-\d.]+)\]", lines[name]).groups()
                assert float(low) == pytest.approx(record[f"{key}_low"], abs=0.006)
                assert float(high) == pytest.approx(record[f"{key}_high"], abs=0.006)
                shown += 1
    assert shown >= 1
