"""granudb's vocabulary: one name per concept, with its unit and meaning.

The names are the database columns, the JSON keys and the CSV headers; this table gives
each a title, its SI unit (as Pint spells it, ``None`` for text and pure numbers) and a
sentence a newcomer can act on. Datasette metadata, Data Package schemas and report
labels are all generated from here, so they cannot drift apart.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace

from granudb.vocabulary.ranges import ABOVE_ABSOLUTE_ZERO, NON_NEGATIVE, POSITIVE, Rule


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


def interval_columns(column: str) -> tuple[str, str]:
    """The columns of ``column``'s 95 % coverage interval (its low and high end, same
    unit): ``low95_lubricated_friction``, ``high95_lubricated_friction``."""
    return f"low95_{column}", f"high95_{column}"


#: The column naming the method that gave a row's u, intervals and probabilities.
PROPAGATION_METHOD = "propagation_method"


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


@dataclass(frozen=True)
class Stored:
    """How one table stores a term: the one declaration of a stored column.

    From it come the SQLAlchemy column and its CHECK (``granudb.db.models``), the Core
    row's fields (``granudb.db.catalog_rows``), the rule checked before a write
    (``granudb.vocabulary.rules.RULES``), the catalogue's properties, listing columns and
    command options (``granudb.vocabulary.catalog``) and the Data Package schema
    (``granudb.io.package_schema``).

    ``sql`` is "float", "integer", "text", "string" (``length`` characters), "boolean" or
    "datetime" (with time zone); ``server_default`` what the database itself fills in;
    ``unique`` that no two rows share the value (a source's key);
    ``nullable`` False makes a value required (unless ``default`` fills it); ``rule`` its
    range, enforced by the CHECK ``check`` (the constraint's name; ``guarded`` False writes
    it without ``IS NULL OR``, which NULL passes anyway; ``check_sql`` a CHECK that also
    reads other columns); ``words`` the words a text takes; ``one_line`` the longest
    one-line text; ``uncertain`` that a standard uncertainty ``u_<column>`` is stored
    beside it; ``listed`` that the narrow table for people shows it; ``companion`` a
    listing column shown right after it; ``group`` a part of the table ("target": a free
    target sphere's velocities; "dry": a material's own dry values); ``keyed`` that the
    column is part of the row's key within its parent.
    """

    column: str
    table: str
    sql: str = "float"
    nullable: bool = True
    length: int | None = None
    default: float | str | None = None
    server_default: str | None = None
    unique: bool = False
    rule: Rule | None = None
    check: str | None = None
    guarded: bool = True
    check_sql: str | None = None
    words: tuple[str, ...] = ()
    one_line: int | None = None
    uncertain: bool = False
    listed: bool = False
    companion: str | None = None
    group: str | None = None
    keyed: bool = False

    @property
    def constraint(self) -> str | None:
        """The SQL of the column's CHECK (None: it has none besides finiteness)."""
        c = self.column
        if self.check_sql is not None:
            return self.check_sql
        if self.words:
            words = f"{c} IN ({', '.join(repr(w) for w in self.words)})"
            return f"{c} IS NULL OR {words}" if self.nullable and self.guarded else words
        if self.rule is None:
            return None
        rule, parts = self.rule, []
        if rule.minimum is not None:
            parts.append(f"{c} {'>=' if rule.min_inclusive else '>'} {_sql_number(rule.minimum)}")
        if rule.maximum is not None:
            parts.append(f"{c} {'<=' if rule.max_inclusive else '<'} {_sql_number(rule.maximum)}")
        body = " AND ".join(parts)
        if self.nullable and self.guarded:
            return f"{c} IS NULL OR ({body})" if len(parts) > 1 else f"{c} IS NULL OR {body}"
        return body

    @property
    def uncertainty(self) -> Stored:
        """The declaration of this column's standard uncertainty ``u_<column>``: same
        unit, never negative, empty when not stated."""
        u = uncertainty_column(self.column)
        return Stored(u, self.table, check=f"{u}_non_negative", rule=NON_NEGATIVE)


def _sql_number(value: float) -> str:
    return str(int(value)) if float(value).is_integer() else repr(float(value))


_HALF_PI = Rule(0.0, math.pi / 2, max_inclusive=False)
#: The years a source may carry (the table's check constraint).
SOURCE_YEARS = (1600, 3000)

#: Every stored value column of the catalogue, the collisions, the pairs' values and the
#: reported runs, in the order every door shows them (keys, names, links to other rows
#: and timestamps are the tables' structure, ``granudb.db.models``).
STORED: tuple[Stored, ...] = (
    # materials
    Stored("density_kg_m3", "materials", nullable=False, rule=POSITIVE,
           check="density_positive", uncertain=True, listed=True),
    Stored("youngs_modulus_pa", "materials", nullable=False, rule=POSITIVE,
           check="youngs_modulus_positive", uncertain=True, listed=True),
    Stored("poisson_ratio", "materials", nullable=False,
           rule=Rule(-1.0, 0.5, min_inclusive=False, max_inclusive=False),
           check="poisson_ratio_range", uncertain=True, listed=True),
    # the roughness is optional: empty means "not stated" (docs/physics.md §18), never 0
    Stored("roughness_rms_m", "materials", rule=NON_NEGATIVE, check="roughness_non_negative",
           guarded=False, uncertain=True, listed=True),
    Stored("correlation_length_m", "materials", rule=POSITIVE,
           check="correlation_length_positive", uncertain=True),
    Stored("shear_modulus_pa", "materials", rule=POSITIVE, check="shear_modulus_positive",
           uncertain=True, listed=True, companion="shear_modulus_derived"),
    Stored("yield_stress_pa", "materials", rule=POSITIVE, check="yield_stress_positive",
           uncertain=True),
    Stored("dry_restitution", "materials", rule=Rule(0.0, 1.0, min_inclusive=False),
           check="dry_restitution_range", uncertain=True, group="dry"),
    Stored("dry_friction", "materials", rule=NON_NEGATIVE, check="dry_friction_non_negative",
           uncertain=True, group="dry"),
    Stored("dry_provenance", "materials", sql="text"),
    Stored("brittleness", "materials", sql="string", length=20, words=("brittle", "ductile"),
           check="brittleness_word"),
    Stored("conditions", "materials", sql="text", one_line=1000),
    # fluids
    Stored("glycerol_mass_fraction", "fluids", rule=Rule(0.0, 1.0),
           check="glycerol_mass_fraction_range", uncertain=True, listed=True),
    Stored("reference_density_kg_m3", "fluids", nullable=False, rule=POSITIVE,
           check="density_positive", uncertain=True, listed=True),
    Stored("reference_viscosity_pa_s", "fluids", nullable=False, rule=POSITIVE,
           check="viscosity_positive", uncertain=True, listed=True),
    Stored("reference_temperature_c", "fluids", nullable=False, default=20.0,
           rule=ABOVE_ABSOLUTE_ZERO, check="reference_temperature_above_zero_k",
           uncertain=True, listed=True),
    # C = 0 makes Gohar's film (5.6) vanish and the lubricated friction (5.8) infinite;
    # a fluid whose coefficient is not known leaves it empty.
    Stored("pressure_viscosity_pa_inv", "fluids", rule=POSITIVE,
           check="pressure_viscosity_positive", uncertain=True, listed=True),
    Stored("conditions", "fluids", sql="text", one_line=1000),
    # fluid points
    Stored("temperature_c", "fluid_points", nullable=False, rule=ABOVE_ABSOLUTE_ZERO,
           check="temperature_above_zero_k", keyed=True),
    Stored("viscosity_pa_s", "fluid_points", nullable=False, rule=POSITIVE,
           check="viscosity_positive", uncertain=True),
    Stored("density_kg_m3", "fluid_points", rule=POSITIVE, check="density_positive",
           uncertain=True),
    # collisions: the particle's measurements (and the set-up's), in the order of the
    # content hash, then the free target sphere's velocities. With a free target (its
    # wall_v_n_in given) the rules are on relative velocities: the particle may start at
    # rest or move on forward (checked on import).
    Stored("diameter_m", "collisions", nullable=False, rule=POSITIVE,
           check="diameter_positive", uncertain=True),
    Stored("wall_diameter_m", "collisions", rule=POSITIVE, check="wall_diameter_positive"),
    Stored("nominal_angle_rad", "collisions", rule=_HALF_PI, check="nominal_angle_range",
           group="angle"),
    Stored("v_n_in_m_s", "collisions", nullable=False, rule=POSITIVE,
           check="v_n_in_positive_or_free",
           check_sql="v_n_in_m_s > 0 OR wall_v_n_in_m_s IS NOT NULL", uncertain=True,
           listed=True),
    Stored("v_t_in_m_s", "collisions", nullable=False, rule=NON_NEGATIVE,
           check="v_t_in_non_negative", uncertain=True),
    Stored("omega_in_rad_s", "collisions", uncertain=True),
    Stored("v_n_out_m_s", "collisions", nullable=False, rule=NON_NEGATIVE,
           check="v_n_out_non_negative_or_free",
           check_sql="v_n_out_m_s >= 0 OR wall_v_n_in_m_s IS NOT NULL", uncertain=True),
    Stored("v_t_out_m_s", "collisions", nullable=False, uncertain=True),
    Stored("omega_out_rad_s", "collisions", uncertain=True),
    Stored("temperature_c", "collisions", rule=ABOVE_ABSOLUTE_ZERO,
           check="temperature_above_zero_k", uncertain=True),
    Stored("wall_v_n_in_m_s", "collisions", group="target"),
    Stored("wall_v_t_in_m_s", "collisions", group="target"),
    Stored("wall_omega_in_rad_s", "collisions", group="target"),
    Stored("wall_v_n_out_m_s", "collisions", group="target"),
    Stored("wall_v_t_out_m_s", "collisions", group="target"),
    Stored("wall_omega_out_rad_s", "collisions", group="target"),
    # a pair's measured values (either way round)
    Stored("dry_restitution", "pair_values", rule=Rule(0.0, 1.0, min_inclusive=False),
           check="dry_restitution_range"),
    Stored("dry_friction", "pair_values", rule=NON_NEGATIVE, check="dry_friction_non_negative"),
    Stored("immersed_friction", "pair_values", rule=NON_NEGATIVE,
           check="immersed_friction_non_negative"),
    # sources: every stored number points to one (a released dataset keeps each as it was:
    # the revisions hold the same columns, without the key's uniqueness or a default)
    Stored("key", "sources", sql="string", length=100, nullable=False, unique=True,
           check="key_not_empty", check_sql="length(key) > 0"),
    Stored("citation", "sources", sql="text", nullable=False),
    Stored("doi", "sources", sql="string", length=200),
    Stored("url", "sources", sql="string", length=500),
    Stored("year", "sources", sql="integer", check="year_range",
           check_sql="year IS NULL OR (year >= {} AND year <= {})".format(*SOURCE_YEARS)),
    Stored("kind", "sources", sql="string", length=40, nullable=False, default="publication"),
    Stored("notes", "sources", sql="text"),
    # datasets: named, versioned collections of runs (a name's versions are its key)
    Stored("version", "datasets", sql="string", length=50, nullable=False, default="1.0.0",
           keyed=True),
    Stored("title", "datasets", sql="text"),
    Stored("license", "datasets", sql="string", length=200),
    Stored("content_hash", "datasets", sql="string", length=80),
    # the dataset's own DOI (e.g. a Zenodo version DOI), once it has been published
    Stored("doi", "datasets", sql="string", length=200),
    # JSON lists: people {"given_names", "family_names", "orcid", "affiliation"}; keywords
    Stored("authors", "datasets", sql="text"),
    Stored("keywords", "datasets", sql="text"),
    # draft (editable) → released (immutable) → superseded (a newer version was released)
    Stored("state", "datasets", sql="string", length=20, nullable=False, default="draft",
           server_default="draft", words=("draft", "released", "superseded"),
           check="state_known"),
    Stored("released_at", "datasets", sql="datetime"),
    # a run as a paper reports it: the quantities it states, never a velocity
    Stored("diameter_m", "reported_runs", rule=POSITIVE, check="diameter_positive"),
    Stored("incidence_angle_rad", "reported_runs", rule=_HALF_PI, check="incidence_angle_range",
           uncertain=True),
    Stored("normal_restitution", "reported_runs", check="normal_restitution_non_negative",
           check_sql="normal_restitution IS NULL OR normal_restitution >= 0", uncertain=True),
    Stored("tangential_restitution", "reported_runs", uncertain=True),
    Stored("omega_out_rad_s", "reported_runs", uncertain=True),
    # the paper states the sphere arrives without spin (Walton's Ψ then follows)
    Stored("no_spin_in", "reported_runs", sql="boolean", nullable=False, default=False),
    # who read the values from the figure or file, its licence, and the shipped reference
    # dataset ("NAME VERSION") the run came from (migration 0013)
    Stored("digitiser", "reported_runs", sql="text"),
    Stored("licence", "reported_runs", sql="text"),
    Stored("reference_package", "reported_runs", sql="string", length=200),
)  # fmt: skip

#: CHECKs that read several declared columns of a table, by table and constraint name.
TABLE_CHECKS: dict[str, dict[str, str]] = {
    "pair_values": {
        "has_a_value": "dry_restitution IS NOT NULL OR dry_friction IS NOT NULL "
        "OR immersed_friction IS NOT NULL"
    },
    "reported_runs": {
        "states_a_restitution": "normal_restitution IS NOT NULL "
        "OR tangential_restitution IS NOT NULL"
    },
}


def stored(table: str, *, uncertainties: bool = False) -> list[Stored]:
    """The declared columns of ``table`` in order; with ``uncertainties``, each uncertain
    column's ``u_`` column follows the declared ones."""
    declared = [s for s in STORED if s.table == table]
    extra = [s.uncertainty for s in declared if s.uncertain] if uncertainties else []
    return [*declared, *extra]


def stored_values(table: str, group: str | None = None) -> list[str]:
    """The names of ``table``'s declared numbers (of ``group`` only, when given)."""
    return [
        s.column for s in stored(table) if s.sql == "float" and (group is None or s.group == group)
    ]


def keyed(table: str) -> list[str]:
    """The declared columns that key a row of ``table`` within its parent (a fluid's
    points by temperature), which also order the rows."""
    return [s.column for s in stored(table) if s.keyed]


#: The rule of every ruled stored column (one name has one rule in every table).
STORED_RULES: dict[str, Rule] = {s.column: s.rule for s in STORED if s.rule is not None}

#: The measured columns of a collision, SI, in the order of the content hash and of every
#: export; the free target sphere's velocities (``COLLISION_TARGET``) come after the
#: particle's, the stated uncertainties (``COLLISION_UNCERTAINTIES``) last.
COLLISION_TARGET = stored_values("collisions", "target")
#: The particle's measured columns (and the set-up's), SI, in the order of the hash.
_PARTICLE_MEASURED = [c for c in stored_values("collisions") if c not in COLLISION_TARGET]
#: The measured columns that may carry a stated standard uncertainty (issue 27): the
#: diameter, the particle's velocities and spins, the bath temperature (not a nominal
#: angle or a second sphere's size). Their ``u_`` columns (``COLLISION_UNCERTAINTIES``)
#: are stored per run, read from a file's ``u(v_n_in) [mm/s]`` or ``u_<column>`` columns
#: or filled from a dataset default at import; empty means not stated, never zero.
COLLISION_UNCERTAIN = [s.column for s in stored("collisions") if s.uncertain]
COLLISION_UNCERTAINTIES = [uncertainty_column(c) for c in COLLISION_UNCERTAIN]
#: Every stored number of a collision: the measurements (the target sphere's last), then
#: their stated uncertainties.
COLLISION_MEASURED = [*_PARTICLE_MEASURED, *COLLISION_TARGET, *COLLISION_UNCERTAINTIES]
#: The stored columns a one-line listing of runs shows (``collisions list``, a report).
COLLISION_LISTED = [s.column for s in stored("collisions") if s.listed]
#: The set-up's nominal angle, shown beside the incidence angle derived from the
#: velocities.
COLLISION_ANGLE = stored_values("collisions", "angle")
#: The text columns of a collision as people and files name them.
COLLISION_TEXT = ["run", "particle", "wall", "fluid", "notes"]
#: What every collision row must have (a file's rows, a package's table). Empty spin cells
#: mean "not measured"; the angle is derived from the velocities; the target sphere's
#: velocities are for a free target only.
COLLISION_REQUIRED = [
    "run",
    "particle",
    "wall",
    *(s.column for s in stored("collisions") if not s.nullable),
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
