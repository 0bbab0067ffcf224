"""granudb: a materials-and-regime database for particle-wall collisions in liquids.

The library is the product; the ``granudb`` command is a thin layer over it.
Heavy dependencies (pandas, SQLAlchemy, matplotlib) are imported lazily so that
``granudb --help`` stays fast.
"""

__version__ = "0.1.0"

__all__ = ["__version__", "collisions"]


def collisions(database: str | None = None, **filters: object) -> object:
    """Measured collisions with every derived column, as a pandas DataFrame.

    ``database`` is a URL or SQLite path (default: as the command line); ``filters`` are
    those of ``granudb collisions list``: dataset, version, particle, wall, fluid, min_st,
    max_st, angle_range (radians), regime, critical_stokes.
    """
    from granudb.query import collisions as query

    return query(database, **filters)
