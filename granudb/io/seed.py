"""Reading ``seed_data/``: the published materials, fluids and numbers granudb ships.

The files are meant to be read and edited by people (units in the CSV headers, sources in
TOML). This module turns them into checked SI records; ``granudb.db.seed_store`` writes
them (idempotently, reporting every change).
"""

from __future__ import annotations

import io
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from granudb.errors import ValidationError
from granudb.io.reading import read_text_file
from granudb.io.tables import convert_frame, map_headers
from granudb.lazy import pandas as pd
from granudb.resources import shipped_dir
from granudb.vocabulary import FLUID_PROPERTIES, FLUIDS, MATERIAL_PROPERTIES, MATERIALS
from granudb.vocabulary.rules import check_record

MATERIAL_NUMERIC = list(MATERIAL_PROPERTIES)
MATERIAL_TEXT = ["name", "description", "source", "source_locator", *MATERIALS.texts]
FLUID_NUMERIC = list(FLUID_PROPERTIES)
FLUID_TEXT = [
    "name",
    "description",
    "source",
    "source_locator",
    "density_source",
    "density_locator",
    "pressure_viscosity_source",
    "pressure_viscosity_locator",
    *FLUIDS.texts,
]
POINT_NUMERIC = ["temperature_c", "viscosity_pa_s", "density_kg_m3"]
POINT_TEXT = ["fluid", "source", "source_locator"]
PAIR_NUMERIC = ["dry_restitution", "dry_friction", "immersed_friction"]
PAIR_TEXT = ["particle", "wall", "source", "source_locator", "notes"]
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
    content = read_text_file(path)  # bounded; a binary file refused as such
    if not content.strip():
        raise ValidationError("FILE", path.name, "is empty")
    try:
        raw = pd.read_csv(io.StringIO(content), dtype=str, keep_default_na=False)
    except pd.errors.ParserError as exc:
        first = str(exc).splitlines()[0]
        raise ValidationError("FILE", path.name, f"is not a well-formed CSV ({first})") from None
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


@dataclass
class SeedData:
    """The seed files as SI records, in the order they must be written."""

    sources: list[dict[str, Any]]
    materials: list[dict[str, Any]]
    fluids: list[dict[str, Any]]
    points: list[dict[str, Any]]
    published: list[dict[str, Any]]
    pairs: list[dict[str, Any]] = field(default_factory=list)


def read_seed(folder: Path | None = None) -> SeedData:
    """Every seed file in ``folder`` (default: the shipped ``seed_data``), checked."""
    folder = folder or shipped_dir("seed_data")
    sources = tomllib.loads((folder / "sources.toml").read_text(encoding="utf-8"))["sources"]
    points = folder / "fluid_points.csv"
    pairs = folder / "pair_values.csv"
    return SeedData(
        sources=list(sources),
        materials=read_table(folder / "materials.csv", MATERIAL_NUMERIC, MATERIAL_TEXT),
        fluids=read_table(folder / "fluids.csv", FLUID_NUMERIC, FLUID_TEXT),
        points=read_table(points, POINT_NUMERIC, POINT_TEXT) if points.exists() else [],
        published=read_table(folder / "published_values.csv", PUBLISHED_NUMERIC, PUBLISHED_TEXT),
        pairs=read_table(pairs, PAIR_NUMERIC, PAIR_TEXT) if pairs.exists() else [],
    )
