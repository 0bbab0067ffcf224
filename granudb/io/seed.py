"""Loading ``seed_data/``: the published materials, fluids and numbers granudb ships.

The files are meant to be read and edited by people (units in the CSV headers, sources in
TOML). Loading is idempotent: a second load changes nothing, and a changed value updates
its row and is reported. Rows are never deleted by a load, so nothing a user added is lost.
"""

from __future__ import annotations

import tomllib
from collections import Counter
from pathlib import Path
from typing import Any

from sqlalchemy import select
from sqlalchemy.orm import Session

from granudb.db.models import Fluid, FluidPoint, Material, PublishedValue, Source, name_key
from granudb.db.upsert import Change, upsert
from granudb.errors import ValidationError
from granudb.io.rules import check_record
from granudb.io.tables import convert_frame, map_headers
from granudb.resources import shipped_dir

MATERIAL_NUMERIC = [
    "density_kg_m3",
    "youngs_modulus_pa",
    "poisson_ratio",
    "roughness_rms_m",
    "correlation_length_m",
    "shear_modulus_pa",
]
MATERIAL_TEXT = ["name", "description", "source", "source_locator"]
FLUID_NUMERIC = [
    "glycerol_mass_fraction",
    "density_kg_m3",
    "viscosity_pa_s",
    "reference_temperature_c",
    "pressure_viscosity_pa_inv",
]
FLUID_TEXT = [
    "name",
    "description",
    "source",
    "source_locator",
    "density_source",
    "density_locator",
    "pressure_viscosity_source",
    "pressure_viscosity_locator",
]
POINT_NUMERIC = ["temperature_c", "viscosity_pa_s", "density_kg_m3"]
POINT_TEXT = ["fluid", "source", "source_locator"]
PUBLISHED_NUMERIC = ["value", "uncertainty"]
PUBLISHED_TEXT = [
    "source",
    "source_locator",
    "label",
    "quantity",
    "value_as_printed",
    "particle",
    "wall",
    "fluid",
    "condition",
    "notes",
]


def read_table(path: Path, numeric: list[str], text: list[str]) -> list[dict[str, Any]]:
    """A seed CSV as SI records (``None`` for empty cells)."""
    import pandas as pd

    raw = pd.read_csv(path, dtype=str, keep_default_na=False, encoding="utf-8-sig")
    mapping = map_headers(list(raw.columns), numeric, text, table=path.name)
    # Rows are numbered as a spreadsheet shows them: the header is row 1.
    frame = convert_frame(raw, mapping, table=path.name, first_row=2)
    records = []
    for number, record in enumerate(frame.to_dict("records"), start=2):
        cleaned = {k: (None if _missing(v) else v) for k, v in record.items()}
        check_record(cleaned, row=number)
        records.append(cleaned)
    return records


def _missing(value: Any) -> bool:
    return value is None or (isinstance(value, float) and value != value) or value == ""


class _Resolver:
    """Looks up referenced rows by key or name while loading."""

    def __init__(self, session: Session) -> None:
        self.session = session

    def source(self, key: str | None, where: str) -> int | None:
        if key is None:
            return None
        found = self.session.scalars(select(Source.id).filter_by(key=key)).one_or_none()
        if found is None:
            raise ValidationError(where, key, "names no source in sources.toml")
        return found

    def named(self, model: type, name: str | None, where: str) -> int | None:
        if name is None:
            return None
        found = self.session.scalars(select(model.id).filter_by(name_key=name_key(name)))
        row = found.one_or_none()
        if row is None:
            raise ValidationError(where, name, f"names no {model.__tablename__[:-1]}")
        return row


def load_seed(session: Session, folder: Path | None = None) -> list[str]:
    """Load every seed file in ``folder`` (default: the shipped ``seed_data``).

    Returns one line per change plus a summary line; raises ``ValidationError`` (and the
    caller's transaction rolls back) if a file breaks a rule.
    """
    folder = folder or shipped_dir("seed_data")
    resolve = _Resolver(session)
    changes: list[Change] = []

    sources = tomllib.loads((folder / "sources.toml").read_text(encoding="utf-8"))["sources"]
    for entry in sources:
        values = {k: entry.get(k) for k in ("citation", "doi", "url", "year", "notes")}
        values["kind"] = entry.get("kind", "publication")
        changes.append(
            upsert(session, Source, {"key": entry["key"]}, values, f"source {entry['key']}")[1]
        )

    for row in read_table(folder / "materials.csv", MATERIAL_NUMERIC, MATERIAL_TEXT):
        name = row.pop("name")
        row["source_id"] = resolve.source(row.pop("source"), f"materials.csv {name}")
        changes.append(
            upsert(
                session,
                Material,
                {"name_key": name_key(name)},
                {"name": name, **row},
                f"material {name}",
            )[1]
        )

    for row in read_table(folder / "fluids.csv", FLUID_NUMERIC, FLUID_TEXT):
        name = row.pop("name")
        for prefix in ("", "density_", "pressure_viscosity_"):
            row[f"{prefix}source_id"] = resolve.source(
                row.pop(f"{prefix}source"), f"fluids.csv {name}"
            )
        changes.append(
            upsert(
                session, Fluid, {"name_key": name_key(name)}, {"name": name, **row}, f"fluid {name}"
            )[1]
        )

    points = folder / "fluid_points.csv"
    if points.exists():
        for row in read_table(points, POINT_NUMERIC, POINT_TEXT):
            fluid = row.pop("fluid")
            fluid_id = resolve.named(Fluid, fluid, "fluid_points.csv fluid")
            row["source_id"] = resolve.source(row.pop("source"), "fluid_points.csv")
            key = {"fluid_id": fluid_id, "temperature_c": row.pop("temperature_c")}
            label = f"fluid point {fluid} at {key['temperature_c']:g} °C"
            changes.append(upsert(session, FluidPoint, key, row, label)[1])

    for row in read_table(folder / "published_values.csv", PUBLISHED_NUMERIC, PUBLISHED_TEXT):
        where = f"published_values.csv {row['label']}"
        key = {
            "source_id": resolve.source(row.pop("source"), where),
            "label": row.pop("label"),
            "quantity": row.pop("quantity"),
        }
        row["particle_id"] = resolve.named(Material, row.pop("particle"), where)
        row["wall_id"] = resolve.named(Material, row.pop("wall"), where)
        row["fluid_id"] = resolve.named(Fluid, row.pop("fluid"), where)
        label = f"published value {key['label']} / {key['quantity']}"
        changes.append(upsert(session, PublishedValue, key, row, label)[1])

    session.flush()
    return summarize(changes)


def summarize(changes: list[Change]) -> list[str]:
    """One line per update, then a count of what was added, updated and left alone."""
    lines = [c.describe() for c in changes if c.action == "updated"]
    counts = Counter(c.action for c in changes)
    lines.append(
        f"seed: {counts['added']} added, {counts['updated']} updated, "
        f"{counts['unchanged']} unchanged"
    )
    return lines
