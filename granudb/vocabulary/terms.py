"""granudb's vocabulary: one name per concept, with its unit and meaning.

The names are the database columns, the JSON keys and the CSV headers; this table gives
each a title, its SI unit (as Pint spells it, ``None`` for text and pure numbers) and a
sentence a newcomer can act on. Datasette metadata, Data Package schemas and report
labels are all generated from here, so they cannot drift apart.
"""

from __future__ import annotations

from dataclasses import dataclass, replace


@dataclass(frozen=True)
class Term:
    """One concept: its title, SI unit (as Pint spells it; ``None`` for text and pure
    numbers), a sentence a newcomer can act on, its role and the symbol people read.

    ``role`` is "stored" (a database column), "derived" (computed by
    ``granudb.physics.derive``) or "text"; ``symbol`` is what a table or report shows in
    place of the machine name (``E*``); ``option`` the command-line option that sets it.
    """

    title: str
    unit: str | None
    description: str
    role: str = "stored"
    symbol: str | None = None
    option: str | None = None


TERMS: dict[str, Term] = {
    # identity and provenance
    "name": Term("Name", None, "Unique name, matched case-insensitively."),
    "description": Term("Description", None, "Free text."),
    "source": Term("Source", None, "Key of the source the values come from (sources.key)."),
    "source_locator": Term(
        "Where in the source", None, "Table, figure or section of the source, e.g. 'table 1'."
    ),
    "key": Term("Key", None, "Short stable identifier of a source, e.g. joseph-hunt-2004."),
    "citation": Term("Citation", None, "Full citation."),
    "doi": Term("DOI", None, "Digital Object Identifier (without https://doi.org/)."),
    "url": Term("URL", None, "Where to read the source."),
    "year": Term("Year", None, "Year of publication."),
    "kind": Term("Kind", None, "journal-article, book, correlation, measurement, …"),
    "notes": Term("Notes", None, "Free text."),
    # materials
    "density_kg_m3": Term("Density", "kg/m^3", "Mass density ρ."),
    "youngs_modulus_pa": Term("Young's modulus", "Pa", "Young's modulus E."),
    "poisson_ratio": Term("Poisson ratio", None, "Poisson ratio ν, in (−1, 0.5)."),
    "roughness_rms_m": Term(
        "RMS roughness", "m", "Root-mean-square surface roughness σ (Joseph & Hunt table 1: σ_s)."
    ),
    "correlation_length_m": Term(
        "Roughness correlation length",
        "m",
        "Correlation length of the roughness profile (table 1: λ_p).",
    ),
    "shear_modulus_pa": Term(
        "Shear modulus", "Pa", "Shear modulus G; when empty, derived as E / (2(1 + ν))."
    ),
    # fluids
    "glycerol_mass_fraction": Term(
        "Glycerol mass fraction", None, "Mass fraction of glycerol in water, 0–1."
    ),
    "viscosity_pa_s": Term(
        "Dynamic viscosity",
        "Pa*s",
        "Dynamic viscosity μ of the fluid at the temperature in question (1 cP = 1 mPa·s).",
        symbol="μ",
        option="--viscosity",
    ),
    "reference_viscosity_pa_s": Term(
        "Reference viscosity",
        "Pa*s",
        "The fluid's viscosity at its reference temperature, as the source printed it.",
        symbol="μ_ref",
        option="--reference-viscosity",
    ),
    "reference_density_kg_m3": Term(
        "Reference density",
        "kg/m^3",
        "The fluid's density at its reference temperature.",
        symbol="ρ_f,ref",
        option="--reference-density",
    ),
    "reference_temperature_c": Term(
        "Reference temperature",
        "degC",
        "Temperature at which the fluid's reference viscosity and density were given.",
        option="--reference-temperature",
    ),
    "pressure_viscosity_pa_inv": Term(
        "Pressure–viscosity coefficient",
        "1/Pa",
        "Barus coefficient C in μ(p) = μ₀ exp(C p); empty where not known.",
    ),
    "temperature_c": Term(
        "Temperature",
        "degC",
        "Temperature of the fluid during the collision (sets its viscosity and density).",
        symbol="T",
        option="--temperature",
    ),
    "yield_stress_pa": Term(
        "Yield stress",
        "Pa",
        "Yield stress Y in tension; yield starts below the surface at p_max = 1.6 Y "
        "(Johnson 1985 §11.4). Empty where not known and for brittle solids.",
        symbol="Y",
        option="--yield-stress",
    ),
    # datasets
    "version": Term("Version", None, "Version of the dataset (semantic versioning)."),
    "title": Term("Title", None, "Human-readable title."),
    "license": Term("License", None, "Licence of the data, e.g. CC-BY-4.0."),
    "content_hash": Term(
        "Content hash", None, "sha256 over the dataset's collisions in canonical form."
    ),
    # collisions
    "run": Term("Run", None, "Label of the run, unique within its dataset."),
    "particle": Term("Particle material", None, "Name of the particle's material."),
    "wall": Term("Wall material", None, "Name of the wall's (or second particle's) material."),
    "fluid": Term("Fluid", None, "Name of the fluid; empty for a dry collision."),
    "diameter_m": Term("Particle diameter", "m", "Diameter d of the particle (R = d/2)."),
    "wall_diameter_m": Term(
        "Wall diameter", "m", "Diameter of a second sphere; empty for a flat wall."
    ),
    "nominal_angle_rad": Term(
        "Nominal angle",
        "rad",
        "The set-up's nominal incidence angle, if the lab records one, in [0, π/2); "
        "checked at import against the angle of the velocities. The incidence angle ζ_in "
        "itself (incidence_angle_rad) is derived from the velocities.",
    ),
    "v_n_in_m_s": Term(
        "Normal speed in", "m/s", "Normal speed towards the wall just before contact (> 0)."
    ),
    "v_t_in_m_s": Term(
        "Tangential velocity in",
        "m/s",
        "Tangential velocity before contact; the axis points along it (≥ 0).",
    ),
    "omega_in_rad_s": Term(
        "Spin in",
        "rad/s",
        "Spin before contact, positive where it adds to the contact "
        "point's tangential velocity (v_T = v_t + ωR); empty if not measured.",
    ),
    "v_n_out_m_s": Term(
        "Normal speed out", "m/s", "Normal speed away from the wall just after contact (≥ 0)."
    ),
    "v_t_out_m_s": Term(
        "Tangential velocity out",
        "m/s",
        "Tangential velocity after contact, negative when it recoils.",
    ),
    "omega_out_rad_s": Term(
        "Spin out", "rad/s", "Spin after contact (same sign convention); empty if not measured."
    ),
    "wall_v_n_in_m_s": Term(
        "Target normal velocity in",
        "m/s",
        "A free target sphere's velocity along the normal (from particle to target) just "
        "before contact; empty for a flat wall or a fixed sphere.",
    ),
    "wall_v_t_in_m_s": Term(
        "Target tangential velocity in",
        "m/s",
        "A free target sphere's tangential velocity before contact, on the particle's axis.",
    ),
    "wall_omega_in_rad_s": Term(
        "Target spin in",
        "rad/s",
        "A free target sphere's spin before contact, positive where it adds to the relative "
        "velocity of the contact points.",
    ),
    "wall_v_n_out_m_s": Term(
        "Target normal velocity out", "m/s", "The target sphere's normal velocity after contact."
    ),
    "wall_v_t_out_m_s": Term(
        "Target tangential velocity out",
        "m/s",
        "The target sphere's tangential velocity after contact.",
    ),
    "wall_omega_out_rad_s": Term(
        "Target spin out", "rad/s", "The target sphere's spin after contact."
    ),
    # published values
    "label": Term("Label", None, "What the value describes, e.g. 'dry steel on Zerodur'."),
    "quantity": Term(
        "Quantity", None, "Which quantity (a granudb column name, its unit in the suffix)."
    ),
    "value": Term("Value", None, "The published value, in the SI unit of the quantity."),
    "uncertainty": Term("Uncertainty", None, "The published ± (same unit as the value)."),
    "value_as_printed": Term("As printed", None, "The value exactly as the source printed it."),
    "condition": Term("Condition", None, "Experimental condition, e.g. 'dry (air)'."),
}


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
    "reynolds_number": _derived("Reynolds number", None, "Re", "Re = 2ρ_f R V / μ (§1)"),
    "stokes_number": _derived(
        "Stokes number", None, "St", "St = m*V/(6πμR*²), Davis's pair form (wall: 2ρ_p R V/(9μ))"
    ),
    "normal_stokes_number": _derived(
        "Normal stokes number", None, "St_n", "St_n = m* v_N,in/(6πμR*²) (§4, §9)"
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
        "asperity_contact (σ > x₁/3) / uncertain (x₁/4 < σ ≤ x₁/3) / film (σ ≤ x₁/4) / dry",
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


#: The measured columns of a collision, SI, in the order of the content hash and of every
#: export; the free target sphere's velocities (``COLLISION_TARGET``) come last.
COLLISION_TARGET = [
    "wall_v_n_in_m_s",
    "wall_v_t_in_m_s",
    "wall_omega_in_rad_s",
    "wall_v_n_out_m_s",
    "wall_v_t_out_m_s",
    "wall_omega_out_rad_s",
]
COLLISION_MEASURED = [
    "diameter_m",
    "wall_diameter_m",
    "nominal_angle_rad",
    "v_n_in_m_s",
    "v_t_in_m_s",
    "omega_in_rad_s",
    "v_n_out_m_s",
    "v_t_out_m_s",
    "omega_out_rad_s",
    "temperature_c",
    *COLLISION_TARGET,
]
#: The text columns of a collision as people and files name them.
COLLISION_TEXT = ["run", "particle", "wall", "fluid", "notes"]

#: A material's stored properties (SI), in the order tables and exports show them.
MATERIAL_PROPERTIES = [
    "density_kg_m3",
    "youngs_modulus_pa",
    "poisson_ratio",
    "roughness_rms_m",
    "correlation_length_m",
    "shear_modulus_pa",
    "yield_stress_pa",
]
#: A fluid's stored properties (SI).
FLUID_PROPERTIES = [
    "glycerol_mass_fraction",
    "reference_density_kg_m3",
    "reference_viscosity_pa_s",
    "reference_temperature_c",
    "pressure_viscosity_pa_inv",
]


TABLES: dict[str, str] = {
    "sources": "Publications, correlations and campaigns that stored numbers come from.",
    "materials": "Particle and wall materials; Joseph & Hunt (2004) table 1 ships as seed data.",
    "fluids": "Fluids with density, reference viscosity and Barus pressure–viscosity "
    "coefficient; viscosity–temperature points are in fluid_points.",
    "fluid_points": "Viscosity (and density) of a fluid against temperature.",
    "datasets": "Named, versioned, curated collections of measured collisions.",
    "collisions": "One measured impact per row; normal speeds positive, tangential axis along "
    "the incoming motion, spin positive where it adds to the contact point's "
    "velocity (v_T = v_t + ωR).",
    "collision_imports": "Every file imported into a dataset, by sha256, so none is imported "
    "twice.",
    "published_values": "Numbers exactly as a source printed them, with table or figure.",
}


def term(column: str) -> Term:
    """The term for ``column``; ids and foreign keys get a generic one."""
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


#: The symbols people read for stored columns (derived ones carry theirs above).
_SYMBOLS = {
    "diameter_m": "d",
    "wall_diameter_m": "d₂",
    "nominal_angle_rad": "ζ_nom",
    "v_n_in_m_s": "v_n,in",
    "v_t_in_m_s": "v_t,in",
    "omega_in_rad_s": "ω_in",
    "v_n_out_m_s": "v_n,out",
    "v_t_out_m_s": "v_t,out",
    "omega_out_rad_s": "ω_out",
    "density_kg_m3": "ρ",
    "youngs_modulus_pa": "E",
    "poisson_ratio": "ν",
    "roughness_rms_m": "σ",
    "shear_modulus_pa": "G",
    "pressure_viscosity_pa_inv": "C",
}
TERMS.update(
    {
        name: replace(TERMS[name], symbol=symbol)
        for name, symbol in _SYMBOLS.items()
        if name in TERMS
    }
)
