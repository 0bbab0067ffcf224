"""DEM reproduction of a published oblique-impact sweep (Kharaz et al.'s e_t(θ)).

``oblique_sweep`` builds the one-pair model a reference dataset states (sphere and wall
constants, e and μ_f), runs a sphere on a flat wall at each incidence angle in each
installed code (``granudb.dem.verify``: the exported deck, a temporary directory, the
rebound read back) and turns each code's rebound into e_t by the exact no-spin-in relation
of ``granudb.physics.reported`` (e_t = (Ψ_out/Ψ_in + 1/K²)/(1 + 1/K²)). A code that is not
installed gives rows with status "not checked" and no e_t, never a pass.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from granudb.dem import verify
from granudb.dem.runs import Case
from granudb.dem.spec import DemModel, PairParameters, ParticleType, Value
from granudb.physics import reported

SPHERE, WALL = "sphere", "wall"


def model(conditions: dict[str, float], provenance: str) -> DemModel:
    """The one-pair model of a dataset's ``conditions`` (SI, granudb's names). A flat
    wall's density enters no contact law (its mass is infinite): the sphere's is written."""
    sphere = ParticleType(
        SPHERE,
        conditions["sphere_youngs_modulus_pa"],
        conditions["sphere_poisson_ratio"],
        conditions["sphere_density_kg_m3"],
        conditions["diameter_m"],
    )
    wall = ParticleType(
        WALL,
        conditions["wall_youngs_modulus_pa"],
        conditions["wall_poisson_ratio"],
        conditions["sphere_density_kg_m3"],
        None,
        is_wall=True,
    )
    e = Value(conditions["normal_restitution"], provenance)
    mu = Value(conditions["sliding_friction"], provenance)
    pairs = [PairParameters(SPHERE, WALL, e, mu), PairParameters(SPHERE, SPHERE, e, mu)]
    return DemModel([sphere, wall], pairs, conditions["impact_speed_m_s"])


def oblique_sweep(
    conditions: dict[str, float],
    angles_deg: Sequence[float],
    codes: Sequence[str],
    provenance: str,
) -> list[dict[str, Any]]:
    """One row per code and angle: e_t, e and spin the code gives, its status and note."""
    dem = model(conditions, provenance)
    speed = conditions["impact_speed_m_s"]
    cases = [Case(SPHERE, WALL, speed, float(a)) for a in angles_deg]
    rows = []
    for record in verify.verify(dem, cases, codes=tuple(codes)):
        e_t = math.nan
        if record.psi_in and record.psi_out is not None:
            e_t = float(reported.tangential_restitution_from_rebound(record.psi_in, record.psi_out))
        rows.append(
            {
                "code": record.code,
                "angle_deg": record.angle_deg,
                "status": record.status,
                "tangential_restitution": e_t,
                "normal_restitution": record.achieved_e,
                "note": record.note or record.reason,
            }
        )
    return rows
