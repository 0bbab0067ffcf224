"""granudb: a materials-and-regime database for particle collisions in liquids.

The library is the product; the ``granudb`` command is its face. Every public function
lives in ``granudb.api`` and is available here under the same name, imported on first
use (the table ``granudb.api.NAMES``), so that ``import granudb`` and ``granudb --help``
stay fast.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from granudb import api
from granudb.version import __version__ as __version__

#: Every public name: the functions named after the commands, ``connect``, the errors.
__all__ = sorted({"__version__", *api.NAMES})


if TYPE_CHECKING:
    # One `from m import (a as a, …)` per module, the explicit re-exports checkers need:
    # isort: off
    # Static type checkers see each public function with its signature (and an unknown
    # name as an error); at run time the names load on first use. Written by
    # tools/type_exports.py from granudb.api.NAMES.
    from granudb.api import (
        ConfirmationNeeded as ConfirmationNeeded,
        GranudbError as GranudbError,
        MissingInput as MissingInput,
        PackageError as PackageError,
        ValidationError as ValidationError,
        add_fluid as add_fluid,
        add_fluid_point as add_fluid_point,
        add_material as add_material,
        add_pair_value as add_pair_value,
        add_source as add_source,
        collisions as collisions,
        connect as connect,
        database_file as database_file,
        dataset as dataset,
        datasets as datasets,
        datasette_metadata as datasette_metadata,
        db_current as db_current,
        db_downgrade as db_downgrade,
        db_history as db_history,
        db_seed as db_seed,
        db_upgrade as db_upgrade,
        dem_export as dem_export,
        dem_verify as dem_verify,
        derive as derive,
        diff_datasets as diff_datasets,
        dry_values as dry_values,
        edit_dataset as edit_dataset,
        export_dataset as export_dataset,
        fit_gap_viscosity as fit_gap_viscosity,
        fit_reported as fit_reported,
        fit_restitution as fit_restitution,
        fit_walton as fit_walton,
        fluid as fluid,
        fluid_history as fluid_history,
        fluids as fluids,
        grant_role as grant_role,
        import_collisions as import_collisions,
        import_dataset as import_dataset,
        import_fluid_points as import_fluid_points,
        import_reported_runs as import_reported_runs,
        material as material,
        material_history as material_history,
        materials as materials,
        new_dataset_version as new_dataset_version,
        pair as pair,
        pair_values as pair_values,
        reference_dem as reference_dem,
        reference_import as reference_import,
        reference_list as reference_list,
        reference_reproduce as reference_reproduce,
        reference_show as reference_show,
        release_dataset as release_dataset,
        remove_collisions as remove_collisions,
        remove_dataset as remove_dataset,
        remove_fluid as remove_fluid,
        remove_material as remove_material,
        report as report,
        reported_runs as reported_runs,
        source as source,
        source_history as source_history,
        sources as sources,
        update_fluid as update_fluid,
        update_material as update_material,
        update_source as update_source,
        validate_dataset as validate_dataset,
    )
    # isort: on
else:

    def __getattr__(name: str) -> Any:
        if name in api.NAMES:
            return getattr(api, name)
        raise AttributeError(f"module 'granudb' has no attribute {name!r}")


def __dir__() -> list[str]:
    return __all__
