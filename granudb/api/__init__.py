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
from typing import TYPE_CHECKING, Any

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
    "reference_import": "reference",
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
    "spreadsheet_cell": "presentation",
    "derived_terms": "presentation",
    "fit_people_view": "presentation",
    "qualified_value": "scenario",
    "interval_text": "scenario",
    "method_text": "scenario",
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

if TYPE_CHECKING:
    # One `from m import (a as a, …)` per module, the explicit re-exports checkers need:
    # isort: off
    # What static type checkers see: every name of the tables above, with its real
    # signature (tools/type_exports.py writes this list from them). At run time the
    # names load on first use through ``__getattr__`` below.
    from granudb.api.catalog import (
        fluid as fluid,
        fluid_history as fluid_history,
        fluids as fluids,
        material as material,
        material_history as material_history,
        materials as materials,
        source as source,
        source_history as source_history,
        sources as sources,
    )
    from granudb.api.catalog_changes import (
        add_fluid as add_fluid,
        add_fluid_point as add_fluid_point,
        add_material as add_material,
        import_fluid_points as import_fluid_points,
        remove_fluid as remove_fluid,
        remove_material as remove_material,
        update_fluid as update_fluid,
        update_material as update_material,
    )
    from granudb.api.collision_changes import (
        import_collisions as import_collisions,
        remove_collisions as remove_collisions,
    )
    from granudb.api.collision_listing import (
        collisions as collisions,
    )
    from granudb.api.database import (
        connect as connect,
        grant_role as grant_role,
    )
    from granudb.api.dataset_versions import (
        dataset as dataset,
        datasets as datasets,
        diff_datasets as diff_datasets,
        edit_dataset as edit_dataset,
        new_dataset_version as new_dataset_version,
        release_dataset as release_dataset,
        remove_dataset as remove_dataset,
    )
    from granudb.api.datasette import (
        database_file as database_file,
        datasette_metadata as datasette_metadata,
    )
    from granudb.api.dem import (
        DEM_CODES as DEM_CODES,
        DEM_VALUE_SOURCES as DEM_VALUE_SOURCES,
        VERIFY_TOLERANCES as VERIFY_TOLERANCES,
        dem_export as dem_export,
        dem_verify as dem_verify,
        verify_document as verify_document,
        verify_passed as verify_passed,
        verify_table as verify_table,
    )
    from granudb.api.derivation import (
        derive as derive,
    )
    from granudb.api.errors import (
        ConfirmationNeeded as ConfirmationNeeded,
        GranudbError as GranudbError,
        MissingInput as MissingInput,
        PackageError as PackageError,
        ValidationError as ValidationError,
        __version__ as __version__,
    )
    from granudb.api.fits import (
        RESTITUTION_MODELS as RESTITUTION_MODELS,
        fit_gap_viscosity as fit_gap_viscosity,
        fit_restitution as fit_restitution,
        fit_walton as fit_walton,
    )
    from granudb.api.inputs import (
        dataset_ref as dataset_ref,
    )
    from granudb.api.lab_report import (
        REPORT_FORMATS as REPORT_FORMATS,
        report as report,
    )
    from granudb.api.packages import (
        export_dataset as export_dataset,
        import_dataset as import_dataset,
        validate_dataset as validate_dataset,
    )
    from granudb.api.pair_dry import (
        add_pair_value as add_pair_value,
        dry_values as dry_values,
        pair_values as pair_values,
    )
    from granudb.api.presentation import (
        COLLISION_FILTERS as COLLISION_FILTERS,
        DATASET_COLUMNS as DATASET_COLUMNS,
        DATASET_GROUP_COLUMNS as DATASET_GROUP_COLUMNS,
        DEFAULT_COLLISION_COLUMNS as DEFAULT_COLLISION_COLUMNS,
        DIFF_COLUMNS as DIFF_COLUMNS,
        FIT_TABLE_COLUMNS as FIT_TABLE_COLUMNS,
        FLUIDS as FLUIDS,
        MATERIALS as MATERIALS,
        PAIR_VALUE_COLUMNS as PAIR_VALUE_COLUMNS,
        POINT_COLUMNS as POINT_COLUMNS,
        PUBLISHED_NARROW as PUBLISHED_NARROW,
        SOURCE_COLUMNS as SOURCE_COLUMNS,
        SOURCE_FIELDS as SOURCE_FIELDS,
        SOURCE_NARROW as SOURCE_NARROW,
        derived_terms as derived_terms,
        display as display,
        display_uncertain as display_uncertain,
        fit_people_view as fit_people_view,
        parameter_of as parameter_of,
        spreadsheet_cell as spreadsheet_cell,
        term as term,
    )
    from granudb.api.reference import (
        DEM_REFERENCE_CODES as DEM_REFERENCE_CODES,
        REFERENCE_CHECK_COLUMNS as REFERENCE_CHECK_COLUMNS,
        REFERENCE_CHECK_NARROW as REFERENCE_CHECK_NARROW,
        REFERENCE_COLUMNS as REFERENCE_COLUMNS,
        REFERENCE_DEM_COLUMNS as REFERENCE_DEM_COLUMNS,
        REFERENCE_DEM_NARROW as REFERENCE_DEM_NARROW,
        REFERENCE_NARROW as REFERENCE_NARROW,
        REFERENCE_VALUE_COLUMNS as REFERENCE_VALUE_COLUMNS,
        reference_dem as reference_dem,
        reference_import as reference_import,
        reference_list as reference_list,
        reference_reproduce as reference_reproduce,
        reference_show as reference_show,
    )
    from granudb.api.reported import (
        REPORTED_COLUMNS as REPORTED_COLUMNS,
        REPORTED_FITS as REPORTED_FITS,
        REPORTED_NARROW as REPORTED_NARROW,
        fit_reported as fit_reported,
        import_reported_runs as import_reported_runs,
        reported_runs as reported_runs,
    )
    from granudb.api.scenario import (
        interval_text as interval_text,
        method_text as method_text,
        pair as pair,
        qualified_value as qualified_value,
        target_words as target_words,
    )
    from granudb.api.schema import (
        db_current as db_current,
        db_downgrade as db_downgrade,
        db_history as db_history,
        db_seed as db_seed,
        db_upgrade as db_upgrade,
        load_seed as load_seed,
    )
    from granudb.api.source_changes import (
        add_source as add_source,
        update_source as update_source,
    )
    # isort: on
else:

    def __getattr__(name: str) -> Any:
        module = NAMES.get(name) or FACE.get(name)
        if module is None:
            raise AttributeError(f"module 'granudb.api' has no attribute {name!r}")
        value = getattr(import_module(f"granudb.api.{module}"), name)
        globals()[name] = value  # the next access does not come here again
        return value


def __dir__() -> list[str]:
    return __all__
