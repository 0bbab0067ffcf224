"""granudb's vocabulary: one name per concept, with its unit and meaning.

The names are the database columns, the JSON keys and the CSV headers; this table gives
each a title, its SI unit (as Pint spells it, ``None`` for text and pure numbers) and a
sentence a newcomer can act on. Datasette metadata, Data Package schemas and report
labels are all generated from here, so they cannot drift apart.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Term:
    title: str
    unit: str | None
    description: str


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
    "viscosity_pa_s": Term("Dynamic viscosity", "Pa*s", "Dynamic viscosity μ (1 cP = 1 mPa·s)."),
    "reference_temperature_c": Term(
        "Reference temperature", "degC", "Temperature at which the fluid's viscosity was given."
    ),
    "pressure_viscosity_pa_inv": Term(
        "Pressure–viscosity coefficient",
        "1/Pa",
        "Barus coefficient C in μ(p) = μ₀ exp(C p); empty where not known.",
    ),
    "temperature_c": Term("Temperature", "degC", "Temperature."),
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
    "incidence_angle_rad": Term(
        "Incidence angle",
        "rad",
        "ζ_in: angle between the contact point's path and the wall normal, in [0, π/2).",
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
        "point's tangential velocity (v_T = v_t + ωR).",
    ),
    "v_n_out_m_s": Term(
        "Normal speed out", "m/s", "Normal speed away from the wall just after contact (≥ 0)."
    ),
    "v_t_out_m_s": Term(
        "Tangential velocity out",
        "m/s",
        "Tangential velocity after contact, negative when it recoils.",
    ),
    "omega_out_rad_s": Term("Spin out", "rad/s", "Spin after contact (same sign convention)."),
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
    if column.endswith("_id"):
        return Term(
            column[:-3].replace("_", " ").capitalize(),
            None,
            f"Reference to {column[:-3].replace('_', ' ')}.",
        )
    return Term(column.replace("_", " ").capitalize(), None, "")


def datasette_metadata(database_name: str = "granudb") -> dict[str, Any]:
    """Datasette ``metadata.json`` for a granudb SQLite file: titles, descriptions, units.

    Datasette shows a column description as a tooltip and a ``units`` entry beside values;
    foreign keys display the referenced row's ``name`` (or ``key`` for sources).
    ``database_name`` is what Datasette calls the file: its name without ``.sqlite``.
    """
    from granudb import __version__
    from granudb.db.models import Base

    tables: dict[str, Any] = {}
    for table in Base.metadata.sorted_tables:
        columns = {
            c.name: term(c.name).description or term(c.name).title
            for c in table.columns
            if c.name != "id"
        }
        units = {c.name: term(c.name).unit for c in table.columns if term(c.name).unit is not None}
        entry: dict[str, Any] = {"description": TABLES.get(table.name, ""), "columns": columns}
        if units:
            entry["units"] = units
        if "name" in table.columns:
            entry["label_column"] = "name"
        elif table.name == "sources":
            entry["label_column"] = "key"
        tables[table.name] = entry
    return {
        "title": "granudb",
        "description": "Materials, fluids and measured particle–wall collisions in liquids "
        f"(granudb {__version__}). Values are SI; column names carry the unit.",
        "source": "Joseph & Hunt (2004), J. Fluid Mech. 510, 71–93 (seed data)",
        "source_url": "https://doi.org/10.1017/S002211200400919X",
        "databases": {database_name: {"tables": tables}},
    }
