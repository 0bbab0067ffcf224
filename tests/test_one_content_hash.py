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


def _respell(folder: Path, old: str, new: str, *, declared: str | None = None) -> None:
    """The package with the name ``old`` spelled ``new`` in every table (its files' sizes
    and hashes updated, as a tool that writes packages would), declaring ``declared``."""
    import hashlib

    descriptor = json.loads((folder / "datapackage.json").read_text())
    for resource in descriptor["resources"]:
        path = folder / resource["path"]
        lines = path.read_text(encoding="utf-8").split("\n")
        cells = [",".join(new if c == old else c for c in line.split(",")) for line in lines]
        payload = "\n".join(cells).encode("utf-8")
        path.write_bytes(payload)
        resource["bytes"] = len(payload)
        resource["hash"] = "sha256:" + hashlib.sha256(payload).hexdigest()
    if declared is not None:
        descriptor["granudb:content_hash"] = declared
    (folder / "datapackage.json").write_text(json.dumps(descriptor, indent=2))


def test_a_name_in_another_case_imports_with_the_hash_it_declares(
    opened, new_db: str, tmp_path: Path
) -> None:
    """'STEEL' and 'ZERODUR' in a package are this database's steel and Zerodur: the
    package's declared hash is verified, stored, shown and declared again on export."""
    granudb.import_collisions(EXAMPLE, dataset="cased", db=opened)
    folder = tmp_path / "cased"
    declared = _agree(opened, "cased", folder)
    _respell(folder, "steel", "STEEL")
    _respell(folder, "Zerodur", "ZERODUR")
    assert "STEEL" in (folder / "data" / "collisions.csv").read_text()
    other = granudb.connect(new_db)
    try:
        result = granudb.import_dataset(folder, db=other)
        assert result.content_hash == result.declared_hash == declared
        assert _agree(other, "cased", tmp_path / "again") == declared
        assert "STEEL" not in (tmp_path / "again" / "data" / "collisions.csv").read_text()
    finally:
        other.dispose()


def test_a_hash_recorded_before_names_were_canonical_still_holds(
    opened, new_db: str, tmp_path: Path
) -> None:
    """A package exported by an earlier granudb declares the hash of the names as spelled
    ('Zerodur'): it imports, and its release keeps that hash in show and export."""
    from granudb.db import datasets
    from granudb.db.content_hash import content_hash

    granudb.import_collisions(EXAMPLE, dataset="old", db=opened)
    with opened.session() as session:
        spelled = content_hash(session, datasets.get_dataset(session, "old"), spelled=True)
    folder = tmp_path / "old"
    canonical = _agree(opened, "old", folder)
    assert spelled != canonical  # 'Zerodur' ≠ 'zerodur'
    _respell(folder, "no-such-name", "-", declared=spelled)
    other = granudb.connect(new_db)
    try:
        result = granudb.import_dataset(folder, db=other)
        assert result.content_hash == spelled
        assert _agree(other, "old", tmp_path / "again") == spelled
    finally:
        other.dispose()
    _respell(folder, "no-such-name", "-", declared="0" * 64)
    other = granudb.connect(new_db)
    try:
        with pytest.raises(granudb.GranudbError, match="content hash: computed"):
            granudb.import_dataset(folder, as_name="forged", db=other)
    finally:
        other.dispose()
