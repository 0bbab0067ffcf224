"""The paper's fits on stored runs: ``granudb fit walton|restitution|gap-viscosity`` are
``fit_walton``, ``fit_restitution`` and ``fit_gap_viscosity``. Each takes the collision
filters of ``granudb.collisions`` and returns one row per group (dataset × particle ×
wall × fluid) with the keys documented in ``granudb.analysis.fits``: a DataFrame, or a
list of records with ``as_frame=False``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from granudb.analysis import fits
from granudb.analysis.collisions import select_collisions
from granudb.analysis.fluid_state import fluid_model
from granudb.analysis.restitution_fit import DEFAULT_MODEL
from granudb.api import inputs
from granudb.api.collision_listing import collision_query
from granudb.api.database import opened
from granudb.db import catalog_rows
from granudb.lazy import pandas as pd

#: The forms of e(St_n) ``fit_restitution`` fits.
RESTITUTION_MODELS = tuple(fits.RESTITUTION_MODELS)


def _fit(db: Any, filters: dict[str, Any], as_frame: bool, run: Callable) -> Any:
    query = collision_query(**filters)
    with opened(db) as database, database.session() as session:
        rows = run(session, select_collisions(session, query))
    return pd.DataFrame.from_records(rows) if as_frame else rows


def fit_walton(db: Any = None, *, as_frame: bool = True, **filters: Any) -> Any:
    """Walton's β (sticking) and μ_f (sliding) with ē per group (Joseph & Hunt figures 4,
    6, 9), each with its bootstrap interval and the model chosen; ``filters`` as
    ``granudb.collisions``.

    Examples
    --------
    >>> import granudb
    >>> granudb.fit_walton(db=db, fluid="dry").empty  # no runs stored yet
    True
    """
    return _fit(db, filters, as_frame, lambda _session, frame: fits.walton(frame))


def fit_restitution(
    model: str | None = None, db: Any = None, *, as_frame: bool = True, **filters: Any
) -> Any:
    """e against the normal Stokes number for the immersed runs of each pair (figure 5):
    ``model`` "exponential" (e = e_dry exp(−k/St_n), Legendre et al. 2006; the default)
    or "threshold" (e = e_dry (1 − St_c/St_n)).

    Examples
    --------
    >>> import granudb
    >>> granudb.fit_restitution(db=db).empty
    True
    """
    chosen = DEFAULT_MODEL if model is None else inputs.choice(model, RESTITUTION_MODELS, "model")
    return _fit(db, filters, as_frame, lambda _session, frame: fits.restitution(frame, chosen))


def fit_gap_viscosity(db: Any = None, *, as_frame: bool = True, **filters: Any) -> Any:
    """The gap viscosity μ₀ that (5.8) needs to match the measured sliding friction, and
    the gap temperature it implies through the fluid's μ(T) (figure 14, table 2).

    Examples
    --------
    >>> import granudb
    >>> granudb.fit_gap_viscosity(db=db).empty
    True
    """

    def run(session: Any, frame: Any) -> Any:
        rows = catalog_rows.fluid_rows(session.connection())
        return fits.gap_viscosity(frame, {f.name: fluid_model(f) for f in rows})

    return _fit(db, filters, as_frame, run)
