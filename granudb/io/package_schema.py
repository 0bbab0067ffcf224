"""The Table Schemas of a granudb Data Package, generated from the vocabulary and rules.

One resource per table a receiver needs to load a dataset without guesswork: collisions,
the materials and fluids they name, the fluids' viscosity points, and the sources cited.
Field names are granudb's column names (SI, unit in the suffix); each field also carries
``unit`` (the Frictionless community convention, see the package README), a title, a
description and the same constraints the database enforces.
"""

from __future__ import annotations

from typing import Any

from granudb.vocabulary import term
from granudb.vocabulary.rules import RULES

# (name, type, required) per resource, in file column order.
RESOURCES: dict[str, list[tuple[str, str, bool]]] = {
    "sources": [
        ("key", "string", True),
        ("citation", "string", True),
        ("doi", "string", False),
        ("url", "string", False),
        ("year", "integer", False),
        ("kind", "string", True),
        ("notes", "string", False),
    ],
    "materials": [
        ("name", "string", True),
        ("description", "string", False),
        ("density_kg_m3", "number", True),
        ("youngs_modulus_pa", "number", True),
        ("poisson_ratio", "number", True),
        ("roughness_rms_m", "number", True),
        ("correlation_length_m", "number", False),
        ("shear_modulus_pa", "number", False),
        ("yield_stress_pa", "number", False),
        ("source", "string", False),
        ("source_locator", "string", False),
    ],
    "fluids": [
        ("name", "string", True),
        ("description", "string", False),
        ("glycerol_mass_fraction", "number", False),
        ("reference_density_kg_m3", "number", True),
        ("reference_viscosity_pa_s", "number", True),
        ("reference_temperature_c", "number", True),
        ("pressure_viscosity_pa_inv", "number", False),
        ("source", "string", False),
        ("source_locator", "string", False),
        ("density_source", "string", False),
        ("density_locator", "string", False),
        ("pressure_viscosity_source", "string", False),
        ("pressure_viscosity_locator", "string", False),
    ],
    "fluid_points": [
        ("fluid", "string", True),
        ("temperature_c", "number", True),
        ("viscosity_pa_s", "number", True),
        ("density_kg_m3", "number", False),
        ("source", "string", False),
        ("source_locator", "string", False),
    ],
    "collisions": [
        ("run", "string", True),
        ("particle", "string", True),
        ("wall", "string", True),
        ("fluid", "string", False),
        ("diameter_m", "number", True),
        ("wall_diameter_m", "number", False),
        ("nominal_angle_rad", "number", False),
        ("v_n_in_m_s", "number", True),
        ("v_t_in_m_s", "number", True),
        ("omega_in_rad_s", "number", False),
        ("v_n_out_m_s", "number", True),
        ("v_t_out_m_s", "number", True),
        ("omega_out_rad_s", "number", False),
        ("temperature_c", "number", False),
        ("wall_v_n_in_m_s", "number", False),
        ("wall_v_t_in_m_s", "number", False),
        ("wall_omega_in_rad_s", "number", False),
        ("wall_v_n_out_m_s", "number", False),
        ("wall_v_t_out_m_s", "number", False),
        ("wall_omega_out_rad_s", "number", False),
        ("notes", "string", False),
    ],
}

PRIMARY_KEYS = {
    "sources": ["key"],
    "materials": ["name"],
    "fluids": ["name"],
    "fluid_points": ["fluid", "temperature_c"],
    "collisions": ["run"],
}

FOREIGN_KEYS: dict[str, list[tuple[str, str, str]]] = {
    # (field, resource, field there)
    "materials": [("source", "sources", "key")],
    "fluids": [
        ("source", "sources", "key"),
        ("density_source", "sources", "key"),
        ("pressure_viscosity_source", "sources", "key"),
    ],
    "fluid_points": [("fluid", "fluids", "name"), ("source", "sources", "key")],
    "collisions": [
        ("particle", "materials", "name"),
        ("wall", "materials", "name"),
        ("fluid", "fluids", "name"),
    ],
}

DESCRIPTIONS = {
    "sources": "Every source cited by the other resources.",
    "materials": "Materials of the particles and walls in this dataset.",
    "fluids": "Fluids of the immersed collisions (dry collisions leave `fluid` empty).",
    "fluid_points": "Viscosity (and density) of each fluid against temperature.",
    "collisions": "One measured impact per row (sign convention in README.md).",
}

MAX_TEXT = {"run": 200, "name": 200, "notes": 10_000, "description": 10_000}


def field_schema(name: str, kind: str, required: bool) -> dict[str, Any]:
    described = term(name)
    field: dict[str, Any] = {"name": name, "type": kind, "title": described.title}
    if described.description:
        field["description"] = described.description
    if described.unit is not None:
        field["unit"] = described.unit
    constraints: dict[str, Any] = {}
    if required:
        constraints["required"] = True
    rule = RULES.get(name)
    if rule is not None:
        if rule.minimum is not None:
            constraints["minimum" if rule.min_inclusive else "exclusiveMinimum"] = rule.minimum
        if rule.maximum is not None:
            constraints["maximum" if rule.max_inclusive else "exclusiveMaximum"] = rule.maximum
    if kind == "string" and name in MAX_TEXT:
        constraints["maxLength"] = MAX_TEXT[name]
    if constraints:
        field["constraints"] = constraints
    return field


def table_schema(resource: str) -> dict[str, Any]:
    schema: dict[str, Any] = {
        "fields": [field_schema(*f) for f in RESOURCES[resource]],
        "missingValues": [""],
        "primaryKey": PRIMARY_KEYS[resource],
    }
    keys = FOREIGN_KEYS.get(resource)
    if keys:
        schema["foreignKeys"] = [
            {"fields": [field], "reference": {"resource": other, "fields": [there]}}
            for field, other, there in keys
        ]
    return schema


def columns(resource: str) -> list[str]:
    return [name for name, _, _ in RESOURCES[resource]]
