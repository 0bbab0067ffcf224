"""Browsing the database in Datasette: ``granudb datasette-metadata`` is
``datasette_metadata`` (``--print-path`` is ``database_file``).

``granudb datasette-metadata > metadata.json && datasette "$(granudb datasette-metadata
--print-path)" -m metadata.json`` opens the SQLite file with titles, column descriptions
and units, generated from the vocabulary.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from sqlalchemy.engine import make_url

from granudb.config import resolve_database_url
from granudb.errors import ValidationError
from granudb.io.datasette import datasette_metadata as metadata


def database_file(db: Any = None) -> Path:
    """The SQLite file of ``db`` (a URL or a path; default as ``connect``), absolute;
    refused for a database that is not a SQLite file (Datasette reads SQLite).

    Examples
    --------
    >>> import granudb
    >>> granudb.database_file(tmp / "lab.sqlite").name
    'lab.sqlite'
    """
    url = make_url(resolve_database_url(None if db is None else str(db)))
    path = url.database if url.get_backend_name() == "sqlite" else None
    if not path or path == ":memory:" or path.startswith("file:"):
        raise ValidationError(
            "db",
            url.render_as_string(),
            "is not a SQLite file (Datasette reads SQLite)",
            parameter=True,
        )
    return Path(path).resolve()


def datasette_metadata(db: Any = None) -> dict[str, Any]:
    """Datasette ``metadata.json`` for the database (titles, descriptions, units), naming
    the database as Datasette does: its file name without ``.sqlite``.

    Examples
    --------
    >>> import granudb
    >>> "collisions" in granudb.datasette_metadata()["databases"]["granudb"]["tables"]
    True
    """
    url = make_url(resolve_database_url(None if db is None else str(db)))
    path = url.database if url.get_backend_name() == "sqlite" and url.database else None
    return metadata(Path(path).stem if path else "granudb")
