"""Two-sphere collisions (docs/physics.md §9) and the contact point's incidence angle.

Each test here fails on the code before issue 13 (no target velocities, St of the single
particle, ζ_in of the centre's path, β = −inf for a normal impact).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from granudb.physics import contact, flow, impact, pair
from granudb.physics.derive import derive
from granudb.physics.numeric import PhysicsInputError

GLASS = {
    "density_kg_m3": 2540.0,
    "youngs_modulus_pa": 60e9,
    "poisson_ratio": 0.23,
    "roughness_rms_m": 0.1305e-6,
}
ZERODUR = {
    "density_kg_m3": 2540.0,
    "youngs_modulus_pa": 91e9,
    "poisson_ratio": 0.24,
    "roughness_rms_m": 0.0155e-6,
}
D = 12.7e-3


def _pair(particle: dict, target: dict) -> dict:
    out = {f"particle_{k}": v for k, v in particle.items()}
    out.update({f"wall_{k}": v for k, v in target.items()})
    return out


GLASS_GLASS = _pair(GLASS, GLASS)
GLASS_WALL = _pair(GLASS, ZERODUR)
GLYCEROL_45 = {"viscosity_pa_s": 4.5e-3, "fluid_density_kg_m3": 1112.0}


def test_pair_stokes_number_of_two_equal_free_spheres_is_twice_the_wall_value() -> None:
    # Davis, Serayssol & Hinch (1986): St = m*V/(6πμR*²); m* = m/2 and R* = R/2 for two
    # equal spheres, so St doubles. Before issue 13 derive() used the particle's R and ρ_p.
    common = dict(diameter_m=D, v_n_in_m_s=0.1193, **GLYCEROL_45)
    wall = derive(**GLASS_GLASS, **common)
    free = derive(**GLASS_GLASS, **common, wall_diameter_m=D, wall_v_n_in_m_s=0.0)
    assert float(wall["stokes_number"]) == pytest.approx(95.0, abs=0.5)  # figure 3
    for name in ("stokes_number", "normal_stokes_number", "added_mass_stokes_number"):
        assert float(free[name]) == pytest.approx(2 * float(wall[name]), rel=1e-12)
    # Re and x₁ use R* too (a fixed sphere has m* = m₁, R* = R/2)
    assert float(free["reynolds_number"]) == pytest.approx(float(wall["reynolds_number"]) / 2)


def test_a_fixed_sphere_is_immovable_and_a_free_one_shares_its_mass() -> None:
    common = dict(diameter_m=D, v_n_in_m_s=0.3, wall_diameter_m=D)
    fixed = derive(**GLASS_GLASS, **common)
    free = derive(**GLASS_GLASS, **common, wall_v_n_in_m_s=0.0)
    m = float(contact.sphere_mass(2540.0, D))
    assert float(fixed["effective_mass_kg"]) == pytest.approx(m, rel=1e-12)
    assert float(free["effective_mass_kg"]) == pytest.approx(m / 2, rel=1e-12)
    assert float(free["effective_radius_m"]) == pytest.approx(D / 4, rel=1e-12)


def test_collision_parameters_come_from_relative_contact_point_velocities() -> None:
    # Equal free spheres, target at rest: the particle stops and the target leaves at
    # 0.97 v (e = 0.97); tangentially the particle keeps 0.1, the target takes 0.05 and
    # both spin. Before issue 13 e would be 0 (from the particle alone) and the target's
    # velocities could not be given.
    out = derive(
        **GLASS_GLASS,
        diameter_m=D,
        wall_diameter_m=D,
        v_n_in_m_s=1.0,
        v_t_in_m_s=0.5,
        omega_in_rad_s=0.0,
        v_n_out_m_s=0.0,
        v_t_out_m_s=0.1,
        omega_out_rad_s=-10.0,
        wall_v_n_in_m_s=0.0,
        wall_v_t_in_m_s=0.0,
        wall_omega_in_rad_s=0.0,
        wall_v_n_out_m_s=0.97,
        wall_v_t_out_m_s=0.05,
        wall_omega_out_rad_s=-10.0,
    )
    r = D / 2
    u_out = 0.1 - 0.05 - 10.0 * r - 10.0 * r
    assert float(out["normal_restitution"]) == pytest.approx(0.97, rel=1e-12)
    assert float(out["rotational_restitution"]) == pytest.approx(-u_out / 0.5, rel=1e-12)
    assert float(out["effective_rebound"]) == pytest.approx(u_out / 1.0, rel=1e-12)
    b = float(out["walton_factor"])
    assert b == pytest.approx(3.5, rel=1e-12)
    assert float(out["sliding_friction"]) == pytest.approx((0.5 - u_out) / (1.97 * b), rel=1e-12)


def test_a_receding_target_lowers_the_approach_speed_everywhere() -> None:
    common = dict(diameter_m=D, wall_diameter_m=D, **GLYCEROL_45)
    moving = derive(**GLASS_GLASS, **common, v_n_in_m_s=0.5, wall_v_n_in_m_s=0.2)
    still = derive(**GLASS_GLASS, **common, v_n_in_m_s=0.3, wall_v_n_in_m_s=0.0)
    for name in ("normal_speed_m_s", "impact_load_n", "max_pressure_pa", "normal_stokes_number"):
        assert float(moving[name]) == pytest.approx(float(still[name]), rel=1e-12), name


@pytest.mark.parametrize(
    ("extra", "field"),
    [
        ({"wall_v_n_in_m_s": 0.0}, "wall_diameter_m"),  # a flat wall cannot move
        ({"wall_diameter_m": D, "wall_v_n_out_m_s": 0.1}, "wall_v_n_in_m_s"),
        ({"wall_diameter_m": D, "wall_v_n_in_m_s": 0.4}, "wall_v_n_in_m_s"),  # recedes
    ],
)
def test_inconsistent_target_velocities_are_refused_in_one_line(extra, field) -> None:
    with pytest.raises(PhysicsInputError) as info:
        derive(**GLASS_GLASS, diameter_m=D, v_n_in_m_s=0.3, **extra)
    assert info.value.field == field and "\n" not in str(info.value)


def test_walton_factor_for_walls_fixed_and_free_spheres() -> None:
    m1 = 2.72e-3
    assert float(pair.walton_factor(m1, m1)) == 3.5  # flat wall or fixed sphere
    assert float(pair.walton_factor(m1 / 2, m1, m1)) == pytest.approx(3.5, rel=1e-15)
    # a thin hollow shell (K² = 2/3) hitting a solid sphere of equal mass
    b = float(pair.walton_factor(m1 / 2, m1, m1, particle_gyration=2 / 3))
    assert b == pytest.approx(1 + 0.5 * (1.5 + 2.5), rel=1e-15)


@given(st.floats(1e-4, 10), st.floats(1e-4, 10), st.floats(0.1, 0.9), st.floats(0.01, 0.5))
def test_walton_sliding_and_friction_invert_each_other(m1, m2, e, mu) -> None:
    b = pair.walton_factor(contact.effective_mass(m1, m2), m1, m2)
    psi_out = pair.walton_sliding_rebound(2.0, mu, e, b)
    assert float(pair.pair_sliding_friction(2.0, psi_out, e, b)) == pytest.approx(mu, rel=1e-9)
    # B = 7/2 reproduces the wall's (2.9)
    assert float(pair.pair_sliding_friction(2.0, psi_out, e, b)) == pytest.approx(
        float(impact.sliding_friction(2.0, psi_out, e)), rel=1e-9
    )


def test_pair_stokes_number_equals_joseph_hunt_for_a_wall() -> None:
    m = contact.sphere_mass(2540.0, D)
    assert float(pair.pair_stokes_number(m, 0.2, 3e-3, D / 2)) == pytest.approx(
        float(flow.stokes_number(2540.0, D / 2, 0.2, 3e-3)), rel=1e-12
    )


def test_incidence_angle_follows_the_contact_point_so_spin_counts() -> None:
    # v_t = 0.1 with backspin ω = −40 rad/s: v_T = 0.1 − 0.254 = −0.154 m/s. The contact
    # point's path makes atan(0.154/0.2) with the normal; before issue 13 derive returned
    # atan(0.1/0.2), the centre's path.
    out = derive(**GLASS_WALL, diameter_m=D, v_n_in_m_s=0.2, v_t_in_m_s=0.1, omega_in_rad_s=-40.0)
    v_t = 0.1 - 40.0 * D / 2
    assert float(out["tangential_speed_m_s"]) == pytest.approx(v_t, rel=1e-12)
    assert float(out["incidence_angle_rad"]) == pytest.approx(np.arctan(abs(v_t) / 0.2))
    assert 0 <= float(out["incidence_angle_rad"]) < np.pi / 2


def test_beta_of_a_normal_impact_is_nan_not_infinite() -> None:
    out = derive(
        **GLASS_WALL,
        diameter_m=D,
        v_n_in_m_s=0.2,
        v_n_out_m_s=0.19,
        v_t_out_m_s=0.001,
        omega_out_rad_s=0.0,
    )
    assert np.isnan(out["rotational_restitution"])
    assert float(out["incidence_angle_rad"]) == 0.0


def test_mixed_targets_vectorized_equal_row_by_row() -> None:
    # flat walls, fixed spheres and free spheres (some with missing after-impact target
    # velocities), with yield stresses known or not, in one call and one row at a time
    rng = np.random.default_rng(13)
    n = 60
    kind = rng.integers(0, 3, n)  # 0 flat, 1 fixed sphere, 2 free sphere
    free = kind == 2
    vn = rng.uniform(0.05, 1.0, n)

    def target(values: np.ndarray, missing: float = 0.0) -> np.ndarray:
        values = np.where(free, values, np.nan)
        return np.where(free & (rng.random(n) < missing), np.nan, values)

    inputs = dict(
        v_n_in_m_s=vn,
        v_t_in_m_s=rng.uniform(0, 1, n),
        omega_in_rad_s=rng.uniform(-30, 30, n),
        v_n_out_m_s=rng.uniform(0, 0.5, n),
        v_t_out_m_s=rng.uniform(-0.2, 0.5, n),
        omega_out_rad_s=rng.uniform(-30, 30, n),
        wall_diameter_m=np.where(kind == 0, np.nan, rng.uniform(5e-3, 3e-2, n)),
        wall_v_n_in_m_s=target(rng.uniform(-0.5, 0.04, n)),
        wall_v_t_in_m_s=target(rng.uniform(-0.5, 0.5, n), 0.2),
        wall_omega_in_rad_s=target(rng.uniform(-30, 30, n), 0.2),
        wall_v_n_out_m_s=target(rng.uniform(0, 0.5, n), 0.2),
        wall_v_t_out_m_s=target(rng.uniform(-0.5, 0.5, n), 0.2),
        wall_omega_out_rad_s=target(rng.uniform(-30, 30, n), 0.2),
        particle_yield_stress_pa=np.where(rng.random(n) < 0.5, np.nan, 1e9),
        wall_yield_stress_pa=np.where(rng.random(n) < 0.5, np.nan, 2e9),
        viscosity_pa_s=np.where(rng.random(n) < 0.2, np.nan, rng.uniform(1e-3, 0.1, n)),
        fluid_density_kg_m3=np.full(n, 1100.0),
        pressure_viscosity_pa_inv=np.where(rng.random(n) < 0.3, np.nan, 6e-9),
    )
    together = derive(**GLASS_WALL, diameter_m=D, **inputs)
    for i in range(n):
        alone = derive(**GLASS_WALL, diameter_m=D, **{k: v[i] for k, v in inputs.items()})
        for name, values in together.items():
            a, b = np.asarray(values)[i], np.asarray(alone[name]).ravel()[0]
            if np.asarray(values).dtype == object:
                assert a == b, (name, i)
            else:
                np.testing.assert_allclose(a, b, rtol=1e-13, equal_nan=True, err_msg=name)
    assert {"film", "uncertain", "asperity_contact", "dry"} >= set(together["roughness_regime"])
    assert set(together["elastic_state"]) <= {"elastic", "yield_exceeded", "unknown"}


@given(
    st.floats(2e-3, 3e-2),
    st.floats(2e-3, 3e-2),
    st.floats(0.1, 1.0),
    st.floats(-0.3, 0.05),
    st.floats(-1.0, 1.0),
    st.floats(-50, 50),
    st.floats(-50, 50),
    st.floats(0.3, 0.99),
    st.floats(0.01, 0.3),
)
def test_sliding_impulse_of_a_free_pair_is_recovered(d1, d2, v1, v2, vt2, w1, w2, e, mu):
    # Build a sliding collision of two unequal free spheres from the impulse balance
    # (normal impulse m*(1+e)v_N, tangential μ_f times it against the slip, torques R × F
    # about n × t) and check derive() gets e, μ_f and Ψ_out = Ψ_in − μ_f(1+e)B back:
    # this pins the sign convention of the target's velocities and spin.
    m1, m2 = (float(contact.sphere_mass(2540.0, d)) for d in (d1, d2))
    r1, r2 = d1 / 2, d2 / 2
    i1, i2 = 0.4 * m1 * r1**2, 0.4 * m2 * r2**2
    m_eff = m1 * m2 / (m1 + m2)
    vt1 = 0.8
    v_n = v1 - v2
    u = vt1 - vt2 + w1 * r1 + w2 * r2
    j_n = m_eff * (1 + e) * v_n
    j_t = mu * j_n * np.sign(u)
    b = 1 + m_eff * (r1**2 / i1 + r2**2 / i2)
    if abs(u) <= mu * (1 + e) * b * v_n:  # it would stick: not a sliding collision
        return
    out = derive(
        **GLASS_GLASS,
        diameter_m=d1,
        wall_diameter_m=d2,
        v_n_in_m_s=v1,
        v_t_in_m_s=vt1,
        omega_in_rad_s=w1,
        v_n_out_m_s=-(v1 - j_n / m1),  # stored away from the target
        v_t_out_m_s=vt1 - j_t / m1,
        omega_out_rad_s=w1 - r1 * j_t / i1,
        wall_v_n_in_m_s=v2,
        wall_v_t_in_m_s=vt2,
        wall_omega_in_rad_s=w2,
        wall_v_n_out_m_s=v2 + j_n / m2,
        wall_v_t_out_m_s=vt2 + j_t / m2,
        wall_omega_out_rad_s=w2 - r2 * j_t / i2,
    )
    assert float(out["normal_restitution"]) == pytest.approx(e, rel=1e-9)
    assert float(out["walton_factor"]) == pytest.approx(b, rel=1e-12)
    # μ_f of (2.9) is signed with Ψ_in; the fits fold by the sign of v_T,in
    assert float(out["sliding_friction"]) * np.sign(u) == pytest.approx(mu, rel=1e-7)
    psi_in = float(out["effective_incidence"])
    assert float(out["effective_rebound"]) == pytest.approx(
        psi_in - np.sign(u) * mu * (1 + e) * b, rel=1e-7, abs=1e-9
    )
