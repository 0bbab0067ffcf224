"""Queries and changes for the catalogue: materials, fluids and sources.

Every function takes a ``Session`` (the caller owns the transaction) and speaks in SI
records keyed by the public column names, so the CLI, the reports and the Python API all
see the same vocabulary. Lookups by name are case-insensitive; a name that is not there
is an error listing the names that are.
"""

from __future__ import annotations

from typing import Any

from sqlalchemy import func, select
from sqlalchemy.orm import Session

# The record builders live with the Core reads (``catalog_rows``); re-exported here.
from granudb.db.catalog_rows import fluid_record as fluid_record
from granudb.db.catalog_rows import material_record as material_record
from granudb.db.catalog_rows import point_records as point_records
from granudb.db.catalog_rows import source_key as _key
from granudb.db.models import (
    Collision,
    Dataset,
    Fluid,
    FluidPoint,
    Material,
    PublishedValue,
    name_key,
)
from granudb.db.sources import get_source
from granudb.db.upsert import Change, same_value
from granudb.errors import ConflictError, NotFoundError, ValidationError
from granudb.vocabulary.columns import FLUID_FIELDS, MATERIAL_FIELDS
from granudb.vocabulary.rules import check_record
from granudb.vocabulary.text import check_name


def list_materials(session: Session) -> list[Material]:
    return list(session.scalars(select(Material).order_by(Material.name_key)))


def get_material(session: Session, name: str) -> Material:
    found = session.scalars(select(Material).filter_by(name_key=name_key(name))).one_or_none()
    if found is None:
        known = ", ".join(m.name for m in list_materials(session)) or "none yet"
        raise NotFoundError(f"material: {name!r} is not in the database (known: {known})")
    return found


def _apply(row: Any, values: dict[str, Any], allowed: set[str], label: str) -> Change:
    diffs = []
    for column, new in values.items():
        if column not in allowed:
            raise ValidationError(column, new, "is not a field that can be set")
        old = getattr(row, column)
        if not same_value(old, new):
            diffs.append((column, old, new))
            setattr(row, column, new)
    return Change("updated" if diffs else "unchanged", label, diffs)


def add_material(
    session: Session, name: str, values: dict[str, Any], source: str | None = None
) -> Material:
    """Add a material; refuses a name that exists (compared case-insensitively)."""
    _check_name("material", name)
    check_record(values)
    existing = session.scalars(select(Material).filter_by(name_key=name_key(name)))
    if (clash := existing.one_or_none()) is not None:
        raise ConflictError(
            f"material: {name!r} already exists as {clash.name!r} (use `granudb materials update`)"
        )
    unknown = set(values) - MATERIAL_FIELDS
    if unknown:
        raise ValidationError(
            sorted(unknown)[0], values[sorted(unknown)[0]], "is not a material field"
        )
    material = Material(name=name, name_key=name_key(name), **values)
    _check_shear_modulus(material)
    if source is not None:
        material.source = get_source(session, source)
    session.add(material)
    session.flush()
    return material


def update_material(
    session: Session,
    name: str,
    values: dict[str, Any],
    source: str | None = None,
    new_name: str | None = None,
) -> Change:
    """Change the given fields of a material; returns what changed (field by field)."""
    material = get_material(session, name)
    check_record(values)
    change = _apply(material, values, MATERIAL_FIELDS, f"material {material.name}")
    change = _rename_and_source(session, Material, material, change, source, new_name)
    _check_shear_modulus(material)
    session.flush()
    return change


def _check_shear_modulus(material: Material) -> None:
    if material.shear_modulus_pa is None:
        return
    # E, ν and G of an isotropic solid satisfy ν = E/(2G) − 1; an explicit G is allowed to
    # differ (anisotropic or measured), but must still give ν inside (−1, 0.5).
    implied = material.youngs_modulus_pa / (2.0 * material.shear_modulus_pa) - 1.0
    if not -1.0 < implied < 0.5:
        raise ValidationError(
            "shear_modulus_pa",
            material.shear_modulus_pa,
            f"with youngs_modulus_pa {material.youngs_modulus_pa:g} implies a Poisson ratio "
            f"of {implied:.3g}, outside (−1, 0.5)",
        )


def _rename_and_source(
    session: Session,
    model: type,
    row: Any,
    change: Change,
    source: str | None,
    new_name: str | None,
) -> Change:
    diffs = list(change.diffs)
    if source is not None:
        found = get_source(session, source)
        if row.source_id != found.id:
            diffs.append(("source", _key(row.source), found.key))
            row.source = found
    if new_name is not None and new_name != row.name:
        kind = model.__tablename__[:-1]
        _check_name(kind, new_name)
        clash = session.scalars(
            select(model).filter_by(name_key=name_key(new_name)).where(model.id != row.id)
        ).one_or_none()
        if clash is not None:
            raise ConflictError(f"{kind}: {new_name!r} already exists")
        diffs.append(("name", row.name, new_name))
        row.name, row.name_key = new_name, name_key(new_name)
    return Change("updated" if diffs else "unchanged", change.label, diffs)


def _usage(session: Session, column: Any, *, role: str) -> list[str]:
    rows = session.execute(
        select(Dataset.name, Dataset.version, func.count())
        .join(Collision, Collision.dataset_id == Dataset.id)
        .where(column)
        .group_by(Dataset.name, Dataset.version)
        .order_by(Dataset.name, Dataset.version)
    ).all()
    return [f"{n} collisions in dataset {d} {v} (as {role})" for d, v, n in rows]


def material_removal(session: Session, name: str) -> list[str]:
    """What removing the material deletes (for the confirmation); refuses one in use."""
    material = _unused_material(session, name)
    return [f"material {material.name}"]


def remove_material(session: Session, name: str) -> Material:
    """Delete a material that nothing refers to; otherwise say what refers to it."""
    material = _unused_material(session, name)
    session.delete(material)
    session.flush()
    return material


def _unused_material(session: Session, name: str) -> Material:
    material = get_material(session, name)
    uses = _usage(session, Collision.particle_id == material.id, role="particle")
    uses += _usage(session, Collision.wall_id == material.id, role="wall")
    published = session.scalar(
        select(func.count())
        .select_from(PublishedValue)
        .where(
            (PublishedValue.particle_id == material.id) | (PublishedValue.wall_id == material.id)
        )
    )
    if published:
        uses.append(f"{published} published values")
    if uses:
        raise ConflictError(
            f"material: {material.name!r} is still used by {'; '.join(uses)}; remove those first"
        )
    return material


# --- fluids ----------------------------------------------------------------------------


def list_fluids(session: Session) -> list[Fluid]:
    return list(session.scalars(select(Fluid).order_by(Fluid.name_key)))


def get_fluid(session: Session, name: str) -> Fluid:
    found = session.scalars(select(Fluid).filter_by(name_key=name_key(name))).one_or_none()
    if found is None:
        known = ", ".join(f.name for f in list_fluids(session)) or "none yet"
        raise NotFoundError(f"fluid: {name!r} is not in the database (known: {known})")
    return found


def add_fluid(
    session: Session, name: str, values: dict[str, Any], source: str | None = None
) -> Fluid:
    """Add a fluid; refuses a name that exists (compared case-insensitively)."""
    _check_name("fluid", name)
    check_record(values)
    clash = session.scalars(select(Fluid).filter_by(name_key=name_key(name))).one_or_none()
    if clash is not None:
        raise ConflictError(
            f"fluid: {name!r} already exists as {clash.name!r} (use `granudb fluids update`)"
        )
    unknown = set(values) - FLUID_FIELDS
    if unknown:
        first = sorted(unknown)[0]
        raise ValidationError(first, values[first], "is not a fluid field")
    fluid = Fluid(name=name, name_key=name_key(name), **values)
    if source is not None:
        fluid.source = get_source(session, source)
    session.add(fluid)
    session.flush()
    return fluid


def update_fluid(
    session: Session,
    name: str,
    values: dict[str, Any],
    source: str | None = None,
    new_name: str | None = None,
) -> Change:
    fluid = get_fluid(session, name)
    check_record(values)
    change = _apply(fluid, values, FLUID_FIELDS, f"fluid {fluid.name}")
    change = _rename_and_source(session, Fluid, fluid, change, source, new_name)
    session.flush()
    return change


def fluid_removal(session: Session, name: str) -> list[str]:
    """What removing the fluid deletes (for the confirmation); refuses one in use."""
    fluid = _unused_fluid(session, name)
    return [f"fluid {fluid.name} with its {len(fluid.points)} viscosity points"]


def remove_fluid(session: Session, name: str) -> Fluid:
    """Delete a fluid (and its viscosity points) that no collision or published value uses."""
    fluid = _unused_fluid(session, name)
    session.delete(fluid)
    session.flush()
    return fluid


def _unused_fluid(session: Session, name: str) -> Fluid:
    fluid = get_fluid(session, name)
    uses = _usage(session, Collision.fluid_id == fluid.id, role="fluid")
    published = session.scalar(
        select(func.count()).select_from(PublishedValue).where(PublishedValue.fluid_id == fluid.id)
    )
    if published:
        uses.append(f"{published} published values")
    if uses:
        raise ConflictError(
            f"fluid: {fluid.name!r} is still used by {'; '.join(uses)}; remove those first"
        )
    return fluid


def add_fluid_points(
    session: Session,
    name: str,
    points: list[dict[str, Any]],
    source: str | None = None,
    *,
    replace: bool = False,
) -> list[str]:
    """Add measured (temperature, viscosity[, density]) points to a fluid; one line per
    point. A point at a temperature the fluid already has is refused, naming the stored
    value, unless ``replace`` (then the line says what it replaced): a stored number is
    never changed silently."""
    fluid = get_fluid(session, name)
    source_row = get_source(session, source) if source is not None else None
    by_temperature = {p.temperature_c: p for p in fluid.points}
    seen: set[float] = set()
    lines = []
    for index, point in enumerate(points, start=1):
        check_record(point, row=index)
        t = point["temperature_c"]
        if t in seen:
            raise ValidationError("temperature_c", f"{t:g} °C", "appears twice", row=index)
        seen.add(t)
        existing = by_temperature.get(t)
        if existing is not None and not replace:
            raise ConflictError(
                f"fluid {fluid.name}: a point at {t:g} °C exists already "
                f"({existing.viscosity_pa_s * 1e3:.4g} mPa·s); give --replace to change it"
            )
        if existing is None:
            existing = FluidPoint(fluid=fluid, temperature_c=t)
            session.add(existing)
            lines.append(
                f"added {fluid.name} at {t:g} °C: {point['viscosity_pa_s'] * 1e3:.4g} mPa·s"
            )
        else:
            lines.append(
                f"replaced {fluid.name} at {t:g} °C: {existing.viscosity_pa_s * 1e3:.4g} → "
                f"{point['viscosity_pa_s'] * 1e3:.4g} mPa·s"
            )
        existing.viscosity_pa_s = point["viscosity_pa_s"]
        existing.density_kg_m3 = point.get("density_kg_m3")
        existing.source = source_row
    session.flush()
    return lines


def _check_name(kind: str, name: str) -> None:
    """The shared name rules (``granudb.vocabulary.text``), named for this kind of row;
    ``dry`` is reserved for fluids: it means "no fluid" everywhere."""
    check_name(f"{kind} name", name)
    if kind == "fluid" and name.casefold() == "dry":
        raise ValidationError("fluid name", name, "is reserved: 'dry' means no fluid")
