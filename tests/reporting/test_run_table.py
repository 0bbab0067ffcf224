"""A dataset report has a table of its runs (issue 24): every run of a small set in the
report itself; beyond ``RUN_TABLE_LIMIT`` the first runs, with every run in a CSV beside
the report (written as the report is: refused if it exists, unless ``--force``). Each row
carries the run's Walton branch (the one classification) and what its derivation assumed,
the same in HTML, Markdown and the CSV."""

from __future__ import annotations

import csv
import html as htmllib
import re

from paper_runs import paper_rows

from granudb.reporting.tables import RUN_TABLE_LIMIT
from granudb.vocabulary.listings import REPORT_RUN_COLUMNS

ASSUMED = "assumed: no temperature given, so glycerol-37 at its reference"


def _import(cli, db, csv_writer, tmp_path, runs_per_group: int) -> str:
    rows = paper_rows(runs_per_group=runs_per_group)
    unmeasured = next(r for r in rows if r[3] == "glycerol-37")
    unmeasured[12] = ""  # a wet run without a temperature
    source = csv_writer(tmp_path / "runs.csv", rows)
    assert cli("collisions", "import", str(source), "--dataset", "t", db=db).exit_code == 0
    return unmeasured[0]


def _report(cli, db, out, *extra: str):
    fmt = "md" if out.suffix == ".md" else "html"
    return cli("report", "--dataset", "t", "--format", fmt, "--output", str(out), *extra, db=db)


def _html_rows(html: str) -> dict[str, list[str]]:
    section = html[html.index('<section id="runs">') :]
    section = section[: section.index("</section>")]
    rows = {}
    for row in re.findall(r"<tr>(.*?)</tr>", section, re.S):
        cells = [htmllib.unescape(c) for c in re.findall(r"<td>(.*?)</td>", row, re.S)]
        if cells:
            rows[cells[0]] = cells
    return rows


def test_small_set_lists_every_run_with_branch_and_assumption(
    cli, db, csv_writer, tmp_path
) -> None:
    unmeasured = _import(cli, db, csv_writer, tmp_path, runs_per_group=5)
    result = _report(cli, db, tmp_path / "r.html")
    assert result.exit_code == 0, result.stderr
    rows = _html_rows((tmp_path / "r.html").read_text("utf-8"))
    assert len(rows) == 20 and not list(tmp_path.glob("*_runs.csv"))
    branch = REPORT_RUN_COLUMNS.index("walton_branch")
    note = REPORT_RUN_COLUMNS.index("derivation_note")
    assert rows[unmeasured][note].startswith(ASSUMED)
    assert {r[note] for k, r in rows.items() if k != unmeasured} == {"—"}
    assert {r[branch] for r in rows.values()} <= {"sticking", "sliding", "not determined"}
    assert _report(cli, db, tmp_path / "r.md").exit_code == 0
    markdown = (tmp_path / "r.md").read_text("utf-8")
    appendix = markdown[markdown.index("## Appendix: Runs") :]
    assert appendix.count("\n| ") == 21  # the header and every run
    line = next(x for x in appendix.splitlines() if x.startswith(f"| {unmeasured} "))
    assert ASSUMED in line.replace("\\", "")


def test_large_set_shows_the_first_runs_and_writes_every_run_beside(
    cli, db, csv_writer, tmp_path
) -> None:
    per_group = RUN_TABLE_LIMIT // 4 + 1
    unmeasured = _import(cli, db, csv_writer, tmp_path, runs_per_group=per_group)
    out = tmp_path / "big.html"
    result = _report(cli, db, out)
    assert result.exit_code == 0, result.stderr
    html = out.read_text("utf-8")
    assert len(_html_rows(html)) == RUN_TABLE_LIMIT
    assert 'href="big_runs.csv"' in html and f"The first {RUN_TABLE_LIMIT} of" in html
    with (tmp_path / "big_runs.csv").open(encoding="utf-8") as handle:
        table = list(csv.DictReader(handle))
    assert len(table) == 4 * per_group and list(table[0]) == REPORT_RUN_COLUMNS
    notes = {r["run"]: r["derivation_note"] for r in table}
    assert notes.pop(unmeasured).startswith(ASSUMED) and set(notes.values()) == {""}
    branches = {r["walton_branch"] for r in table}
    assert {"sticking", "sliding"} <= branches  # the paper's dry groups split
    # The Markdown report of the same runs shares the CSV; a different CSV is not overwritten.
    assert _report(cli, db, tmp_path / "big.md").exit_code == 0
    (tmp_path / "big_runs.csv").write_text("mine\n", "utf-8")
    out.unlink()
    refused = _report(cli, db, out)
    assert refused.exit_code != 0 and "big_runs.csv" in refused.stderr and not out.exists()
    assert (tmp_path / "big_runs.csv").read_text("utf-8") == "mine\n"
    assert _report(cli, db, out, "--force").exit_code == 0
    assert len((tmp_path / "big_runs.csv").read_text("utf-8").splitlines()) == 4 * per_group + 1
