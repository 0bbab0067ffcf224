"""The paper's fits on stored runs: ``granudb fit walton|restitution|gap-viscosity`` are
``fit_walton``, ``fit_restitution`` and ``fit_gap_viscosity``. Each takes the collision
filters of ``granudb.collisions`` and returns one row per group (dataset × particle ×
wall × fluid) with the keys documented in ``granudb.analysis.fits``: a DataFrame, or a
list of records with ``as_frame=False``.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from granudb.analysis import fits
from granudb.api import inputs
from granudb.api.collision_listing import collision_query
from granudb.api.database import opened
from granudb.errors import ValidationError
from granudb.lazy import pandas as pd
from granudb.output_files import write_text
from granudb.scenario.collisions import select_collisions
from granudb.scenario.plug_ins import fluid_curves, gap_scale, stokes_scale
from granudb.vocabulary.escaping import spreadsheet_frame

#: The forms of e(St_n) ``fit_restitution`` fits.
RESTITUTION_MODELS = tuple(fits.RESTITUTION_MODELS)
#: How the Walton and restitution fits state their uncertainty (``method``).
FIT_METHODS = fits.FIT_METHODS


def _method(method: str | None, draws: Any) -> str:
    """The method asked (the bootstrap when None); a draws file only with "bayes"."""
    chosen = fits.DEFAULT_METHOD if method is None else inputs.choice(method, FIT_METHODS, "method")
    if draws is not None and chosen != "bayes":
        raise ValidationError(
            "draws",
            str(draws),
            "posterior draws need method bayes (--method bayes)",
            parameter=True,
        )
    return chosen


def _fit(
    db: Any, filters: dict[str, Any], as_frame: bool, run: Callable[..., Any], draws: Any = None
) -> Any:
    """Run a fit on the selected runs; with a ``draws`` list in ``run``'s closure, the
    posterior draws go to ``frame.attrs["draws"]`` and, when ``draws`` is a path, to that
    CSV file (a new file: an existing one is refused)."""
    query = collision_query(**filters)
    found: list[Any] = []
    with opened(db) as database, database.session() as session:
        rows = run(session, select_collisions(session, query), found)
    table = pd.concat(found, ignore_index=True) if found else None
    if draws is not None:
        frame = spreadsheet_frame(table if table is not None else pd.DataFrame())
        text = frame.to_csv(index=False)  # for spreadsheets: no text cell runs as a formula
        write_text(Path(draws), text, field="draws")
    if not as_frame:
        return rows
    frame = pd.DataFrame.from_records(rows)
    if table is not None:
        frame.attrs["draws"] = table
    return frame


def fit_walton(
    db: Any = None,
    *,
    as_frame: bool = True,
    method: str | None = None,
    draws: str | Path | None = None,
    **filters: Any,
) -> Any:
    """Walton's β (sticking) and μ_f (sliding) with ē per group (Joseph & Hunt figures 4,
    6, 9), each with its bootstrap interval and the model chosen; ``filters`` as
    ``granudb.collisions``. ``method="bayes"``: posterior medians and 95 % credible
    intervals (emcee; priors, sampler settings and convergence in every row), the
    posterior draws (chain, draw, one column per parameter) in ``frame.attrs["draws"]``
    and, with ``draws`` a new file's path, written there as CSV.

    Examples
    --------
    >>> import granudb
    >>> granudb.fit_walton(db=db, fluid="dry").empty  # no runs stored yet
    True
    >>> granudb.fit_walton(db=db, method="bayes").empty
    True
    """
    chosen = _method(method, draws)
    return _fit(
        db,
        filters,
        as_frame,
        lambda _session, frame, found: fits.walton(frame, method=chosen, draws=found),
        draws,
    )


def fit_restitution(
    model: str | None = None,
    db: Any = None,
    *,
    as_frame: bool = True,
    method: str | None = None,
    draws: str | Path | None = None,
    **filters: Any,
) -> Any:
    """e against the normal Stokes number for the immersed runs of each pair (figure 5):
    ``model`` "exponential" (e = e_dry exp(−k/St_n), Legendre et al. 2006; the default)
    or "threshold" (e = e_dry (1 − St_c/St_n)). ``method`` and ``draws`` as
    ``fit_walton``.

    Examples
    --------
    >>> import granudb
    >>> granudb.fit_restitution(db=db).empty
    True
    >>> granudb.fit_restitution(db=db, method="bayes").empty
    True
    """
    chosen = None if model is None else inputs.choice(model, RESTITUTION_MODELS, "model")
    how = _method(method, draws)
    return _fit(
        db,
        filters,
        as_frame,
        lambda session, frame, found: fits.restitution(
            frame, chosen, method=how, draws=found, stokes_scale=stokes_scale(session, frame)
        ),
        draws,
    )


def fit_gap_viscosity(db: Any = None, *, as_frame: bool = True, **filters: Any) -> Any:
    """The gap viscosity μ₀ that (5.8) needs to match the measured sliding friction, and
    the gap temperature it implies through the fluid's μ(T) (figure 14, table 2).

    Examples
    --------
    >>> import granudb
    >>> granudb.fit_gap_viscosity(db=db).empty
    True
    """

    def run(session: Any, frame: Any, _draws: list[Any]) -> Any:
        models, curves = fluid_curves(session.connection())
        return fits.gap_viscosity(frame, models, gap_scale=gap_scale(session, frame),
                                  curves=curves)  # fmt: skip

    return _fit(db, filters, as_frame, run)
