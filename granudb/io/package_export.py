"""Export a dataset as a Frictionless Data Package (v2): datapackage.json, CSV resources
with Table Schemas, a README and a CITATION.cff.

Everything a receiver needs is inside: the collisions, the materials and fluids they name
(with viscosity points), and every source cited. Values are SI under granudb's column
names; each resource's byte count and sha256 are in ``datapackage.json``, and the dataset's
content hash (``granudb:content_hash``) lets the receiver check nothing changed on the way.
"""

from __future__ import annotations

import hashlib
import io
import json
import re
import zipfile
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from granudb.db.package_queries import ExportData
from granudb.errors import ConflictError, ValidationError
from granudb.io.package_metadata import citation_cff, contributors, keywords, zenodo_json
from granudb.io.package_schema import DESCRIPTIONS, columns, table_schema
from granudb.output_files import write_bytes, write_folder
from granudb.version import __version__
from granudb.vocabulary.escaping import doi_address, markdown_code, markdown_link, markdown_text

PROFILE = "https://datapackage.org/profiles/2.0/datapackage.json"
RESOURCE_ORDER = ["collisions", "materials", "fluids", "fluid_points", "sources"]


def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value)  # shortest text that reads back as the same float
    return str(value)


def _field(text: str) -> str:
    """One CSV field, quoted when it holds a comma, a quote, a line feed or a carriage
    return (the ``csv`` module quotes only the characters of its own line ending, so a bare
    CR in a note went out unquoted and split the row for every reader)."""
    if any(c in text for c in ',"\r\n') or text != text.strip(" "):
        return '"' + text.replace('"', '""') + '"'
    return text


def _csv_bytes(header: list[str], rows: list[dict[str, Any]]) -> bytes:
    """RFC 4180 CSV with LF line ends; values byte-exact (no formula neutralising, see
    the README: the content hash covers them)."""
    lines = [",".join(_field(c) for c in header)]
    lines += [",".join(_field(_cell(row.get(c))) for c in header) for row in rows]
    return ("\n".join(lines) + "\n").encode("utf-8")


def package_name(dataset: str) -> str:
    """A Data Package ``name``: lower-case letters, digits and ``.-_`` only."""
    name = re.sub(r"[^a-z0-9._-]+", "-", dataset.lower()).strip("-")
    return name or "granudb-dataset"


def _readme(data: ExportData, tables: dict[str, list[dict[str, Any]]]) -> str:
    """The package's README.md: contents, conventions, integrity and how to cite."""
    dataset = data.dataset
    pairs: dict[tuple[str, str, str], int] = {}
    for row in tables["collisions"]:
        group = (row["particle"], row["wall"], row["fluid"] or "dry")
        pairs[group] = pairs.get(group, 0) + 1
    lines = [
        f"# {markdown_text(dataset['title'] or dataset['name'])}",
        "",
        f"Dataset {markdown_code(dataset['name'])}, version {markdown_text(dataset['version'])}, "
        "exported by "
        f"granudb {__version__} as a [Frictionless Data Package](https://datapackage.org) (v2).",
        "",
        _paragraphs(dataset["description"] or ""),
        "",
        "## Contents",
        "",
        "| particle | wall | fluid | runs |",
        "|---|---|---|---:|",
        *(
            f"| {markdown_text(p)} | {markdown_text(w)} | {markdown_text(f)} | {n} |"
            for (p, w, f), n in sorted(pairs.items())
        ),
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
        f"Content hash of the collisions: `{data.content_hash}` (granudb recomputes it on "
        "import, over the run labels, the particle, wall and fluid names as written in "
        "`collisions.csv`, and the values). Each resource's sha256 and size are in "
        "`datapackage.json`.",
        "",
        "## Opening the CSV files in a spreadsheet",
        "",
        "The CSV files hold every value byte for byte, as stored: the hashes cover them, so "
        "nothing is escaped. A text cell that begins with `=`, `+`, `-`, `@`, a tab or a "
        "carriage return is therefore a formula to a spreadsheet program: import the files "
        "as text (or with a Data Package reader) rather than double-clicking them. "
        "granudb's own human-facing CSV (`--format csv`) prefixes such text cells with `'`.",
        "",
        "## How to cite",
        "",
        f"Cite the dataset as in `CITATION.cff` (Zenodo metadata: `.zenodo.json`); license: "
        f"{markdown_text(dataset['license'] or 'not stated')}.",
    ]
    if tables["sources"]:
        lines += ["", "Sources of the values:", ""]
        lines += [
            f"- {markdown_text(s['citation'])}"
            + (f" {markdown_link(doi_address(s['doi']))}" if s["doi"] else "")
            for s in tables["sources"]
        ]
    return "\n".join(lines) + "\n"


def _paragraphs(text: str) -> str:
    """Free text (a description) as Markdown: its lines kept, each escaped as text
    (``granudb.vocabulary.escaping``), so nothing in it becomes markup."""
    return "\n".join(markdown_text(line) for line in text.splitlines())


def _descriptor(
    data: ExportData, resources: list[dict[str, Any]], sources: list[dict[str, Any]], created: str
) -> dict[str, Any]:
    dataset = data.dataset
    descriptor: dict[str, Any] = {
        "$schema": PROFILE,
        "name": package_name(dataset["name"]),
        "title": dataset["title"] or dataset["name"],
        "description": dataset["description"] or f"granudb dataset {dataset['name']}",
        "version": dataset["version"],
        "created": created,
        "keywords": keywords(dataset),
        "contributors": contributors(dataset),
        "sources": [
            {
                "title": s["citation"],
                **(
                    {"path": f"https://doi.org/{s['doi']}"}
                    if s["doi"]
                    else ({"path": s["url"]} if s["url"] else {})
                ),
            }
            for s in sources
        ],
        "granudb:dataset": dataset["name"],
        "granudb:content_hash": data.content_hash,
        "granudb:version": __version__,
        **dataset_record(dataset),
        "resources": resources,
    }
    if dataset["license"]:
        descriptor["licenses"] = [{"name": dataset["license"]}]
    if dataset["doi"]:
        descriptor["id"] = f"https://doi.org/{dataset['doi']}"
    return descriptor


#: A released version and one superseded since are both releases to a receiver (which
#: versions a database holds is its own affair).
PACKAGE_STATUS = {"draft": "draft", "released": "released", "superseded": "released"}


def dataset_record(dataset: dict[str, Any]) -> dict[str, Any]:
    """The dataset's own metadata as stored, for an importer to store it again unchanged
    (the round trip is lossless): the title and description as stored (``null`` where the
    descriptor's ``title``/``description`` are placeholders from the name), the authors
    and keywords as lists, the key of the dataset's own source, and its status (draft or
    released). The descriptor's standard fields say the same for other readers."""
    source = dataset["source"]
    return {
        "granudb:status": PACKAGE_STATUS[dataset["state"]],
        "granudb:title": dataset["title"],
        "granudb:description": dataset["description"],
        "granudb:authors": dataset["authors"],
        "granudb:keywords": dataset["keywords"],
        "granudb:source": None if source is None else source["key"],
    }


def build_package(data: ExportData, created: str | None = None) -> dict[str, bytes]:
    """Every file of the package, by relative path.

    ``created`` defaults to the dataset's creation time (in UTC, whatever the database
    server's time zone), so exporting the same dataset twice gives the same bytes."""
    stamp = data.dataset.get("created_at")
    created = created or (
        stamp.replace(tzinfo=stamp.tzinfo or UTC).astimezone(UTC).replace(microsecond=0).isoformat()
        if isinstance(stamp, datetime)
        else datetime.now(UTC).replace(microsecond=0).isoformat()
    )
    files: dict[str, bytes] = {}
    resources = []
    for name in RESOURCE_ORDER:
        payload = _csv_bytes(columns(name), data.tables[name])
        path = f"data/{name}.csv"
        files[path] = payload
        resources.append(
            {
                "name": name,
                "type": "table",
                "path": path,
                "format": "csv",
                "mediatype": "text/csv",
                "encoding": "utf-8",
                "bytes": len(payload),
                "hash": "sha256:" + hashlib.sha256(payload).hexdigest(),
                "description": DESCRIPTIONS[name],
                "schema": table_schema(name),
            }
        )
    descriptor = _descriptor(data, resources, data.tables["sources"], created)
    files["datapackage.json"] = (
        json.dumps(descriptor, indent=2, ensure_ascii=False) + "\n"
    ).encode("utf-8")
    files["README.md"] = _readme(data, data.tables).encode("utf-8")
    files["CITATION.cff"] = citation_cff(data.dataset, data.content_hash, created).encode("utf-8")
    files[".zenodo.json"] = zenodo_json(data.dataset, data.content_hash, created).encode("utf-8")
    return files


def _zip_bytes(files: dict[str, bytes]) -> bytes:
    """The package as one zip archive (fixed timestamps and modes: the same files, the same
    bytes). Each entry is a regular file readable by all (``-rw-r--r--``), so the files a
    colleague unpacks are not private to whoever unpacks them."""
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        for path in sorted(files):
            info = zipfile.ZipInfo(path, date_time=(2000, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = (0o100644 & 0xFFFF) << 16
            archive.writestr(info, files[path])
    return buffer.getvalue()


def write_package(files: dict[str, bytes], output: Path, *, overwrite: bool = False) -> Path:
    """Write to a folder, or to a zip file when ``output`` ends in ``.zip``; an existing
    file, or a folder that is not empty, is refused (nothing is overwritten). Written
    through ``granudb.output_files``: all or nothing, no symbolic link followed."""
    if not output.parent.is_dir():
        raise ValidationError("--output", str(output), "is in a folder that does not exist")
    if output.suffix.lower() == ".zip":
        if (output.exists() or output.is_symlink()) and not overwrite:
            raise ConflictError(f"--output: {output} exists (remove it or choose another)")
        return write_bytes(output, _zip_bytes(files), replace=overwrite, field="--output")
    if output.is_symlink() or output.is_file():
        raise ConflictError(f"--output: {output} exists and is not a folder (choose another)")
    if output.is_dir() and any(output.iterdir()) and not overwrite:
        raise ConflictError(f"--output: folder {output} is not empty (choose an empty one)")
    return write_folder(output, files, replace=overwrite, field="--output")
