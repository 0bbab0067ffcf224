"""Runs of the DEM codes test the codes and granudb's decks, not the database backend: they
run once, in the SQLite pass; the PostgreSQL pass deselects them (the exports they start
from are tested on both backends)."""

from __future__ import annotations

import os

import pytest


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line("markers", "dem_run: runs a DEM code (once, in the SQLite pass)")


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if os.environ.get("GRANUDB_TEST_BACKEND", "sqlite") == "sqlite":
        return
    runs = [i for i in items if i.get_closest_marker("dem_run") is not None]
    if runs:
        config.hook.pytest_deselected(items=runs)
        items[:] = [i for i in items if i.get_closest_marker("dem_run") is None]
