"""The package the tests of this folder break: the example runs exported as a folder."""

from __future__ import annotations

from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"


@pytest.fixture
def package(cli, db: str, tmp_path: Path) -> Path:
    imported = cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db)
    assert imported.exit_code == 0, imported.stderr
    out = tmp_path / "pkg"
    assert cli("dataset", "export", "example", "--output", str(out), db=db).exit_code == 0
    return out
