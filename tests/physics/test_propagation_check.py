"""Known-truth checks of first order's check and the Monte Carlo behind it."""

from __future__ import annotations

import numpy as np
import pytest
from support import STEEL_ON_ZERODUR

from granudb.physics.derive import derive
from granudb.physics.propagation_check import FIRST_ORDER, Z95

SCENARIO = {
    **STEEL_ON_ZERODUR,
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


def test_the_call_budget_bounds_the_monte_carlo_and_says_where_it_stopped() -> None:
    """300 rows that all need the Monte Carlo (25 % on μ), a budget for about 100 of them
    at two batches: the first rows get the Monte Carlo, the rest keep first order with a
    method that names the budget; within the budget the rows agree with a call that has
    no limit (same seeds); nothing is silently left without an interval."""
    from granudb.physics.propagation_check import BATCH, MIN_BATCHES

    rows = 300
    table = {k: np.full(rows, v) for k, v in SCENARIO.items()}
    u = {"u_viscosity_pa_s": np.full(rows, 0.25 * SCENARIO["viscosity_pa_s"])}
    budget = 100 * MIN_BATCHES * BATCH
    got = derive(**table, uncertainties=u, monte_carlo_draws=budget)
    methods = list(got["propagation_method"])
    served = [m.startswith("Monte Carlo") for m in methods]
    assert 0 < sum(served) <= 100 and served == sorted(served, reverse=True)
    unserved = methods[sum(served)]
    assert unserved.startswith(FIRST_ORDER) and "stokes_number" in unserved
    assert f"budget of {budget:,} draws" in unserved and "monte_carlo_draws" in unserved
    first = sum(served)
    st = float(got["stokes_number"][0])
    # the rows beyond the budget keep first order's interval (log-normal), not NaN
    assert float(got["high95_stokes_number"][first]) == pytest.approx(
        st * np.exp(Z95 * float(got["u_stokes_number"][first]) / st), rel=1e-9
    )
    # within the budget: the Monte Carlo's skewed interval, as with no limit
    unlimited = derive(**{k: v[:1] for k, v in table.items()}, uncertainties={
        k: v[:1] for k, v in u.items()})  # fmt: skip
    assert float(got["high95_stokes_number"][0]) == pytest.approx(
        float(unlimited["high95_stokes_number"][0]), rel=0.02
    )
    assert float(got["high95_stokes_number"][0]) > float(got["high95_stokes_number"][first])
    # a budget of 0: first order everywhere, each row saying the Monte Carlo was not run
    none = derive(**table, uncertainties=u, monte_carlo_draws=0)
    assert all("Monte Carlo not run" in m for m in none["propagation_method"])


def test_the_restitution_u_across_the_step_is_the_exact_integral() -> None:
    """Near St_c e = ceiling·exp(−35/St_am) above the step St_n > St_c and 0 below, St_am
    and St_n comonotone log-normal (one viscosity): first order's u(e) is the standard
    deviation of that law, which adaptive quadrature gives independently."""
    from scipy import integrate, stats

    critical = 10.0
    viscosity = SCENARIO["viscosity_pa_s"]
    # the viscosity that puts St_n at 1.03 St_c, then 3 % on it: the step is inside
    st_n = float(derive(**SCENARIO)["normal_stokes_number"])
    near = {**SCENARIO, "viscosity_pa_s": viscosity * st_n / (1.03 * critical)}
    got = derive(**near, uncertainties={"u_viscosity_pa_s": 0.03 * near["viscosity_pa_s"]})
    assert 0.025 < float(got["probability_rebound"]) < 0.975
    s_am = float(got["u_added_mass_stokes_number"] / got["added_mass_stokes_number"])
    s_n = float(got["u_normal_stokes_number"] / got["normal_stokes_number"])
    st_am, ceiling = float(got["added_mass_stokes_number"]), float(got["restitution_ceiling"])
    step = np.log(critical / float(got["normal_stokes_number"])) / s_n

    def moment(k: int) -> float:
        def f(z: float) -> float:
            e = ceiling * np.exp(-35.0 / (st_am * np.exp(s_am * z)))
            return float(e**k * stats.norm.pdf(z))

        return integrate.quad(f, step, np.inf, epsabs=0.0, epsrel=1e-12, limit=200)[0]

    exact = np.sqrt(moment(2) - moment(1) ** 2)
    assert float(got["u_predicted_restitution"]) == pytest.approx(exact, rel=1e-9)
