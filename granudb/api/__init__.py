"""The public Python API: the whole product, and the one door of the command line.

Every command of ``granudb`` is a function here with the command's name (README, "In
Python", has the table): ``granudb materials add`` is ``add_material``, an option
``--angle-range`` is the parameter ``angle_range``, and an error names whichever the
caller used. Every function takes ``db=`` (an opened database from ``connect``, a URL, a
SQLite path, or nothing for the default) and accepts quantities as SI numbers or as
strings with units (``"12.7 mm"``), checked by one gate (``granudb.api.inputs``).

Modules load on first use, from the table below — the one place granudb's own modules
are loaded lazily — so that ``import granudb`` and ``granudb --help`` stay fast and
``granudb materials list`` never imports pandas.
"""

from __future__ import annotations

from importlib import import_module
from typing import Any

from granudb.config import ENV_VAR as DATABASE_ENV_VAR  # noqa: F401 (public: the --db variable)

#: Public name → the module of ``granudb.api`` that defines it. The functions named after
#: commands come first (``COMMAND_FUNCTIONS`` in ``granudb.cli.main`` maps each command
#: to one of them); then what the command line's face uses to print results.
NAMES: dict[str, str] = {
    # database and schema
    "connect": "database",
    "db_upgrade": "schema",
    "db_downgrade": "schema",
    "db_current": "schema",
    "db_history": "schema",
    "db_seed": "schema",
    "grant_role": "database",
    # catalogue
    "materials": "catalog",
    "material": "catalog",
    "material_history": "catalog",
    "fluid_history": "catalog",
    "fluids": "catalog",
    "fluid": "catalog",
    "sources": "catalog",
    "source": "catalog",
    "source_history": "catalog",
    "add_source": "source_changes",
    "update_source": "source_changes",
    "add_material": "catalog_changes",
    "update_material": "catalog_changes",
    "remove_material": "catalog_changes",
    "add_fluid": "catalog_changes",
    "update_fluid": "catalog_changes",
    "remove_fluid": "catalog_changes",
    "add_fluid_point": "catalog_changes",
    "import_fluid_points": "catalog_changes",
    "pair_values": "pair_dry",
    "add_pair_value": "pair_dry",
    "dry_values": "pair_dry",
    # collisions and what is derived from them
    "pair": "scenario",
    "derive": "derivation",
    "collisions": "collision_listing",
    "import_collisions": "collision_changes",
    "remove_collisions": "collision_changes",
    "fit_walton": "fits",
    "fit_restitution": "fits",
    "fit_gap_viscosity": "fits",
    "report": "lab_report",
    # datasets
    "datasets": "dataset_versions",
    "dataset": "dataset_versions",
    "diff_datasets": "dataset_versions",
    "edit_dataset": "dataset_versions",
    "release_dataset": "dataset_versions",
    "new_dataset_version": "dataset_versions",
    "remove_dataset": "dataset_versions",
    "export_dataset": "packages",
    "validate_dataset": "packages",
    "import_dataset": "packages",
    "datasette_metadata": "datasette",
    "database_file": "datasette",
    # the reference library of published collision data
    "reference_list": "reference",
    "reference_show": "reference",
    "reference_reproduce": "reference",
    "reference_dem": "reference",
    # runs as papers report them
    "import_reported_runs": "reported",
    "reported_runs": "reported",
    "fit_reported": "reported",
    # DEM
    "dem_export": "dem",
    "dem_verify": "dem",
    # errors and version (from the base modules)
    "GranudbError": "errors",
    "ValidationError": "errors",
    "ConfirmationNeeded": "errors",
    "MissingInput": "errors",
    "PackageError": "errors",
    "__version__": "errors",
}

#: What the command line's face uses to print results; in ``granudb.api`` but not in
#: ``granudb.__all__``.
FACE: dict[str, str] = {
    "display": "presentation",
    "display_uncertain": "presentation",
    "term": "presentation",
    "derived_terms": "presentation",
    "qualified_value": "scenario",
    "target_words": "scenario",
    "verify_table": "dem",
    "verify_passed": "dem",
    "verify_document": "dem",
    "VERIFY_TOLERANCES": "dem",
    "DEFAULT_COLLISION_COLUMNS": "presentation",
    "FIT_TABLE_COLUMNS": "presentation",
    "MATERIALS": "presentation",
    "FLUIDS": "presentation",
    "POINT_COLUMNS": "presentation",
    "PAIR_VALUE_COLUMNS": "presentation",
    "SOURCE_COLUMNS": "presentation",
    "SOURCE_NARROW": "presentation",
    "SOURCE_FIELDS": "presentation",
    "DATASET_COLUMNS": "presentation",
    "DATASET_GROUP_COLUMNS": "presentation",
    "DIFF_COLUMNS": "presentation",
    "PUBLISHED_NARROW": "presentation",
    "REPORT_FORMATS": "lab_report",
    "COLLISION_FILTERS": "presentation",
    "RESTITUTION_MODELS": "fits",
    "DEM_CODES": "dem",
    "DEM_VALUE_SOURCES": "dem",
    "parameter_of": "presentation",
    "dataset_ref": "inputs",
    "load_seed": "schema",
    "REFERENCE_COLUMNS": "reference",
    "REFERENCE_CHECK_COLUMNS": "reference",
    "REFERENCE_CHECK_NARROW": "reference",
    "REFERENCE_NARROW": "reference",
    "REFERENCE_DEM_COLUMNS": "reference",
    "REFERENCE_DEM_NARROW": "reference",
    "DEM_REFERENCE_CODES": "reference",
    "REPORTED_COLUMNS": "reported",
    "REPORTED_NARROW": "reported",
    "REPORTED_FITS": "reported",
    "REFERENCE_VALUE_COLUMNS": "reference",
}

__all__ = sorted({**NAMES, **FACE, "DATABASE_ENV_VAR": ""})


def __getattr__(name: str) -> Any:
    module = NAMES.get(name) or FACE.get(name)
    if module is None:
        raise AttributeError(f"module 'granudb.api' has no attribute {name!r}")
    value = getattr(import_module(f"granudb.api.{module}"), name)
    globals()[name] = value  # the next access does not come here again
    return value


def __dir__() -> list[str]:
    return __all__
