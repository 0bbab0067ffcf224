"""Helpers tests import (``pythonpath = tests`` in pyproject)."""

from __future__ import annotations

import hashlib
import sqlite3
from pathlib import Path


def dump_hash(path: Path) -> str:
    """A hash of the database's logical content (schema and every row).

    Logical, not bytes: a read can checkpoint the WAL and change the file without changing
    any data, and it is the data that must stay the same.
    """
    connection = sqlite3.connect(path)
    try:
        digest = hashlib.sha256()
        for line in connection.iterdump():
            digest.update(line.encode())
        return digest.hexdigest()
    finally:
        connection.close()
