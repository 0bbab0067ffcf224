"""Model limits and predictions of issue 13 (docs/physics.md §10–§12, §14; items 3–9).

Each test fails on the code before issue 13; the comment says how.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from granudb.physics import apparatus, contact, flow, limits, lubrication, viscosity
from granudb.physics.derive import derive
from granudb.physics.numeric import PhysicsInputError

R = 12.7e-3 / 2
STEEL_ZERODUR = {
    "particle_density_kg_m3": 7780.0,
    "particle_youngs_modulus_pa": 190e9,
    "particle_poisson_ratio": 0.27,
    "particle_roughness_rms_m": 0.0236e-6,
    "wall_density_kg_m3": 2540.0,
    "wall_youngs_modulus_pa": 91e9,
    "wall_poisson_ratio": 0.24,
    "wall_roughness_rms_m": 0.0155e-6,
    "diameter_m": 2 * R,
}
GLYCEROL_37 = {
    "viscosity_pa_s": 3e-3,
    "fluid_density_kg_m3": 1090.4,
    "pressure_viscosity_pa_inv": 6e-9,
}
WATER = {"viscosity_pa_s": 1e-3, "fluid_density_kg_m3": 998.0}  # no coefficient (seed data)


def _at(speed: float, degrees: float, **fluid) -> dict:
    angle = np.radians(degrees)
    return derive(
        **STEEL_ZERODUR,
        v_n_in_m_s=speed * np.cos(angle),
        v_t_in_m_s=speed * np.sin(angle),
        **fluid,
    )


# --- §11 yield (item 3) ---------------------------------------------------------------


def test_yield_constant_and_speed() -> None:
    assert float(limits.YIELD_SPEED_CONSTANT) == pytest.approx(np.pi**4 * 1.6**5 / 40, rel=1e-15)
    assert float(limits.YIELD_SPEED_CONSTANT) == pytest.approx(
        25.5, abs=0.05
    )  # docs/physics.md §11
    # at V_y, (5.5) gives exactly p_max = 1.6 Y
    e_star = float(contact.reduced_modulus(190e9, 0.27, 91e9, 0.24))
    v_y = limits.yield_speed(7780.0, 1.5e9, e_star)
    p = contact.max_pressure_from_impact(7780.0, v_y, e_star)
    assert float(p) == pytest.approx(1.6 * 1.5e9, rel=1e-12)


def test_yield_is_a_named_state_and_quasi_static_is_not_valid_above_it() -> None:
    # Issue 13: at 5 m/s and 30° steel on Zerodur has p_max = 4.07 GPa and the
    # quasi-static verdict said "valid". Y = 1.5 GPa is an illustrative steel value (not
    # seed data).
    out = _at(5.0, 30.0, particle_yield_stress_pa=1.5e9, wall_yield_stress_pa=np.nan)
    assert float(out["max_pressure_pa"]) == pytest.approx(4.07e9, rel=0.01)
    assert out["elastic_state"] == "yield_exceeded"
    assert not bool(out["quasi_static_valid"])
    v_y = float(out["yield_speed_m_s"])
    e_star = float(out["reduced_modulus_pa"])
    assert v_y == pytest.approx(float(limits.yield_speed(7780.0, 1.5e9, e_star)), rel=1e-12)
    # below V_y with the wall's Y unknown: "unknown", never "elastic"
    slow = _at(0.5 * v_y, 0.0, particle_yield_stress_pa=1.5e9)
    assert slow["elastic_state"] == "unknown" and bool(slow["quasi_static_valid"])
    both = _at(0.5 * v_y, 0.0, particle_yield_stress_pa=1.5e9, wall_yield_stress_pa=3e9)
    assert both["elastic_state"] == "elastic"
    none = _at(5.0, 0.0)
    assert none["elastic_state"] == "unknown" and np.isnan(none["yield_speed_m_s"])


# --- §12 bounds of (5.8) (item 4) -----------------------------------------------------


def test_exact_constant_of_5_10_makes_it_equal_to_5_8() -> None:
    k = 2 * np.pi / 4.3384 * (3 / 4) ** (2 / 3) * (4 / 3) ** (-2 / 7) * (5 * np.pi / 4) ** (-6 / 35)
    assert float(lubrication.DIMENSIONLESS_FRICTION_FACTOR) == pytest.approx(k, rel=1e-15)
    assert round(k, 2) == lubrication.PRINTED_FRICTION_FACTOR == 0.87
    es = float(contact.reduced_modulus(190e9, 0.27, 91e9, 0.24))
    eta = 375e-12
    for speed, u, mu in [(0.05, 0.01, 1e-3), (0.3, 0.1, 3e-3), (1.0, 1.0, 48e-3)]:
        load = contact.hertz_impact_load(R, es, 7780.0, speed)
        a = contact.max_contact_radius(R, load, es)
        p = contact.max_pressure(load, a)
        h = lubrication.traction_film_thickness(R, mu, u, eta, load, es)
        integral = lubrication.friction_integral(eta * p)
        full = lubrication.lubricated_friction(mu, u, load, h, a, eta, p)
        short = lubrication.lubricated_friction_dimensionless(
            mu, u, es, R, eta, 7780.0, speed, integral
        )
        assert float(short) == pytest.approx(float(full), rel=1e-12)
        back = lubrication.viscosity_for_friction(full, u, es, R, eta, 7780.0, speed, integral)
        assert float(back) == pytest.approx(mu, rel=1e-10)


def test_lubricated_friction_above_its_bound_is_not_used_for_maw() -> None:
    # Issue 13: steel on Zerodur in 37 % glycerol at 30°, 5 m/s gives μ_f = 169 from (5.8)
    # and the regime said "stick". The value is kept (it is what (5.8) says) but flagged,
    # and Maw's regime uses the limiting-shear cap min(0.11, 0.1) instead.
    out = _at(5.0, 30.0, **GLYCEROL_37)
    assert float(out["lubricated_friction"]) == pytest.approx(169, rel=0.02)
    assert out["lubricated_friction_state"] == "above_limit"
    assert float(out["friction_coefficient_used"]) == pytest.approx(0.1)
    assert out["tangential_regime"] != "stick"
    # inside the paper's range (0.3 m/s) (5.8) is in range and used as before
    low = _at(0.3, 30.0, **GLYCEROL_37)
    assert low["lubricated_friction_state"] == "in_range"
    assert float(low["friction_coefficient_used"]) == float(low["lubricated_friction"]) < 0.1


def test_friction_cap_follows_the_dry_value_and_the_limiting_shear_slope() -> None:
    out = _at(5.0, 30.0, **GLYCEROL_37, dry_friction=0.05)
    assert float(out["friction_coefficient_used"]) == 0.05
    out = _at(0.3, 30.0, **GLYCEROL_37, limiting_shear_slope=0.001)
    assert out["lubricated_friction_state"] == "above_limit"


def test_a_zero_pressure_coefficient_is_refused() -> None:
    # C = 0 made Gohar's film vanish and μ_f infinite; before issue 13 it was accepted.
    with pytest.raises(PhysicsInputError) as info:
        _at(0.3, 20.0, **{**GLYCEROL_37, "pressure_viscosity_pa_inv": 0.0})
    assert info.value.field == "pressure_viscosity_pa_inv"


# --- item 6: water, no silent NaN -------------------------------------------------------


def test_water_without_a_coefficient_is_a_named_state_not_the_dry_value() -> None:
    # Issue 13: steel in water at 0.3 m/s, 20° silently fell back to μ_f = 0.11 and said
    # "slip then stick" (the paper's μ_f ≈ 0.02 gives gross slip). Now the state names the
    # missing coefficient; μ_f is only bounded by the cap, which here cannot decide.
    out = _at(0.3, 20.0, **WATER)
    assert out["lubricated_friction_state"] == "no_pressure_coefficient"
    assert np.isnan(out["lubricated_friction"])
    assert out["tangential_regime"] == "undetermined"
    # at 45° even the cap gives gross slip, so the regime is certain; the paper's
    # μ_f ≈ 0.02 (ζ_in > 10°) agrees
    steep = _at(0.3, 45.0, **WATER)
    assert steep["tangential_regime"] == "gross_slip"
    # no NaN in any verdict column
    for name in ("tangential_regime", "roughness_regime", "elastic_state", "rebound_expected"):
        assert str(out[name]) not in {"nan", "None"}


# --- item 5: three-state roughness -----------------------------------------------------


def test_roughness_regime_has_an_uncertain_band() -> None:
    # σ between x₁/4 and x₁/3 is "uncertain" (Davis's band); before issue 13 only σ > h_m.
    sigma = float(contact.composite_roughness(0.0236e-6, 0.0155e-6))
    e_star = float(contact.reduced_modulus(190e9, 0.27, 91e9, 0.24))

    def speed_for(x1: float) -> float:  # invert x₁ = (4 μ v R^{3/2} / (π E*))^{2/5}
        return x1**2.5 * np.pi * e_star / (4 * 1e-3 * R**1.5)

    for ratio, expected in [(2.5, "asperity_contact"), (3.5, "uncertain"), (4.5, "film")]:
        out = _at(speed_for(ratio * sigma), 0.0, **WATER)
        assert float(out["elastic_length_m"]) == pytest.approx(ratio * sigma, rel=1e-9)
        assert out["roughness_regime"] == expected
        assert bool(out["roughness_exceeds_gap"]) == (expected == "asperity_contact")
    assert _at(0.3, 0.0)["roughness_regime"] == "dry"


# --- §10 predicted wet restitution (item 7) ---------------------------------------------


def test_predicted_restitution_follows_legendre_and_gondret() -> None:
    st_values = np.array([5.0, 10.0, 10.5, 35.0, 1e6])
    e = flow.predicted_restitution(st_values)
    assert e[:2].tolist() == [0.0, 0.0]  # no rebound at or below St_c
    assert e[3] == pytest.approx(0.97 * np.exp(-1.0), rel=1e-12)  # St = β_L
    assert e[4] == pytest.approx(0.97, rel=1e-4)
    assert np.all(np.diff(e) >= 0)


def test_predicted_restitution_in_derive() -> None:
    # Figure 3's glass sphere in 45 % glycerol at St = 95: added-mass St = 95 (1 + ρ_f/(2ρ_p)).
    # Comparison with the paper: the seed text of Joseph & Hunt's figure 5 gives measured e
    # against St cos ζ_in only as a plot (no numbers are printed), so no numeric check is
    # possible from the stored sources. What the text does state — e of oblique collisions
    # depends on the normal Stokes number alone, "regardless of the incident angle" — is
    # why the prediction uses the normal approach speed (checked below: the tangential
    # velocity does not change it).
    glass = {
        "particle_density_kg_m3": 2540.0,
        "particle_youngs_modulus_pa": 60e9,
        "particle_poisson_ratio": 0.23,
        "particle_roughness_rms_m": 0.1305e-6,
    }
    wall = {k: v for k, v in STEEL_ZERODUR.items() if k.startswith("wall_")}
    out = derive(
        **glass,
        **wall,
        diameter_m=2 * R,
        v_n_in_m_s=0.1193,
        viscosity_pa_s=4.5e-3,
        fluid_density_kg_m3=1112.0,
    )
    st_am = float(out["added_mass_stokes_number"])
    assert st_am == pytest.approx(
        float(flow.stokes_number(2540.0 + 0.5 * 1112.0, R, 0.1193, 4.5e-3)), rel=1e-12
    )
    assert float(out["predicted_restitution"]) == pytest.approx(0.97 * np.exp(-35 / st_am))
    oblique = derive(
        **glass,
        **wall,
        diameter_m=2 * R,
        v_n_in_m_s=0.1193,
        v_t_in_m_s=0.2,
        viscosity_pa_s=4.5e-3,
        fluid_density_kg_m3=1112.0,
    )
    assert float(oblique["predicted_restitution"]) == float(out["predicted_restitution"])
    dry = derive(**glass, **wall, diameter_m=2 * R, v_n_in_m_s=0.1193)
    assert float(dry["predicted_restitution"]) == 0.97
    stuck = derive(
        **glass,
        **wall,
        diameter_m=2 * R,
        v_n_in_m_s=0.001,
        viscosity_pa_s=0.05,
        fluid_density_kg_m3=1200.0,
    )
    assert float(stuck["predicted_restitution"]) == 0.0


# --- (A 2), §14 (item 8) -----------------------------------------------------------------


@given(st.floats(1e-3, 0.1), st.floats(1e3, 1e9), st.floats(1e-10, 1e-5), st.floats(0.1, 10))
def test_consistent_time_scale_ratio_is_dimensionless(radius, kappa, k_s, scale) -> None:
    ratio = float(apparatus.consistent_time_scale_ratio(radius, kappa, k_s))
    mass = 1.0  # √(κ I₀/(m K_s)) with I₀ = 0.4 m R²: independent of m
    assert ratio == pytest.approx(np.sqrt(kappa * 0.4 * mass * radius**2 / (mass * k_s)))
    # change the unit of length by `scale`: R→sR, κ [N/m]→κ/s, K_s [N·m]→s K_s; unchanged
    rescaled = apparatus.consistent_time_scale_ratio(radius * scale, kappa / scale, k_s * scale)
    assert float(rescaled) == pytest.approx(ratio, rel=1e-12)
    printed = float(apparatus.time_scale_ratio(radius, kappa, k_s))
    assert ratio == pytest.approx(printed * radius**2 * np.sqrt(0.4), rel=1e-12)


# --- item 9: viscosity continuous in temperature --------------------------------------

GLYCEROL_45_POINTS = (
    [10, 15, 20, 25, 30, 35, 40, 45, 50, 55, 60],
    [6.813, 5.586, 4.648, 3.919, 3.343, 2.882, 2.508, 2.201, 1.948, 1.735, 1.556],
)


def test_referenced_viscosity_passes_through_the_printed_value_and_is_continuous() -> None:
    # Before issue 13 glycerol-45 read 4.500 cP at 20.5 °C, 4.552 at 20.6 and 4.490 at 21
    # (printed value within ±0.5 °C, seed points outside). Referenced to the printed
    # 4.5 cP at 20 °C, the Andrade interpolation of the points is exact there and monotonic.
    table = viscosity.TabulatedViscosity(
        GLYCEROL_45_POINTS[0], np.array(GLYCEROL_45_POINTS[1]) * 1e-3
    )
    model = viscosity.ReferencedViscosity(table, 20.0, 4.5e-3)
    assert float(model.viscosity(20.0)) == pytest.approx(4.5e-3, rel=1e-14)
    t = np.linspace(19.0, 22.0, 3001)
    mu = model.viscosity(t)
    assert np.all(np.diff(mu) < 0)
    assert np.max(np.abs(np.diff(mu))) < 1e-3 * 4.5e-3  # no jump anywhere near T_ref
    assert float(model.temperature_for_viscosity(model.viscosity(20.6))) == pytest.approx(20.6)
    cheng = viscosity.ReferencedViscosity(viscosity.GlycerolWater(0.45), 20.0, 4.5e-3)
    assert float(cheng.viscosity(20.0)) == pytest.approx(4.5e-3, rel=1e-14)


def test_referenced_viscosity_refuses_with_the_callers_number() -> None:
    table = viscosity.TabulatedViscosity(
        GLYCEROL_45_POINTS[0], np.array(GLYCEROL_45_POINTS[1]) * 1e-3
    )
    model = viscosity.ReferencedViscosity(table, 20.0, 4.5e-3)
    top = float(model.viscosity(10.0))
    assert float(model.temperature_for_viscosity(top)) == pytest.approx(10.0)
    with pytest.raises(viscosity.ViscosityRangeError) as info:
        model.temperature_for_viscosity(0.02)
    assert info.value.value == "0.02 Pa·s" and f"{top:g}" in str(info.value)


@pytest.mark.parametrize("fluid", [GLYCEROL_37, WATER, {}])
def test_a_normal_impact_sticks_in_any_fluid(fluid) -> None:
    # no tangential motion: ψ_in = 0, "stick", never a 0/0 read as gross slip
    out = _at(0.3, 0.0, **fluid)
    assert float(out["maw_psi_in"]) == 0.0
    assert out["tangential_regime"] == "stick"
    assert np.isfinite(out["friction_coefficient_used"])
