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
from granudb.errors import ConflictError, ValidationError
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


def refused_at_once(cli, db: str, path: Path, rows: int, count: int) -> str:
    """The one line the command line and Python both refuse ``path`` with (first row
    ``rows``, ``count`` problems), no traceback, the database unchanged."""
    before = dump_hash(db)
    result = cli("collisions", "import", str(path), "--dataset", "d", db=db)
    assert result.exit_code == 1
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in result.stderr, result.stderr
    assert dump_hash(db) == before
    with pytest.raises(ValidationError) as caught:  # Python: the same line, the same rows
        granudb.import_collisions(path, dataset="d", db=db)
    assert "Error: " + str(caught.value) == lines[0]
    assert caught.value.row == rows and caught.value.count == count
    assert dump_hash(db) == before
    return lines[0]


FILE_PROBLEMS = [
    row("ok-1"),
    row("bad-speed", v_n_in="-300"),  # row 3: a rule
    row("bad label ", notes="x"),  # row 4: a name rule (the pandas path)
    row("text", diameter="twelve"),  # row 5: not a number
    row("ok-2"),
    row("fast", v_n_out="900"),  # row 7: e > 1.05
    row("both", v_n_in="-1", omega_in="inf"),  # row 8: two problems in one row
]
#: What only the database finds, mixed with the file's own problem (issue 24).
DATABASE_PROBLEMS = [
    row("ok-1"),
    row("typo", particle="stell"),  # row 3: an unknown material, close to steel
    row("hot", fluid="water", temperature="80"),  # row 4: outside water's data
    row("text", diameter="twelve"),  # row 5: the file's own problem
    row("ok-2"),
    row("wall", wall="unobtainium"),  # row 7: an unknown target material
    row("wet", fluid="mercury"),  # row 8: an unknown fluid
    row("typo-2", particle="stell"),  # row 9: the same unknown name again
]


@pytest.mark.parametrize(
    ("rows", "name", "listed", "said"),
    [
        (
            FILE_PROBLEMS,
            "lab-2024 run sheet.csv",
            [3, 4, 5, 7, 8, 8],
            [
                "6 problems: row 3: v_n_in [mm/s]: -300",
                "diameter [mm]: 'twelve' is not a number",
                "run: 'bad label ' must not begin or end with spaces",
                "omega_in [rad/s]: 'inf' must be a finite number",
            ],
        ),
        (
            DATABASE_PROBLEMS,
            "mixed sheet.csv",
            [3, 4, 5, 7, 8, 9],
            [
                "6 problems: row 3: particle: 'stell' is not in the database; "
                "did you mean 'steel'?",
                "temperature [degC]: 80 °C is outside fluid water's viscosity data",
                "diameter [mm]: 'twelve' is not a number",
                "wall: 'unobtainium' is not in the database (known: ",
                "fluid: 'mercury' is not in the database",
            ],
        ),
    ],
    ids=["file", "file-and-database"],
)
def test_problems_of_every_kind_come_at_once_in_row_order(
    cli, db: str, tmp_path: Path, rows: list[list[str]], name: str, listed: list[int], said
) -> None:
    line = refused_at_once(cli, db, write_csv(tmp_path / name, rows), 3, len(listed))
    assert line.startswith(f"Error: {name}: {said[0]}")
    assert listed_rows(line) == listed
    assert all(part in line for part in said), line
    assert "collisions.csv" not in line and "more problems" not in line


def only_the_file(i: int) -> list[str]:
    return row(f"r{i}", v_n_in="-1" if i % 3 == 0 else "300")


def file_and_database(i: int) -> list[str]:
    if i % 4 == 1:
        return row(f"r{i}", particle="stell")  # an unknown name
    if i % 4 == 2:
        return row(f"r{i}", fluid="water", temperature="95")  # outside water's data
    return row(f"r{i}", v_n_in="-1" if i % 25 == 0 else "300")  # the file's own


@pytest.mark.parametrize(
    ("made", "size", "is_bad"),
    [
        (only_the_file, 300, lambda i: i % 3 == 0),
        (file_and_database, 400, lambda i: i % 4 in (1, 2) or i % 25 == 0),
    ],
)
def test_many_problems_are_capped_with_the_count_across_chunks(
    db: str, tmp_path: Path, made, size: int, is_bad
) -> None:
    path = write_csv(tmp_path / "many.csv", [made(i) for i in range(size)])
    bad = [i + 2 for i in range(size) if is_bad(i)]  # spreadsheet rows (header = row 1)
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
    assert caught.value.count == len(bad)
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


def test_runs_already_stored_are_all_listed_with_the_files_problems(
    cli, db: str, tmp_path: Path
) -> None:
    first = write_csv(tmp_path / "first.csv", [row("a"), row("b"), row("c")])
    assert cli("collisions", "import", str(first), "--dataset", "d", db=db).exit_code == 0
    again = [row("new-1"), row("a"), row("x", v_n_in="-1"), row("c"), row("new-2"), row("new-2")]
    path = write_csv(tmp_path / "second.csv", again)
    before = dump_hash(db)
    result = cli("collisions", "import", str(path), "--dataset", "d", db=db)
    assert result.exit_code == 1 and "Traceback" not in result.stderr
    line = result.stderr.strip()
    assert listed_rows(line) == [3, 4, 5, 7]
    assert line.count("appears twice") == 3 and "row 4: v_n_in [mm/s]: -1" in line
    assert dump_hash(db) == before


def test_runs_already_stored_in_early_chunks_do_not_stop_the_reading(
    db: str, tmp_path: Path
) -> None:
    """Asking "is this the same file again?" at a stored run finished the reader early; a
    refusal that goes on to list every problem must read on (it hung before)."""
    first = write_csv(tmp_path / "first.csv", [row(f"r{i}") for i in range(10)])
    second = [row(f"s{i}") for i in range(200)]
    second[1], second[150] = row("r3"), row("r7")  # spreadsheet rows 3 and 152
    path = write_csv(tmp_path / "second.csv", second)
    database = open_database(db)
    try:
        import_file(database, first, dataset="d")
        before = dump_hash(db)
        with pytest.raises(ValidationError) as caught:
            import_file(database, path, dataset="d", chunk_rows=7)
        with pytest.raises(ConflictError, match="was already imported"):
            import_file(database, first, dataset="d", chunk_rows=3)  # the same file again
    finally:
        database.dispose()
    assert listed_rows(str(caught.value)) == [3, 152]
    assert dump_hash(db) == before
