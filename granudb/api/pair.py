"""``granudb.pair``: what happens when this particle hits that wall in this fluid."""

from __future__ import annotations

from typing import Any

from granudb.api import inputs
from granudb.api.database import opened


def pair(
    particle: str,
    wall: str,
    *,
    diameter: float | str,
    velocity: float | str,
    angle: float | str = 0.0,
    fluid: str | None = None,
    temperature: float | str | None = None,
    viscosity: float | str | None = None,
    wall_diameter: float | str | None = None,
    critical_stokes: float = 10.0,
    db: Any = None,
) -> dict[str, Any]:
    """Properties, every derived quantity and the verdicts for one collision (SI).

    Quantities are SI numbers or strings with units (``"12.7 mm"``, ``"0.3 m/s"``,
    ``"30 deg"``, ``"20 degC"``, ``"0.8 cP"``); ``fluid=None`` or ``"dry"`` is a dry
    collision; ``viscosity`` overrides the fluid's (what-if). The result is the document
    ``granudb pair --format json`` prints: derived values at the top level under the
    vocabulary's names, the inputs, the particle, wall and fluid with their sources.

    >>> import granudb
    >>> result = granudb.pair("steel", "Zerodur", fluid="glycerol-37", diameter="12.7 mm",
    ...                       velocity="0.3 m/s", angle="30 deg", db=db)
    >>> round(result["reduced_modulus_pa"] / 1e9, 2)
    65.64
    """
    from granudb.analysis.pair import derive_pair, is_dry, pair_json
    from granudb.errors import ValidationError

    if is_dry(fluid):
        for name, given in (("viscosity", viscosity), ("temperature", temperature)):
            if given is not None:
                raise ValidationError(
                    name, given, "needs a fluid (a dry collision has none)", parameter=True
                )
    values = {
        "diameter_m": inputs.quantity(diameter, "diameter_m", "diameter"),
        "speed_m_s": inputs.quantity(velocity, "impact_speed_m_s", "velocity"),
        "angle_rad": inputs.angle(angle),
        "temperature_c": inputs.quantity(temperature, "temperature_c", "temperature"),
        "viscosity_pa_s": inputs.quantity(viscosity, "viscosity_pa_s", "viscosity"),
        "wall_diameter_m": inputs.quantity(wall_diameter, "wall_diameter_m", "wall_diameter"),
    }
    with opened(db) as database, database.reading() as connection:
        result = derive_pair(
            connection, particle, wall, fluid=fluid, critical_stokes=critical_stokes, **values
        )
    return pair_json(result)
