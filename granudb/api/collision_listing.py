"""``granudb.collisions()``: measured collisions with every derived column, and the
collision filters every listing, fit and report takes.

The filters are the fields of ``granudb.scenario.collisions.CollisionQuery`` (dataset,
version, particle, wall, fluid, min_normal_stokes, max_normal_stokes, angle_range,
regime, roughness_exceeds_gap, rebound_expected, critical_stokes), named once there and
checked once here (``collision_query``); the command line's options are the same names
with dashes.
"""

from __future__ import annotations

import difflib
import re
from typing import Any

from granudb.api import inputs
from granudb.api.database import opened
from granudb.db import lookup_rows
from granudb.errors import ValidationError
from granudb.reporting.pinned import announce_pinned
from granudb.scenario.collision_query import COLLISION_FILTERS, TANGENTIAL_REGIMES, CollisionQuery
from granudb.scenario.collisions import select_collisions
from granudb.vocabulary.listings import COLLISION_NARROW

#: The collision filters, in the order help texts list them.
_TEXT_FILTERS = ("dataset", "version", "particle", "wall", "fluid")
_FLAG_FILTERS = ("roughness_exceeds_gap", "rebound_expected")


def collision_query(**filters: Any) -> CollisionQuery:
    """The ``CollisionQuery`` for these filters, each checked and named on refusal
    (``angle_range`` as ``"20..60 deg"`` or a pair of angles; ``None``: any)."""
    unknown = sorted(set(filters) - set(COLLISION_FILTERS))
    if unknown:
        name = unknown[0]
        close = difflib.get_close_matches(name, COLLISION_FILTERS, n=1)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        raise ValidationError(
            name,
            filters[name],
            f"is not a collision filter (filters: {', '.join(COLLISION_FILTERS)}){hint}",
            parameter=True,
        )
    given: dict[str, Any] = {}
    for name in _TEXT_FILTERS:
        if filters.get(name) is not None:
            given[name] = inputs.text(filters[name], name)
    if "dataset" in given:  # NAME@VERSION, as every --dataset that reads accepts it
        given["dataset"], version = inputs.dataset_ref(given["dataset"], given.get("version"))
        if version is not None:
            given["version"] = version
    for name in ("min_normal_stokes", "max_normal_stokes"):
        if filters.get(name) is not None:
            given[name] = inputs.quantity(filters[name], "normal_stokes_number", name)
    if filters.get("angle_range") is not None:
        given["angle_range"] = inputs.angle_range(filters["angle_range"])
    if filters.get("regime") is not None:
        given["regime"] = inputs.choice(filters["regime"], TANGENTIAL_REGIMES, "regime")
    for name in _FLAG_FILTERS:
        if filters.get(name) is not None:
            given[name] = inputs.flag(filters[name], name)
    if filters.get("critical_stokes") is not None:
        given["critical_stokes"] = inputs.critical_stokes(filters["critical_stokes"])
    query = CollisionQuery(**given)
    query.check()
    return query


def natural_key(label: object) -> tuple[Any, ...]:
    """Sort run labels as people count: run-2 before run-10."""
    parts = re.split(r"(\d+)", str(label))
    return tuple((0, int(p), "") if p.isdigit() else (1, 0, p.casefold()) for p in parts)


def chosen_columns(columns: Any, wide: bool, available: list[str]) -> list[str]:
    """The columns to show, the same in every format: the default listing, every column
    (``wide``), or ``columns`` (a list, or text "a,b,c" of machine names)."""
    if columns is None:
        return available if wide else COLLISION_NARROW
    if isinstance(columns, str):
        chosen = [c.strip() for c in columns.split(",") if c.strip()]
    elif isinstance(columns, list | tuple) and all(isinstance(c, str) for c in columns):
        chosen = list(columns)
    else:
        raise ValidationError(
            "columns", repr(columns)[:60], "must be a list of column names", parameter=True
        )
    unknown = [c for c in chosen if c not in available]
    if unknown or not chosen:
        raise ValidationError(
            "columns",
            ", ".join(unknown) or str(columns),
            f"are not columns of the listing (known: {', '.join(available)})",
            parameter=True,
        )
    return chosen


def collisions(
    db: Any = None,
    *,
    columns: Any = None,
    wide: bool = False,
    as_frame: bool = True,
    **filters: Any,
) -> Any:
    """Measured collisions with e, β, Ψ_in, μ_f (2.9), St_n, Λ and Maw's regime, one row
    per run, sorted by dataset, version and run (run-2 before run-10): a DataFrame (SI,
    units in ``attrs["units"]``), or a list of records with ``as_frame=False``.

    ``columns`` picks columns (a list, or "a,b,c"), ``wide=True`` gives every derived
    column; the default is the listing's (``granudb collisions list``). ``filters`` are
    the collision filters (``COLLISION_FILTERS``): dataset, version, particle, wall, fluid
    ("dry" for dry runs), min_normal_stokes, max_normal_stokes, angle_range (``"20..60
    deg"``: ζ_in of the contact point's path), regime (stick, slip_then_stick,
    gross_slip), roughness_exceeds_gap, rebound_expected, critical_stokes.

    Examples
    --------
    >>> import granudb
    >>> granudb.collisions(db=db, fluid="dry").empty
    True
    """
    query = collision_query(**filters)
    with opened(db) as database, database.session() as session:
        frame = select_collisions(session, query)
        if not frame.empty:  # a release's runs: say what it pins that has changed since
            connection = session.connection()
            pinned = lookup_rows.single_dataset_id(connection, frame)
            ref = f"{frame['dataset'].iat[0]}@{frame['version'].iat[0]}"
            announce_pinned(connection, pinned, ref)
    shown = chosen_columns(columns, wide, list(frame.columns))
    if not frame.empty:
        order = sorted(
            range(len(frame)),
            key=lambda i: (
                frame["dataset"].iat[i],
                frame["version"].iat[i],
                natural_key(frame["run"].iat[i]),
            ),
        )
        frame = frame.iloc[order].reset_index(drop=True)
    units = frame.attrs.get("units", {})
    frame = frame[shown]
    frame.attrs["units"] = {c: u for c, u in units.items() if c in shown}
    return frame if as_frame else frame.to_dict("records")
