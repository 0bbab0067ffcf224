"""The PostgreSQL driver is an extra (issue 34): ``pip install .`` installs none, and a
PostgreSQL URL without its driver is refused in one line that names the extra."""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_no_postgresql_driver_is_a_hard_dependency() -> None:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    assert not [d for d in project["dependencies"] if d.lower().startswith(("psycopg", "pg8000"))]
    assert any(d.startswith("psycopg") for d in project["optional-dependencies"]["postgres"])


def test_a_missing_driver_names_the_extra(tmp_path: Path) -> None:
    # pg8000 is a PostgreSQL driver granudb never installs: the same path as a missing psycopg
    url = "postgresql+pg8000://reader@127.0.0.1:9/lab"
    result = subprocess.run(
        [sys.executable, "-m", "granudb", "--db", url, "materials", "list"],
        capture_output=True,
        text=True,
        check=False,
        cwd=tmp_path,
    )
    assert result.returncode == 1
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert "needs a driver that is not installed (pg8000)" in lines[0]
    assert "pip install 'granudb[postgres]'" in lines[0]
