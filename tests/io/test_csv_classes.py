"""The CSV classes of issue 25 that are unambiguous are read correctly (the refusals are in
tests/bad_inputs/): semicolon and tab files, ``name (unit)`` headers, spaces around header
names, negative zero, spreadsheet formulas kept as data but neutralised where people open
them, line breaks in notes through export and import, and concurrent imports."""

from __future__ import annotations

import csv
import io
import json
import math
import threading
from pathlib import Path

from support import COLLISION_HEADER, GOOD_ROW, write_csv

import granudb
from granudb.errors import GranudbError

CORPUS = Path(__file__).resolve().parents[1] / "bad_inputs"
EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"


def windows_csv(path: Path, rows: list[list[str]]) -> Path:
    """A file as spreadsheets on Windows write it: CRLF row ends, LF inside quoted cells."""
    with path.open("w", encoding="utf-8", newline="") as handle:
        csv.writer(handle, lineterminator="\r\n").writerows([COLLISION_HEADER, *rows])
    return path


def listing(cli, db: str, dataset: str) -> list[dict]:
    shown = cli("collisions", "list", "--dataset", dataset, "--wide", "--format", "json", db=db)
    assert shown.exit_code == 0, shown.stderr
    return [{k: v for k, v in r.items() if k != "dataset"} for r in json.loads(shown.stdout)]


def imports(cli, db: str, path: Path, dataset: str, *options: str) -> list[dict]:
    done = cli("collisions", "import", str(path), "--dataset", dataset, *options, db=db)
    assert done.exit_code == 0, done.stderr
    return listing(cli, db, dataset)


def test_other_delimiters_and_header_spellings_read_the_same_runs(
    cli, db: str, tmp_path: Path
) -> None:
    expected = imports(cli, db, write_csv(tmp_path / "plain.csv", [GOOD_ROW]), "plain")
    semicolon = write_csv(tmp_path / "semi.csv", [GOOD_ROW], delimiter=";")
    paren = [h.replace("[", "(").replace("]", ")") for h in COLLISION_HEADER]
    spaced = [f"  {h} " for h in COLLISION_HEADER]
    files = {
        "semi": semicolon,
        "tab": CORPUS / "read" / "tab_delimited.csv",
        "paren": write_csv(tmp_path / "paren.csv", [GOOD_ROW], paren),
        "spaced": write_csv(tmp_path / "spaced.csv", [GOOD_ROW], spaced),
        "crlf": windows_csv(tmp_path / "crlf.csv", [GOOD_ROW]),
        "semi-stated": semicolon,
    }
    for dataset, path in files.items():
        options = ("--delimiter", ";") if dataset == "semi-stated" else ()
        assert imports(cli, db, path, dataset, *options) == expected, dataset


def test_negative_zero_is_read_as_zero(cli, db: str, tmp_path: Path) -> None:
    row = list(GOOD_ROW)
    row[COLLISION_HEADER.index("v_n_out [mm/s]")] = "-0"
    row[COLLISION_HEADER.index("v_t_out [mm/s]")] = "-0.0"
    row[COLLISION_HEADER.index("omega_in [rad/s]")] = "-0e5"
    (run,) = imports(cli, db, write_csv(tmp_path / "z.csv", [row]), "z")
    for column in ("v_n_out_m_s", "v_t_out_m_s", "omega_in_rad_s"):
        assert run[column] == 0.0 and math.copysign(1.0, run[column]) == 1.0, column


FORMULAS = ["=1+2", "+SUM(A1:A9)", "-2+3", "@cmd", '=HYPERLINK("http://example.org")']


def test_formulas_are_data_but_never_run_where_people_open_them(
    cli, db: str, tmp_path: Path
) -> None:
    rows = []
    for i, label in enumerate(FORMULAS):
        row = list(GOOD_ROW)
        row[0] = label
        row[COLLISION_HEADER.index("notes")] = f"=cmd|' /C calc'!A{i}"
        rows.append(row)
    listed = imports(cli, db, write_csv(tmp_path / "f.csv", rows), "f")
    assert sorted(r["run"] for r in listed) == sorted(FORMULAS)  # stored verbatim
    shown = cli("collisions", "list", "--dataset", "f", "--wide", "--format", "csv", db=db)
    cells = list(csv.DictReader(io.StringIO(shown.stdout)))
    assert sorted(c["run"] for c in cells) == sorted("'" + f for f in FORMULAS)
    assert all(c["notes"].startswith("'=cmd") for c in cells)
    out = tmp_path / "pkg"  # a machine format keeps the bytes: the package round-trips
    assert cli("dataset", "export", "f", "--output", str(out), db=db).exit_code == 0
    assert cli("dataset", "import", str(out), "--as", "f2", db=db).exit_code == 0
    assert sorted(r["run"] for r in listing(cli, db, "f2")) == sorted(FORMULAS)


def test_line_breaks_in_notes_survive_export_and_import(cli, db: str, tmp_path: Path) -> None:
    row = list(GOOD_ROW)
    row[COLLISION_HEADER.index("notes")] = "first line\nsecond line\n\ttabbed"
    path = windows_csv(tmp_path / "n.csv", [row])  # a Windows file
    (run,) = imports(cli, db, path, "n")
    assert run["notes"] == "first line\nsecond line\n\ttabbed"
    out = tmp_path / "pkg"
    assert cli("dataset", "export", "n", "--output", str(out), db=db).exit_code == 0
    exported = out / "data" / "collisions.csv"
    assert b"\r" not in exported.read_bytes().replace(b"\r\n", b"")  # no bare CR written
    (again,) = imports(cli, db, exported, "n-again")  # granudb's SI columns read back
    assert again == run | {"run": again["run"]} and again["notes"] == run["notes"]


def _import_at_once(db: str, files: list[Path], dataset: str) -> list[object]:
    """Import ``files`` into ``dataset`` from threads started together: each outcome."""
    outcomes: list[object] = [None] * len(files)
    start = threading.Barrier(len(files))

    def work(i: int) -> None:
        start.wait()
        try:
            outcomes[i] = granudb.import_collisions(files[i], dataset=dataset, db=db).rows
        except GranudbError as exc:  # a refusal; anything else fails the test
            outcomes[i] = exc

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(files))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return outcomes


def test_concurrent_imports_land_consistently(cli, db: str, tmp_path: Path) -> None:
    same = _import_at_once(db, [EXAMPLE, EXAMPLE], "same")  # one wins, one is refused
    assert sorted(isinstance(o, GranudbError) for o in same) == [False, True], same
    assert len(listing(cli, db, "same")) == 12
    parts = []
    for part in range(2):
        rows = []
        for i in range(40):
            row = list(GOOD_ROW)
            row[0] = f"p{part}-{i}"
            rows.append(row)
        parts.append(write_csv(tmp_path / f"part{part}.csv", rows))
    both = _import_at_once(db, parts, "both")  # different runs: both land, or one refused
    landed = sum(o for o in both if isinstance(o, int))
    assert landed >= 40 and len(listing(cli, db, "both")) == landed, both
    out = tmp_path / "pkg"  # the stored content hash matches the rows: the package
    assert cli("dataset", "export", "both", "--output", str(out), db=db).exit_code == 0
    again = cli("dataset", "import", str(out), "--as", "both-again", db=db)
    assert again.exit_code == 0, again.stderr  # (import checks the declared hash)
