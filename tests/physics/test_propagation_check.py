"""Known-truth checks of first order's check and the Monte Carlo behind it."""

from __future__ import annotations

import numpy as np
import pytest

from granudb.physics.derive import derive
from granudb.physics.propagation_check import FIRST_ORDER, Z95

SCENARIO = {
    "particle_density_kg_m3": 7780.0,
    "particle_youngs_modulus_pa": 190e9,
    "particle_poisson_ratio": 0.27,
    "particle_roughness_rms_m": 23.6e-9,
    "wall_density_kg_m3": 2540.0,
    "wall_youngs_modulus_pa": 91e9,
    "wall_poisson_ratio": 0.24,
    "wall_roughness_rms_m": 15.5e-9,
    "diameter_m": 0.0127,
    "v_n_in_m_s": 0.3,
    "fluid_density_kg_m3": 1090.0,
    "viscosity_pa_s": 3.2e-3,
}


def test_a_linear_quantity_keeps_first_order_with_its_lognormal_interval() -> None:
    """R = d/2 (flat wall): 1 % on d gives u(R) = 1 % of R by first order, and the 95 %
    interval of first order on ln R, R·exp(±1.96·0.01); v_N, linear, keeps ±1.96u."""
    got = derive(**SCENARIO, uncertainties={"u_diameter_m": 0.01 * SCENARIO["diameter_m"]})
    radius = float(got["effective_radius_m"])
    assert got["propagation_method"].item() == FIRST_ORDER
    assert float(got["u_effective_radius_m"]) == pytest.approx(0.01 * radius, rel=1e-12)
    assert float(got["high95_effective_radius_m"]) == pytest.approx(
        radius * np.exp(0.01 * Z95), rel=1e-12
    )
    got = derive(**SCENARIO, uncertainties={"u_v_n_in_m_s": 0.003})
    assert float(got["low95_normal_speed_m_s"]) == pytest.approx(0.3 - Z95 * 0.003, rel=1e-12)


def test_a_curved_quantity_goes_to_monte_carlo_with_the_analytic_quantiles() -> None:
    """St ∝ 1/μ with μ normal at 25 %: the 95 % interval of St is St₀/(1 ± 1.96·0.25)
    (a monotone map of μ's quantiles), skewed upward; first order's ±1.96u is not."""
    rel = 0.25
    got = derive(**SCENARIO, uncertainties={"u_viscosity_pa_s": rel * SCENARIO["viscosity_pa_s"]})
    method = got["propagation_method"].item()
    assert method.startswith("Monte Carlo") and "stokes_number" in method
    st = float(got["stokes_number"])
    assert float(got["low95_stokes_number"]) == pytest.approx(st / (1 + Z95 * rel), rel=0.03)
    assert float(got["high95_stokes_number"]) == pytest.approx(st / (1 - Z95 * rel), rel=0.03)
    # a quantity the viscosity does not reach keeps no u (not 0), and no interval
    assert np.isnan(float(got["u_reduced_modulus_pa"]))
    assert np.isnan(float(got["low95_reduced_modulus_pa"]))


def test_the_same_scenario_gives_the_same_numbers() -> None:
    u = {"u_viscosity_pa_s": 0.25 * SCENARIO["viscosity_pa_s"]}
    first, again = derive(**SCENARIO, uncertainties=u), derive(**SCENARIO, uncertainties=u)
    assert float(first["u_stokes_number"]) == float(again["u_stokes_number"])
