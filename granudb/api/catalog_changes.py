"""Changing the catalogue, for Python users and the command line: add, update and remove
materials and fluids, and add a fluid's viscosity points.

``granudb materials add|update|remove`` are ``add_material``, ``update_material`` and
``remove_material``; the same for fluids, plus ``add_fluid_point`` and
``import_fluid_points`` (``granudb fluids points add|import``). Both kinds of entry run
through one implementation (``granudb.db.catalog_changes``) with their specification
(``granudb.vocabulary.MATERIALS`` / ``FLUIDS``): a property's parameter here is its option
there (``youngs_modulus`` ↔ ``--youngs-modulus``), and a value is an SI number or a
string with its unit (``"190 GPa"``).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from granudb.api import inputs
from granudb.api.catalog import entry
from granudb.api.consent import Confirm, agreed, unchanged
from granudb.api.database import opened
from granudb.db import catalog_changes
from granudb.io.seed import POINT_NUMERIC, read_table
from granudb.reporting.format import display
from granudb.vocabulary import FLUIDS, MATERIALS, Catalogue
from granudb.vocabulary.text import check_text


@dataclass(frozen=True)
class Update:
    """What an update did: ``action`` "updated" or "unchanged", the entry, and each
    changed field as (column, old, new) in SI; ``str()`` says it for people."""

    action: str
    label: str
    changes: list[tuple[str, Any, Any]]

    def __str__(self) -> str:
        if not self.changes:
            return f"{self.action} {self.label}"
        parts = ", ".join(
            f"{c} {_human(c, old)} → {_human(c, new)}" for c, old, new in self.changes
        )
        return f"{self.action} {self.label}: {parts}"


def _human(column: str, value: Any) -> str:
    if value is None:
        return "(none)"
    if isinstance(value, str):
        return repr(value)
    return display(value, column)


def _values(catalogue: Catalogue, given: dict[str, Any]) -> dict[str, Any]:
    """``{parameter: value}`` (``None``: not given) → ``{column: SI value or text}``."""
    values: dict[str, Any] = {}
    for parameter, value in given.items():
        if value is None:
            continue
        column = catalogue.parameters[parameter]
        if column in catalogue.properties:
            values[column] = inputs.quantity(value, column, parameter)
        else:
            values[column] = check_text(parameter, inputs.text(value, parameter))
    return values


def _required(catalogue: Catalogue, given: dict[str, Any]) -> None:
    for parameter, column in catalogue.parameters.items():
        if column in catalogue.required and given.get(parameter) is None:
            raise inputs.missing(parameter, f"is required to add a {catalogue.kind}")


def _given(catalogue: Catalogue, arguments: dict[str, Any]) -> dict[str, Any]:
    """The catalogue's parameters as the caller passed them (``locals()`` of a public
    function whose keyword arguments are the spec's parameters)."""
    return {parameter: arguments[parameter] for parameter in catalogue.parameters}


def _add(catalogue: Catalogue, name: str, source: str | None, db: Any, given: dict) -> dict:
    _required(catalogue, given)
    values = _values(catalogue, given)
    name = inputs.text(name, "name")
    with opened(db) as database:
        with database.session(write=True) as session:
            catalog_changes.add_entry(session, catalogue, name, values, source)
        return entry(catalogue, name, database)


def _update(
    catalogue: Catalogue, name: str, source: str | None, rename: str | None, db: Any, given: dict
) -> Update:
    values = _values(catalogue, given)
    with opened(db) as database, database.session(write=True) as session:
        change = catalog_changes.update_entry(
            session, catalogue, inputs.text(name, "name"), values, source, rename
        )
    return Update(change.action, change.label, change.diffs)


def _remove(catalogue: Catalogue, name: str, confirm: Confirm | None, db: Any) -> str:
    name = inputs.text(name, "name")
    with opened(db) as database:
        with database.session() as session:
            losses = catalog_changes.removal(session, catalogue, name)
        action = f"{catalogue.plural} remove {name}"
        agreed(confirm, action, losses)
        with database.session(write=True) as session:
            unchanged(action, losses, catalog_changes.removal(session, catalogue, name))
            return catalog_changes.remove_entry(session, catalogue, name)


def add_material(
    name: str,
    *,
    density: Any = None,
    youngs_modulus: Any = None,
    poisson_ratio: Any = None,
    roughness: Any = None,
    correlation_length: Any = None,
    shear_modulus: Any = None,
    yield_stress: Any = None,
    dry_restitution: Any = None,
    dry_friction: Any = None,
    dry_source: str | None = None,
    brittleness: str | None = None,
    description: str | None = None,
    source: str | None = None,
    source_locator: str | None = None,
    db: Any = None,
) -> dict[str, Any]:
    """Add a material; returns it as ``material`` does. Density, Young's modulus, Poisson
    ratio and roughness are required; a shear modulus not given is derived,
    G = E / (2(1 + ν)); with a ``yield_stress`` (in tension) yield starts at 1.6 Y.
    ``dry_restitution`` and ``dry_friction`` are the material's own dry values, cited by
    ``dry_source`` (the pair's prediction uses them, docs/physics.md §18);
    ``brittleness`` is "brittle" (cracks instead of yielding) or "ductile".

    Examples
    --------
    >>> import granudb
    >>> granudb.add_material("PTFE", density="2.2 g/cm^3", youngs_modulus="0.5 GPa",
    ...                      poisson_ratio=0.46, roughness="0.2 um", db=db)["density_kg_m3"]
    2200.0
    """
    given = _given(MATERIALS, locals())
    return _add(MATERIALS, name, source, db, given)


def update_material(
    name: str,
    *,
    density: Any = None,
    youngs_modulus: Any = None,
    poisson_ratio: Any = None,
    roughness: Any = None,
    correlation_length: Any = None,
    shear_modulus: Any = None,
    yield_stress: Any = None,
    dry_restitution: Any = None,
    dry_friction: Any = None,
    dry_source: str | None = None,
    brittleness: str | None = None,
    description: str | None = None,
    source: str | None = None,
    source_locator: str | None = None,
    rename: str | None = None,
    db: Any = None,
) -> Update:
    """Change the given properties of a material (``None``: leave as it is), its source
    or its name; returns what changed, field by field.

    Examples
    --------
    >>> import granudb
    >>> print(granudb.update_material("glass", roughness="130.5 nm", db=db))
    unchanged material glass
    """
    given = _given(MATERIALS, locals())
    return _update(MATERIALS, name, source, rename, db, given)


def remove_material(name: str, *, confirm: Confirm | None = None, db: Any = None) -> str:
    """Remove a material no collision or published value refers to; returns its name.
    ``confirm(action, losses)`` is asked first (the command line's prompt); without it
    the call itself is the consent.

    Examples
    --------
    >>> import granudb
    >>> _ = granudb.add_material("test", density=1000, youngs_modulus=1e9,
    ...                          poisson_ratio=0.3, roughness=0, db=db)
    >>> granudb.remove_material("test", db=db)
    'test'
    """
    return _remove(MATERIALS, name, confirm, db)


def add_fluid(
    name: str,
    *,
    reference_viscosity: Any = None,
    reference_density: Any = None,
    reference_temperature: Any = None,
    pressure_viscosity: Any = None,
    glycerol_fraction: Any = None,
    description: str | None = None,
    source: str | None = None,
    source_locator: str | None = None,
    db: Any = None,
) -> dict[str, Any]:
    """Add a fluid; returns it as ``fluid`` does. The reference viscosity and density are
    required, at ``reference_temperature`` (default 20 °C); the Barus
    ``pressure_viscosity`` coefficient is needed for the lubricated friction (5.8).

    Examples
    --------
    >>> import granudb
    >>> granudb.add_fluid("silicone oil", reference_viscosity="9.6 cP",
    ...                   reference_density="960 kg/m^3", db=db)["reference_temperature_c"]
    20.0
    """
    given = _given(FLUIDS, locals())
    return _add(FLUIDS, name, source, db, given)


def update_fluid(
    name: str,
    *,
    reference_viscosity: Any = None,
    reference_density: Any = None,
    reference_temperature: Any = None,
    pressure_viscosity: Any = None,
    glycerol_fraction: Any = None,
    description: str | None = None,
    source: str | None = None,
    source_locator: str | None = None,
    rename: str | None = None,
    db: Any = None,
) -> Update:
    """Change the given values of a fluid, its source or its name; returns what changed.

    Examples
    --------
    >>> import granudb
    >>> print(granudb.update_fluid("glycerol-45", reference_viscosity="4.5 cP", db=db))
    unchanged fluid glycerol-45
    """
    given = _given(FLUIDS, locals())
    return _update(FLUIDS, name, source, rename, db, given)


def remove_fluid(name: str, *, confirm: Confirm | None = None, db: Any = None) -> str:
    """Remove a fluid (with its points) that no collision or published value uses;
    ``confirm`` as ``remove_material``.

    Examples
    --------
    >>> import granudb
    >>> _ = granudb.add_fluid("oil", reference_viscosity=0.1, reference_density=900, db=db)
    >>> granudb.remove_fluid("oil", db=db)
    'oil'
    """
    return _remove(FLUIDS, name, confirm, db)


def add_fluid_point(
    name: str,
    *,
    temperature: Any = None,
    viscosity: Any = None,
    density: Any = None,
    source: str | None = None,
    replace: bool = False,
    db: Any = None,
) -> list[str]:
    """Add one measured point (temperature, viscosity[, density]) to a fluid; a point at a
    temperature the fluid has is refused unless ``replace``. Returns one line per point.

    Examples
    --------
    >>> import granudb
    >>> granudb.add_fluid_point("water", temperature="23 degC", viscosity="0.9325 cP", db=db)
    ['added water at 23 °C: 0.9325 mPa·s']
    """
    if temperature is None:
        raise inputs.missing("temperature", "is required for a fluid point")
    if viscosity is None:
        raise inputs.missing("viscosity", "is required for a fluid point")
    point = {
        "temperature_c": inputs.quantity(temperature, "temperature_c", "temperature"),
        "viscosity_pa_s": inputs.quantity(viscosity, "viscosity_pa_s", "viscosity"),
    }
    if density is not None:
        point["density_kg_m3"] = inputs.quantity(density, "density_kg_m3", "density")
    return _add_points(name, [point], source, replace, db)


def import_fluid_points(
    name: str,
    file: str | Path,
    *,
    source: str | None = None,
    replace: bool = False,
    db: Any = None,
) -> list[str]:
    """Add every point of a CSV file (``temperature [degC]``, ``viscosity [cP]``, optional
    ``density [kg/m^3]``; units in the headers), all or none. Returns one line per point.

    Examples
    --------
    >>> import granudb
    >>> points = tmp / "water.csv"
    >>> _ = points.write_text("temperature [degC],viscosity [cP]\\n21,0.978\\n24,0.911\\n")
    >>> granudb.import_fluid_points("water", points, db=db)
    ['added water at 21 °C: 0.978 mPa·s', 'added water at 24 °C: 0.911 mPa·s']
    """
    points = read_table(Path(inputs.path(file, "file")), POINT_NUMERIC, [])
    return _add_points(name, points, source, replace, db)


def _add_points(
    name: str, points: list[dict], source: str | None, replace: bool, db: Any
) -> list[str]:
    with opened(db) as database, database.session(write=True) as session:
        return catalog_changes.add_fluid_points(
            session, inputs.text(name, "name"), points, source, replace=replace
        )
