"""granudb's CSV cell limit is its own: a library that raises Python's process-wide
``csv.field_size_limit`` (frictionless does when it is imported) changes neither which
files granudb refuses nor the message, and granudb leaves the process's limit as it was."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest

import granudb

CORPUS = Path(__file__).resolve().parents[1] / "bad_inputs" / "csv"


@pytest.mark.parametrize("process_limit", [131_072, 2**31 - 1])
def test_a_huge_cell_is_refused_whatever_the_process_limit(
    process_limit: int, tmp_path: Path
) -> None:
    before = csv.field_size_limit(process_limit)
    try:
        db = granudb.connect(str(tmp_path / "g.sqlite"))
        with pytest.raises(granudb.ValidationError, match="field larger than field limit"):
            granudb.import_collisions(CORPUS / "huge_field.csv", dataset="bad", db=db)
        assert csv.field_size_limit() == process_limit
        assert granudb.datasets(db=db, as_frame=False) == []
        db.dispose()
    finally:
        csv.field_size_limit(before)
