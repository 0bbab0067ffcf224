"""The one-pass columnar import (issue 17): same values, same hash, same refusals.

The import reads the file once with Arrow (hashing it as it goes), checks columns, inserts
only the columns with values and computes the dataset's content hash from the arrays it
inserted. These tests pin that every shortcut gives what the slow definitions give: the
content hash equals ``granudb.db.content_hash`` of the stored rows, the file's sha256 equals
hashlib's of the file, floats are formatted exactly as ``repr``, and line breaks inside
quoted notes survive the reader's read boundaries.
"""

from __future__ import annotations

import hashlib
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from support import GOOD_ROW, write_csv

from granudb.api.database import connect as open_database
from granudb.db import bulk_hash, datasets
from granudb.db.content_hash import content_hash
from granudb.io import collision_chunks
from granudb.io.collision_import import import_collisions


def _rows(n: int, seed: int = 0) -> list[list[str]]:
    rng = np.random.default_rng(seed)
    rows = []
    for i in range(n):
        v_n = rng.uniform(50, 400)
        angle = rng.uniform(0, 60)
        v_t = v_n * math.tan(math.radians(angle))
        row = list(GOOD_ROW)
        row[0] = f"run-{i}-é" if i % 7 == 0 else f"run-{i}"
        row[1] = "STEEL" if i % 5 == 0 else "steel"  # names resolve case-insensitively
        row[3] = ["", "water", "glycerol-37"][i % 3]
        row[5] = "" if i % 4 == 0 else f"{angle:.4f}"
        row[6], row[7] = f"{v_n:.3f}", f"{v_t:.3f}"
        row[8] = "" if i % 6 == 0 else f"{rng.uniform(-50, 50):.6g}"
        row[9], row[10] = f"{0.8 * v_n:.3f}", f"{0.3 * v_t:.3f}"
        row[12] = "20" if row[3] else ""
        row[13] = 'a "quoted"\nnote, on two lines' if i % 11 == 0 else ""
        rows.append(row)
    return rows


def _stored_hash(db: str) -> tuple[str, str]:
    database = open_database(db)
    try:
        with database.session() as session:
            dataset = datasets.get_dataset(session, "d")
            return dataset.content_hash, content_hash(session, dataset)
    finally:
        database.dispose()


def test_content_hash_from_the_inserted_arrays_equals_the_stored_rows_hash(
    db: str, tmp_path: Path, monkeypatch
) -> None:
    # Small chunks and read sizes, so rows cross chunk and read boundaries (a quoted
    # note's line break among them).
    monkeypatch.setattr(collision_chunks, "READ_BYTES", 4096)
    monkeypatch.setattr(bulk_hash, "HASH_BLOCK_ROWS", 333)
    path = write_csv(tmp_path / "c.csv", _rows(2_500))
    database = open_database(db)
    try:
        result = import_collisions(database, path, dataset="d", chunk_rows=700)
    finally:
        database.dispose()
    assert result.rows == 2_500
    assert result.sha256 == hashlib.sha256(path.read_bytes()).hexdigest()
    kept, recomputed = _stored_hash(db)
    assert kept == recomputed


def test_notes_with_line_breaks_and_quotes_survive_read_boundaries(
    db: str, tmp_path: Path, monkeypatch
) -> None:
    from sqlalchemy import text
    from support import engine_for

    monkeypatch.setattr(collision_chunks, "READ_BYTES", 64)
    path = write_csv(tmp_path / "c.csv", _rows(60))
    database = open_database(db)
    try:
        import_collisions(database, path, dataset="d")
    finally:
        database.dispose()
    engine = engine_for(db)
    with engine.connect() as connection:
        notes = connection.execute(
            text("SELECT notes FROM collisions WHERE notes IS NOT NULL")
        ).scalars()
        assert sorted(set(notes)) == ['a "quoted"\nnote, on two lines']
    engine.dispose()


def test_a_second_import_into_a_dataset_with_runs_keeps_the_hash_right(
    db: str, tmp_path: Path
) -> None:
    rows = _rows(300)
    first = write_csv(tmp_path / "a.csv", rows[:150])
    second = write_csv(tmp_path / "b.csv", rows[150:])
    database = open_database(db)
    try:
        import_collisions(database, first, dataset="d")
        import_collisions(database, second, dataset="d")
    finally:
        database.dispose()
    kept, recomputed = _stored_hash(db)
    assert kept == recomputed


def test_the_same_file_again_is_refused_as_a_repeat(cli, db: str, tmp_path: Path) -> None:
    path = write_csv(tmp_path / "c.csv", _rows(50))
    assert cli("collisions", "import", str(path), "--dataset", "d", db=db).exit_code == 0
    again = cli("collisions", "import", str(path), "--dataset", "d", db=db)
    assert again.exit_code != 0
    assert "was already imported into dataset d" in again.stderr


def test_a_repeated_run_across_chunks_is_refused_with_its_row(db: str, tmp_path: Path, cli) -> None:
    rows = _rows(30)
    rows[25][0] = rows[3][0]
    path = write_csv(tmp_path / "c.csv", rows)
    database = open_database(db)
    try:
        from granudb.errors import ValidationError

        with pytest.raises(ValidationError) as info:
            import_collisions(database, path, dataset="d", chunk_rows=10)
    finally:
        database.dispose()
    assert "row 27" in str(info.value) and "appears twice" in str(info.value)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=False), min_size=1, max_size=50))
def test_float_texts_are_repr(values: list[float]) -> None:
    texts = bulk_hash.float_texts(np.array(values, dtype=np.float64)).to_pylist()
    assert texts == ["" if math.isnan(v) else repr(v) for v in values]


def test_float_texts_at_the_format_edges() -> None:
    edges = [0.0, -0.0, 1e-4, 9.999e-5, 1e10, 9999999999.5, 1e16, 5e-324, 20.0, -3.5, 1e300]
    texts = bulk_hash.float_texts(np.array(edges)).to_pylist()
    assert texts == [repr(v) for v in edges]
