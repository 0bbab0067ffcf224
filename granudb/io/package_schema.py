"""The Table Schemas of a granudb Data Package, generated from the vocabulary and rules.

One resource per table a receiver needs to load a dataset without guesswork: collisions,
the materials and fluids they name, the fluids' viscosity points, and the sources cited.
Field names are granudb's column names (SI, unit in the suffix); each field also carries
``unit`` (the Frictionless community convention, see the package README), a title, a
description and the same constraints the database enforces.
"""

from __future__ import annotations

import math
from typing import Any

from granudb.io.units import check_unit_expression, registry
from granudb.vocabulary.catalog import (
    DRY_VALUE_PROPERTIES,
    FLUIDS,
    MATERIALS,
    ONE_LINE_TEXTS,
    POINT_COLUMNS,
    POINT_UNCERTAINTIES,
    SOURCE_COLUMNS,
    SOURCE_REQUIRED,
    Catalogue,
)
from granudb.vocabulary.derived import term
from granudb.vocabulary.rules import RULES
from granudb.vocabulary.terms import COLLISION_MEASURED, COLLISION_REQUIRED, COLLISION_UNCERTAINTIES

#: Text columns of a package's tables (names, keys, citations); sources and locators too.
_TEXT = {"key", "citation", "doi", "url", "kind", "notes", "name", "description", "run"}
_TEXT |= {"particle", "wall", "fluid", *MATERIALS.texts, *FLUIDS.texts}


def _fields(columns: list[str], required: list[str]) -> list[tuple[str, str, bool]]:
    def kind(column: str) -> str:
        if column == "year":
            return "integer"
        text = column in _TEXT or column.endswith(("source", "_locator"))
        return "string" if text else "number"

    return [(c, kind(c), c in required) for c in columns]


def _catalogue(spec: Catalogue) -> list[tuple[str, str, bool]]:
    """A catalogue's table: name, description, its properties, its sources (each with a
    locator); a property with a default is always stored, so it is required here."""
    sources = ["source", "source_locator"]
    for extra in spec.trailing:
        if extra.endswith("_source"):
            sources += [extra, extra.removesuffix("_source") + "_locator"]
    required = ["name", *spec.required, *spec.defaults]
    # the standard uncertainties last; a package written before them (or before the dry
    # values) lacks those columns (``OPTIONAL_COLUMNS``) and still reads
    shown = [
        "name",
        "description",
        *spec.properties,
        *spec.texts,
        *sources,
        *spec.uncertainties.values(),
    ]
    return _fields(shown, required)


def _point_columns() -> list[str]:
    shown = (c for c in POINT_COLUMNS if c != "source")
    return ["fluid", *shown, "source", "source_locator", *POINT_UNCERTAINTIES]


#: (name, type, required) per resource, in file column order: generated from the
#: vocabulary's catalogue specs and collision columns.
RESOURCES: dict[str, list[tuple[str, str, bool]]] = {
    "sources": _fields(SOURCE_COLUMNS, SOURCE_REQUIRED),
    "materials": _catalogue(MATERIALS),
    "fluids": _catalogue(FLUIDS),
    "fluid_points": _fields(_point_columns(), ["fluid", "temperature_c", "viscosity_pa_s"]),
    "collisions": _fields(
        ["run", "particle", "wall", "fluid", *COLLISION_MEASURED, "notes"], COLLISION_REQUIRED
    ),
}

#: Columns a resource's file may lack, read as empty: those added after granudb's first
#: packages (issue 27's uncertainties and conditions; issue 23's dry values, their origin
#: and brittleness).
OPTIONAL_COLUMNS: dict[str, list[str]] = {
    "materials": [
        *DRY_VALUE_PROPERTIES,
        *MATERIALS.texts,
        *MATERIALS.uncertainties.values(),
    ],
    "fluids": [*FLUIDS.texts, *FLUIDS.uncertainties.values()],
    "fluid_points": list(POINT_UNCERTAINTIES),
    "collisions": list(COLLISION_UNCERTAINTIES),
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

MAX_TEXT = {"run": 200, "name": 200, "notes": 10_000, "description": 10_000, **ONE_LINE_TEXTS}


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
        # Strict bounds are written as the inclusive bound (true of every valid value)
        # and stated exactly in the description: Frictionless (5.x) refuses a schema with
        # ``exclusiveMinimum``, and granudb re-checks the strict rule on import anyway.
        if rule.minimum is not None:
            constraints["minimum"] = rule.minimum
        if rule.maximum is not None:
            constraints["maximum"] = rule.maximum
        if not (rule.min_inclusive and rule.max_inclusive):
            field["description"] = f"{field.get('description', '')} Rule: {rule.text}.".strip()
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


def _same_unit(declared: str, expected: str) -> bool:
    try:
        spelled = check_unit_expression(declared)  # bounded cost: m**(9**9**9) never reaches Pint
        ureg = registry()
        factor = ureg.Quantity(1.0, spelled).to(expected).magnitude
        offset = ureg.Quantity(0.0, spelled).to(expected).magnitude
    except Exception:  # noqa: BLE001 - any Pint failure means "not the same unit"
        return False
    return math.isclose(factor - offset, 1.0, rel_tol=1e-12) and abs(offset) < 1e-12


def check_schema(name: str, resource: dict[str, Any], problems: list[str]) -> None:
    """Append a problem for each field of a package's schema that granudb cannot read."""
    schema = resource.get("schema")
    if not isinstance(schema, dict) or not isinstance(schema.get("fields"), list):
        problems.append(f"{name}: has no Table Schema with fields")
        return
    expected = {n: (kind, required) for n, kind, required in RESOURCES[name]}
    seen = set()
    for entry in schema["fields"]:
        if not isinstance(entry, dict) or not isinstance(entry.get("name"), str):
            problems.append(f"{name}: a schema field has no name")
            continue
        field_name = entry["name"][:80]
        seen.add(field_name)
        if field_name not in expected:
            problems.append(
                f"{name}.{field_name}: is not a field granudb knows (known: {', '.join(expected)})"
            )
            continue
        unit = term(field_name).unit
        declared = entry.get("unit")
        if declared is not None and unit is not None and not _same_unit(str(declared), unit):
            problems.append(
                f"{name}.{field_name}: unit {str(declared)[:40]!r} is not {unit!r}, the SI "
                "unit this column holds"
            )
        if declared is not None and unit is None and str(declared) not in {"", "1", "-"}:
            problems.append(
                f"{name}.{field_name}: unit {str(declared)[:40]!r} on a column without unit"
            )
    for field_name, (_, required) in expected.items():
        if required and field_name not in seen:
            problems.append(f"{name}.{field_name}: required field is missing from the schema")
