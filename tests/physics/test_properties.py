"""Properties that must hold whatever the numbers (Hypothesis)."""

from __future__ import annotations

from math import comb

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.integrate import quad
from support import STEEL_ON_ZERODUR

from granudb.physics import contact, flow, impact, lubrication
from granudb.physics.derive import derive
from granudb.physics.numeric import PhysicsInputError as ValidationError
from granudb.vocabulary import DERIVED_TERMS

DERIVED_NAMES = tuple(DERIVED_TERMS)

moduli = st.floats(1e6, 1e12)
ratios = st.floats(-0.99, 0.49)
positive = st.floats(1e-3, 1e3)


@given(moduli, ratios, moduli, ratios)
def test_reduced_moduli_are_symmetric_in_the_pair(e1, nu1, e2, nu2) -> None:
    assert float(contact.reduced_modulus(e1, nu1, e2, nu2)) == pytest.approx(
        float(contact.reduced_modulus(e2, nu2, e1, nu1)), rel=1e-12
    )
    g1, g2 = contact.shear_modulus(e1, nu1), contact.shear_modulus(e2, nu2)
    assert float(contact.reduced_shear_modulus(g1, nu1, g2, nu2)) == pytest.approx(
        float(contact.reduced_shear_modulus(g2, nu2, g1, nu1)), rel=1e-12
    )


@given(moduli, ratios)
def test_rigid_wall_limit(e1, nu1) -> None:
    assert float(contact.reduced_modulus(e1, nu1, np.inf, 0.3)) == pytest.approx(
        e1 / (1 - nu1**2), rel=1e-12
    )
    g1 = contact.shear_modulus(e1, nu1)
    ratio = impact.stiffness_ratio(
        contact.reduced_shear_modulus(g1, nu1, np.inf, 0.3),
        contact.reduced_modulus(e1, nu1, np.inf, 0.3),
    )
    assert float(ratio) == pytest.approx((1 - nu1) / (2 - nu1), rel=1e-12)


@given(moduli, ratios)
def test_identical_materials_give_maws_poisson_factor(e, nu) -> None:
    g = contact.shear_modulus(e, nu)
    ratio = impact.stiffness_ratio(
        contact.reduced_shear_modulus(g, nu, g, nu), contact.reduced_modulus(e, nu, e, nu)
    )
    assert float(ratio) == pytest.approx((1 - nu) / (2 - nu), rel=1e-12)


@given(
    st.floats(100, 20000),
    st.floats(1e-4, 0.1),
    positive,
    st.floats(1e-4, 1.0),
    st.floats(0.1, 10),
    st.floats(0.1, 10),
)
def test_stokes_number_scales_as_speed_over_viscosity(rho, radius, speed, mu, k1, k2) -> None:
    base = float(flow.stokes_number(rho, radius, speed, mu))
    assert float(flow.stokes_number(rho, radius, speed * k1, mu * k2)) == pytest.approx(
        base * k1 / k2, rel=1e-12
    )


def test_friction_integral_at_zero_and_against_quadrature() -> None:
    assert float(lubrication.friction_integral(0.0)) == 0.5
    for c in [0.0, 0.01, 0.1, 0.5, 1.0, 2.0]:
        expected, _ = quad(
            lambda z, c=c: (1 + c * np.sqrt(1 - z * z)) ** 16 * z, 0, 1, epsabs=0, epsrel=1e-13
        )
        assert float(lubrication.friction_integral(c)) == pytest.approx(expected, rel=1e-11)
    exact = sum(comb(16, k) * 0.3**k / (k + 2) for k in range(17))
    assert float(lubrication.friction_integral(0.3)) == pytest.approx(exact, rel=1e-14)


@given(st.floats(0, 5), st.floats(0, 5))
def test_friction_integral_increases(c1, c2) -> None:
    low, high = sorted((c1, c2))
    assert float(lubrication.friction_integral(low)) <= float(lubrication.friction_integral(high))


@given(st.floats(0.01, 5), st.floats(-1, 1), st.floats(0.05, 1))
def test_equation_2_9_equals_2_10_on_the_sticking_line(psi_in, beta, e) -> None:
    psi_out = -beta * psi_in
    assert float(impact.sliding_friction(psi_in, psi_out, e)) == pytest.approx(
        float(impact.sticking_friction(psi_in, beta, e)), rel=1e-12
    )


SCENARIO = STEEL_ON_ZERODUR


def test_vectorized_derivation_equals_row_by_row() -> None:
    rng = np.random.default_rng(7)
    n = 50
    inputs = dict(
        v_n_in_m_s=rng.uniform(0.01, 1, n),
        v_t_in_m_s=rng.uniform(0, 1, n),
        omega_in_rad_s=rng.uniform(-5, 5, n),
        viscosity_pa_s=np.where(rng.random(n) < 0.2, np.nan, rng.uniform(1e-3, 0.1, n)),
        fluid_density_kg_m3=np.full(n, 1100.0),
        pressure_viscosity_pa_inv=np.full(n, 6e-9),
        v_n_out_m_s=rng.uniform(0, 0.5, n),
        v_t_out_m_s=rng.uniform(-0.2, 0.5, n),
        omega_out_rad_s=rng.uniform(-5, 5, n),
    )
    together = derive(**SCENARIO, **inputs)
    assert set(together) == set(DERIVED_NAMES)
    for i in range(n):
        alone = derive(**SCENARIO, **{k: v[i] for k, v in inputs.items()})
        for name in DERIVED_NAMES:
            a, b = np.asarray(together[name])[i], np.asarray(alone[name]).ravel()[0]
            if isinstance(a, str) or a.dtype == object:
                assert a == b, name
            else:
                np.testing.assert_allclose(a, b, rtol=1e-13, equal_nan=True, err_msg=name)


def test_dry_collisions_have_no_fluid_numbers_and_rebound() -> None:
    out = derive(**SCENARIO, v_n_in_m_s=0.3, v_t_in_m_s=0.1)
    assert np.isnan(out["stokes_number"]) and np.isnan(out["min_gap_m"])
    assert bool(out["rebound_expected"]) and not bool(out["roughness_exceeds_gap"])
    assert float(out["friction_coefficient_used"]) == 0.11


def test_slow_viscous_impact_does_not_rebound() -> None:
    out = derive(**SCENARIO, v_n_in_m_s=0.001, viscosity_pa_s=0.05, fluid_density_kg_m3=1200.0)
    assert float(out["normal_stokes_number"]) < 10
    assert not bool(out["rebound_expected"])


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("v_n_in_m_s", -0.1, "v_n_in_m_s: -0.1 must be > 0"),
        ("v_t_in_m_s", -0.1, "v_t_in_m_s: -0.1 must be ≥ 0"),
        ("diameter_m", 0.0, "diameter_m: 0 must be > 0"),
        ("particle_poisson_ratio", 0.5, "particle_poisson_ratio: 0.5 must be > -1 and < 0.5"),
    ],
)
def test_bad_input_is_refused_in_one_line(field, value, message) -> None:
    values = {**SCENARIO, "v_n_in_m_s": 0.3, field: value}
    with pytest.raises(ValidationError) as info:
        derive(**values)
    assert str(info.value).startswith(message)
    assert "\n" not in str(info.value)
