"""The SQLite database opens in a real Datasette with granudb's titles, descriptions, units."""

from __future__ import annotations

import asyncio
import json
import shutil
from pathlib import Path

import pytest


@pytest.mark.sqlite_only
def test_datasette_serves_the_database_with_granudb_metadata(cli, db: str, tmp_path: Path) -> None:
    from datasette.app import Datasette

    path = tmp_path / "lab.sqlite"
    shutil.copy(db, path)
    result = cli("datasette-metadata", db=path)
    assert result.exit_code == 0, result.stderr
    metadata = json.loads(result.stdout)
    tables = metadata["databases"]["lab"]["tables"]
    assert tables["materials"]["units"]["youngs_modulus_pa"] == "Pa"
    assert "v_n_in_m_s" in tables["collisions"]["columns"]
    assert tables["sources"]["label_column"] == "key"

    async def browse() -> tuple[int, list, str]:
        datasette = Datasette([str(path)], metadata=metadata)
        rows = await datasette.client.get("/lab/materials.json?_shape=array")
        page = await datasette.client.get("/lab/materials")
        return rows.status_code, rows.json(), page.text

    status, rows, page = asyncio.run(browse())
    assert status == 200
    assert {r["name"] for r in rows} == {"glass", "steel", "Zerodur"}
    assert "Young&#39;s modulus E." in page or "Young's modulus E." in page
