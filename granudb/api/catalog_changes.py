"""Changing the catalogue, for Python users and the command line: add, update and remove
materials and fluids, and add a fluid's viscosity points.

The same concept as ``granudb.db.catalog_changes`` seen from the API's side: here the
inputs are parsed and checked and consent is asked; there the rows are written.

``granudb materials add|update|remove`` are ``add_material``, ``update_material`` and
``remove_material``; the same for fluids, plus ``add_fluid_point`` and
``import_fluid_points`` (``granudb fluids points add|import``). Both kinds of entry run
through one implementation (``granudb.db.catalog_changes``) with their specification
(``granudb.vocabulary.MATERIALS`` / ``FLUIDS``): a property's parameter here is its option
there (``youngs_modulus`` ↔ ``--youngs-modulus``), and a value is an SI number or a
string with its unit (``"190 GPa"``), with its standard uncertainty if known
(``"190 GPa ± 5 %"``, ``"23.6 ± 2 nm"``; stored as ``u_<column>``, absolute SI).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

from granudb.api import inputs
from granudb.api.catalog import entry
from granudb.api.consent import Confirm, agreed, unchanged
from granudb.api.database import opened
from granudb.db import catalog_changes
from granudb.io.seed import POINT_NUMERIC, read_table
from granudb.reporting.format import display
from granudb.vocabulary import FLUIDS, MATERIALS, Catalogue
from granudb.vocabulary.catalog import ONE_LINE_TEXTS
from granudb.vocabulary.text import check_name, check_text

F = TypeVar("F", bound=Callable[..., Any])


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
            # "190 GPa ± 5 %": the value and its standard uncertainty, set together (a
            # value given without ± has none: the old u belonged to the old value)
            values[column], values[catalogue.uncertainties[column]] = inputs.uncertain_quantity(
                value, column, parameter
            )
        elif column in ONE_LINE_TEXTS:  # conditions: one line
            limit = ONE_LINE_TEXTS[column]
            values[column] = check_name(parameter, inputs.text(value, parameter), max_length=limit)
        else:
            values[column] = check_text(parameter, inputs.text(value, parameter))
    return values


def _required(catalogue: Catalogue, given: dict[str, Any]) -> None:
    for parameter, column in catalogue.parameters.items():
        if column in catalogue.required and given.get(parameter) is None:
            raise inputs.missing(parameter, f"is required to add a {catalogue.kind}")


def _given(catalogue: Catalogue, values: dict[str, Any]) -> dict[str, Any]:
    """``values`` (a public function's ``**values``) if each is one of the catalogue's
    parameters, else ``ValidationError`` with the nearest name."""
    return inputs.known_options(values, catalogue.parameters, f"a value of a {catalogue.kind}")


def _takes(catalogue: Catalogue) -> Callable[[F], F]:
    """The decorated function's ``**values`` are the catalogue's parameters, shown in its
    signature as keywords defaulting to ``None``, generated from the specification as the
    command line's options are."""
    return inputs.shows_keywords(dict.fromkeys(catalogue.parameters))


def _add(
    catalogue: Catalogue, name: str, source: str | None, db: Any, given: dict[str, Any]
) -> dict[str, Any]:
    _required(catalogue, given)
    values = _values(catalogue, given)
    name = inputs.text(name, "name")
    with opened(db) as database:
        with database.session(write=True) as session:
            catalog_changes.add_entry(session, catalogue, name, values, source)
        return entry(catalogue, name, database)


def _update(
    catalogue: Catalogue,
    name: str,
    source: str | None,
    rename: str | None,
    db: Any,
    given: dict[str, Any],
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


@_takes(MATERIALS)
def add_material(
    name: str, *, source: str | None = None, db: Any = None, **values: Any
) -> dict[str, Any]:
    """Add a material; returns it as ``material`` does. ``values``: ``density``,
    ``youngs_modulus``, ``poisson_ratio`` and ``roughness`` (required),
    ``correlation_length``, ``shear_modulus``, ``yield_stress``, ``dry_restitution``,
    ``dry_friction`` (each an SI number or a string with its unit, optionally with its
    standard uncertainty, "190 GPa ± 5 %"), ``dry_source``, ``brittleness``,
    ``description``, ``source_locator`` and ``conditions`` (text; the conditions of the
    values as the source gives them, one line). A shear modulus not given is derived,
    G = E / (2(1 + ν)); with a ``yield_stress`` (in tension) yield starts at 1.6 Y.
    ``dry_restitution`` and ``dry_friction`` are the material's own dry values, cited by
    ``dry_source`` (the pair's prediction uses them, docs/physics.md §18); ``brittleness``
    is "brittle" (cracks instead of yielding) or "ductile".

    Examples
    --------
    >>> import granudb
    >>> granudb.add_material("PTFE", density="2.2 g/cm^3", youngs_modulus="0.5 GPa",
    ...                      poisson_ratio=0.46, roughness="0.2 um", db=db)["density_kg_m3"]
    2200.0
    """
    return _add(MATERIALS, name, source, db, _given(MATERIALS, values))


@_takes(MATERIALS)
def update_material(
    name: str,
    *,
    source: str | None = None,
    rename: str | None = None,
    db: Any = None,
    **values: Any,
) -> Update:
    """Change the given values of a material (those of ``add_material``; ``None``: leave
    as it is), its source or its name; returns what changed, field by field.

    Examples
    --------
    >>> import granudb
    >>> print(granudb.update_material("glass", roughness="130.5 nm", db=db))
    unchanged material glass
    """
    return _update(MATERIALS, name, source, rename, db, _given(MATERIALS, values))


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


@_takes(FLUIDS)
def add_fluid(
    name: str, *, source: str | None = None, db: Any = None, **values: Any
) -> dict[str, Any]:
    """Add a fluid; returns it as ``fluid`` does. ``values``: ``reference_viscosity`` and
    ``reference_density`` (required), at ``reference_temperature`` (default 20 °C),
    ``pressure_viscosity`` (Barus; needed for the lubricated friction (5.8)),
    ``glycerol_fraction`` (each an SI number or a string with its unit), ``description``,
    ``source_locator`` and ``conditions`` (text; the conditions, one line).

    Examples
    --------
    >>> import granudb
    >>> granudb.add_fluid("silicone oil", reference_viscosity="9.6 cP",
    ...                   reference_density="960 kg/m^3", db=db)["reference_temperature_c"]
    20.0
    """
    return _add(FLUIDS, name, source, db, _given(FLUIDS, values))


@_takes(FLUIDS)
def update_fluid(
    name: str,
    *,
    source: str | None = None,
    rename: str | None = None,
    db: Any = None,
    **values: Any,
) -> Update:
    """Change the given values of a fluid (those of ``add_fluid``), its source or its
    name; returns what changed.

    Examples
    --------
    >>> import granudb
    >>> change = granudb.update_fluid("glycerol-45", reference_temperature="21 degC", db=db)
    >>> change.action, change.changes
    ('updated', [('reference_temperature_c', 20.0, 21.0)])
    """
    return _update(FLUIDS, name, source, rename, db, _given(FLUIDS, values))


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
    Viscosity and density may carry their standard uncertainty (``"1.31 ± 0.01 cP"``).

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
    point = {"temperature_c": inputs.quantity(temperature, "temperature_c", "temperature")}
    # viscosity and density may carry their standard uncertainty: "1.31 ± 0.01 cP"
    point["viscosity_pa_s"], point["u_viscosity_pa_s"] = inputs.uncertain_quantity(
        viscosity, "viscosity_pa_s", "viscosity"
    )
    if density is not None:
        point["density_kg_m3"], point["u_density_kg_m3"] = inputs.uncertain_quantity(
            density, "density_kg_m3", "density"
        )
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
    name: str, points: list[dict[str, Any]], source: str | None, replace: bool, db: Any
) -> list[str]:
    with opened(db) as database, database.session(write=True) as session:
        return catalog_changes.add_fluid_points(
            session, inputs.text(name, "name"), points, source, replace=replace
        )
