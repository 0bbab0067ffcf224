"""Fixtures for the report tests: the paper's pairs (``paper_runs``), imported."""

from __future__ import annotations

import pytest
from paper_runs import EXAMPLE, paper_rows, write_csv


@pytest.fixture
def csv_writer():
    """``write_csv(path, rows)`` for tests that make their own runs."""
    return write_csv


@pytest.fixture
def paper_db(cli, db, tmp_path) -> str:
    """A database with the synthetic paper dataset imported as ``paper``."""
    source = write_csv(tmp_path / "paper.csv", paper_rows())
    result = cli("collisions", "import", str(source), "--dataset", "paper", db=db)
    assert result.exit_code == 0, result.stderr
    return db


@pytest.fixture
def example_db(cli, db) -> str:
    result = cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db)
    assert result.exit_code == 0, result.stderr
    return db
