"""The paper's fits on stored runs, for Python users: each returns a DataFrame, one row per
group (dataset × particle × wall × fluid), with the keys documented in
``granudb.analysis.fits``."""

from __future__ import annotations

from typing import Any

from granudb.api.collisions import collision_query
from granudb.api.database import opened


def _fit(db: Any, filters: dict[str, Any], run: Any) -> Any:
    import pandas as pd

    from granudb.analysis.collisions import select_collisions

    query = collision_query(**filters)
    with opened(db) as database, database.session() as session:
        frame = select_collisions(session, query)
        rows = run(session, frame)
    return pd.DataFrame.from_records(rows)


def fit_walton(db: Any = None, **filters: Any) -> Any:
    """Walton's β (sticking) and μ_f (sliding) with ē per group (Joseph & Hunt figures 4,
    6, 9), each with its bootstrap interval and the model chosen; ``filters`` as
    ``granudb.collisions``.

    >>> import granudb
    >>> granudb.fit_walton(db=db, fluid="dry").empty  # no runs stored yet
    True
    """
    from granudb.analysis import fits

    return _fit(db, filters, lambda _session, frame: fits.walton(frame))


def fit_restitution(model: str = "exponential", db: Any = None, **filters: Any) -> Any:
    """e against the normal Stokes number for the immersed runs of each pair (figure 5);
    ``model`` is "threshold" or "exponential".

    >>> import granudb
    >>> granudb.fit_restitution("exponential", db=db).empty
    True
    """
    from granudb.analysis import fits

    return _fit(db, filters, lambda _session, frame: fits.restitution(frame, model))


def fit_gap_viscosity(db: Any = None, **filters: Any) -> Any:
    """The gap viscosity μ₀ that (5.8) needs to match the measured sliding friction, and
    the gap temperature it implies through the fluid's μ(T) (figure 14, table 2).

    >>> import granudb
    >>> granudb.fit_gap_viscosity(db=db).empty
    True
    """
    from granudb.analysis import fits
    from granudb.analysis.fluid_state import fluid_model
    from granudb.db import catalog

    def run(session: Any, frame: Any) -> Any:
        models = {f.name: fluid_model(f) for f in catalog.list_fluids(session)}
        return fits.gap_viscosity(frame, models)

    return _fit(db, filters, run)
