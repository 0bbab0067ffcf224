"""Every problem of a collision file in one refusal (issue 24): in row order, capped with
the count, naming the user's file; the same from the command line and from Python, and the
database unchanged."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from support import COLLISION_HEADER, GOOD_ROW, dump_hash, write_csv

import granudb
from granudb.api.database import connect as open_database
from granudb.errors import ValidationError
from granudb.io.collision_import import import_collisions as import_file
from granudb.io.tables import SHOWN_ROW_PROBLEMS


def row(label: str, **cells: str) -> list[str]:
    out = list(GOOD_ROW)
    out[0] = label
    for name, value in cells.items():
        out[[h.split(" ")[0] for h in COLLISION_HEADER].index(name)] = value
    return out


def listed_rows(message: str) -> list[int]:
    return [int(n) for n in re.findall(r"(?:^|; |problems: )row (\d+):", message)]


def test_problems_of_every_kind_come_at_once_in_row_order(cli, db: str, tmp_path: Path) -> None:
    rows = [
        row("ok-1"),
        row("bad-speed", v_n_in="-300"),  # row 3: a rule
        row("bad label ", notes="x"),  # row 4: a name rule (the pandas path)
        row("text", diameter="twelve"),  # row 5: not a number
        row("ok-2"),
        row("fast", v_n_out="900"),  # row 7: e > 1.05
        row("both", v_n_in="-1", omega_in="inf"),  # row 8: two problems in one row
    ]
    path = write_csv(tmp_path / "lab-2024 run sheet.csv", rows)
    before = dump_hash(db)
    result = cli("collisions", "import", str(path), "--dataset", "d", db=db)
    assert result.exit_code == 1
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in result.stderr, result.stderr
    line = lines[0]
    assert line.startswith("Error: lab-2024 run sheet.csv: 6 problems: row 3: v_n_in [mm/s]: -300")
    assert listed_rows(line) == [3, 4, 5, 7, 8, 8]
    assert "diameter [mm]: 'twelve' is not a number" in line
    assert "run: 'bad label ' must not begin or end with spaces" in line
    assert "omega_in [rad/s]: 'inf' must be a finite number" in line
    assert "collisions.csv" not in line and "more problems" not in line
    assert dump_hash(db) == before
    with pytest.raises(ValidationError) as caught:  # Python: the same line, the same rows
        granudb.import_collisions(path, dataset="d", db=db)
    assert "Error: " + str(caught.value) == line
    assert caught.value.row == 3 and caught.value.count == 6
    assert dump_hash(db) == before


def test_many_problems_are_capped_with_the_count_across_chunks(db: str, tmp_path: Path) -> None:
    rows = [row(f"r{i}", v_n_in="-1" if i % 3 == 0 else "300") for i in range(300)]
    path = write_csv(tmp_path / "many.csv", rows)
    bad = [i + 2 for i in range(300) if i % 3 == 0]  # spreadsheet rows (header = row 1)
    before = dump_hash(db)
    database = open_database(db)
    try:
        with pytest.raises(ValidationError) as caught:
            import_file(database, path, dataset="d", chunk_rows=7)  # problems in many chunks
    finally:
        database.dispose()
    message = str(caught.value)
    assert message.startswith(f"many.csv: {len(bad)} problems: row 2: v_n_in [mm/s]: -1 must be")
    assert listed_rows(message) == bad[:SHOWN_ROW_PROBLEMS]
    assert message.endswith(f"; … and {len(bad) - SHOWN_ROW_PROBLEMS} more problems")
    assert dump_hash(db) == before


def test_a_problem_only_the_database_finds_names_the_file_too(cli, db: str, tmp_path: Path) -> None:
    path = write_csv(tmp_path / "plate.csv", [row("a"), row("b", particle="unobtainium")])
    result = cli("collisions", "import", str(path), "--dataset", "d", db=db)
    assert result.exit_code == 1
    assert result.stderr.startswith("Error: plate.csv: row 3: particle: 'unobtainium' is not in")


def test_ragged_rows_are_all_listed(cli, db: str, tmp_path: Path) -> None:
    lines = [",".join(COLLISION_HEADER), ",".join(GOOD_ROW), "r2,steel", ",".join(GOOD_ROW + ["x"])]
    path = tmp_path / "ragged.csv"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    result = cli("collisions", "import", str(path), "--dataset", "d", db=db)
    assert result.exit_code == 1
    assert result.stderr.strip() == (
        "Error: ragged.csv: 2 problems: row 3: cells: 2 where the header has 14 (truncated?); "
        "row 4: cells: 15 where the header has 14"
    )
