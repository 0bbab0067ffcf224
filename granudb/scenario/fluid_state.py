"""A fluid at a temperature: its viscosity and density, and where each number came from.

With no temperature the fluid's reference values are used exactly as the source printed
them. At a temperature, one continuous model: the fluid's measured (or correlated) points,
interpolated by ``TabulatedViscosity`` (Andrade's law between neighbouring points) and
scaled by ``ReferencedViscosity`` so that it passes exactly through the printed value at
the reference temperature (the points supply only how viscosity changes with
temperature). Nothing is extrapolated: a temperature outside a fluid's data is refused,
naming the range that is covered.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from granudb.errors import ValidationError
from granudb.physics.viscosity import ReferencedViscosity, TabulatedViscosity
from granudb.scenario.refusals import physics_refusal

if TYPE_CHECKING:
    from granudb.db.catalog_rows import FluidRow
    from granudb.db.models import Fluid


@dataclass
class FluidState:
    """A fluid at one temperature, and where each number came from."""

    name: str
    viscosity_pa_s: float
    density_kg_m3: float
    temperature_c: float
    pressure_viscosity_pa_inv: float | None
    basis: str


def fluid_model(fluid: Fluid | FluidRow) -> TabulatedViscosity | ReferencedViscosity | None:
    """The fluid's viscosity–temperature model (None with fewer than two points), anchored
    to the printed reference value when the reference temperature lies inside the data."""
    points: list[Any] = sorted(fluid.points, key=lambda p: p.temperature_c)  # ORM or Core
    if len(points) < 2:
        return None
    densities = [p.density_kg_m3 if p.density_kg_m3 is not None else np.nan for p in points]
    table = TabulatedViscosity(
        [p.temperature_c for p in points], [p.viscosity_pa_s for p in points], densities
    )
    if not table.low_c <= fluid.reference_temperature_c <= table.high_c:
        return table
    return ReferencedViscosity(table, fluid.reference_temperature_c, fluid.reference_viscosity_pa_s)


def _printed(fluid: Fluid | FluidRow) -> str:
    source = fluid.source.key if fluid.source else "no source"
    locator = f", {fluid.source_locator}" if fluid.source_locator else ""
    return (
        f"{fluid.reference_viscosity_pa_s * 1e3:.4g} mPa·s at "
        f"{fluid.reference_temperature_c:g} °C as printed ({source}{locator})"
    )


def fluid_state(
    fluid: Fluid | FluidRow, temperature_c: float | None = None, viscosity_pa_s: float | None = None
) -> FluidState:
    """The fluid at ``temperature_c`` (default: its reference temperature, printed value).

    ``viscosity_pa_s`` overrides the viscosity (what-if studies, the paper's gap fits).
    Errors name the Python parameters (``temperature``); the command line shows them as
    its options.
    """
    density = fluid.reference_density_kg_m3
    model = fluid_model(fluid)
    if temperature_c is None or (model is None and temperature_c == fluid.reference_temperature_c):
        temperature = fluid.reference_temperature_c
        viscosity = fluid.reference_viscosity_pa_s
        basis = _printed(fluid)
    else:
        if model is None:
            raise ValidationError(
                "temperature",
                f"{temperature_c:g} °C",
                f"differs from fluid {fluid.name}'s reference {fluid.reference_temperature_c:g} "
                "°C and it has no viscosity–temperature points (give a viscosity instead)",
                parameter=True,
            )
        temperature = temperature_c
        with physics_refusal("temperature"):
            viscosity = float(model.viscosity(temperature_c))
            if _has_density(model):
                density = float(model.density(temperature_c))
        point_source = next((p.source.key for p in fluid.points if p.source), "no source")
        anchored = isinstance(model, ReferencedViscosity)
        basis = (
            f"at {temperature_c:g} °C: {len(fluid.points)} points ({model.low_c:g}–"
            f"{model.high_c:g} °C, {point_source}), Andrade-interpolated"
            + (f", scaled through the printed {_printed(fluid)}" if anchored else "")
        )
    if viscosity_pa_s is not None:
        viscosity = viscosity_pa_s
        basis = f"{viscosity_pa_s * 1e3:.4g} mPa·s given as the viscosity (what-if)"
    return FluidState(
        fluid.name, viscosity, density, temperature, fluid.pressure_viscosity_pa_inv, basis
    )


def assumptions_per_row(
    fluids: dict[int, Fluid], fluid_ids: np.ndarray, temperatures: np.ndarray
) -> np.ndarray:
    """What ``fluid_states_per_row`` assumed for each row, in words (None: nothing): a wet
    run without a temperature is taken at its fluid's reference temperature; a fluid
    whose points give no density at the run's temperature lends its reference density."""
    said = np.full(len(fluid_ids), None, dtype=object)
    for fluid_id, fluid in fluids.items():
        rows = fluid_ids == fluid_id
        if not rows.any():
            continue
        missing = rows & np.isnan(temperatures)
        if missing.any():
            said[missing] = (
                f"assumed: no temperature given, so {fluid.name} at its reference "
                f"{fluid.reference_temperature_c:g} °C ({fluid.reference_viscosity_pa_s * 1e3:.4g}"
                f" mPa·s, {fluid.reference_density_kg_m3:g} kg/m³)"
            )
        model = fluid_model(fluid)
        given = rows & ~np.isnan(temperatures)
        if model is not None and given.any() and not _has_density(model):
            said[given] = (
                f"assumed: {fluid.name}'s density at the run's temperature is not known; "
                f"its reference density {fluid.reference_density_kg_m3:g} kg/m³ is used"
            )
    return said


def fluid_states_per_row(
    fluids: dict[int, Fluid], fluid_ids: np.ndarray, temperatures: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Viscosity, density and a reason per row (stored collisions).

    A row's fluid at its temperature from the fluid's points, or the printed reference
    values when the row has no temperature. A row whose temperature the fluid's data do
    not cover gets NaN and a reason instead of failing the whole read: one bad row must
    not hide every other.
    """
    n = len(fluid_ids)
    viscosity, density = np.full(n, np.nan), np.full(n, np.nan)
    reason = np.full(n, None, dtype=object)
    for fluid_id, fluid in fluids.items():
        rows = fluid_ids == fluid_id
        if not rows.any():
            continue
        viscosity[rows] = fluid.reference_viscosity_pa_s
        density[rows] = fluid.reference_density_kg_m3
        measured = rows & ~np.isnan(temperatures)
        if not measured.any():
            continue
        model = fluid_model(fluid)
        if model is None:  # only the printed point: usable at exactly its temperature
            measured &= temperatures != fluid.reference_temperature_c
        low, high = (model.low_c, model.high_c) if model else (np.nan, np.nan)
        outside = measured & ~((temperatures >= low) & (temperatures <= high))
        if outside.any():
            covered = f"{low:g}–{high:g} °C" if model else "only its reference temperature"
            viscosity[outside] = density[outside] = np.nan
            reason[outside] = [
                f"temperature {t:g} °C is outside fluid {fluid.name}'s data ({covered})"
                for t in temperatures[outside]
            ]
        inside = measured & ~outside
        if model is not None and inside.any():  # without a model every measured is outside
            viscosity[inside] = model.viscosity(temperatures[inside])
            if _has_density(model):
                density[inside] = model.density(temperatures[inside])
    return viscosity, density, reason


def _has_density(model: TabulatedViscosity | ReferencedViscosity) -> bool:
    table = model.model if isinstance(model, ReferencedViscosity) else model
    return getattr(table, "density_kg_m3", None) is not None


#: Temperature step of the central difference dμ/dT through the fluid model [K].
_DT = 0.05


def state_uncertainty(
    fluid: Fluid | FluidRow,
    state: FluidState,
    u_temperature_c: float | None = None,
    u_viscosity_pa_s: float | None = None,
    viscosity_given: bool = False,
) -> tuple[float | None, float | None]:
    """Standard uncertainties (u(μ), u(ρ_f)) of ``state``, None where nothing is known.

    u(μ): a viscosity given by the caller carries its own ``u_viscosity_pa_s``. Else the
    stored relative uncertainty of the reference viscosity, applied at the state's
    temperature (the model passes through the printed value, so its relative
    uncertainty is assumed to carry over; without one, the points' relative uncertainties
    interpolated at the temperature), combined in quadrature (GUM (10)) with
    |dμ/dT|·u(T) for the temperature's uncertainty and for the reference temperature's,
    dμ/dT by central difference of the fluid's model (``fluid_model``). u(ρ_f): the
    reference density's relative uncertainty at the state's density. A temperature
    uncertainty without a model is refused: it could not reach μ.
    """
    if viscosity_given:
        return u_viscosity_pa_s, _relative(fluid, "reference_density_kg_m3", state.density_kg_m3)
    parts: list[float] = []
    relative = _relative(fluid, "reference_viscosity_pa_s", state.viscosity_pa_s)
    if relative is None:
        relative = _from_points(fluid, state)
    if relative is not None:
        parts.append(relative)
    temperatures = [
        u
        for u in (u_temperature_c, getattr(fluid, "u_reference_temperature_c", None))
        if u is not None and u > 0
    ]
    if temperatures:
        model = fluid_model(fluid)
        if model is None:
            raise ValidationError(
                "temperature",
                f"± {temperatures[0]:g} K",
                f"cannot reach the viscosity: fluid {fluid.name} has no viscosity–temperature "
                "points (give the viscosity with its ± instead)",
                parameter=True,
            )
        low = max(state.temperature_c - _DT, model.low_c)
        high = min(state.temperature_c + _DT, model.high_c)
        with physics_refusal("temperature"):
            slope = float(model.viscosity(high) - model.viscosity(low)) / (high - low)
        parts += [abs(slope) * u for u in temperatures]
    density = _relative(fluid, "reference_density_kg_m3", state.density_kg_m3)
    return (float(np.hypot.reduce(parts)) if parts else None), density


def _relative(fluid: Fluid | FluidRow, column: str, value: float) -> float | None:
    """The stored uncertainty of ``column`` as a fraction of its value, times ``value``."""
    u = getattr(fluid, f"u_{column}", None)
    return None if u is None else u / getattr(fluid, column) * value


def _from_points(fluid: Fluid | FluidRow, state: FluidState) -> float | None:
    """u(μ) at the state's temperature from the points' stated uncertainties: their
    relative u interpolated linearly in temperature (None when no point states one)."""
    stated = sorted(
        (p.temperature_c, u / p.viscosity_pa_s)
        for p in fluid.points
        if (u := getattr(p, "u_viscosity_pa_s", None)) is not None
    )
    if not stated:
        return None
    temperatures, relative = zip(*stated, strict=True)
    return float(np.interp(state.temperature_c, temperatures, relative)) * state.viscosity_pa_s
