"""Joining stored properties to the physics: one scenario (``granudb pair``) or a table of
measured collisions, derived in one vectorized pass.

The fluid's viscosity and density at a temperature come from its measured (or correlated)
points, interpolated by ``TabulatedViscosity``; with no temperature given, the reference
value as the source printed it is used. Nothing is extrapolated: a temperature outside a
fluid's data is refused with the range that is covered.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from sqlalchemy.orm import Session

from granudb.analysis._errors import physics_refusal
from granudb.db import catalog
from granudb.db.models import Fluid, Material
from granudb.errors import ValidationError
from granudb.physics.derive import derive, scalar_view
from granudb.physics.viscosity import TabulatedViscosity

REFERENCE_TOLERANCE_C = 0.5  # a temperature this close to the reference uses the printed value


@dataclass
class FluidState:
    """A fluid at one temperature, and where each number came from."""

    name: str
    viscosity_pa_s: float
    density_kg_m3: float
    temperature_c: float
    pressure_viscosity_pa_inv: float | None
    basis: str


def fluid_model(fluid: Fluid) -> TabulatedViscosity | None:
    """The fluid's viscosity–temperature model, or None when it has fewer than two points."""
    points = sorted(fluid.points, key=lambda p: p.temperature_c)
    if len(points) < 2:
        return None
    densities = [p.density_kg_m3 if p.density_kg_m3 is not None else np.nan for p in points]
    return TabulatedViscosity(
        [p.temperature_c for p in points], [p.viscosity_pa_s for p in points], densities
    )


def fluid_state(
    fluid: Fluid, temperature_c: float | None = None, viscosity_pa_s: float | None = None
) -> FluidState:
    """The fluid at ``temperature_c`` (default: its reference temperature, printed value).

    ``viscosity_pa_s`` overrides the viscosity (what-if studies, the paper's gap fits).
    """
    source = fluid.source.key if fluid.source else "no source"
    model = fluid_model(fluid)
    density = fluid.reference_density_kg_m3
    if temperature_c is None or abs(temperature_c - fluid.reference_temperature_c) <= (
        REFERENCE_TOLERANCE_C
    ):
        temperature = fluid.reference_temperature_c if temperature_c is None else temperature_c
        viscosity = fluid.reference_viscosity_pa_s
        basis = (
            f"{fluid.reference_viscosity_pa_s * 1e3:.4g} mPa·s at "
            f"{fluid.reference_temperature_c:g} °C"
            f" as printed ({source}{', ' + fluid.source_locator if fluid.source_locator else ''})"
        )
    elif model is None:
        raise ValidationError(
            "--temperature",
            f"{temperature_c:g} °C",
            f"differs from fluid {fluid.name}'s reference {fluid.reference_temperature_c:g} °C "
            "and it has no viscosity–temperature points (give --viscosity instead)",
        )
    else:
        temperature = temperature_c
        with physics_refusal("--temperature"):
            viscosity = float(model.viscosity(temperature_c))
            if model.density_kg_m3 is not None:
                density = float(model.density(temperature_c))
        point_source = next((p.source.key for p in fluid.points if p.source), source)
        basis = (
            f"interpolated at {temperature_c:g} °C from {len(fluid.points)} points "
            f"({model.low_c:g}–{model.high_c:g} °C, {point_source})"
        )
    if viscosity_pa_s is not None:
        viscosity = viscosity_pa_s
        basis = f"{viscosity_pa_s * 1e3:.4g} mPa·s given with --viscosity"
    return FluidState(
        fluid.name, viscosity, density, temperature, fluid.pressure_viscosity_pa_inv, basis
    )


def _material_inputs(prefix: str, material: Material) -> dict[str, Any]:
    return {
        f"{prefix}_density_kg_m3": material.density_kg_m3,
        f"{prefix}_youngs_modulus_pa": material.youngs_modulus_pa,
        f"{prefix}_poisson_ratio": material.poisson_ratio,
        f"{prefix}_roughness_rms_m": material.roughness_rms_m,
        f"{prefix}_shear_modulus_pa": (
            np.nan if material.shear_modulus_pa is None else material.shear_modulus_pa
        ),
    }


@dataclass
class PairResult:
    """Everything ``granudb pair`` shows: inputs, properties with sources, derived values."""

    particle: dict[str, Any]
    wall: dict[str, Any]
    fluid: dict[str, Any] | None
    fluid_state: FluidState | None
    inputs: dict[str, Any]
    derived: dict[str, Any]
    citations: dict[str, str] = field(default_factory=dict)


def derive_pair(
    session: Session,
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
    critical_stokes: float = 10.0,
) -> PairResult:
    """Derive one scenario: ``particle`` hits ``wall`` (in ``fluid``) at ``speed_m_s``,
    ``angle_rad`` from the normal, without spin."""
    if not 0.0 <= angle_rad < np.pi / 2:
        raise ValidationError("--angle", f"{np.degrees(angle_rad):g} deg", "must be ≥ 0° and < 90°")
    if not speed_m_s > 0:
        raise ValidationError("--velocity", f"{speed_m_s:g} m/s", "must be > 0")
    if viscosity_pa_s is not None and fluid is None:
        raise ValidationError(
            "--viscosity",
            f"{viscosity_pa_s:g} Pa·s",
            "needs --fluid (a dry collision has no viscosity)",
        )
    first = catalog.get_material(session, particle)
    second = catalog.get_material(session, wall)
    state = None
    fluid_row = None
    if fluid is not None:
        fluid_row = catalog.get_fluid(session, fluid)
        state = fluid_state(fluid_row, temperature_c, viscosity_pa_s)
    elif temperature_c is not None:
        raise ValidationError(
            "--temperature",
            f"{temperature_c:g} °C",
            "needs --fluid (it sets the fluid's viscosity)",
        )
    inputs = {
        "diameter_m": diameter_m,
        "wall_diameter_m": wall_diameter_m,
        "impact_speed_m_s": speed_m_s,
        "incidence_angle_rad": angle_rad,
        "v_n_in_m_s": speed_m_s * np.cos(angle_rad),
        "v_t_in_m_s": speed_m_s * np.sin(angle_rad),
        "temperature_c": state.temperature_c if state else None,
        "critical_stokes": critical_stokes,
    }
    with physics_refusal():
        result = derive(
            **_material_inputs("particle", first),
            **_material_inputs("wall", second),
            diameter_m=diameter_m,
            wall_diameter_m=np.nan if wall_diameter_m is None else wall_diameter_m,
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
        )
    derived = scalar_view(result)
    for name in (
        "normal_restitution",
        "rotational_restitution",
        "effective_rebound",
        "sliding_friction",
    ):
        derived.pop(name)  # a scenario has no measured rebound
    citations = {}
    for row in (first, second, fluid_row):
        if row is not None and row.source is not None:
            citations[row.source.key] = row.source.citation
    fluid_record = catalog.fluid_record(fluid_row) if fluid_row is not None else None
    return PairResult(
        catalog.material_record(first),
        catalog.material_record(second),
        fluid_record,
        state,
        inputs,
        derived,
        citations,
    )


def pair_json(result: PairResult) -> dict[str, Any]:
    """The JSON document of ``granudb pair``: SI values under stable snake_case names."""
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
        **result.derived,
        "sources": result.citations,
    }


# --- measured collisions -----------------------------------------------------------------

LISTED_COLUMNS = [
    "dataset",
    "version",
    "run",
    "particle",
    "wall",
    "fluid",
    "diameter_m",
    "incidence_angle_rad",
    "nominal_angle_rad",
    "v_n_in_m_s",
    "v_t_in_m_s",
    "omega_in_rad_s",
    "v_n_out_m_s",
    "v_t_out_m_s",
    "omega_out_rad_s",
    "temperature_c",
    "viscosity_pa_s",
    "normal_restitution",
    "rotational_restitution",
    "effective_incidence",
    "effective_rebound",
    "sliding_friction",
    "normal_stokes_number",
    "reynolds_number",
    "min_gap_m",
    "composite_roughness_m",
    "film_parameter",
    "roughness_exceeds_gap",
    "rebound_expected",
    "tangential_regime",
    "quasi_static_valid",
    "shear_strain",
    "tangential_speed_m_s",
    "lubricated_friction",
    "effective_radius_m",
    "reduced_modulus_pa",
    "notes",
]


def _fluid_viscosity(
    fluids: dict[int, Fluid], fluid_ids: np.ndarray, temperatures: np.ndarray, runs: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Viscosity and density per row: at the run's temperature from the fluid's points, or
    the printed reference values when the run has no temperature."""
    viscosity = np.full(len(fluid_ids), np.nan)
    density = np.full(len(fluid_ids), np.nan)
    for fluid_id, fluid in fluids.items():
        rows = fluid_ids == fluid_id
        if not rows.any():
            continue
        viscosity[rows] = fluid.reference_viscosity_pa_s
        density[rows] = fluid.reference_density_kg_m3
        measured = rows & ~np.isnan(temperatures)
        near = measured & (
            np.abs(temperatures - fluid.reference_temperature_c) <= REFERENCE_TOLERANCE_C
        )
        measured &= ~near
        if not measured.any():
            continue
        model = fluid_model(fluid)
        if model is None:
            index = int(np.flatnonzero(measured)[0])
            raise ValidationError(
                f"run {runs[index]}",
                f"{temperatures[index]:g} °C",
                f"differs from fluid {fluid.name}'s reference temperature and the fluid has no "
                "viscosity–temperature points",
            )
        outside = measured & ((temperatures < model.low_c) | (temperatures > model.high_c))
        if outside.any():
            index = int(np.flatnonzero(outside)[0])
            raise ValidationError(
                f"run {runs[index]}",
                f"{temperatures[index]:g} °C",
                f"is outside fluid {fluid.name}'s viscosity data ({model.low_c:g}–"
                f"{model.high_c:g} °C); granudb does not extrapolate",
            )
        viscosity[measured] = model.viscosity(temperatures[measured])
        if model.density_kg_m3 is not None:
            density[measured] = model.density(temperatures[measured])
    return viscosity, density


def collision_table(
    session: Session,
    *,
    dataset: str | None = None,
    version: str | None = None,
    particle: str | None = None,
    wall: str | None = None,
    fluid: str | None = None,
    critical_stokes: float = 10.0,
) -> Any:
    """Measured collisions with every derived column, as a pandas DataFrame (SI)."""
    import pandas as pd
    from sqlalchemy import select
    from sqlalchemy.orm import aliased

    from granudb.db import datasets as dataset_queries
    from granudb.db.datasets import COLUMNS
    from granudb.db.models import Collision, Dataset

    first, second = aliased(Material), aliased(Material)
    material_columns = [
        "density_kg_m3",
        "youngs_modulus_pa",
        "poisson_ratio",
        "roughness_rms_m",
        "shear_modulus_pa",
    ]
    # Plain columns, not ORM objects: 100,000 rows load in a fraction of a second.
    query = (
        select(
            Dataset.name.label("dataset"),
            Dataset.version.label("version"),
            Collision.run,
            first.name.label("particle"),
            second.name.label("wall"),
            Collision.fluid_id,
            *(getattr(Collision, name) for name in COLUMNS),
            Collision.notes,
            *(getattr(first, name).label(f"particle_{name}") for name in material_columns),
            *(getattr(second, name).label(f"wall_{name}") for name in material_columns),
        )
        .join(Dataset, Collision.dataset_id == Dataset.id)
        .join(first, Collision.particle_id == first.id)
        .join(second, Collision.wall_id == second.id)
    )
    if dataset is not None:
        query = query.where(
            Collision.dataset_id == dataset_queries.get_dataset(session, dataset, version).id
        )
    if particle is not None:
        query = query.where(Collision.particle_id == catalog.get_material(session, particle).id)
    if wall is not None:
        query = query.where(Collision.wall_id == catalog.get_material(session, wall).id)
    if fluid is not None:
        if fluid.lower() == "dry":
            query = query.where(Collision.fluid_id.is_(None))
        else:
            query = query.where(Collision.fluid_id == catalog.get_fluid(session, fluid).id)
    query = query.order_by(Dataset.name, Dataset.version, Collision.run)
    result_rows = session.connection().execute(query)
    frame = pd.DataFrame(result_rows.fetchall(), columns=list(result_rows.keys()))
    fluids = {f.id: f for f in catalog.list_fluids(session)}
    if frame.empty:
        return pd.DataFrame({c: [] for c in LISTED_COLUMNS})

    def floats(name: str) -> np.ndarray:
        return pd.to_numeric(frame[name], errors="coerce").to_numpy(dtype=float)

    c = {name: floats(name) for name in COLUMNS}
    fluid_ids = frame["fluid_id"].fillna(-1).to_numpy(dtype=int)
    runs = frame["run"].to_numpy(dtype=object)
    viscosity, density = _fluid_viscosity(fluids, fluid_ids, c["temperature_c"], runs)
    props = {
        f"{prefix}_{name}": floats(f"{prefix}_{name}")
        for prefix in ("particle", "wall")
        for name in material_columns
    }
    barus_by_id = {
        i: (np.nan if f.pressure_viscosity_pa_inv is None else f.pressure_viscosity_pa_inv)
        for i, f in fluids.items()
    }
    names_by_id = {i: f.name for i, f in fluids.items()}
    barus = pd.Series(fluid_ids).map(barus_by_id).to_numpy(dtype=float)
    with physics_refusal():
        result = derive(
            **props,
            diameter_m=c["diameter_m"],
            wall_diameter_m=c["wall_diameter_m"],
            v_n_in_m_s=c["v_n_in_m_s"],
            v_t_in_m_s=c["v_t_in_m_s"],
            omega_in_rad_s=c["omega_in_rad_s"],
            v_n_out_m_s=c["v_n_out_m_s"],
            v_t_out_m_s=c["v_t_out_m_s"],
            omega_out_rad_s=c["omega_out_rad_s"],
            fluid_density_kg_m3=density,
            viscosity_pa_s=viscosity,
            pressure_viscosity_pa_inv=barus,
            critical_stokes=critical_stokes,
        )
    frame = pd.DataFrame(
        {
            "dataset": frame["dataset"].to_numpy(dtype=object),
            "version": frame["version"].to_numpy(dtype=object),
            "run": runs,
            "particle": frame["particle"].to_numpy(dtype=object),
            "wall": frame["wall"].to_numpy(dtype=object),
            "fluid": pd.Series(fluid_ids).map(names_by_id).to_numpy(dtype=object),
            **c,
            "viscosity_pa_s": viscosity,
            "particle_density_kg_m3": props["particle_density_kg_m3"],
            "notes": frame["notes"].to_numpy(dtype=object),
        }
    )
    for name, values in result.items():
        if name not in frame:
            frame[name] = values
    ordered = LISTED_COLUMNS + [n for n in frame.columns if n not in LISTED_COLUMNS]
    return frame[ordered]
