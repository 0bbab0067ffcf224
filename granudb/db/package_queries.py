"""What a Data Package export reads: a dataset, its runs and everything they refer to.

The queries live here (all SQL is in ``granudb.db``); ``granudb.io.package_export`` only
serialises the plain records returned. Rows carry every stored column by name, with
references turned into the names a receiver can resolve (material and fluid names,
source keys), never database ids.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

from sqlalchemy import inspect, select
from sqlalchemy.orm import Session

from granudb.db import catalog_rows, datasets
from granudb.db.catalog_differences import sources_read
from granudb.db.content_hash import export_hash
from granudb.db.models import Collision, Dataset, Fluid, FluidPoint, Material, Source
from granudb.vocabulary.listings import DATASET_DESCRIPTION
from granudb.vocabulary.terms import keyed


@dataclass(frozen=True)
class ExportData:
    """A dataset's metadata (``dataset``), content hash and tables, as plain values."""

    dataset: dict[str, Any]
    content_hash: str
    tables: dict[str, list[dict[str, Any]]]


def _values(row: Any) -> dict[str, Any]:
    return {c.key: getattr(row, c.key) for c in inspect(row).mapper.column_attrs}


def _json_list(text: object) -> list[Any]:
    """A JSON list stored as text (``authors``, ``keywords``), or [] when absent or bad."""
    if not isinstance(text, str) or not text.strip():
        return []
    try:
        value = json.loads(text)
    except ValueError:
        return []
    return value if isinstance(value, list) else []


def dataset_metadata(dataset: Dataset, source: dict[str, Any] | None = None) -> dict[str, Any]:
    """The dataset's descriptive metadata; ``authors`` and ``keywords`` are read when the
    schema has them (JSON text) and are empty lists otherwise. ``source`` is the
    dataset's own source as the dataset cites it (a release: as released); without it,
    the row as it is today."""
    source = source or (None if dataset.source is None else _values(dataset.source))
    return {
        **{field: getattr(dataset, field) for field in DATASET_DESCRIPTION},
        "state": dataset.state,
        "doi": dataset.doi,
        "created_at": dataset.created_at,
        "authors": _json_list(getattr(dataset, "authors", None)),
        "keywords": _json_list(getattr(dataset, "keywords", None)),
        "source": source,
    }


def _collisions(session: Session, dataset: Dataset) -> list[Collision]:
    return list(
        session.scalars(
            select(Collision).where(Collision.dataset_id == dataset.id).order_by(Collision.run)
        )
    )


def _sources(session: Session, ids: set[int | None]) -> list[Source]:
    return list(
        session.scalars(select(Source).where(Source.id.in_(ids - {None})).order_by(Source.key))
    )


def export_data(session: Session, name: str, version: str | None = None) -> ExportData:
    """Everything the export of dataset ``name`` (at ``version``, default newest) needs."""
    dataset = datasets.get_dataset(session, name, version)
    collisions = _collisions(session, dataset)
    material_ids = {c.particle_id for c in collisions} | {c.wall_id for c in collisions}
    fluid_ids = {c.fluid_id for c in collisions if c.fluid_id is not None}
    materials = list(
        session.scalars(
            select(Material).where(Material.id.in_(material_ids)).order_by(Material.name)
        )
    )
    fluids = list(
        session.scalars(select(Fluid).where(Fluid.id.in_(fluid_ids)).order_by(Fluid.name))
    )
    points = list(session.scalars(select(FluidPoint).where(FluidPoint.fluid_id.in_(fluid_ids))))
    source_ids = {dataset.source_id} | {m.source_id for m in materials}
    for fluid in fluids:
        source_ids |= {fluid.source_id, fluid.density_source_id, fluid.pressure_viscosity_source_id}
    source_ids |= {p.source_id for p in points}
    sources = _sources(session, source_ids)
    # a release cites its sources as they were when released (the one place: sources_read)
    as_released = sources_read(session.connection(), dataset.id)
    keys = {s.id: s.key for s in sources}
    names = {m.id: m.name for m in materials}
    fluid_names = {f.id: f.name for f in fluids}

    def key(source_id: int | None) -> str | None:
        return None if source_id is None else keys.get(source_id)

    tables = {
        "collisions": [
            {
                **_values(c),
                "particle": names[c.particle_id],
                "wall": names[c.wall_id],
                "fluid": None if c.fluid_id is None else fluid_names.get(c.fluid_id),
            }
            for c in collisions
        ],
        "materials": [{**_values(m), "source": key(m.source_id)} for m in materials],
        "fluids": [
            {
                **_values(f),
                "source": key(f.source_id),
                "density_source": key(f.density_source_id),
                "pressure_viscosity_source": key(f.pressure_viscosity_source_id),
            }
            for f in fluids
        ],
        "fluid_points": sorted(
            (
                {**_values(p), "fluid": fluid_names[p.fluid_id], "source": key(p.source_id)}
                for p in points
            ),
            key=lambda r: (r["fluid"], *(r[c] for c in keyed("fluid_points"))),
        ),
        "sources": [
            {**_values(s), **catalog_rows.source_record(as_released[s.key])} for s in sources
        ],  # fmt: skip
    }
    # the dataset's own source, cited as every other file of the package cites it
    own = next((s for s in tables["sources"] if s["id"] == dataset.source_id), None)
    return ExportData(dataset_metadata(dataset, own), export_hash(session, dataset), tables)
