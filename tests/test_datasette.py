"""The SQLite database opens in a real Datasette with granudb's titles, descriptions, units:
served on loopback, every table page and a row page answer 200."""

from __future__ import annotations

import asyncio
import json
import shutil
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from granudb.io.seed import read_seed

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "collisions_example.csv"


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
    assert {r["name"] for r in rows} == {m["name"] for m in read_seed().materials}
    assert "Young&#39;s modulus E." in page or "Young's modulus E." in page


def test_no_offset_unit_reaches_datasette(cli, db: str) -> None:
    """Datasette multiplies values by their unit; °C cannot be multiplied (HTTP 500)."""
    metadata = json.loads(cli("datasette-metadata", db=db).stdout)
    for table in next(iter(metadata["databases"].values()))["tables"].values():
        assert not {"degC", "celsius"} & set(table.get("units", {}).values())


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _get(url: str) -> int:
    try:
        with urllib.request.urlopen(url, timeout=30) as response:  # noqa: S310 - loopback
            return response.status
    except urllib.error.HTTPError as exc:
        return exc.code
    except (urllib.error.URLError, OSError):
        return 0  # not listening yet


@pytest.mark.sqlite_only
def test_every_table_page_answers_200_in_a_served_datasette(cli, tmp_path: Path) -> None:
    path = tmp_path / "lab.sqlite"
    imported = cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=path)
    assert imported.exit_code == 0, imported.stderr
    shown = cli("datasette-metadata", "--print-path", db=path)
    assert shown.exit_code == 0 and shown.stdout.strip() == str(path.resolve())
    metadata = tmp_path / "metadata.json"
    metadata.write_text(cli("datasette-metadata", db=path).stdout, encoding="utf-8")
    port = _free_port()
    tool = shutil.which("datasette") or str(Path(sys.executable).parent / "datasette")
    server = subprocess.Popen(
        [tool, "serve", shown.stdout.strip(), "-m", str(metadata), "-h", "127.0.0.1"]
        + ["-p", str(port)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    base = f"http://127.0.0.1:{port}/lab"
    try:
        deadline = time.monotonic() + 60
        while _get(base + ".json") != 200:
            assert server.poll() is None, server.stderr.read().decode()[-2000:]
            assert time.monotonic() < deadline, "datasette did not start"
            time.sleep(0.2)
        with urllib.request.urlopen(base + ".json", timeout=30) as response:  # noqa: S310
            listed = json.load(response)
        tables = [t["name"] for t in listed["tables"]]
        assert {"collisions", "fluids", "fluid_points", "materials", "datasets"} <= set(tables)
        statuses = {t: _get(f"{base}/{t}") for t in tables}
        assert statuses == dict.fromkeys(tables, 200)
        assert _get(f"{base}/collisions/1") == 200
        assert _get(f"{base}/fluid_points/1") == 200
        assert _get(f"{base}/collisions.json?_shape=array") == 200
    finally:
        server.terminate()
        server.wait(timeout=30)


def test_print_path_refuses_a_database_that_is_not_a_file(cli) -> None:
    result = cli("datasette-metadata", "--print-path", db="sqlite://")
    assert result.exit_code == 1
    assert result.stderr.strip().startswith("Error: --db:")
    assert "internal error" not in result.stderr
