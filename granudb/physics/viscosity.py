"""Viscosity and density of the liquid at a temperature (docs/physics.md §6, thermal correction).

Two models, one interface (``viscosity(T)``, ``density(T)``, ``temperature_for_viscosity``):

- ``GlycerolWater``: the Cheng (2008) viscosity correlation for water–glycerol mixtures,
  Ind. Eng. Chem. Res. 47, 3285 (doi:10.1021/ie071349z), valid 0–100 °C, with the density
  model of Volk & Kähler (2018), Exp. Fluids 59, 75 (doi:10.1007/s00348-018-2527-y;
  validated 15–30 °C by its authors, used with that caveat elsewhere).
- ``TabulatedViscosity``: measured (temperature, viscosity[, density]) points,
  interpolated as ln μ linear in 1/T (Andrade's law between neighbouring points).

``ReferencedViscosity`` wraps either so that it passes exactly through a fluid's printed
reference viscosity at its reference temperature while staying continuous in T.

All refuse temperatures outside their range with ``ViscosityRangeError`` instead of
extrapolating silently.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from granudb.physics.arguments import parameters
from granudb.physics.numeric import Numeric, PhysicsInputError, as_float

KELVIN = 273.15
CHENG_RANGE_C = (0.0, 100.0)


class ViscosityRangeError(PhysicsInputError):
    """A temperature (or viscosity) outside what a fluid model covers."""


@parameters
def water_viscosity_cheng(temperature_c: Numeric) -> Numeric:
    r"""Viscosity of water, μ_w = 1.790 exp((−1230 − T)T / (36100 + 360T)) mPa·s,
    T in °C (Cheng 2008, eq. 21); returned in Pa·s.

    Examples
    --------
    >>> round(float(water_viscosity_cheng(20.0)) * 1e3, 3)
    1.005
    """
    t = as_float(temperature_c)
    return 1.790e-3 * np.exp((-1230.0 - t) * t / (36100.0 + 360.0 * t))


@parameters
def glycerol_viscosity_cheng(temperature_c: Numeric) -> Numeric:
    r"""Viscosity of glycerol, μ_g = 12100 exp((−1233 + T)T / (9900 + 70T)) mPa·s
    (Cheng 2008, eq. 22); returned in Pa·s.

    Examples
    --------
    >>> round(float(glycerol_viscosity_cheng(20.0)), 3)
    1.414
    """
    t = as_float(temperature_c)
    return 12.100 * np.exp((-1233.0 + t) * t / (9900.0 + 70.0 * t))


@parameters
def glycerol_water_viscosity(mass_fraction: Numeric, temperature_c: Numeric) -> Numeric:
    r"""Viscosity of a water–glycerol mixture, μ = μ_w^α μ_g^{1−α} [Pa·s] (Cheng 2008).

    α = 1 − C_m + a b C_m (1 − C_m) / (a C_m + b (1 − C_m)), a = 0.705 − 0.0017 T,
    b = (4.9 + 0.036 T) a^{2.5}; C_m the glycerol mass fraction, T in °C.

    Examples
    --------
    37 % and 78 % wt glycerol at the paper's ambient temperatures (docs/physics.md §6 quotes
    3.1 and 47.6 cP):

    >>> round(float(glycerol_water_viscosity(0.37, 21.5)) * 1e3, 2)
    3.09
    >>> round(float(glycerol_water_viscosity(0.78, 20.5)) * 1e3, 1)
    47.6
    """
    cm = as_float(mass_fraction)
    t = as_float(temperature_c)
    a = 0.705 - 0.0017 * t
    b = (4.9 + 0.036 * t) * a**2.5
    with np.errstate(invalid="ignore", divide="ignore"):
        alpha = 1.0 - cm + a * b * cm * (1.0 - cm) / (a * cm + b * (1.0 - cm))
    alpha = np.where(cm <= 0.0, 1.0, np.where(cm >= 1.0, 0.0, alpha))
    return water_viscosity_cheng(t) ** alpha * glycerol_viscosity_cheng(t) ** (1.0 - alpha)


@parameters
def water_density_volk(temperature_c: Numeric) -> Numeric:
    r"""Density of water, ρ_w = 1000 (1 − |(T − 3.98)/615|^{1.71}) kg/m³ (Volk & Kähler 2018).

    Examples
    --------
    >>> round(float(water_density_volk(20.0)), 2)
    998.05
    """
    t = as_float(temperature_c)
    return 1000.0 * (1.0 - np.abs((t - 3.98) / 615.0) ** 1.71)


@parameters
def glycerol_density_volk(temperature_c: Numeric) -> Numeric:
    r"""Density of glycerol, ρ_g = 1273 − 0.612 T kg/m³ (Volk & Kähler 2018, after Cheng).

    Examples
    --------
    >>> round(float(glycerol_density_volk(20.0)), 2)
    1260.76
    """
    return 1273.0 - 0.612 * as_float(temperature_c)


@parameters
def glycerol_water_density(mass_fraction: Numeric, temperature_c: Numeric) -> Numeric:
    r"""Density of a water–glycerol mixture with volume contraction (Volk & Kähler 2018):
    ρ = ρ_ideal (1 + κ sin(C_m^{1.31} π)^{0.81}) [kg/m³], with
    1/ρ_ideal = C_m/ρ_g + (1 − C_m)/ρ_w and κ = 1.78×10⁻⁶ T² − 1.82×10⁻⁴ T + 1.41×10⁻².

    Examples
    --------
    45 % wt at 20 °C (the paper's figure 3 fluid, "≈ 1112 kg/m³"):

    >>> round(float(glycerol_water_density(0.45, 20.0)), 1)
    1112.5
    """
    cm = as_float(mass_fraction)
    t = as_float(temperature_c)
    ideal = 1.0 / (cm / glycerol_density_volk(t) + (1.0 - cm) / water_density_volk(t))
    kappa = 1.78e-6 * t**2 - 1.82e-4 * t + 1.41e-2
    return ideal * (1.0 + kappa * np.sin(cm**1.31 * np.pi) ** 0.81)


#: What each checked argument is, and its unit, for the refusal.
_RANGES = {"temperature_c": ("temperature", "°C"), "viscosity_pa_s": ("viscosity", "Pa·s")}


def _check_range(name: str, values: np.ndarray, low: float, high: float) -> None:
    what, unit = _RANGES[name]
    finite = values[np.isfinite(values)]
    bad = finite[(finite < low - 1e-9) | (finite > high + 1e-9)]
    if bad.size:
        raise ViscosityRangeError(
            name,
            f"{float(bad[0]):g} {unit}",
            f"is outside the {what} range {low:g} to {high:g} {unit} of the fluid model "
            "(granudb does not extrapolate)",
        )


@dataclass(frozen=True)
class GlycerolWater:
    """The Cheng (2008) / Volk & Kähler (2018) model of one water–glycerol mixture."""

    mass_fraction: float
    low_c: float = CHENG_RANGE_C[0]
    high_c: float = CHENG_RANGE_C[1]

    def viscosity(self, temperature_c: Numeric) -> Numeric:
        t = as_float(temperature_c)
        _check_range("temperature_c", np.atleast_1d(t), self.low_c, self.high_c)
        return glycerol_water_viscosity(self.mass_fraction, t)

    def density(self, temperature_c: Numeric) -> Numeric:
        t = as_float(temperature_c)
        _check_range("temperature_c", np.atleast_1d(t), self.low_c, self.high_c)
        return glycerol_water_density(self.mass_fraction, t)

    def temperature_for_viscosity(self, viscosity: Numeric) -> Numeric:
        """The temperature [°C] at which the mixture has ``viscosity`` [Pa·s] (bisection;
        viscosity falls monotonically with temperature)."""
        mu = as_float(viscosity)
        hot, cold = self.viscosity(self.high_c), self.viscosity(self.low_c)
        _check_range("viscosity_pa_s", np.atleast_1d(mu), float(hot), float(cold))
        low = np.full(mu.shape, self.low_c)
        high = np.full(mu.shape, self.high_c)
        for _ in range(60):  # 100 °C / 2^60: far below any measurement's resolution
            middle = 0.5 * (low + high)
            too_viscous = glycerol_water_viscosity(self.mass_fraction, middle) > mu
            low = np.where(too_viscous, middle, low)
            high = np.where(too_viscous, high, middle)
        return 0.5 * (low + high)


class TabulatedViscosity:
    """Viscosity (and optionally density) from measured points, Andrade-interpolated.

    Between neighbouring points ln μ is linear in 1/T (T in kelvin), the form of Andrade's
    law μ = A exp(B/T); density is linear in T. Outside the points: ``ViscosityRangeError``.

    Examples
    --------
    >>> table = TabulatedViscosity([10, 20, 30], [1.307e-3, 1.002e-3, 0.798e-3])
    >>> round(float(table.viscosity(25.0)) * 1e3, 3)
    0.892
    >>> round(float(table.temperature_for_viscosity(table.viscosity(25.0))), 6)
    25.0
    """

    def __init__(
        self, temperature_c: Numeric, viscosity_pa_s: Numeric, density_kg_m3: Numeric | None = None
    ) -> None:
        t = np.asarray(temperature_c, dtype=float)
        mu = np.asarray(viscosity_pa_s, dtype=float)
        if t.ndim != 1 or t.size < 2 or t.shape != mu.shape:
            raise PhysicsInputError(
                "points", t.size, "need at least two (temperature, viscosity) pairs"
            )
        order = np.argsort(t)
        self.temperature_c = t[order]
        self.viscosity_pa_s = mu[order]
        if np.any(np.diff(self.temperature_c) <= 0):
            raise PhysicsInputError("temperature_c", "repeated", "must differ between points")
        if np.any(self.viscosity_pa_s <= 0):
            raise PhysicsInputError("viscosity_pa_s", "≤ 0", "must be > 0 at every point")
        self._x = 1.0 / (self.temperature_c + KELVIN)
        self._y = np.log(self.viscosity_pa_s)
        self.density_kg_m3 = None
        if density_kg_m3 is not None:
            rho = np.asarray(density_kg_m3, dtype=float)[order]
            self.density_kg_m3 = rho if np.all(np.isfinite(rho)) else None

    @property
    def low_c(self) -> float:
        return float(self.temperature_c[0])

    @property
    def high_c(self) -> float:
        return float(self.temperature_c[-1])

    def viscosity(self, temperature_c: Numeric) -> Numeric:
        t = as_float(temperature_c)
        _check_range("temperature_c", np.atleast_1d(t), self.low_c, self.high_c)
        x = 1.0 / (t + KELVIN)
        # np.interp needs increasing x: 1/T decreases with T, so interpolate reversed.
        return np.exp(np.interp(x, self._x[::-1], self._y[::-1]))

    def density(self, temperature_c: Numeric) -> Numeric:
        if self.density_kg_m3 is None:
            raise ViscosityRangeError("density_kg_m3", "(none)", "is not in the fluid's points")
        t = as_float(temperature_c)
        _check_range("temperature_c", np.atleast_1d(t), self.low_c, self.high_c)
        return np.interp(t, self.temperature_c, self.density_kg_m3)

    def temperature_for_viscosity(self, viscosity: Numeric) -> Numeric:
        """The temperature [°C] at which the fluid has ``viscosity`` [Pa·s]."""
        mu = as_float(viscosity)
        low, high = float(self.viscosity_pa_s.min()), float(self.viscosity_pa_s.max())
        _check_range("viscosity_pa_s", np.atleast_1d(mu), low, high)
        # ln μ is monotonic in 1/T between points when the data are (viscosity falls with T).
        y = np.log(mu)
        order = np.argsort(self._y)
        x = np.interp(y, self._y[order], self._x[order])
        return 1.0 / x - KELVIN


class ReferencedViscosity:
    """A temperature model scaled to pass through a printed reference point.

    μ(T) = μ_ref × μ_model(T) / μ_model(T_ref): continuous (and as smooth as the model)
    in T, exactly the printed μ_ref at the printed T_ref, and with the model's temperature
    dependence everywhere. The printed value is the anchor; the model (a correlation or
    Andrade-interpolated measured points) supplies only the ratio μ(T)/μ(T_ref). This
    replaces "the printed value within ±0.5 °C of T_ref, the model outside", which jumps
    at ±0.5 °C (glycerol-45: 4.500 cP at 20.5 °C, 4.552 at 20.6 °C, 4.490 at 21 °C).
    Density comes from the model unscaled. The range is the model's.

    Examples
    --------
    >>> table = TabulatedViscosity([10, 20, 30], [1.307e-3, 1.002e-3, 0.798e-3])
    >>> water = ReferencedViscosity(table, 20.0, 1.0e-3)
    >>> float(water.viscosity(20.0))
    0.001
    >>> round(float(water.temperature_for_viscosity(water.viscosity(25.0))), 6)
    25.0
    """

    def __init__(
        self,
        model: GlycerolWater | TabulatedViscosity,
        reference_temperature_c: float,
        reference_viscosity_pa_s: float,
    ) -> None:
        if not reference_viscosity_pa_s > 0:
            raise PhysicsInputError(
                "viscosity_pa_s", f"{reference_viscosity_pa_s:g}", "must be > 0"
            )
        self.model = model
        self.reference_temperature_c = float(reference_temperature_c)
        self.reference_viscosity_pa_s = float(reference_viscosity_pa_s)
        self.scale = self.reference_viscosity_pa_s / float(
            model.viscosity(self.reference_temperature_c)
        )

    @property
    def low_c(self) -> float:
        return float(self.model.low_c)

    @property
    def high_c(self) -> float:
        return float(self.model.high_c)

    def viscosity(self, temperature_c: Numeric) -> Numeric:
        return self.scale * self.model.viscosity(temperature_c)

    def density(self, temperature_c: Numeric) -> Numeric:
        return self.model.density(temperature_c)

    def temperature_for_viscosity(self, viscosity: Numeric) -> Numeric:
        """The temperature [°C] at which the referenced fluid has ``viscosity`` [Pa·s].

        The range is checked on the referenced viscosities, so a refusal quotes the
        number the caller gave and the range it can have."""
        mu = as_float(viscosity)
        low = float(self.viscosity(self.high_c))
        high = float(self.viscosity(self.low_c))
        _check_range("viscosity_pa_s", np.atleast_1d(mu), low, high)
        floor, ceiling = sorted(
            (float(self.model.viscosity(self.high_c)), float(self.model.viscosity(self.low_c)))
        )
        return self.model.temperature_for_viscosity(np.clip(mu / self.scale, floor, ceiling))
