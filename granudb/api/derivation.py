"""``granudb.derive()``: every derived column for a table of your own."""

from __future__ import annotations

from typing import Any


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

    from granudb.analysis.refusals import physics_refusal
    from granudb.errors import ValidationError
    from granudb.physics.derive import derive as derive_arrays
    from granudb.vocabulary.listings import units_of

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
