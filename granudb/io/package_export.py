"""Export a dataset as a Frictionless Data Package (v2): datapackage.json, CSV resources
with Table Schemas, a README and a CITATION.cff.

Everything a receiver needs is inside: the collisions, the materials and fluids they name
(with viscosity points), and every source cited. Values are SI under granudb's column
names; each resource's byte count and sha256 are in ``datapackage.json``, and the dataset's
content hash (``granudb:content_hash``) lets the receiver check nothing changed on the way.
"""

from __future__ import annotations

import csv
import hashlib
import io
import json
import re
import zipfile
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from sqlalchemy import select
from sqlalchemy.orm import Session

from granudb.db.models import Collision, Dataset, Fluid, FluidPoint, Material, Source
from granudb.errors import ConflictError, ValidationError
from granudb.io.package_schema import DESCRIPTIONS, columns, table_schema
from granudb.version import __version__

PROFILE = "https://datapackage.org/profiles/2.0/datapackage.json"
RESOURCE_ORDER = ["collisions", "materials", "fluids", "fluid_points", "sources"]


@dataclass
class ExportResult:
    path: Path
    dataset: str
    version: str
    content_hash: str
    rows: dict[str, int]


def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value)  # shortest text that reads back as the same float
    return str(value)


def _csv_bytes(header: list[str], rows: list[dict[str, Any]]) -> bytes:
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(header)
    for row in rows:
        writer.writerow([_cell(row.get(c)) for c in header])
    return buffer.getvalue().encode("utf-8")


def package_name(dataset: str) -> str:
    """A Data Package ``name``: lower-case letters, digits and ``.-_`` only."""
    name = re.sub(r"[^a-z0-9._-]+", "-", dataset.lower()).strip("-")
    return name or "granudb-dataset"


def _tables(session: Session, dataset: Dataset) -> dict[str, list[dict[str, Any]]]:
    collisions = list(
        session.scalars(
            select(Collision).where(Collision.dataset_id == dataset.id).order_by(Collision.run)
        )
    )
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
    names = {m.id: m.name for m in materials}
    fluid_names = {f.id: f.name for f in fluids}
    points = list(
        session.scalars(
            select(FluidPoint)
            .where(FluidPoint.fluid_id.in_(fluid_ids))
            .order_by(FluidPoint.fluid_id, FluidPoint.temperature_c)
        )
    )

    source_ids = {dataset.source_id} | {m.source_id for m in materials}
    for fluid in fluids:
        source_ids |= {fluid.source_id, fluid.density_source_id, fluid.pressure_viscosity_source_id}
    source_ids |= {p.source_id for p in points}
    sources = list(
        session.scalars(
            select(Source).where(Source.id.in_(source_ids - {None})).order_by(Source.key)
        )
    )
    keys = {s.id: s.key for s in sources}

    def key(source_id: int | None) -> str | None:
        return keys.get(source_id) if source_id is not None else None

    return {
        "collisions": [
            {
                **{
                    c: getattr(row, c)
                    for c in columns("collisions")
                    if c not in {"particle", "wall", "fluid"}
                },
                "particle": names[row.particle_id],
                "wall": names[row.wall_id],
                "fluid": fluid_names.get(row.fluid_id),
            }
            for row in collisions
        ],
        "materials": [
            {
                **{c: getattr(m, c) for c in columns("materials") if c != "source"},
                "source": key(m.source_id),
            }
            for m in materials
        ],
        "fluids": [
            {
                **{
                    c: getattr(f, c)
                    for c in columns("fluids")
                    if c not in {"source", "density_source", "pressure_viscosity_source"}
                },
                "source": key(f.source_id),
                "density_source": key(f.density_source_id),
                "pressure_viscosity_source": key(f.pressure_viscosity_source_id),
            }
            for f in fluids
        ],
        "fluid_points": sorted(
            (
                {
                    "fluid": fluid_names[p.fluid_id],
                    "temperature_c": p.temperature_c,
                    "viscosity_pa_s": p.viscosity_pa_s,
                    "density_kg_m3": p.density_kg_m3,
                    "source": key(p.source_id),
                    "source_locator": p.source_locator,
                }
                for p in points
            ),
            key=lambda r: (r["fluid"], r["temperature_c"]),
        ),
        "sources": [{c: getattr(s, c) for c in columns("sources")} for s in sources],
    }


def _readme(
    dataset: Dataset,
    tables: dict[str, list[dict[str, Any]]],
    content_hash: str,
    sources: list[dict[str, Any]],
) -> str:
    pairs: dict[tuple[str, str, str], int] = {}
    for row in tables["collisions"]:
        group = (row["particle"], row["wall"], row["fluid"] or "dry")
        pairs[group] = pairs.get(group, 0) + 1
    lines = [
        f"# {dataset.title or dataset.name}",
        "",
        f"Dataset `{dataset.name}`, version {dataset.version}, exported by granudb "
        f"{__version__} as a [Frictionless Data Package](https://datapackage.org) (v2).",
        "",
        dataset.description or "",
        "",
        "## Contents",
        "",
        "| particle | wall | fluid | runs |",
        "|---|---|---|---:|",
        *(f"| {p} | {w} | {f} | {n} |" for (p, w, f), n in sorted(pairs.items())),
        "",
        "Resources: `collisions.csv` (one impact per row), `materials.csv`, `fluids.csv`, "
        "`fluid_points.csv` (viscosity against temperature), `sources.csv`. Every value is "
        "SI and the column name carries its unit (`v_n_in_m_s`, `youngs_modulus_pa`); each "
        "field of the Table Schemas in `datapackage.json` also states it in a `unit` "
        "property (a community convention: the standard has no unit property yet).",
        "",
        "## Sign convention",
        "",
        "Normal speeds `v_n_in_m_s` and `v_n_out_m_s` are both positive (towards the wall "
        "before, away after), so e = v_n_out / v_n_in. The tangential axis points along the "
        "incoming tangential motion (`v_t_in_m_s` ≥ 0). Spin is positive where it adds to "
        "the contact point's tangential velocity: v_T = v_t + ωR, R = diameter / 2.",
        "",
        "## Integrity",
        "",
        f"Content hash of the collisions: `{content_hash}` (granudb recomputes it on "
        "import). Each resource's sha256 and size are in `datapackage.json`.",
        "",
        "## How to cite",
        "",
        f"Cite the dataset as in `CITATION.cff`; license: {dataset.license or 'not stated'}.",
    ]
    if sources:
        lines += ["", "Sources of the values:", ""]
        lines += [
            f"- {s['citation']}" + (f" https://doi.org/{s['doi']}" if s["doi"] else "")
            for s in sources
        ]
    return "\n".join(lines) + "\n"


def _citation(dataset: Dataset, content_hash: str, created: str) -> str:
    def quoted(text: str) -> str:
        return json.dumps(text, ensure_ascii=False)  # JSON strings are valid YAML

    lines = [
        "cff-version: 1.2.0",
        "message: If you use this dataset, please cite it as below.",
        "type: dataset",
        f"title: {quoted(dataset.title or dataset.name)}",
        f"version: {quoted(dataset.version)}",
        f"date-released: {quoted(created[:10])}",
        "authors:",
        f"  - name: {quoted(dataset.source.citation if dataset.source else 'granudb user')}",
    ]
    if dataset.license:
        lines.append(f"license: {quoted(dataset.license)}")
    if dataset.doi:
        lines.append(f"doi: {quoted(dataset.doi)}")
    elif dataset.source is not None and dataset.source.doi:
        lines.append(f"doi: {quoted(dataset.source.doi)}")
    lines.append(f"abstract: {quoted(dataset.description or '')}")
    lines.append(f"keywords: [{quoted('granudb:content_hash=' + content_hash)}]")
    return "\n".join(lines) + "\n"


def build_package(
    session: Session, dataset: Dataset, content_hash: str, created: str | None = None
) -> dict[str, bytes]:
    """Every file of the package, by relative path."""
    created = created or datetime.now(UTC).replace(microsecond=0).isoformat()
    tables = _tables(session, dataset)
    files: dict[str, bytes] = {}
    resources = []
    for name in RESOURCE_ORDER:
        data = _csv_bytes(columns(name), tables[name])
        path = f"data/{name}.csv"
        files[path] = data
        resources.append(
            {
                "name": name,
                "type": "table",
                "path": path,
                "format": "csv",
                "mediatype": "text/csv",
                "encoding": "utf-8",
                "bytes": len(data),
                "hash": "sha256:" + hashlib.sha256(data).hexdigest(),
                "description": DESCRIPTIONS[name],
                "schema": table_schema(name),
            }
        )
    descriptor: dict[str, Any] = {
        "$schema": PROFILE,
        "name": package_name(dataset.name),
        "title": dataset.title or dataset.name,
        "description": dataset.description or f"granudb dataset {dataset.name}",
        "version": dataset.version,
        "created": created,
        "keywords": ["granudb", "particle-wall collisions", "restitution", "friction"],
        "contributors": [{"title": "granudb export", "roles": ["publisher"]}],
        "sources": [
            {
                "title": s["citation"],
                **(
                    {"path": f"https://doi.org/{s['doi']}"}
                    if s["doi"]
                    else ({"path": s["url"]} if s["url"] else {})
                ),
            }
            for s in tables["sources"]
        ],
        "granudb:dataset": dataset.name,
        "granudb:content_hash": content_hash,
        "granudb:version": __version__,
        "resources": resources,
    }
    if dataset.license:
        descriptor["licenses"] = [{"name": dataset.license}]
    if dataset.doi:
        descriptor["id"] = f"https://doi.org/{dataset.doi}"
    files["datapackage.json"] = (
        json.dumps(descriptor, indent=2, ensure_ascii=False) + "\n"
    ).encode("utf-8")
    files["README.md"] = _readme(dataset, tables, content_hash, tables["sources"]).encode("utf-8")
    files["CITATION.cff"] = _citation(dataset, content_hash, created).encode("utf-8")
    return files


def write_package(files: dict[str, bytes], output: Path, *, overwrite: bool = False) -> Path:
    """Write to a folder, or to a zip file when ``output`` ends in ``.zip``."""
    if output.suffix.lower() == ".zip":
        if output.exists() and not overwrite:
            raise ConflictError(f"--output: {output} exists (remove it or choose another)")
        if not output.parent.is_dir():
            raise ValidationError("--output", str(output), "is in a folder that does not exist")
        temporary = output.with_name(output.name + ".part")
        with zipfile.ZipFile(temporary, "w", compression=zipfile.ZIP_DEFLATED) as archive:
            for path in sorted(files):
                info = zipfile.ZipInfo(path, date_time=(2000, 1, 1, 0, 0, 0))
                info.compress_type = zipfile.ZIP_DEFLATED
                archive.writestr(info, files[path])
        temporary.replace(output)
        return output
    if output.exists() and any(output.iterdir()) and not overwrite:
        raise ConflictError(f"--output: folder {output} is not empty (choose an empty one)")
    if not output.parent.is_dir():
        raise ValidationError("--output", str(output), "is in a folder that does not exist")
    for path, data in files.items():
        target = output / path
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(data)
    return output
