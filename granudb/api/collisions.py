"""``granudb.collisions()``: measured collisions with every derived column, and
``granudb.derive()`` for a table of your own."""

from __future__ import annotations

from typing import Any

from granudb.api import _inputs
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
        angle_range=_inputs.angle_range(angle_range),
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


def derive(frame: Any, **options: Any) -> Any:
    """Every derived column for a DataFrame of your own collisions or scenarios.

    ``frame`` has the SI input columns of ``granudb.physics.derive.derive`` (e.g.
    ``particle_density_kg_m3``, ``wall_youngs_modulus_pa``, ``diameter_m``,
    ``v_n_in_m_s``; missing optional ones default as there); ``options`` are its keyword
    options (``critical_stokes``). Returns a copy with the derived columns added.

    >>> import granudb, pandas as pd
    >>> scenarios = pd.DataFrame({
    ...     "particle_density_kg_m3": [7780.0], "particle_youngs_modulus_pa": [190e9],
    ...     "particle_poisson_ratio": [0.27], "particle_roughness_rms_m": [23.6e-9],
    ...     "wall_density_kg_m3": [2540.0], "wall_youngs_modulus_pa": [91e9],
    ...     "wall_poisson_ratio": [0.24], "wall_roughness_rms_m": [15.5e-9],
    ...     "diameter_m": [0.0127], "v_n_in_m_s": [0.3]})
    >>> round(float(granudb.derive(scenarios)["reduced_modulus_pa"][0]) / 1e9, 2)
    65.64
    """
    import inspect

    from granudb.analysis._errors import physics_refusal
    from granudb.analysis.collisions import units_of
    from granudb.errors import ValidationError
    from granudb.physics.derive import derive as derive_arrays

    accepted = set(inspect.signature(derive_arrays).parameters)
    unknown = sorted(set(options) - accepted)
    if unknown:
        raise ValidationError(unknown[0], options[unknown[0]], "is not an option of derive")
    inputs = {c: frame[c].to_numpy(dtype=float) for c in frame.columns if c in accepted}
    with physics_refusal():
        derived = derive_arrays(**inputs, **options)
    out = frame.copy()
    for name, values in derived.items():
        out[name] = values
    out.attrs["units"] = units_of(out.columns)
    return out
