"""Every derived quantity and verdict for a table of collisions or scenarios, in one
vectorized pass (no per-row Python, no quadrature).

``derive()`` takes arrays (or scalars, broadcast together) of the pair's material
properties, the fluid's state, the particle size and the velocities, and returns a dict of
arrays under granudb's column names (their units and meanings are in
``granudb.vocabulary.DERIVED_TERMS``). A dry collision has ``viscosity_pa_s`` NaN: its
fluid quantities are NaN, its roughness verdict False and rebound is expected. Where an
input makes a quantity undefined (no pressure–viscosity coefficient, no measured rebound)
that quantity is NaN, element by element.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from granudb.physics import contact, flow, impact, lubrication
from granudb.physics._types import Numeric, PhysicsInputError

#: Friction coefficient assumed where asperities touch or the collision is dry; the paper's
#: dry fits give 0.11 (steel) and 0.106 (glass) on Zerodur (§3).
DRY_FRICTION = 0.11


def _check(name: str, values: np.ndarray, ok: np.ndarray, rule: str) -> None:
    bad = ~ok
    if bad.any():
        index = int(np.flatnonzero(bad.ravel())[0])
        raise PhysicsInputError(
            name, f"{values.ravel()[index]:g}", rule, row=index + 1 if values.size > 1 else None
        )


def derive(
    *,
    particle_density_kg_m3: Numeric,
    particle_youngs_modulus_pa: Numeric,
    particle_poisson_ratio: Numeric,
    particle_roughness_rms_m: Numeric,
    wall_density_kg_m3: Numeric,
    wall_youngs_modulus_pa: Numeric,
    wall_poisson_ratio: Numeric,
    wall_roughness_rms_m: Numeric,
    diameter_m: Numeric,
    v_n_in_m_s: Numeric,
    v_t_in_m_s: Numeric = 0.0,
    omega_in_rad_s: Numeric = 0.0,
    particle_shear_modulus_pa: Numeric = np.nan,
    wall_shear_modulus_pa: Numeric = np.nan,
    wall_diameter_m: Numeric = np.nan,
    fluid_density_kg_m3: Numeric = np.nan,
    viscosity_pa_s: Numeric = np.nan,
    pressure_viscosity_pa_inv: Numeric = np.nan,
    v_n_out_m_s: Numeric = np.nan,
    v_t_out_m_s: Numeric = np.nan,
    omega_out_rad_s: Numeric = np.nan,
    critical_stokes: float = flow.CRITICAL_STOKES_NUMBER,
    dry_friction: float = DRY_FRICTION,
    gap_fraction: float = lubrication.GAP_FRACTION,
) -> dict[str, np.ndarray]:
    """Derive every derived column (``granudb.vocabulary.DERIVED_TERMS``) for arrays of collisions.

    Inputs are SI and broadcast together. NaN shear modulus: derived from E and ν. NaN
    ``wall_diameter_m``: a flat wall (infinite radius and mass). NaN ``viscosity_pa_s``: a
    dry collision. NaN after-impact velocities: a scenario (per-collision parameters NaN).
    The tangential regime uses ``dry_friction`` where the collision is dry or the roughness
    exceeds the gap, else the lubricated friction (5.8) — the paper's regime argument (§4).

    Raises ``PhysicsInputError`` on unphysical input (non-positive size, speed or modulus,
    ν outside (−1, 0.5), incidence outside [0°, 90°)).
    """
    arrays = np.broadcast_arrays(
        *(
            np.asarray(v, dtype=float)
            for v in (
                particle_density_kg_m3,
                particle_youngs_modulus_pa,
                particle_poisson_ratio,
                particle_roughness_rms_m,
                particle_shear_modulus_pa,
                wall_density_kg_m3,
                wall_youngs_modulus_pa,
                wall_poisson_ratio,
                wall_roughness_rms_m,
                wall_shear_modulus_pa,
                wall_diameter_m,
                diameter_m,
                v_n_in_m_s,
                v_t_in_m_s,
                omega_in_rad_s,
                fluid_density_kg_m3,
                viscosity_pa_s,
                pressure_viscosity_pa_inv,
                v_n_out_m_s,
                v_t_out_m_s,
                omega_out_rad_s,
            )
        )
    )
    (
        rho1,
        e1,
        nu1,
        s1,
        g1,
        rho2,
        e2,
        nu2,
        s2,
        g2,
        d2,
        d,
        vn,
        vt,
        w,
        rho_f,
        mu,
        c_barus,
        vn_out,
        vt_out,
        w_out,
    ) = arrays

    _check("diameter_m", d, d > 0, "must be > 0")
    _check("v_n_in_m_s", vn, vn > 0, "must be > 0 (the normal speed towards the wall)")
    _check("v_t_in_m_s", vt, vt >= 0, "must be ≥ 0 (the tangential axis points along it)")
    for name, values in (
        ("particle_youngs_modulus_pa", e1),
        ("wall_youngs_modulus_pa", e2),
        ("particle_density_kg_m3", rho1),
        ("wall_density_kg_m3", rho2),
    ):
        _check(name, values, values > 0, "must be > 0")
    for name, values in (("particle_poisson_ratio", nu1), ("wall_poisson_ratio", nu2)):
        _check(name, values, (values > -1) & (values < 0.5), "must be > -1 and < 0.5")
    _check("viscosity_pa_s", mu, np.isnan(mu) | (mu > 0), "must be > 0 (NaN for dry)")

    g1 = np.where(np.isnan(g1), contact.shear_modulus(e1, nu1), g1)
    g2 = np.where(np.isnan(g2), contact.shear_modulus(e2, nu2), g2)
    flat = np.isnan(d2)
    radius = d / 2.0
    e_star = contact.reduced_modulus(e1, nu1, e2, nu2)
    g_star = contact.reduced_shear_modulus(g1, nu1, g2, nu2)
    r_eff = contact.effective_radius(radius, np.where(flat, np.inf, d2 / 2.0))
    m1 = contact.sphere_mass(rho1, d)
    m_eff = contact.effective_mass(m1, np.where(flat, np.inf, contact.sphere_mass(rho2, d2)))
    speed = np.hypot(vn, vt)

    load = contact.peak_impact_force(m_eff, vn, e_star, r_eff)
    a = contact.max_contact_radius(r_eff, load, e_star)
    p_max = contact.max_pressure(load, a)
    delta = contact.max_approach(m_eff, vn, e_star, r_eff)
    t_c = contact.contact_time(m_eff, r_eff, e_star, vn)
    c_wave = np.minimum(contact.wave_speed(e1, rho1), contact.wave_speed(e2, rho2))
    qs_ratio = contact.quasi_static_ratio(a, c_wave, t_c)

    immersed = ~np.isnan(mu)
    re = flow.reynolds_number(rho_f, radius, speed, mu)
    st = flow.stokes_number(rho1, radius, speed, mu)
    st_n = flow.normal_stokes_number(rho1, radius, vn, mu)
    x1 = lubrication.davis_elastic_length(mu, vn, r_eff, e_star)
    h_m = lubrication.ehd_min_gap(x1, gap_fraction)
    eta_hat = lubrication.chu_cameron_coefficient(c_barus)
    x3 = lubrication.piezoviscous_length(eta_hat, mu, vn, r_eff)
    sigma = contact.composite_roughness(s1, s2)
    with np.errstate(divide="ignore", invalid="ignore"):
        film = np.where(immersed, h_m / sigma, np.nan)
    rough = immersed & (sigma > h_m)

    u = impact.contact_point_velocity(vt, w, radius)
    u_abs = np.abs(u)
    h_film = lubrication.traction_film_thickness(r_eff, mu, u_abs, eta_hat, load, e_star)
    integral = lubrication.friction_integral(eta_hat * p_max)
    mu_lub = lubrication.lubricated_friction(mu, u_abs, load, h_film, a, eta_hat, p_max)
    mu_lub = np.where(immersed & ~np.isnan(eta_hat), mu_lub, np.nan)
    strain = lubrication.shear_strain(mu, u_abs, e_star, r_eff)

    full_film = immersed & ~rough & np.isfinite(mu_lub) & (mu_lub > 0)
    mu_used = np.where(full_film, mu_lub, dry_friction)
    ratio = impact.stiffness_ratio(g_star, e_star)
    chi = impact.maw_chi(ratio)
    psi_maw = impact.maw_psi(ratio, u_abs, mu_used, vn)
    regime = np.asarray(impact.TANGENTIAL_REGIME_NAMES, dtype=object)[
        impact.tangential_regime(psi_maw, chi)
    ]

    e = impact.normal_restitution(vn, vn_out)
    u_out = impact.contact_point_velocity(vt_out, w_out, radius)
    beta = impact.rotational_restitution(u, u_out)
    psi_in = impact.effective_incidence(u, vn)
    psi_out = impact.effective_rebound(u_out, vn)
    mu_f = impact.sliding_friction(psi_in, psi_out, e)

    nan = np.full(d.shape, np.nan)
    fluid = {  # dry rows: NaN
        "reynolds_number": re,
        "stokes_number": st,
        "normal_stokes_number": st_n,
        "elastic_length_m": x1,
        "min_gap_m": h_m,
        "piezoviscous_length_m": x3,
        "traction_film_m": h_film,
        "shear_strain": strain,
    }
    fluid = {k: np.where(immersed, v, nan) for k, v in fluid.items()}
    return {
        "reduced_modulus_pa": e_star,
        "reduced_shear_modulus_pa": g_star,
        "effective_radius_m": r_eff,
        "particle_mass_kg": m1,
        "effective_mass_kg": m_eff,
        "impact_speed_m_s": speed,
        "incidence_angle_rad": np.arctan2(vt, vn),
        "reynolds_number": fluid["reynolds_number"],
        "stokes_number": fluid["stokes_number"],
        "normal_stokes_number": fluid["normal_stokes_number"],
        "impact_load_n": load,
        "contact_radius_m": a,
        "max_pressure_pa": p_max,
        "max_approach_m": delta,
        "contact_time_s": t_c,
        "wave_speed_m_s": c_wave,
        "quasi_static_ratio": qs_ratio,
        "quasi_static_valid": qs_ratio < contact.QUASI_STATIC_LIMIT,
        "elastic_length_m": fluid["elastic_length_m"],
        "min_gap_m": fluid["min_gap_m"],
        "eta_hat_pa_inv": eta_hat,
        "piezoviscous_length_m": fluid["piezoviscous_length_m"],
        "composite_roughness_m": sigma,
        "film_parameter": film,
        "roughness_exceeds_gap": rough,
        "rebound_expected": ~immersed | (st_n > critical_stokes),
        "tangential_speed_m_s": u,
        "traction_film_m": np.where(np.isnan(eta_hat), nan, fluid["traction_film_m"]),
        "friction_integral": np.where(np.isnan(eta_hat), nan, integral),
        "lubricated_friction": mu_lub,
        "shear_strain": fluid["shear_strain"],
        "friction_coefficient_used": mu_used,
        "maw_chi": chi,
        "maw_psi_in": psi_maw,
        "tangential_regime": regime,
        "normal_restitution": e,
        "rotational_restitution": beta,
        "effective_incidence": psi_in,
        "effective_rebound": psi_out,
        "sliding_friction": mu_f,
    }


def scalar_view(result: dict[str, np.ndarray], index: int = 0) -> dict[str, Any]:
    """One row of a ``derive`` result as plain Python values (for one scenario)."""
    row: dict[str, Any] = {}
    for name, values in result.items():
        value = np.asarray(values).ravel()[index]
        row[name] = value.item() if hasattr(value, "item") else value
    return row
