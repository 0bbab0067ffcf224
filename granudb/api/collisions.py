"""Measured collisions for Python users: a DataFrame with every derived column."""

from __future__ import annotations

from typing import Any

from granudb.api.database import opened


def collisions(db: Any = None, **filters: Any) -> Any:
    """Measured collisions with every derived column, as a pandas DataFrame (SI).

    ``db`` is an opened database (``granudb.connect``), a URL or a SQLite path (default:
    as the command line); ``filters`` are those of ``granudb collisions list``: dataset,
    version, particle, wall, fluid, min_st, max_st, angle_range (radians), regime,
    critical_stokes.
    """
    from granudb.analysis.query import CollisionQuery, select_collisions

    with opened(db) as database, database.session() as session:
        return select_collisions(session, CollisionQuery(**filters))
