"""One content hash (issue 35): what ``dataset show`` says, what the export declares and
what an import of that export stores are the same hash, after a material or fluid is
renamed. A draft's hash is over the names it reads today (a rename hashes it again); a
released version keeps the names it was released with, and its hash. Both backends."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import granudb

EXAMPLE = Path(__file__).resolve().parent / ".." / "examples" / "collisions_example.csv"


def _declared(folder: Path) -> str:
    return json.loads((folder / "datapackage.json").read_text())["granudb:content_hash"]


def _agree(db, name: str, folder: Path) -> str:
    shown = granudb.dataset(name, db=db)["content_hash"]
    granudb.export_dataset(name, folder, db=db)
    assert _declared(folder) == shown
    return shown


@pytest.fixture
def renamed(opened, tmp_path: Path) -> dict[str, str]:
    """A released dataset and a draft of the same runs, hashed before and after steel and
    glycerol-37 are renamed."""
    granudb.import_collisions(EXAMPLE, dataset="released", db=opened)
    granudb.release_dataset("released", db=opened)
    granudb.import_collisions(EXAMPLE, dataset="draft", db=opened)
    before = {n: _agree(opened, n, tmp_path / f"{n}-before") for n in ("released", "draft")}
    granudb.update_material("steel", rename="Steel 316L", db=opened)
    granudb.update_fluid("glycerol-37", rename="Glycerol 37 %", db=opened)
    after = {n: _agree(opened, n, tmp_path / f"{n}-after") for n in ("released", "draft")}
    return {**{f"{n} before": h for n, h in before.items()}, **after}


def test_show_and_export_agree_after_a_rename(renamed: dict[str, str]) -> None:
    assert renamed["released"] == renamed["released before"]  # a release keeps its names
    assert renamed["draft"] != renamed["draft before"]  # a draft reads the new ones
    assert renamed["draft"] != renamed["released"]


def test_an_import_of_the_export_stores_the_declared_hash(
    renamed: dict[str, str], new_db: str, tmp_path: Path
) -> None:
    other = granudb.connect(new_db)
    try:
        for name in ("released", "draft"):
            result = granudb.import_dataset(tmp_path / f"{name}-after", db=other)
            assert result.content_hash == result.declared_hash == renamed[name]
            assert granudb.dataset(name, db=other)["content_hash"] == renamed[name]
    finally:
        other.dispose()
