"""One scenario: a particle of a given size hits a wall (or a second sphere), in a fluid or
dry, at a speed and an angle, without spin: every derived quantity and verdict.

Inputs are SI floats; ``granudb.pair`` also accepts strings with units. Errors name
the Python parameters (``velocity``); the command line shows them as its options.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from sqlalchemy.engine import Connection

from granudb.db import catalog_rows
from granudb.errors import ValidationError
from granudb.physics.derive import derive, scalar_view
from granudb.scenario.dry_values import DryValues, provenance_keys, resolve
from granudb.scenario.fluid_state import FluidState, fluid_state, state_uncertainty
from granudb.scenario.refusals import physics_refusal

if TYPE_CHECKING:
    from sqlalchemy.orm import Session

    from granudb.db.catalog_rows import MaterialRow
    from granudb.db.models import Material

#: Per-collision parameters that need a measured rebound: a scenario has none.
MEASURED_ONLY = (
    "normal_restitution",
    "rotational_restitution",
    "effective_rebound",
    "sliding_friction",
)


def material_inputs(prefix: str, material: Material | MaterialRow) -> dict[str, Any]:
    """A material's stored properties as ``derive()`` keyword arguments."""
    return {
        f"{prefix}_density_kg_m3": material.density_kg_m3,
        f"{prefix}_youngs_modulus_pa": material.youngs_modulus_pa,
        f"{prefix}_poisson_ratio": material.poisson_ratio,
        # not stated: NaN, so every σ-dependent quantity is NaN (docs/physics.md §18)
        f"{prefix}_roughness_rms_m": (
            np.nan if material.roughness_rms_m is None else material.roughness_rms_m
        ),
        f"{prefix}_shear_modulus_pa": (
            np.nan if material.shear_modulus_pa is None else material.shear_modulus_pa
        ),
        f"{prefix}_yield_stress_pa": (
            np.nan if material.yield_stress_pa is None else material.yield_stress_pa
        ),
    }


def material_uncertainties(prefix: str, material: Material | MaterialRow) -> dict[str, float]:
    """A material's stored standard uncertainties as ``derive()``'s ``uncertainties``
    (``u_particle_youngs_modulus_pa``, …); properties without one are left out."""
    out = {}
    for column in ("density_kg_m3", "youngs_modulus_pa", "poisson_ratio", "roughness_rms_m",
                   "yield_stress_pa"):  # fmt: skip
        u = getattr(material, f"u_{column}", None)
        if u is not None:
            out[f"u_{prefix}_{column}"] = u
    return out


@dataclass
class PairResult:
    """Everything ``granudb pair`` shows: inputs, properties with sources, derived values."""

    particle: dict[str, Any]
    wall: dict[str, Any]
    fluid: dict[str, Any] | None
    fluid_state: FluidState | None
    inputs: dict[str, Any]
    derived: dict[str, Any]
    dry: DryValues
    citations: dict[str, str] = field(default_factory=dict)
    #: The same sources as stored rows (citation and DOI), for a report's references.
    cited_sources: dict[str, Any] = field(default_factory=dict)


def is_dry(fluid: str | None) -> bool:
    """``None`` and ``"dry"`` (any case) both mean a dry collision, everywhere."""
    return fluid is None or fluid.strip().casefold() == "dry"


#: What the particle hits: a flat wall (R₂ = m₂ = ∞), a fixed sphere (R₂ finite, m₂ = ∞)
#: or a free sphere at rest (both finite), docs/physics.md §9.
TARGETS = ("wall", "fixed", "free")
TARGET_WORDS = {"wall": "flat wall", "fixed": "fixed sphere", "free": "free sphere at rest"}


def target_kind(target: str | None, wall_diameter_m: float | None) -> str:
    """The one rule for what a scenario's target is: a second sphere's diameter makes it a
    sphere, free unless ``target`` says fixed; without one it is a flat wall."""
    if target is None:
        return "wall" if wall_diameter_m is None else "free"
    if target not in TARGETS:
        raise ValidationError(
            "target", target, f"must be one of {', '.join(TARGETS)}", parameter=True
        )
    if target == "wall" and wall_diameter_m is not None:
        raise ValidationError(
            "target", target, "is a flat wall, which has no wall_diameter", parameter=True
        )
    if target != "wall" and wall_diameter_m is None:
        raise ValidationError(
            "target", target, "is a sphere: give its wall_diameter", parameter=True
        )
    return target


def _check_scenario(
    diameter_m: float, speed_m_s: float, angle_rad: float, critical_stokes: float
) -> None:
    if not (math.isfinite(diameter_m) and diameter_m > 0):
        raise ValidationError("diameter", f"{diameter_m:g} m", "must be > 0", parameter=True)
    if not (math.isfinite(speed_m_s) and speed_m_s > 0):
        raise ValidationError("velocity", f"{speed_m_s:g} m/s", "must be > 0", parameter=True)
    if not 0.0 <= angle_rad < math.pi / 2:
        raise ValidationError(
            "angle", f"{math.degrees(angle_rad):g} deg", "must be ≥ 0° and < 90°", parameter=True
        )
    if not (math.isfinite(critical_stokes) and critical_stokes > 0):
        raise ValidationError(
            "critical_stokes", f"{critical_stokes:g}", "must be > 0", parameter=True
        )


def derive_pair(
    reader: Connection | Session,
    particle: str,
    wall: str,
    *,
    diameter_m: float,
    speed_m_s: float,
    angle_rad: float = 0.0,
    fluid: str | None = None,
    temperature_c: float | None = None,
    viscosity_pa_s: float | None = None,
    wall_diameter_m: float | None = None,
    target: str | None = None,
    critical_stokes: float = 10.0,
    dataset_id: int | None = None,
    uncertainties: dict[str, float | None] | None = None,
) -> PairResult:
    """Derive one scenario: ``particle`` hits ``wall`` (in ``fluid``) at ``speed_m_s``,
    ``angle_rad`` from the normal, without spin. The target is a flat wall, or with
    ``wall_diameter_m`` a sphere, free and at rest unless ``target`` is "fixed"
    (``target_kind``); m*, R*, the Walton factor, Hertz, the Stokes and Reynolds numbers
    and the predicted e are those of that target. ``reader`` is a Core connection
    (``Database.reading()``, no ORM needed: issue 17's start-up bound) or a session.
    With ``dataset_id`` the materials and fluid are read as that dataset's runs use them
    (a release keeps the values it was released with).

    ``uncertainties``: standard uncertainties of the scenario's inputs (``u_diameter_m``,
    ``u_impact_speed_m_s``, ``u_temperature_c``, ``u_viscosity_pa_s``; None: not
    given); with the materials' and the fluid's stored ones they are propagated into
    ``u_<column>`` of every derived quantity and the verdict probabilities
    (``granudb.physics.uncertainty``). The speed's u is one source for v_n and v_t;
    one material on both sides is one source.
    """
    given_u = {k: v for k, v in (uncertainties or {}).items() if v is not None}
    _check_scenario(diameter_m, speed_m_s, angle_rad, critical_stokes)
    target = target_kind(target, wall_diameter_m)
    if is_dry(fluid):
        for name, value in (("viscosity", viscosity_pa_s), ("temperature", temperature_c)):
            if value is not None:
                raise ValidationError(
                    name, f"{value:g}", "needs a fluid (a dry collision has none)", parameter=True
                )
    connection = reader if isinstance(reader, Connection) else reader.connection()
    first = catalog_rows.get_material_row(connection, particle, dataset_id)
    second = catalog_rows.get_material_row(connection, wall, dataset_id)
    fluid_row = (
        None
        if fluid is None or is_dry(fluid)
        else catalog_rows.get_fluid_row(connection, fluid, dataset_id)
    )
    state = fluid_state(fluid_row, temperature_c, viscosity_pa_s) if fluid_row else None
    u_viscosity, u_density = (
        state_uncertainty(
            fluid_row,
            state,
            given_u.get("u_temperature_c"),
            given_u.get("u_viscosity_pa_s"),
            viscosity_given=viscosity_pa_s is not None,
        )
        if fluid_row is not None and state is not None
        else (None, None)
    )
    speed_u = given_u.get("u_impact_speed_m_s")
    propagated = {
        **material_uncertainties("particle", first),
        **material_uncertainties("wall", second),
        "u_diameter_m": given_u.get("u_diameter_m"),
        "u_v_n_in_m_s": None if speed_u is None else speed_u * math.cos(angle_rad),
        "u_v_t_in_m_s": None if speed_u is None else speed_u * math.sin(angle_rad),
        "u_viscosity_pa_s": u_viscosity,
        "u_fluid_density_kg_m3": u_density,
    }
    if (
        state is not None
        and fluid_row is not None
        and fluid_row.u_pressure_viscosity_pa_inv is not None
    ):
        propagated["u_pressure_viscosity_pa_inv"] = fluid_row.u_pressure_viscosity_pa_inv
    if u_viscosity is not None:  # the fluid's state, with the temperature's share
        given_u["u_viscosity_pa_s"] = u_viscosity
    if u_density is not None:
        given_u["u_fluid_density_kg_m3"] = u_density
    measured = catalog_rows.pair_value_rows(
        connection, particle, wall, before=catalog_rows.released_at(connection, dataset_id)
    )
    released = catalog_rows.released_at(connection, dataset_id)
    sources = catalog_rows.sources_as_of(connection, released)
    dry = resolve(first, second, measured, sources)
    inputs = {
        "diameter_m": diameter_m,
        "wall_diameter_m": wall_diameter_m,
        "target": target,
        "impact_speed_m_s": speed_m_s,
        "incidence_angle_rad": angle_rad,
        "v_n_in_m_s": speed_m_s * math.cos(angle_rad),
        "v_t_in_m_s": speed_m_s * math.sin(angle_rad),
        "temperature_c": state.temperature_c if state else None,
        "critical_stokes": critical_stokes,
        **given_u,
    }
    with physics_refusal():
        result = derive(
            **material_inputs("particle", first),
            **material_inputs("wall", second),
            diameter_m=diameter_m,
            wall_diameter_m=np.nan if wall_diameter_m is None else wall_diameter_m,
            wall_v_n_in_m_s=0.0 if target == "free" else np.nan,
            v_n_in_m_s=inputs["v_n_in_m_s"],
            v_t_in_m_s=inputs["v_t_in_m_s"],
            fluid_density_kg_m3=state.density_kg_m3 if state else np.nan,
            viscosity_pa_s=state.viscosity_pa_s if state else np.nan,
            pressure_viscosity_pa_inv=(
                state.pressure_viscosity_pa_inv
                if state and state.pressure_viscosity_pa_inv is not None
                else np.nan
            ),
            critical_stokes=critical_stokes,
            uncertainties={k: np.nan if v is None else v for k, v in propagated.items()},
            correlated_materials=first.name.casefold() == second.name.casefold(),
            one_speed=True,
            dry_restitution=dry.restitution,
            dry_friction=dry.friction,
            immersed_friction=dry.immersed_friction,
        )
    derived = {k: v for k, v in scalar_view(result).items() if k not in MEASURED_ONLY}
    citations = {
        row.source.key: row.source.citation
        for row in (first, second, fluid_row)
        if row is not None and row.source is not None
    }
    # the sources the dry values used cite (a pair's measurement) and those the two
    # materials' own dry values name (their provenance, shown with the materials)
    cited = dry.keys() | {
        key for row in (first, second) for key in provenance_keys(row.dry_provenance, sources)
    }
    if fluid_row is not None:  # the fluid's density and C may cite sources of their own
        cited |= {
            source.key
            for source in (fluid_row.density_source, fluid_row.pressure_viscosity_source)
            if source is not None
        }
    citations.update({key: sources[key].citation for key in sorted(cited) if key in sources})
    cited_sources = {key: sources.get(key, text) for key, text in citations.items()}
    return PairResult(
        catalog_rows.material_record(first),
        catalog_rows.material_record(second),
        catalog_rows.fluid_record(fluid_row) if fluid_row is not None else None,
        state,
        inputs,
        derived,
        dry,
        citations,
        cited_sources,
    )


def pair_json(result: PairResult) -> dict[str, Any]:
    """The document of ``granudb pair --format json`` and ``granudb.pair()``: SI values
    under the vocabulary's names. The fluid carries its stored reference values
    (``reference_viscosity_pa_s``) and its state at the temperature (``viscosity_pa_s``);
    ``dry_values`` the pair's dry e and μ with each one's basis and source."""
    fluid = None
    if result.fluid is not None and result.fluid_state is not None:
        fluid = {
            **result.fluid,
            "viscosity_pa_s": result.fluid_state.viscosity_pa_s,
            "density_kg_m3": result.fluid_state.density_kg_m3,
            "temperature_c": result.fluid_state.temperature_c,
            "viscosity_basis": result.fluid_state.basis,
        }
    return {
        "particle": result.particle,
        "wall": result.wall,
        "fluid": fluid,
        "inputs": result.inputs,
        "dry_values": result.dry.record(),
        **result.derived,
        "sources": result.citations,
    }
