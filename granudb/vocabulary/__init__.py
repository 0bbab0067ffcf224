"""granudb's one vocabulary: every name, its unit, meaning, symbol and physical rule.

Every list of columns in granudb (catalogue and seed columns, listed and exported
columns, Data Package schemas, report labels, Datasette metadata, DataFrame
``attrs["units"]``) is generated from here, so a concept has one name everywhere.
This package sits at the bottom of the layers: it imports nothing of granudb but
``granudb.errors``.
"""

from granudb.vocabulary.catalog import (
    CATALOGUES,
    FLUID_PROPERTIES,
    FLUIDS,
    MATERIAL_PROPERTIES,
    MATERIALS,
    POINT_COLUMNS,
    POINT_UNCERTAINTIES,
    SOURCE_COLUMNS,
    SOURCE_REQUIRED,
    Catalogue,
)
from granudb.vocabulary.derived import DERIVED_TERMS, term
from granudb.vocabulary.rules import RULES, Rule, check_record, check_value
from granudb.vocabulary.terms import (
    COLLISION_MEASURED,
    COLLISION_REQUIRED,
    COLLISION_TARGET,
    COLLISION_TEXT,
    COLLISION_UNCERTAIN,
    COLLISION_UNCERTAINTIES,
    TABLES,
    TERMS,
    Term,
    plain_uncertainty_header,
    uncertainty_column,
)
from granudb.vocabulary.uncertainty import (
    PROBABILITY_TERMS,
    UNCERTAIN_DERIVED,
    UNCERTAINTY_TERMS,
)
from granudb.vocabulary.units import UNITS, Unit, unit_of_column

__all__ = [
    "CATALOGUES",
    "FLUIDS",
    "MATERIALS",
    "Catalogue",
    "COLLISION_MEASURED",
    "COLLISION_REQUIRED",
    "COLLISION_TARGET",
    "COLLISION_TEXT",
    "COLLISION_UNCERTAIN",
    "COLLISION_UNCERTAINTIES",
    "plain_uncertainty_header",
    "FLUID_PROPERTIES",
    "MATERIAL_PROPERTIES",
    "POINT_COLUMNS",
    "POINT_UNCERTAINTIES",
    "SOURCE_COLUMNS",
    "SOURCE_REQUIRED",
    "DERIVED_TERMS",
    "PROBABILITY_TERMS",
    "UNCERTAIN_DERIVED",
    "UNCERTAINTY_TERMS",
    "uncertainty_column",
    "RULES",
    "TABLES",
    "TERMS",
    "UNITS",
    "Rule",
    "Term",
    "Unit",
    "check_record",
    "check_value",
    "term",
    "unit_of_column",
]
