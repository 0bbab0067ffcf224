"""Where the database is.

Precedence: an explicit URL (``--db``), then ``GRANUDB_DATABASE_URL``, then the embedded
default: a SQLite file ``granudb.sqlite`` in the user's data directory as given by
platformdirs (Linux: ``$XDG_DATA_HOME/granudb`` or ``~/.local/share/granudb``; macOS:
``~/Library/Application Support/granudb``; Windows: ``%LOCALAPPDATA%\\granudb``).
A bare path is accepted wherever a URL is and means a SQLite file.
"""

from __future__ import annotations

import os
from pathlib import Path

from granudb.lazy import platformdirs

ENV_VAR = "GRANUDB_DATABASE_URL"


def default_database_path() -> Path:
    """The embedded default SQLite file (its folder is created on first use)."""
    return platformdirs.user_data_path("granudb", appauthor=False) / "granudb.sqlite"


def resolve_database_url(url: str | None = None) -> str:
    """The SQLAlchemy URL to use, from ``url``, the environment, or the default."""
    chosen = url or os.environ.get(ENV_VAR) or ""
    if not chosen:
        return f"sqlite:///{default_database_path()}"
    if "://" not in chosen:
        return f"sqlite:///{Path(chosen).expanduser().resolve()}"
    return chosen
