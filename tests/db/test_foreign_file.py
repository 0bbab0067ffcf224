"""A database file that is not granudb's is refused before anything touches it: the bytes
of a foreign SQLite file (its journal mode included) and of a non-SQLite file are the
same after the refusal, and no -wal or -shm file appears beside it (issue 25)."""

from __future__ import annotations

import hashlib
import sqlite3
from pathlib import Path

import pytest


def _foreign_sqlite(path: Path) -> Path:
    connection = sqlite3.connect(path)
    connection.execute("CREATE TABLE places (id INTEGER PRIMARY KEY, name TEXT)")
    connection.execute("INSERT INTO places (name) VALUES ('Pasadena')")
    connection.commit()
    connection.close()
    return path


def _text_file(path: Path) -> Path:
    path.write_text("run,particle\n1,steel\n", encoding="utf-8")
    return path


@pytest.mark.parametrize(
    ("make", "words"),
    [(_foreign_sqlite, "not a granudb database"), (_text_file, "not a SQLite database")],
)
@pytest.mark.parametrize("command", [["materials", "list"], ["dataset", "list"], ["db", "current"]])
def test_a_foreign_file_is_refused_unchanged(cli, tmp_path, make, words, command) -> None:
    folder = tmp_path / "data"
    folder.mkdir()
    path = make(folder / "places.sqlite")
    before = hashlib.sha256(path.read_bytes()).hexdigest()
    result = cli(*command, "--db", str(path))
    assert result.exit_code == 1, result.stdout
    assert words in result.stderr and result.stderr.count("\n") == 1
    assert hashlib.sha256(path.read_bytes()).hexdigest() == before
    assert sorted(p.name for p in folder.iterdir()) == ["places.sqlite"]
