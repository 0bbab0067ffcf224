"""First-order propagation (GUM, JCGM 100:2008) against Monte Carlo (JCGM 101:2008), the
verdict probabilities, correlation of one material on both sides, and the vocabulary."""

from __future__ import annotations

import numpy as np
import pytest
from support import STEEL_ON_ZERODUR as MATERIALS

from granudb.physics import uncertainty
from granudb.physics.derive import UNCERTAIN_INPUTS, derive
from granudb.physics.numeric import PhysicsInputError
from granudb.physics.uncertainty import certainty, exceedance
from granudb.vocabulary import DERIVED_TERMS, UNCERTAINTY_TERMS, term

#: Steel on Zerodur in 37 % glycerol at 0.3 m/s, 30° (Joseph & Hunt 2004's set-up).
SCENARIO = {
    **MATERIALS,
    "v_n_in_m_s": 0.3 * np.cos(np.radians(30)),
    "v_t_in_m_s": 0.3 * np.sin(np.radians(30)),
    "fluid_density_kg_m3": 1090.0,
    "viscosity_pa_s": 3.2e-3,
    "pressure_viscosity_pa_inv": 6e-9,
}
#: The inputs given an uncertainty in the Monte Carlo comparisons.
UNCERTAIN = (
    "particle_youngs_modulus_pa",
    "wall_youngs_modulus_pa",
    "particle_roughness_rms_m",
    "wall_roughness_rms_m",
    "diameter_m",
    "v_n_in_m_s",
    "v_t_in_m_s",
    "viscosity_pa_s",
    "pressure_viscosity_pa_inv",
    "particle_density_kg_m3",
    "fluid_density_kg_m3",
)
CHECKED = ("stokes_number", "min_gap_m", "lubricated_friction", "film_parameter")


def _first_order_and_monte_carlo(
    relative: float, names: tuple[str, ...], distribution: str, samples: int = 100_000
) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
    u = {f"u_{name}": relative * SCENARIO[name] for name in names}
    first = derive(**SCENARIO, uncertainties=u)
    rng = np.random.default_rng(20261125)
    drawn = dict(SCENARIO)
    for name in names:
        if distribution == "normal":
            noise = rng.standard_normal(samples)
        else:  # rectangular with the same standard deviation (JCGM 101 §6.4.2)
            noise = rng.uniform(-np.sqrt(3.0), np.sqrt(3.0), samples)
        drawn[name] = SCENARIO[name] * (1.0 + relative * noise)
    return first, derive(**drawn)


@pytest.mark.parametrize("relative", [0.01, 0.05])
def test_first_order_agrees_with_monte_carlo_up_to_5_percent(relative: float) -> None:
    first, sampled = _first_order_and_monte_carlo(relative, UNCERTAIN, "normal")
    for name in CHECKED:
        monte_carlo = float(np.std(sampled[name]))
        assert float(first[f"u_{name}"]) == pytest.approx(monte_carlo, rel=0.10), name
        assert monte_carlo > 0.005 * float(first[name])  # the inputs reach every quantity


def test_first_order_and_monte_carlo_part_at_30_percent_viscosity() -> None:
    """St ∝ 1/μ: with u(μ)/μ = 30 % the spread of 1/μ is skewed and wider than first
    order says (by more than 10 % against rectangular draws): derive's check sees it and
    gives the Monte Carlo's u, whose interval of St is skewed upward."""
    first, sampled = _first_order_and_monte_carlo(0.30, ("viscosity_pa_s",), "uniform")
    first_order = float(first["stokes_number"]) * 0.30  # u_r(St) = u_r(μ)
    assert first_order / float(np.std(sampled["stokes_number"])) < 0.90
    assert str(first["propagation_method"]).startswith("Monte Carlo")
    value = float(first["stokes_number"])
    low, high = float(first["low95_stokes_number"]), float(first["high95_stokes_number"])
    assert high - value > 1.5 * (value - low)
    assert float(first["u_stokes_number"]) > 1.1 * first_order


def test_same_material_on_both_sides_is_fully_correlated() -> None:
    """Steel on steel with u(E)/E = 5 %: E* = E/(2(1 − ν²)) carries the whole 5 %, not
    5 %/√2 as two independent steels would."""
    steel = {k: v for k, v in SCENARIO.items() if not k.startswith("wall_")}
    steel |= {"wall_" + k.removeprefix("particle_"): v for k, v in steel.items()
              if k.startswith("particle_")}  # fmt: skip
    u = {"u_particle_youngs_modulus_pa": 9.5e9, "u_wall_youngs_modulus_pa": 9.5e9}
    same = derive(**steel, uncertainties=u, correlated_materials=True)
    apart = derive(**steel, uncertainties=u)
    e_star = float(same["reduced_modulus_pa"])
    assert float(same["u_reduced_modulus_pa"]) / e_star == pytest.approx(0.05, rel=1e-12)
    assert float(apart["u_reduced_modulus_pa"]) / e_star == pytest.approx(0.05 / np.sqrt(2))


def test_contact_probability_near_sigma_over_h_m_of_one_is_uncertain() -> None:
    """A roughness chosen so that σ ≈ h_m (Λ ≈ 1), with 10 % on σ and 5 % on μ: the
    probability of asperity contact lies between 0.2 and 0.8, and it is 'uncertain'."""
    gap = float(derive(**SCENARIO)["min_gap_m"])
    rough = SCENARIO | {"particle_roughness_rms_m": gap * 0.98, "wall_roughness_rms_m": 0.0}
    result = derive(
        **rough,
        uncertainties={"u_particle_roughness_rms_m": 0.1 * gap, "u_viscosity_pa_s": 0.05 * 3.2e-3},
    )
    probability = float(result["probability_asperity_contact"])
    assert 0.2 < probability < 0.8
    assert certainty(probability) == "uncertain"
    # and the probability is that of the Monte Carlo: the share of draws with σ > h_m
    rng = np.random.default_rng(7)
    n = 100_000
    drawn = rough | {
        "particle_roughness_rms_m": gap * 0.98 + 0.1 * gap * rng.standard_normal(n),
        "viscosity_pa_s": 3.2e-3 * (1 + 0.05 * rng.standard_normal(n)),
    }
    drawn["particle_roughness_rms_m"] = np.abs(drawn["particle_roughness_rms_m"])
    share = float(np.mean(derive(**drawn)["roughness_exceeds_gap"]))
    assert probability == pytest.approx(share, abs=0.05)


def test_probabilities_without_uncertainty_are_the_hard_verdicts() -> None:
    result = derive(**SCENARIO, uncertainties={}, particle_yield_stress_pa=1.7e9)
    assert float(result["probability_asperity_contact"]) == float(result["roughness_exceeds_gap"])
    assert float(result["probability_rebound"]) == float(result["rebound_expected"])
    assert float(result["probability_yield"]) == 0.0
    assert np.isnan(derive(**SCENARIO, uncertainties={})["probability_yield"])


def test_the_rule_of_likely() -> None:
    assert [certainty(p) for p in (0.9, 0.1, 0.11, 0.89)] == [
        "likely",
        "likely",
        "uncertain",
        "uncertain",
    ]
    assert float(exceedance(np.exp(1.0), 1.0)) == pytest.approx(0.8413, abs=1e-4)


def test_uncertainty_columns_are_the_vocabulary_and_absent_without_uncertainties() -> None:
    plain = derive(**SCENARIO)
    assert list(plain) == list(DERIVED_TERMS)
    full = derive(**SCENARIO, uncertainties={"u_viscosity_pa_s": 1e-4})
    assert list(full) == [*DERIVED_TERMS, *UNCERTAINTY_TERMS]
    assert term("u_normal_stokes_number").symbol == "u(St_n)"
    assert "u_viscosity_pa_s" in {f"u_{name}" for name in UNCERTAIN_INPUTS}


def test_bad_uncertainties_are_refused_by_name() -> None:
    with pytest.raises(PhysicsInputError, match="u_viscosity_pa_s"):
        derive(**SCENARIO, uncertainties={"u_viscosity_pa_s": -1e-4})
    with pytest.raises(PhysicsInputError, match="u_colour"):
        derive(**SCENARIO, uncertainties={"u_colour": 1.0})


def test_blocks_give_the_same_uncertainties() -> None:
    """A table larger than one block gives each row the uncertainty it has alone."""
    rng = np.random.default_rng(3)
    n = 70_000
    speeds = rng.uniform(0.05, 1.0, n)
    table = derive(**(SCENARIO | {"v_n_in_m_s": speeds}),
                   uncertainties={"u_v_n_in_m_s": 0.02 * speeds}, monte_carlo=False)  # fmt: skip
    one = derive(**(SCENARIO | {"v_n_in_m_s": speeds[-1]}),
                 uncertainties={"u_v_n_in_m_s": 0.02 * speeds[-1]}, monte_carlo=False)  # fmt: skip
    assert float(table["u_min_gap_m"][-1]) == float(one["u_min_gap_m"])


def _straightforward(sens: dict, scaled: dict) -> np.ndarray:
    """u(Q)/|Q| = √(Σ_k (s_k u_k)²) summed source by source, the definition itself."""
    total = np.zeros(())
    for source, value in sens.items():
        if source in scaled:
            total = total + (value * scaled[source]) ** 2
    return np.sqrt(total)


def _combined(factor, parts) -> dict:
    """factor × Σ coefficient × part, source by source."""
    out: dict = {}
    for coefficient, part in parts:
        for source, value in part.items():
            out[source] = out.get(source, 0.0) + coefficient * value
    return {source: value if factor is None else factor * value for source, value in out.items()}


def test_fast_propagation_equals_the_straightforward_sums(monkeypatch) -> None:
    """``propagate`` reuses the variances of parts with no source in common and skips
    zero sensitivities; on scenarios with both correlation flags mixed, target spheres
    free and fixed, dry rows and inputs without an uncertainty, every u column equals
    √(Σ (s_k u_k)²) summed plainly from the same sensitivities, to 1e-12."""
    rng = np.random.default_rng(11)
    n = 2000
    inputs = {
        name: value * rng.uniform(0.8, 1.25, n) if isinstance(value, float) else value
        for name, value in SCENARIO.items()
    }
    inputs["viscosity_pa_s"] = np.where(rng.random(n) < 0.2, np.nan, inputs["viscosity_pa_s"])
    sphere = rng.random(n) < 0.5
    inputs["wall_diameter_m"] = np.where(sphere, 0.01, np.nan)
    inputs["wall_v_n_in_m_s"] = np.where(sphere & (rng.random(n) < 0.5), -0.1, np.nan)
    inputs["particle_yield_stress_pa"] = rng.uniform(2e8, 2e9, n)
    u = {f"u_{name}": 0.05 * inputs[name] for name in UNCERTAIN}
    u["u_particle_yield_stress_pa"] = np.where(rng.random(n) < 0.5, np.nan, 1e8)
    u["u_wall_poisson_ratio"] = 0.01
    seen: list = []
    original = uncertainty.sensitivities

    def spy(*args, **kwargs):
        found = original(*args, **kwargs)
        seen.append((dict(found), args[2]))
        return found

    monkeypatch.setattr(uncertainty, "sensitivities", spy)
    flags = {"correlated_materials": rng.random(n) < 0.5, "one_speed": rng.random(n) < 0.5}
    result = derive(**inputs, uncertainties=u, **flags, monte_carlo=False)
    monkeypatch.undo()
    [(sens, scaled)] = seen
    quantities = {name: value for name, value in sens.items() if name in result}
    quantities.update({name: _combined(*value) for name, value in sens["_sums"].items()})
    assert len(quantities) >= 30
    for name, value in quantities.items():
        relative = _straightforward(value, scaled)
        want = (
            relative + 0.0 * result[name]
            if name == "incidence_angle_rad"
            else (np.abs(result[name]) * relative)
        )
        got = result[f"u_{name}"]
        # e across St_c's step (rebound uncertain) takes its u by quadrature, not sums
        p = result["probability_rebound"]
        first = ~((p > 0.025) & (p < 0.975)) if name == "predicted_restitution" else True
        got, want = np.where(first, got, np.nan), np.where(first, want, np.nan)
        if name == "predicted_restitution":  # 0 or NaN where rebound is not predicted
            keep = np.isfinite(got) & (got > 0)
            got, want = got[keep], want[keep]
        assert np.allclose(got, want, rtol=1e-12, atol=0.0, equal_nan=True), name
