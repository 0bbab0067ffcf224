"""The package's Table Schemas say what the vocabulary says: one list of columns."""

from __future__ import annotations

from granudb.io.package_schema import RESOURCES
from granudb.vocabulary import (
    COLLISION_MEASURED,
    COLLISION_REQUIRED,
    FLUIDS,
    MATERIALS,
    SOURCE_COLUMNS,
    SOURCE_REQUIRED,
)


def _numbers(resource: str) -> list[str]:
    return [name for name, kind, _ in RESOURCES[resource] if kind == "number"]


def _required(resource: str) -> set[str]:
    return {name for name, _, required in RESOURCES[resource] if required}


def test_catalogue_tables_are_the_catalogue_specs() -> None:
    for resource, spec in (("materials", MATERIALS), ("fluids", FLUIDS)):
        # the properties, then their standard uncertainties (last: older packages lack them)
        assert _numbers(resource) == [*spec.properties, *spec.uncertainties.values()]
        assert _required(resource) == {"name", *spec.required, *spec.defaults}


def test_collision_table_is_the_collision_columns() -> None:
    assert _numbers("collisions") == COLLISION_MEASURED
    assert _required("collisions") == set(COLLISION_REQUIRED)


def test_sources_table_is_the_source_columns() -> None:
    assert [name for name, _, _ in RESOURCES["sources"]] == SOURCE_COLUMNS
    assert _required("sources") == set(SOURCE_REQUIRED)


def test_every_source_column_has_its_locator() -> None:
    for fields in RESOURCES.values():
        names = [name for name, _, _ in fields]
        for name in names:
            if name.endswith("source") and name != "source":
                assert name.removesuffix("source") + "locator" in names
