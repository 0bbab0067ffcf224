"""granudb's vocabulary: one name per concept, with its unit and meaning.

The names are the database columns, the JSON keys and the CSV headers; this table gives
each a title, its SI unit (as Pint spells it, ``None`` for text and pure numbers) and a
sentence a newcomer can act on. Datasette metadata, Data Package schemas and report
labels are all generated from here, so they cannot drift apart.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace


@dataclass(frozen=True)
class Term:
    """One concept: its title, SI unit (as Pint spells it; ``None`` for text and pure
    numbers), a sentence a newcomer can act on, its role and the symbol people read.

    ``role`` is "stored" (a database column), "derived" (computed by
    ``granudb.physics.derive``) or "text"; ``symbol`` is what a table or report shows in
    place of the machine name (``E*``); ``option`` the command-line option that sets it
    (the Python parameter is the same name with underscores); ``example`` a value as
    people type it, for help texts.
    """

    title: str
    unit: str | None
    description: str
    role: str = "stored"
    symbol: str | None = None
    option: str | None = None
    example: str | None = None


#: What a standard uncertainty's column name starts with (GUM's u(x); the unit suffix
#: stays, so ``u_youngs_modulus_pa`` is in pascals). ``granudb.vocabulary.uncertainty``.
UNCERTAINTY_PREFIX = "u_"


def uncertainty_column(column: str) -> str:
    """The column of ``column``'s standard uncertainty: ``u_youngs_modulus_pa``."""
    return UNCERTAINTY_PREFIX + column


#: GUM's notation in a file's header, ``u(v_n_in) [mm/s]``: the same column as
#: ``u_v_n_in [mm/s]``.
_UNCERTAINTY_NOTATION = re.compile(r"^\s*u\(\s*([A-Za-z_][A-Za-z0-9_]*)\s*\)")


def plain_uncertainty_header(header: str) -> str:
    """A header written ``u(name) [unit]`` as ``u_name [unit]``; any other unchanged.

    >>> plain_uncertainty_header("u(v_n_in) [mm/s]")
    'u_v_n_in [mm/s]'
    >>> plain_uncertainty_header("v_n_in [mm/s]")
    'v_n_in [mm/s]'
    """
    return _UNCERTAINTY_NOTATION.sub(lambda m: UNCERTAINTY_PREFIX + m[1], header, count=1)


TERMS: dict[str, Term] = {
    # identity and provenance
    "name": Term("Name", None, "Unique name, matched case-insensitively."),
    "description": Term("Description", None, "Free text.", option="--description"),
    "source": Term("Source", None, "Key of the source the values come from (sources.key)."),
    "source_locator": Term(
        "Where in the source",
        None,
        "Table, figure or section of the source, e.g. 'table 1'.",
        option="--source-locator",
        example="table 1",
    ),
    "key": Term("Key", None, "Short stable identifier of a source, e.g. joseph-hunt-2004."),
    "citation": Term("Citation", None, "Full citation."),
    "doi": Term("DOI", None, "Digital Object Identifier (without https://doi.org/)."),
    "url": Term("URL", None, "Where to read the source."),
    "year": Term("Year", None, "Year of publication."),
    "kind": Term("Kind", None, "journal-article, book, correlation, measurement, …"),
    "notes": Term("Notes", None, "Free text."),
    # materials
    "density_kg_m3": Term(
        "Density", "kg/m^3", "Mass density ρ.", option="--density", example="7780 kg/m^3"
    ),
    "youngs_modulus_pa": Term(
        "Young's modulus",
        "Pa",
        "Young's modulus E.",
        option="--youngs-modulus",
        example="190 GPa",
    ),
    "poisson_ratio": Term(
        "Poisson ratio",
        None,
        "Poisson ratio ν, in (−1, 0.5).",
        option="--poisson-ratio",
        example="0.27",
    ),
    "roughness_rms_m": Term(
        "RMS roughness",
        "m",
        "Root-mean-square surface roughness σ (Joseph & Hunt table 1: σ_s).",
        option="--roughness",
        example="23.6 nm",
    ),
    "correlation_length_m": Term(
        "Roughness correlation length",
        "m",
        "Correlation length of the roughness profile (table 1: λ_p).",
        option="--correlation-length",
        example="48 um",
    ),
    "shear_modulus_pa": Term(
        "Shear modulus",
        "Pa",
        "Shear modulus G; when empty, derived as E / (2(1 + ν)).",
        option="--shear-modulus",
        example="75 GPa",
    ),
    # fluids
    "glycerol_mass_fraction": Term(
        "Glycerol mass fraction",
        None,
        "Mass fraction of glycerol in water, 0–1.",
        option="--glycerol-fraction",
        example="45 %",
    ),
    "viscosity_pa_s": Term(
        "Dynamic viscosity",
        "Pa*s",
        "Dynamic viscosity μ of the fluid at the temperature in question (1 cP = 1 mPa·s).",
        symbol="μ",
        option="--viscosity",
        example="2.1 cP",
    ),
    "reference_viscosity_pa_s": Term(
        "Reference viscosity",
        "Pa*s",
        "The fluid's viscosity at its reference temperature, as the source printed it.",
        symbol="μ_ref",
        option="--reference-viscosity",
        example="4.5 cP",
    ),
    "reference_density_kg_m3": Term(
        "Reference density",
        "kg/m^3",
        "The fluid's density at its reference temperature.",
        symbol="ρ_f,ref",
        option="--reference-density",
        example="1112 kg/m^3",
    ),
    "reference_temperature_c": Term(
        "Reference temperature",
        "degC",
        "Temperature at which the fluid's reference viscosity and density were given.",
        option="--reference-temperature",
        example="20 degC",
    ),
    "pressure_viscosity_pa_inv": Term(
        "Pressure–viscosity coefficient",
        "1/Pa",
        "Barus coefficient C in μ(p) = μ₀ exp(C p); empty where not known.",
        option="--pressure-viscosity",
        example="6e-9 1/Pa",
    ),
    "temperature_c": Term(
        "Temperature",
        "degC",
        "Temperature of the fluid during the collision (sets its viscosity and density).",
        symbol="T",
        option="--temperature",
        example="30 degC",
    ),
    "yield_stress_pa": Term(
        "Yield stress",
        "Pa",
        "Yield stress Y in tension; yield starts below the surface at p_max = 1.6 Y "
        "(Johnson 1985 §11.4). Empty where not known and for brittle solids.",
        symbol="Y",
        option="--yield-stress",
        example="1.7 GPa",
    ),
    # a material's own dry values and brittleness (docs/physics.md §18)
    "dry_restitution": Term(
        "Dry restitution",
        None,
        "Normal restitution e of a dry collision of this material (on itself or as a "
        "source measured it), in (0, 1]; cite it with --dry-source. Empty where not known.",
        symbol="e_dry",
        option="--dry-restitution",
        example="0.97",
    ),
    "dry_friction": Term(
        "Dry friction",
        None,
        "Sliding friction coefficient μ_f of a dry contact of this material, ≥ 0; cite it "
        "with --dry-source. Empty where not known.",
        symbol="μ_dry",
        option="--dry-friction",
        example="0.11",
    ),
    "immersed_friction": Term(
        "Immersed friction",
        None,
        "Sliding friction coefficient μ_f of a pair where asperities touch in a liquid "
        "(Joseph & Hunt §4: glass on Zerodur, 0.15), ≥ 0; empty: the dry value is used.",
        symbol="μ_wet",
        option="--immersed-friction",
        example="0.15",
    ),
    "dry_provenance": Term(
        "Source of the dry values",
        None,
        "Where the dry restitution and friction come from (citation and table, figure or section).",
        option="--dry-source",
        example="Joseph & Hunt 2004 §3",
    ),
    "conditions": Term(
        "Conditions",
        None,
        "The conditions of the values where the source gives them (temperature, method), "
        "one line; empty where not stated.",
        option="--conditions",
        example="E by ultrasonic pulse-echo at 20 °C; σ from SEM images",
    ),
    "brittleness": Term(
        "Brittleness",
        None,
        "brittle (fails by Hertzian cone cracks instead of yielding: no yield stress, no "
        "elastic–plastic restitution) or ductile; empty where not known.",
        option="--brittleness",
        example="brittle",
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


#: The measured columns of a collision, SI, in the order of the content hash and of every
#: export; the free target sphere's velocities (``COLLISION_TARGET``) come after the
#: particle's, the stated uncertainties (``COLLISION_UNCERTAINTIES``) last.
COLLISION_TARGET = [
    "wall_v_n_in_m_s",
    "wall_v_t_in_m_s",
    "wall_omega_in_rad_s",
    "wall_v_n_out_m_s",
    "wall_v_t_out_m_s",
    "wall_omega_out_rad_s",
]
#: The particle's measured columns (and the set-up's), SI, in the order of the hash.
_PARTICLE_MEASURED = [
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
]
#: The measured columns that may carry a stated standard uncertainty (issue 27): the
#: diameter, the particle's velocities and spins, the bath temperature (not a nominal
#: angle or a second sphere's size). Their ``u_`` columns (``COLLISION_UNCERTAINTIES``:
#: ``u_v_n_in_m_s`` is u(v_n,in) in m/s) are stored per run, read from a file's
#: ``u(v_n_in) [mm/s]`` or ``u_v_n_in_m_s`` columns or filled from a dataset default at
#: import; empty means not stated, never zero.
COLLISION_UNCERTAIN = [
    c for c in _PARTICLE_MEASURED if c not in ("wall_diameter_m", "nominal_angle_rad")
]
COLLISION_UNCERTAINTIES = [uncertainty_column(c) for c in COLLISION_UNCERTAIN]
#: Every stored number of a collision: the measurements (the target sphere's last), then
#: their stated uncertainties.
COLLISION_MEASURED = [*_PARTICLE_MEASURED, *COLLISION_TARGET, *COLLISION_UNCERTAINTIES]
#: The text columns of a collision as people and files name them.
COLLISION_TEXT = ["run", "particle", "wall", "fluid", "notes"]
#: What every collision row must have (a file's rows, a package's table). Empty spin cells
#: mean "not measured"; the angle is derived from the velocities; the target sphere's
#: velocities are for a free target only.
COLLISION_REQUIRED = [
    "run",
    "particle",
    "wall",
    "diameter_m",
    "v_n_in_m_s",
    "v_t_in_m_s",
    "v_n_out_m_s",
    "v_t_out_m_s",
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
    "reported_runs": "Runs as papers report them: the restitution coefficients, spin and "
    "incidence angle a paper states per run, never a velocity it did not measure.",
}


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
