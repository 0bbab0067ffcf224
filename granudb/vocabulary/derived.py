"""The derived columns: everything ``granudb.physics.derive.derive`` computes, with the
title, SI unit, symbol and relation a person reads (a test checks that the two agree);
and ``term``, which finds any column's term, stored or derived."""

from __future__ import annotations

from granudb.vocabulary.terms import TERMS, Term


def _derived(title: str, unit: str | None, symbol: str, description: str) -> Term:
    return Term(title, unit, description, role="derived", symbol=symbol)


#: Every column ``granudb.physics.derive.derive`` returns, in presentation order; a test
#: checks the two agree.
DERIVED_TERMS: dict[str, Term] = {
    "reduced_modulus_pa": _derived(
        "Reduced modulus", "Pa", "E*", "E*, reduced modulus of the pair (§1)"
    ),
    "reduced_shear_modulus_pa": _derived(
        "Reduced shear modulus", "Pa", "G*", "G*, reduced shear modulus (Appendix)"
    ),
    "effective_radius_m": _derived(
        "Effective radius", "m", "R*", "R, effective radius (1/R = 1/R₁ + 1/R₂)"
    ),
    "particle_mass_kg": _derived("Particle mass", "kg", "m₁", "m₁ = ρ π d³/6"),
    "effective_mass_kg": _derived("Effective mass", "kg", "m*", "m, effective mass (wall: m₂ = ∞)"),
    "walton_factor": _derived(
        "Walton factor",
        None,
        "B",
        "B = 1 + m*(R₁²/I₁ + R₂²/I₂) of the Walton relations (§9; 7/2 for solid spheres)",
    ),
    "impact_speed_m_s": _derived(
        "Impact speed", "m/s", "V", "V = √(v_N² + v_t²), relative speed of the centres"
    ),
    "normal_speed_m_s": _derived(
        "Normal approach speed", "m/s", "v_N,in", "v_N,in = (v₁ − v₂)·n, relative (§9)"
    ),
    "incidence_angle_rad": _derived(
        "Incidence angle",
        "rad",
        "ζ_in",
        "ζ_in of the contact point's path, atan(|v_T,in|/v_N,in): spin counts",
    ),
    "reynolds_number": _derived(
        "Reynolds number",
        None,
        "Re",
        "Re = 2ρ_f R* V / μ, on the pair's effective radius R* (Davis et al. 1986; wall: R)",
    ),
    "stokes_number": _derived(
        "Stokes number", None, "St", "St = m*V/(6πμR*²), Davis's pair form (wall: 2ρ_p R V/(9μ))"
    ),
    "normal_stokes_number": _derived(
        "Normal Stokes number", None, "St_n", "St_n = m* v_N,in/(6πμR*²) (§4, §9)"
    ),
    "added_mass_stokes_number": _derived(
        "Added-mass Stokes number",
        None,
        "St_am",
        "St_n (1 + C_M ρ_f/ρ_p), C_M = 1/2 (Legendre et al. 2006; wall: (ρ_p+ρ_f/2)2Rv_N/(9μ))",
    ),
    "impact_load_n": _derived(
        "Impact load", "N", "W", "W, peak Hertz load at v_N,in ((2.2) for a wall)"
    ),
    "contact_radius_m": _derived("Contact radius", "m", "a", "a = (3RW/(4E*))^{1/3} (2.1)"),
    "max_pressure_pa": _derived("Max pressure", "Pa", "p_max", "p_max = 3W/(2πa²) (5.5)"),
    "max_approach_m": _derived("Max approach", "m", "δ_max", "δ_max = (15mV²/(16E*R^{1/2}))^{2/5}"),
    "contact_time_s": _derived("Contact time", "s", "t_c", "t_c ≈ 2.87 (m²/(R E*² V))^{1/5}"),
    "wave_speed_m_s": _derived(
        "Wave speed", "m/s", "c", "c = √(E/ρ), the slower of the two bodies"
    ),
    "quasi_static_ratio": _derived(
        "Quasi static ratio", None, "a/(c t_c)", "a/(c t_c): Hertz holds when ≪ 1 (thesis (3.18))"
    ),
    "quasi_static_valid": _derived(
        "Quasi static valid",
        None,
        "quasi-static",
        "quasi_static_ratio < 0.1 and yield not exceeded (elastic_state)",
    ),
    "yield_speed_m_s": _derived(
        "Yield speed",
        "m/s",
        "V_y",
        "v_N,in at which p_max = 1.6 Y of the softer known body (§11); NaN: no Y known",
    ),
    "elastic_state": _derived(
        "Elastic state",
        None,
        "yield",
        "elastic / yield_exceeded (p_max > 1.6 Y) / unknown (a Y not known: not 'safe')",
    ),
    "restitution_ceiling": _derived(
        "Dry restitution used",
        None,
        "e_dry,V",
        "the pair's dry e, bounded past yield by Thornton (1997): min(e_dry, e_T(V_y/V)) (§15)",
    ),
    "restitution_model": _derived(
        "Restitution model",
        None,
        "e model",
        "which e applies: elastic (e_dry: below V_y, or past it below the hand-over speed "
        "where Thornton's e falls to e_dry) or elastic_plastic (Thornton 1997, above it) (§15)",
    ),
    "contact_radius_ratio": _derived(
        "Contact radius / radius", None, "a/R*", "a/R*, Hertz's small-strain measure (§16)"
    ),
    "approach_ratio": _derived("Approach / radius", None, "δ/R*", "δ/R* = (a/R*)² (§16)"),
    "hertz_strain_valid": _derived(
        "Hertz small strain valid", None, "a/R* ≤ 0.1", "a/R* ≤ 0.1, Hertz's small strain (§16)"
    ),
    "elastic_length_m": _derived(
        "Elastic length", "m", "x₁", "x₁ = (4μv₀R^{3/2}/(πE*))^{2/5} (§1, Davis et al.)"
    ),
    "min_gap_m": _derived(
        "Min gap", "m", "h_m", "h_m = x₁/3, EHD minimum gap of the approach (§1, §4)"
    ),
    "eta_hat_pa_inv": _derived("Eta hat", "1/Pa", "η̂", "η̂ = C/16 (§5)"),
    "piezoviscous_length_m": _derived("Piezoviscous length", "m", "x₃", "x₃ = (η̂μ₀v₀R)^{1/2} (§1)"),
    "composite_roughness_m": _derived("Composite roughness", "m", "σ", "σ = √(σ₁² + σ₂²)"),
    "film_parameter": _derived(
        "Film parameter",
        None,
        "Λ",
        "Λ = h_m/σ, h_m = x₁/3: < 1 asperity contact, 1–4/3 uncertain (h_m = x₁/4 … x₁/3, "
        "Davis et al. 1986), ≥ 4/3 film",
    ),
    "roughness_exceeds_gap": _derived(
        "Roughness exceeds gap", None, "σ > h_m", "σ > h_m: asperities touch through the film"
    ),
    "roughness_regime": _derived(
        "Roughness regime",
        None,
        "σ vs h_m",
        "asperity_contact (σ > x₁/3) / uncertain (x₁/4 < σ ≤ x₁/3) / film (σ ≤ x₁/4) / dry / "
        "not_stated (a material's roughness is not stated)",
    ),
    "rebound_expected": _derived("Rebound expected", None, "rebound", "St_n > St_c (dry: always)"),
    "predicted_restitution": _derived(
        "Predicted restitution",
        None,
        "e_pred",
        "e_dry exp(−35/St_am) (Legendre et al. 2006); 0 without rebound; dry: e_dry",
    ),
    "tangential_speed_m_s": _derived(
        "Tangential speed", "m/s", "v_T,in", "U = v_T,in = v_t + ωR, contact point's speed"
    ),
    "traction_film_m": _derived("Traction film", "m", "h_film", "Gohar's traction film (5.6)"),
    "friction_integral": _derived("Friction integral", None, "A", "A(η̂ p_max) (5.9)"),
    "lubricated_friction": _derived(
        "Lubricated friction",
        None,
        "μ_f (5.8)",
        "μ_f of the smooth lubricated contact (5.8); read with lubricated_friction_state",
    ),
    "lubricated_friction_state": _derived(
        "Lubricated friction state",
        None,
        "(5.8) range",
        "in_range / above_limit (> min(μ_dry, 0.1), Bair & Winer 1979) / "
        "no_pressure_coefficient / dry",
    ),
    "shear_strain": _derived("Shear strain", None, "γ_s", "(μ₀U/(E*R))^{2/7}, figure 15's axis"),
    "friction_coefficient_used": _derived(
        "Friction coefficient used",
        None,
        "μ_f (Maw)",
        "μ_f for Maw: dry if asperities touch; (5.8) in range; else the cap min(μ_dry, 0.1)",
    ),
    "maw_chi": _derived("Maw chi", None, "χ", "χ = (2G*/E*) B (2.3)"),
    "maw_psi_in": _derived(
        "Maw psi in", None, "ψ_in", "ψ_in = 2(2G*/E*) v_T,in / (μ_f v_N,in) (2.4)"
    ),
    "tangential_regime": _derived(
        "Tangential regime",
        None,
        "regime",
        "stick / slip_then_stick / gross_slip (Maw); undetermined: μ_f only bounded",
    ),
    "normal_restitution": _derived(
        "Normal restitution", None, "e", "e = −v_N,out / v_N,in, relative (§9)"
    ),
    "rotational_restitution": _derived(
        "Rotational restitution", None, "β", "β = −v_T,out / v_T,in (2.8); NaN if v_T,in = 0"
    ),
    "effective_incidence": _derived(
        "Effective incidence", None, "Ψ_in", "Ψ_in = v_T,in / v_N,in (2.5)"
    ),
    "effective_rebound": _derived(
        "Effective rebound", None, "Ψ_out", "Ψ_out = v_T,out / v_N,in (2.5)"
    ),
    "sliding_friction": _derived(
        "Sliding friction", None, "μ_f", "μ_f = (Ψ_in − Ψ_out)/((1+e)B) (2.9)"
    ),
}


def term(column: str) -> Term:
    """The term for any column, stored or derived; ids and foreign keys get a generic one."""
    if column in TERMS:
        return TERMS[column]
    if column in DERIVED_TERMS:
        return DERIVED_TERMS[column]
    if column.endswith("_id"):
        return Term(
            column[:-3].replace("_", " ").capitalize(),
            None,
            f"Reference to {column[:-3].replace('_', ' ')}.",
        )
    return Term(column.replace("_", " ").capitalize(), None, "")
