"""``granudb.collisions()``: measured collisions with every derived column."""

from __future__ import annotations

from typing import Any

from granudb.api import inputs
from granudb.api.database import opened


def collision_query(
    *,
    dataset: str | None = None,
    version: str | None = None,
    particle: str | None = None,
    wall: str | None = None,
    fluid: str | None = None,
    min_normal_stokes: float | None = None,
    max_normal_stokes: float | None = None,
    angle_range: Any = None,
    regime: str | None = None,
    roughness_exceeds_gap: bool | None = None,
    rebound_expected: bool | None = None,
    critical_stokes: float = 10.0,
) -> Any:
    """The ``CollisionQuery`` for these filters (``angle_range`` as ``"20..60 deg"`` or a
    pair of angles), checked; shared by the command line and the Python API."""
    from granudb.analysis.collisions import CollisionQuery

    query = CollisionQuery(
        dataset=dataset,
        version=version,
        particle=particle,
        wall=wall,
        fluid=fluid,
        min_normal_stokes=min_normal_stokes,
        max_normal_stokes=max_normal_stokes,
        angle_range=inputs.angle_range(angle_range),
        regime=regime,
        roughness_exceeds_gap=roughness_exceeds_gap,
        rebound_expected=rebound_expected,
        critical_stokes=critical_stokes,
    )
    query.check()
    return query


def collisions(db: Any = None, **filters: Any) -> Any:
    """Measured collisions with every derived column, as a pandas DataFrame (SI, units in
    ``attrs["units"]``).

    ``filters`` are those of ``granudb collisions list``: dataset, version, particle,
    wall, fluid ("dry" for dry runs), min_normal_stokes, max_normal_stokes, angle_range
    (``"20..60 deg"``: ζ_in of the contact point's path), regime (stick,
    slip_then_stick, gross_slip), roughness_exceeds_gap, rebound_expected,
    critical_stokes.

    >>> import granudb
    >>> granudb.collisions(db=db, fluid="dry").empty
    True
    """
    from granudb.analysis.collisions import select_collisions

    query = collision_query(**filters)
    with opened(db) as database, database.session() as session:
        return select_collisions(session, query)
