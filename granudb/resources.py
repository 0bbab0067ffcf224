"""Files granudb ships: the Alembic migrations and the seed data.

Both live at the top of the repository (``migrations/``, ``seed_data/``) and are installed
inside the package as ``granudb.migrations`` and ``granudb.seed_data`` (see
``pyproject.toml``). Running from a source checkout without installing finds them beside
the package.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path


def shipped_dir(name: str) -> Path:
    """The folder of the shipped ``name`` ("migrations" or "seed_data")."""
    spec = importlib.util.find_spec(f"granudb.{name}")
    if spec is not None and spec.submodule_search_locations:
        return Path(next(iter(spec.submodule_search_locations)))
    return Path(__file__).resolve().parent.parent / name
