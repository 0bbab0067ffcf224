"""The import's overlapped paths (issue 17) give exactly what the plain ones gave.

The content hash is formatted block by block on a worker thread (constant columns once,
the names as one code per triple), SQLite rows go in many to a statement, and run labels
are screened for surrounding spaces by Arrow. Each shortcut is pinned against the slow
definition: ``granudb.db.content_hash`` of the stored rows, ``repr`` of each float, the rows
read back in file order, the pandas path's refusal.
"""

from __future__ import annotations

import csv
import math
import sys
import threading
from pathlib import Path

import numpy as np
import pytest
from sqlalchemy import text
from support import COLLISION_HEADER, GOOD_ROW, engine_for, write_csv

from granudb.api.database import connect as open_database
from granudb.db import bulk_hash, bulk_insert, datasets
from granudb.db.content_hash import content_hash
from granudb.errors import ValidationError
from granudb.io.collision_import import import_collisions

TARGET = ["wall_diameter_m", "wall_v_n_in_m_s", "wall_v_t_in_m_s", "wall_omega_out_rad_s"]


def _rows(n: int) -> list[list[str]]:
    """Rows with every kind of column: constant ones, integral and fractional values,
    three fluids (one dry), notes on some rows, the target sphere's columns on some."""
    rng = np.random.default_rng(1)
    rows = []
    for i in range(n):
        v_n = rng.uniform(50, 400)
        row = list(GOOD_ROW)
        row[0] = f"r-{(i * 7919) % n}"  # not in byte order: the hash sorts
        row[1] = ["steel", "glass"][i % 2]
        row[3] = ["", "water", "glycerol-37"][i % 3]
        row[5] = ""
        row[6] = f"{v_n:.3f}" if i % 5 else "300"
        row[7] = "0" if i % 4 == 0 else f"{rng.uniform(0, 200):.2f}"
        row[9] = f"{0.5 * v_n:.3f}" if i % 5 else "150"
        row[12] = "20" if row[3] else ""
        row[13] = f"note {i}" if i % 9 == 0 else ""
        target = i % 6 == 0
        # the target moves away slower than the particle comes (m/s): they approach
        row += ["25.4", f"{rng.uniform(0, 0.04):.4f}", "0", "-0.0"] if target else ["", "", "", ""]
        rows.append(row)
    return rows


def _import(db: str, path: Path, **options) -> int:
    database = open_database(db)
    try:
        return import_collisions(database, path, dataset="d", **options).rows
    finally:
        database.dispose()


def test_hash_formatted_beside_the_insert_equals_the_stored_rows_hash(
    db: str, tmp_path: Path, monkeypatch
) -> None:
    # Odd sizes: statements of 7 rows, slices of 33, chunks of 50, hash slices of 41.
    monkeypatch.setattr(bulk_insert, "ROWS_PER_STATEMENT", 7)
    monkeypatch.setattr(bulk_insert, "INSERT_SLICE_ROWS", 33)
    monkeypatch.setattr(bulk_hash, "HASH_BLOCK_ROWS", 41)
    path = write_csv(tmp_path / "c.csv", _rows(331), header=[*COLLISION_HEADER, *TARGET])
    assert _import(db, path, chunk_rows=50) == 331
    database = open_database(db)
    try:
        with database.session() as session:
            dataset = datasets.get_dataset(session, "d")
            assert dataset.content_hash == content_hash(session, dataset)
    finally:
        database.dispose()


def test_rows_many_to_a_statement_are_stored_whole_and_in_file_order(
    db: str, tmp_path: Path, monkeypatch
) -> None:
    monkeypatch.setattr(bulk_insert, "ROWS_PER_STATEMENT", 7)
    monkeypatch.setattr(bulk_insert, "INSERT_SLICE_ROWS", 33)
    rows = _rows(101)
    path = write_csv(tmp_path / "c.csv", rows, header=[*COLLISION_HEADER, *TARGET])
    assert _import(db, path, chunk_rows=50) == 101
    engine = engine_for(db)
    with engine.connect() as connection:
        stored = connection.execute(
            text(
                "SELECT run, v_n_in_m_s, wall_v_n_in_m_s, temperature_c, notes, diameter_m, "
                "omega_out_rad_s FROM collisions ORDER BY id"
            )
        ).all()
    engine.dispose()
    assert [r[0] for r in stored] == [row[0] for row in rows]
    # Columns the same in every row are bound once per statement: still in every row.
    assert {(r[5], r[6]) for r in stored} == {(0.0127, -5.0)}
    for row, (_, v_n, wall_v_n, temperature, notes, *_) in zip(rows, stored, strict=True):
        assert math.isclose(v_n, float(row[6]) / 1000, rel_tol=1e-14)
        assert (wall_v_n is None) == (row[15] == "")
        assert (temperature is None) == (row[12] == "")
        assert notes == (row[13] or None)


@pytest.mark.parametrize(
    "values",
    [
        [20.0] * 5,
        [-0.0, -0.0, -0.0],
        [0.0, -0.0, 0.0],
        [1e-5] * 3,
        [1e16, 1e16],
        [0.1, 0.25, 3.5],
        [0.1, 2.0, float("nan"), 7.0],
        [float("nan")] * 2,
        [123456789.0, 0.0001, 9999999999.0],
    ],
)
def test_float_texts_shortcuts_are_repr(values: list[float]) -> None:
    texts = bulk_hash.float_texts(np.array(values, dtype=np.float64)).to_pylist()
    assert texts == ["" if math.isnan(v) else repr(v) for v in values]


WHITESPACE = [chr(c) for c in range(sys.maxunicode + 1) if chr(c).isspace()]


@pytest.mark.parametrize("space", WHITESPACE, ids=[f"U+{ord(c):04X}" for c in WHITESPACE])
@pytest.mark.parametrize("where", ["before", "after"])
def test_a_label_with_any_space_around_it_is_refused(
    db: str, tmp_path: Path, space: str, where: str
) -> None:
    rows = [list(GOOD_ROW) for _ in range(3)]
    for i, row in enumerate(rows):
        row[0] = f"r{i}"
    rows[1][0] = space + "r1" if where == "before" else "r1" + space
    path = write_csv(tmp_path / "c.csv", rows, quoting=csv.QUOTE_ALL)  # "\r" stays in
    with pytest.raises(ValidationError) as info:
        _import(db, path)
    assert "run" in str(info.value) and "row 3" in str(info.value)
    engine = engine_for(db)
    with engine.connect() as connection:
        assert connection.execute(text("SELECT count(*) FROM collisions")).scalar() == 0
    engine.dispose()


def test_a_refused_import_leaves_no_hash_worker_running(db: str, tmp_path: Path) -> None:
    rows = _rows(300)
    rows[250][0] = rows[10][0]  # a repeated run in a later chunk: refused mid-import
    path = write_csv(tmp_path / "c.csv", rows, header=[*COLLISION_HEADER, *TARGET])
    with pytest.raises(ValidationError, match="appears twice"):
        _import(db, path, chunk_rows=50)
    assert not [t for t in threading.enumerate() if t.name.startswith("granudb-hash")]
