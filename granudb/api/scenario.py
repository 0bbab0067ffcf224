"""``granudb.pair``: what happens when this particle hits that wall in this fluid."""

from __future__ import annotations

from typing import Any

from granudb.api import inputs
from granudb.api.database import opened
from granudb.errors import ValidationError
from granudb.reporting.format import display
from granudb.reporting.values import interval_text, method_text, qualified_value
from granudb.reporting.verdicts import verdicts
from granudb.scenario.pair import TARGET_WORDS, TARGETS, derive_pair, is_dry, pair_json

__all__ = ["interval_text", "method_text", "pair", "qualified_value"]


#: The options of one collision scenario (``pair``), written once for Python and the
#: command line; ``diameter`` and ``velocity`` are required, the others' defaults are
#: ``pair``'s.
SCENARIO_OPTIONS = dict.fromkeys(
    ("diameter", "velocity", "angle", "fluid", "temperature", "viscosity", "wall_diameter",
     "target", "critical_stokes")
)  # fmt: skip


@inputs.shows_keywords(SCENARIO_OPTIONS)
def pair(particle: str, wall: str, *, db: Any = None, **scenario: Any) -> dict[str, Any]:
    """Properties, every derived quantity and the verdicts for one collision (SI).

    Quantities are SI numbers or strings with units (``"12.7 mm"``, ``"0.3 m/s"``,
    ``"30 deg"``, ``"20 degC"``, ``"0.8 cP"``); diameter, velocity, temperature and
    viscosity may carry a standard uncertainty (``"0.3 m/s ± 3 %"``, ``"20 degC ± 0.5
    K"``, or a ``(value, u)`` pair), which is propagated with the materials' and the
    fluid's stored ones into ``u_<quantity>`` of each derived value and the verdicts'
    probabilities (``probability_asperity_contact``, ``probability_rebound``,
    ``probability_yield``); ``diameter`` and ``velocity`` are
    required, ``angle`` is 0 unless given; ``fluid=None`` or ``"dry"`` is a dry collision;
    ``viscosity`` overrides the fluid's (what-if); ``wall_diameter`` makes the target a
    sphere, free and at rest unless ``target="fixed"`` (``"wall"``, ``"fixed"``,
    ``"free"``; echoed in ``inputs``); ``critical_stokes`` is St_c of the
    rebound verdict (default 10). The result is the document ``granudb pair --format
    json`` prints: derived values at the top level under the vocabulary's names, the
    inputs, the particle, wall and fluid with their sources, and ``verdicts`` (each with
    its key, title, sentence and whether it is raised as a warning).

    Examples
    --------
    >>> import granudb
    >>> result = granudb.pair("steel", "Zerodur", fluid="glycerol-37", diameter="12.7 mm",
    ...                       velocity="0.3 m/s", angle="30 deg", db=db)
    >>> round(result["reduced_modulus_pa"] / 1e9, 2)
    65.64
    """
    given = {
        **SCENARIO_OPTIONS,
        **inputs.known_options(scenario, SCENARIO_OPTIONS, "an option of pair"),
    }
    (diameter, velocity, angle, fluid, temperature, viscosity, wall_diameter, target,
     critical_stokes) = (given[k] for k in SCENARIO_OPTIONS)  # fmt: skip
    particle = inputs.text(particle, "particle")
    wall = inputs.text(wall, "wall")
    if fluid is not None:
        fluid = inputs.text(fluid, "fluid")
    if is_dry(fluid):
        for name, given in (("viscosity", viscosity), ("temperature", temperature)):
            if given is not None:
                raise ValidationError(
                    name, given, "needs a fluid (a dry collision has none)", parameter=True
                )
    for name, given in (("diameter", diameter), ("velocity", velocity)):
        if given is None:
            raise inputs.missing(name)
    st_c = 10.0 if critical_stokes is None else inputs.critical_stokes(critical_stokes)
    # each may carry its standard uncertainty: "12.7 ± 0.01 mm", "0.3 m/s ± 3 %"
    d, u_d = inputs.uncertain_quantity(diameter, "diameter_m", "diameter")
    speed, u_speed = inputs.uncertain_quantity(velocity, "impact_speed_m_s", "velocity")
    t, u_t = inputs.uncertain_quantity(temperature, "temperature_c", "temperature")
    mu, u_mu = inputs.uncertain_quantity(viscosity, "viscosity_pa_s", "viscosity")
    values: dict[str, Any] = {
        "diameter_m": d,
        "speed_m_s": speed,
        "angle_rad": inputs.angle(0.0 if angle is None else angle),
        "temperature_c": t,
        "viscosity_pa_s": mu,
        "wall_diameter_m": inputs.quantity(wall_diameter, "wall_diameter_m", "wall_diameter"),
    }
    uncertain = {
        "u_diameter_m": u_d,
        "u_impact_speed_m_s": u_speed,
        "u_temperature_c": u_t,
        "u_viscosity_pa_s": u_mu,
    }
    if target is not None:
        target = inputs.choice(target, TARGETS, "target")
    with opened(db) as database, database.reading() as connection:
        result = derive_pair(
            connection,
            particle,
            wall,
            fluid=fluid,
            critical_stokes=st_c,
            target=target,
            uncertainties=uncertain,
            **values,
        )
    document = pair_json(result)
    said = verdicts(
        document,
        st_c,
        immersed=document["fluid"] is not None,
        materials=(document["particle"], document["wall"]),
        fluid_name=document["fluid"]["name"] if document["fluid"] else None,
        dry=document["dry_values"],
    )
    document["critical_stokes"] = st_c
    document["verdicts"] = [
        {"key": v.key, "title": v.name, "text": v.text, "raised": v.raised} for v in said
    ]
    return document


def target_words(scenario_inputs: dict[str, Any]) -> str:
    """What a scenario's particle hits, in words, with a sphere's diameter: "flat wall",
    "free sphere at rest, d = 12.7 mm"."""
    words = TARGET_WORDS[scenario_inputs["target"]]
    diameter = scenario_inputs.get("wall_diameter_m")
    return words if diameter is None else f"{words}, d = {display(diameter, 'diameter_m')}"
