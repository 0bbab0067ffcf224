"""Validate and import a Data Package made by granudb (or by anyone following its schema).

Nothing from a package is trusted: paths must stay inside the package (no absolute paths,
no ``..``, no URLs; zip entries are checked before anything is extracted), files and rows
are size-limited, every resource's bytes and sha256 must match the descriptor, every field
must be one granudb knows with the unit granudb stores, and every value must pass the
database's rules. Validation collects every problem it finds; import refuses on any.

Import merges materials, fluids and sources by name: identical rows are reused; a row with
the same name but different values is a conflict, reported field by field, and is only
resolved by ``rename_conflicts`` (the package's row is imported under a new name). The
whole import is one transaction, so a refusal leaves the database exactly as it was.
"""

from __future__ import annotations

import hashlib
import json
import math
import re
import shutil
import stat
import tempfile
import zipfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from typing import Any

from granudb.errors import GranudbError
from granudb.io.package_schema import PRIMARY_KEYS, RESOURCES, columns
from granudb.vocabulary import term
from granudb.vocabulary.rules import RULES

MAX_DESCRIPTOR_BYTES = 1_000_000
MAX_RESOURCE_BYTES = 2_000_000_000
MAX_PACKAGE_BYTES = 4_000_000_000
MAX_ZIP_ENTRIES = 100
MAX_COMPRESSION_RATIO = 200  # a zip bomb expands thousands of times
MAX_ROWS = 20_000_000
MAX_CELL_CHARS = 10_000
REQUIRED_RESOURCES = {"collisions", "materials", "fluids", "sources"}
SHOWN_PER_PROBLEM = 5


class PackageError(GranudbError):
    """The package fails validation; ``problems`` lists every problem found."""

    def __init__(self, problems: list[str]) -> None:
        self.problems = problems
        first = problems[0] if problems else "unknown problem"
        more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
        super().__init__(f"package: {first}{more}; nothing was imported")


@dataclass
class Validated:
    """A package that passed validation: its descriptor and SI tables (pandas frames)."""

    descriptor: dict[str, Any]
    tables: dict[str, Any]
    problems: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not self.problems


# --- files -----------------------------------------------------------------------------


def _safe_relative(path: object) -> PurePosixPath | None:
    """A resource path as a safe relative path, or None when it may escape the package."""
    if not isinstance(path, str) or not path or len(path) > 500:
        return None
    if "://" in path or path.startswith(("/", "\\", "~")) or "\\" in path or ":" in path:
        return None
    pure = PurePosixPath(path)
    if any(part in {"..", ""} for part in pure.parts) or "\x00" in path:
        return None
    return pure


def _check_zip(archive: zipfile.ZipFile) -> None:
    entries = archive.infolist()
    if len(entries) > MAX_ZIP_ENTRIES:
        raise PackageError([f"zip: {len(entries)} entries, more than {MAX_ZIP_ENTRIES}"])
    total = 0
    for entry in entries:
        if _safe_relative(entry.filename.rstrip("/")) is None:
            raise PackageError(
                [f"zip: entry {entry.filename!r} would be written outside the package folder"]
            )
        mode = entry.external_attr >> 16
        if stat.S_ISLNK(mode):
            raise PackageError([f"zip: entry {entry.filename!r} is a symbolic link"])
        if entry.file_size > MAX_RESOURCE_BYTES:
            raise PackageError(
                [
                    f"zip: entry {entry.filename!r} is {entry.file_size} bytes, "
                    f"more than {MAX_RESOURCE_BYTES}"
                ]
            )
        if entry.compress_size and entry.file_size / entry.compress_size > MAX_COMPRESSION_RATIO:
            raise PackageError(
                [
                    f"zip: entry {entry.filename!r} expands "
                    f"{entry.file_size // entry.compress_size}×: refused as a "
                    "possible zip bomb"
                ]
            )
        total += entry.file_size
    if total > MAX_PACKAGE_BYTES:
        raise PackageError([f"zip: expands to {total} bytes, more than {MAX_PACKAGE_BYTES}"])


@contextmanager
def package_root(path: Path) -> Iterator[Path]:
    """The folder holding ``datapackage.json``: the folder itself, or a checked zip
    extracted into a temporary folder (removed afterwards)."""
    path = Path(path)
    if path.is_dir():
        yield path
        return
    if path.name == "datapackage.json" and path.is_file():
        yield path.parent
        return
    if not path.exists():
        raise PackageError([f"{path} does not exist"])
    if not zipfile.is_zipfile(path):
        raise PackageError([f"{path} is not a folder, a datapackage.json or a zip file"])
    folder = Path(tempfile.mkdtemp(prefix="granudb-package-"))
    try:
        with zipfile.ZipFile(path) as archive:
            _check_zip(archive)
            for entry in archive.infolist():
                target = folder / entry.filename
                if entry.is_dir():
                    target.mkdir(parents=True, exist_ok=True)
                    continue
                target.parent.mkdir(parents=True, exist_ok=True)
                written = 0
                with archive.open(entry) as source, target.open("wb") as sink:
                    while chunk := source.read(1 << 20):
                        written += len(chunk)
                        if written > entry.file_size:  # the header lied about the size
                            raise PackageError(
                                [f"zip: entry {entry.filename!r} is larger than its header says"]
                            )
                        sink.write(chunk)
        yield folder
    except zipfile.BadZipFile as exc:
        raise PackageError([f"zip: {path} is damaged ({exc})"]) from None
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def _sha256(path: Path) -> tuple[int, str]:
    digest = hashlib.sha256()
    size = 0
    with path.open("rb") as handle:
        while chunk := handle.read(1 << 20):
            size += len(chunk)
            digest.update(chunk)
    return size, digest.hexdigest()


# --- validation ------------------------------------------------------------------------


def _read_descriptor(root: Path) -> dict[str, Any]:
    path = root / "datapackage.json"
    if not path.is_file():
        raise PackageError(["datapackage.json: not found at the top of the package"])
    if path.stat().st_size > MAX_DESCRIPTOR_BYTES:
        raise PackageError([f"datapackage.json: larger than {MAX_DESCRIPTOR_BYTES} bytes"])
    try:
        descriptor = json.loads(path.read_text(encoding="utf-8"))
    except UnicodeDecodeError:
        raise PackageError(["datapackage.json: is not UTF-8 text"]) from None
    except json.JSONDecodeError as exc:
        raise PackageError(
            [f"datapackage.json: is not valid JSON ({exc.msg} at line {exc.lineno})"]
        ) from None
    if not isinstance(descriptor, dict) or not isinstance(descriptor.get("resources"), list):
        raise PackageError(["datapackage.json: needs a 'resources' list"])
    return descriptor


def _same_unit(declared: str, expected: str) -> bool:
    from granudb.io.units import check_unit_expression, registry

    try:
        spelled = check_unit_expression(declared)  # bounded cost: m**(9**9**9) never reaches Pint
        ureg = registry()
        factor = ureg.Quantity(1.0, spelled).to(expected).magnitude
        offset = ureg.Quantity(0.0, spelled).to(expected).magnitude
    except Exception:  # noqa: BLE001 - any Pint failure means "not the same unit"
        return False
    return math.isclose(factor - offset, 1.0, rel_tol=1e-12) and abs(offset) < 1e-12


def _check_schema(name: str, resource: dict[str, Any], problems: list[str]) -> None:
    schema = resource.get("schema")
    if not isinstance(schema, dict) or not isinstance(schema.get("fields"), list):
        problems.append(f"{name}: has no Table Schema with fields")
        return
    expected = {n: (kind, required) for n, kind, required in RESOURCES[name]}
    seen = set()
    for entry in schema["fields"]:
        if not isinstance(entry, dict) or not isinstance(entry.get("name"), str):
            problems.append(f"{name}: a schema field has no name")
            continue
        field_name = entry["name"]
        seen.add(field_name)
        if field_name not in expected:
            problems.append(
                f"{name}.{field_name}: is not a field granudb knows (known: {', '.join(expected)})"
            )
            continue
        unit = term(field_name).unit
        declared = entry.get("unit")
        if declared is not None and unit is not None and not _same_unit(str(declared), unit):
            problems.append(
                f"{name}.{field_name}: unit {declared!r} is not {unit!r}, the SI "
                "unit this column holds"
            )
        if declared is not None and unit is None and str(declared) not in {"", "1", "-"}:
            problems.append(f"{name}.{field_name}: unit {declared!r} on a column without unit")
    for field_name, (_, required) in expected.items():
        if required and field_name not in seen:
            problems.append(f"{name}.{field_name}: required field is missing from the schema")


def _rows(mask: Any) -> str:
    import numpy as np

    index = np.flatnonzero(np.asarray(mask)) + 2  # spreadsheet rows: header is row 1
    shown = ", ".join(str(i) for i in index[:SHOWN_PER_PROBLEM])
    more = f" and {len(index) - SHOWN_PER_PROBLEM} more" if len(index) > SHOWN_PER_PROBLEM else ""
    return f"row{'s' if len(index) > 1 else ''} {shown}{more}"


def _read_table(name: str, path: Path, problems: list[str]) -> Any:
    import numpy as np
    import pandas as pd

    try:
        frame = pd.read_csv(
            path,
            dtype=str,
            keep_default_na=False,
            encoding="utf-8",
            na_filter=False,
            on_bad_lines="error",
            nrows=MAX_ROWS + 1,
        )
    except UnicodeDecodeError:
        problems.append(f"{name}: {path.name} is not UTF-8 text")
        return None
    except (pd.errors.ParserError, pd.errors.EmptyDataError, ValueError) as exc:
        problems.append(f"{name}: {path.name} cannot be read as CSV ({str(exc).splitlines()[0]})")
        return None
    if len(frame) > MAX_ROWS:
        problems.append(f"{name}: more than {MAX_ROWS} rows")
        return None
    expected = columns(name)
    if list(frame.columns) != expected:
        missing = [c for c in expected if c not in frame.columns]
        extra = [c for c in frame.columns if c not in expected]
        detail = "; ".join(
            filter(
                None,
                [
                    f"missing {', '.join(missing)}" if missing else "",
                    f"unknown {', '.join(map(str, extra))}" if extra else "",
                    "columns out of order" if not missing and not extra else "",
                ],
            )
        )
        problems.append(f"{name}: header does not match the schema ({detail})")
        return None
    out = pd.DataFrame(index=frame.index)
    for column, kind, required in RESOURCES[name]:
        raw = frame[column]
        empty = raw.str.strip() == ""
        if required and empty.any():
            problems.append(f"{name}.{column}: empty in {_rows(empty)} (required)")
        if kind == "string":
            too_long = raw.str.len() > MAX_CELL_CHARS
            if too_long.any():
                problems.append(
                    f"{name}.{column}: longer than {MAX_CELL_CHARS} characters in {_rows(too_long)}"
                )
            control = raw.str.contains(r"[\x00-\x08\x0b\x0c\x0e-\x1f]", regex=True)
            if control.any():
                problems.append(f"{name}.{column}: control characters in {_rows(control)}")
            out[column] = raw.where(~empty, None)
            continue
        values = pd.to_numeric(raw.where(~empty, None), errors="coerce")
        not_number = ~empty & values.isna()
        if not_number.any():
            problems.append(f"{name}.{column}: not a number in {_rows(not_number)}")
        if kind == "integer":
            fractional = values.notna() & (values != np.floor(values))
            if fractional.any():
                problems.append(f"{name}.{column}: not an integer in {_rows(fractional)}")
        rule = RULES.get(column)
        if rule is not None:
            broken = values.notna() & ~rule.holds_array(values.to_numpy(dtype=float))
            if broken.any():
                problems.append(f"{name}.{column}: {rule.text} — broken in {_rows(broken)}")
        infinite = values.notna() & ~np.isfinite(values.to_numpy(dtype=float))
        if infinite.any() and rule is None:
            problems.append(f"{name}.{column}: not finite in {_rows(infinite)}")
        out[column] = values
    key = PRIMARY_KEYS[name]
    duplicated = frame.duplicated(subset=key, keep="first")
    if duplicated.any():
        problems.append(f"{name}: duplicate {'+'.join(key)} in {_rows(duplicated)}")
    return out


def _check_references(tables: dict[str, Any], problems: list[str]) -> None:
    from granudb.io.package_schema import FOREIGN_KEYS

    for name, keys in FOREIGN_KEYS.items():
        frame = tables.get(name)
        if frame is None:
            continue
        for column, other, there in keys:
            target = tables.get(other)
            if target is None:
                continue
            known = set(target[there].dropna())
            values = frame[column]
            dangling = values.notna() & ~values.isin(known)
            if dangling.any():
                first = values[dangling].iloc[0]
                problems.append(
                    f"{name}.{column}: {first!r} (in {_rows(dangling)}) is not a {there} in {other}"
                )


def _check_restitution(tables: dict[str, Any], problems: list[str]) -> None:
    from granudb.io.collisions_csv import MAX_RESTITUTION

    frame = tables.get("collisions")
    if frame is None:
        return
    e = frame["v_n_out_m_s"] / frame["v_n_in_m_s"]
    too_high = e > MAX_RESTITUTION
    if too_high.any():
        problems.append(
            f"collisions: v_n_out_m_s / v_n_in_m_s above {MAX_RESTITUTION} "
            f"(energy from nowhere) in {_rows(too_high)}"
        )


def validate_root(root: Path) -> Validated:
    """Validate an unpacked package folder; never raises for data problems."""
    descriptor = _read_descriptor(root)
    problems: list[str] = []
    tables: dict[str, Any] = {}
    by_name: dict[str, dict[str, Any]] = {}
    for resource in descriptor["resources"]:
        if not isinstance(resource, dict) or not isinstance(resource.get("name"), str):
            problems.append("datapackage.json: a resource has no name")
            continue
        if resource["name"] in by_name:
            problems.append(f"{resource['name']}: resource name used twice")
        by_name[resource["name"]] = resource
    for missing in sorted(REQUIRED_RESOURCES - set(by_name)):
        problems.append(f"{missing}: resource is missing")
    for name, resource in by_name.items():
        if name not in RESOURCES:
            problems.append(
                f"{name}: is not a resource granudb knows (known: {', '.join(RESOURCES)})"
            )
            continue
        if "data" in resource:
            problems.append(f"{name}: inline 'data' is not accepted; use a CSV file")
            continue
        relative = _safe_relative(resource.get("path"))
        if relative is None:
            problems.append(
                f"{name}: path {resource.get('path')!r} is not a relative path "
                "inside the package (no absolute paths, '..' or URLs)"
            )
            continue
        file = (root / relative).resolve()
        if not file.is_relative_to(root.resolve()) or not file.is_file():
            problems.append(f"{name}: file {relative} is not in the package")
            continue
        size, digest = _sha256(file)
        if size > MAX_RESOURCE_BYTES:
            problems.append(f"{name}: {size} bytes, more than {MAX_RESOURCE_BYTES}")
            continue
        if "bytes" in resource and resource["bytes"] != size:
            problems.append(f"{name}: {size} bytes, the descriptor says {resource['bytes']}")
        declared = resource.get("hash")
        if declared is None:
            problems.append(f"{name}: no sha256 hash in the descriptor")
        elif str(declared).removeprefix("sha256:") != digest:
            problems.append(
                f"{name}: sha256 {digest[:12]}… does not match the descriptor's "
                f"{str(declared).removeprefix('sha256:')[:12]}…"
            )
        _check_schema(name, resource, problems)
        tables[name] = _read_table(name, file, problems)
    if "fluid_points" not in tables:
        import pandas as pd

        tables["fluid_points"] = pd.DataFrame({c: [] for c in columns("fluid_points")})
    _check_references(tables, problems)
    _check_restitution(tables, problems)
    version = descriptor.get("version")
    if version is not None and (
        not isinstance(version, str) or not version.strip() or len(version) > 50
    ):
        problems.append(f"datapackage.json: version {version!r} must be a short string")
    name = descriptor.get("granudb:dataset") or descriptor.get("name")
    if not isinstance(name, str) or not name.strip() or len(name) > 200:
        problems.append("datapackage.json: needs a dataset name ('name')")
    return Validated(descriptor, tables, problems)


def validate_package(path: Path) -> Validated:
    """Validate a package folder, ``datapackage.json`` or zip; problems are collected."""
    with package_root(path) as root:
        return validate_root(root)


NAME_PATTERN = re.compile(r"^[^\x00-\x1f]{1,200}$")


# --- import ----------------------------------------------------------------------------


@dataclass
class PackageImport:
    dataset: str
    version: str
    rows: int
    content_hash: str
    reused: list[str] = field(default_factory=list)
    added: list[str] = field(default_factory=list)
    renamed: list[str] = field(default_factory=list)


def _record(frame: Any) -> list[dict[str, Any]]:
    """Rows of a validated frame as dicts with None for missing values."""
    records = frame.to_dict("records")
    return [
        {k: (None if isinstance(v, float) and math.isnan(v) else v) for k, v in r.items()}
        for r in records
    ]


def _differences(existing: dict[str, Any], incoming: dict[str, Any]) -> list[str]:
    from granudb.db.upsert import same_value

    return [
        f"{k}: {existing.get(k)!r} here, {v!r} in the package"
        for k, v in incoming.items()
        if not same_value(existing.get(k), v)
    ]


class _Merger:
    """Matches the package's sources, materials and fluids against the database."""

    def __init__(self, session: Any, package: str, rename_conflicts: bool) -> None:
        self.session = session
        self.package = package
        self.rename = rename_conflicts
        self.conflicts: list[str] = []
        self.result = PackageImport("", "", 0, "")
        self.source_ids: dict[str, int] = {}
        self.material_ids: dict[str, int] = {}
        self.fluid_ids: dict[str, int] = {}

    def _renamed(self, model: type, name: str) -> str:
        from sqlalchemy import select

        from granudb.db.models import name_key

        candidate = f"{name} ({self.package})"
        number = 2
        while (
            self.session.scalars(select(model.id).filter_by(name_key=name_key(candidate))).first()
            is not None
        ):
            candidate = f"{name} ({self.package} {number})"
            number += 1
        return candidate

    def sources(self, rows: list[dict[str, Any]]) -> None:
        from sqlalchemy import select

        from granudb.db.models import Source
        from granudb.db.sources import source_record

        for row in rows:
            existing = self.session.scalars(select(Source).filter_by(key=row["key"])).first()
            values = {**row, "year": None if row["year"] is None else int(row["year"])}
            if existing is None:
                source = Source(**values)
                self.session.add(source)
                self.session.flush()
                self.source_ids[row["key"]] = source.id
                self.result.added.append(f"source {row['key']}")
                continue
            diffs = _differences(source_record(existing), values)
            if diffs:
                self.conflicts.append(f"source {row['key']}: " + "; ".join(diffs))
            self.source_ids[row["key"]] = existing.id

    def _source(self, key: str | None) -> int | None:
        return None if key is None else self.source_ids[key]

    def named(
        self,
        kind: str,
        model: type,
        rows: list[dict[str, Any]],
        references: dict[str, str],
        points: dict[str, list[dict[str, Any]]] | None,
    ) -> dict[str, int]:
        from sqlalchemy import select

        from granudb.db.models import FluidPoint, name_key

        ids: dict[str, int] = {}
        for row in rows:
            name = row["name"]
            values = {k: v for k, v in row.items() if k not in references and k != "name"}
            for column, id_column in references.items():
                values[id_column] = self._source(row[column])
            own_points = (points or {}).get(name, [])
            existing = self.session.scalars(
                select(model).filter_by(name_key=name_key(name))
            ).first()
            if existing is not None:
                current = {k: getattr(existing, k) for k in values}
                diffs = _differences(current, values)
                if points is not None:
                    here = sorted(
                        (p.temperature_c, p.viscosity_pa_s, p.density_kg_m3)
                        for p in existing.points
                    )
                    there = sorted(
                        (p["temperature_c"], p["viscosity_pa_s"], p["density_kg_m3"])
                        for p in own_points
                    )
                    if len(here) != len(there) or any(
                        _differences(dict(enumerate(a)), dict(enumerate(b)))
                        for a, b in zip(here, there, strict=False)
                    ):
                        diffs.append(
                            f"viscosity points: {len(here)} here, {len(there)} in "
                            "the package, with different values"
                        )
                if not diffs:
                    ids[name] = existing.id
                    self.result.reused.append(f"{kind} {existing.name}")
                    continue
                if not self.rename:
                    self.conflicts.append(f"{kind} {name}: " + "; ".join(diffs))
                    continue
                new_name = self._renamed(model, name)
                self.result.renamed.append(f"{kind} {name} → {new_name}")
            else:
                new_name = name
                self.result.added.append(f"{kind} {name}")
            row_object = model(name=new_name, name_key=name_key(new_name), **values)
            self.session.add(row_object)
            self.session.flush()
            for point in own_points:
                self.session.add(
                    FluidPoint(
                        fluid_id=row_object.id,
                        temperature_c=point["temperature_c"],
                        viscosity_pa_s=point["viscosity_pa_s"],
                        density_kg_m3=point["density_kg_m3"],
                        source_id=self._source(point["source"]),
                        source_locator=point["source_locator"],
                    )
                )
            ids[name] = row_object.id
        return ids


def import_package(
    database: Any, path: Path, *, as_name: str | None = None, rename_conflicts: bool = False
) -> PackageImport:
    """Validate ``path`` and import it in one transaction; raise ``PackageError`` listing
    every problem or conflict (and change nothing) otherwise."""
    from sqlalchemy import select

    from granudb.db import datasets
    from granudb.db.collision_store import insert_collisions
    from granudb.db.models import Dataset, Fluid, Material

    validated = validate_package(path)
    if validated.problems:
        raise PackageError(validated.problems)
    descriptor, tables = validated.descriptor, validated.tables
    name = as_name or descriptor.get("granudb:dataset") or descriptor["name"]
    version = str(descriptor.get("version") or "1.0.0")
    with database.session(write=True) as session:
        if session.scalars(select(Dataset).filter_by(name=name, version=version)).first():
            raise PackageError(
                [
                    f"dataset {name} {version} already exists (use --as NAME, or "
                    "export a new version)"
                ]
            )
        merger = _Merger(session, str(descriptor.get("name") or name), rename_conflicts)
        merger.sources(_record(tables["sources"]))
        materials = merger.named(
            "material", Material, _record(tables["materials"]), {"source": "source_id"}, None
        )
        points: dict[str, list[dict[str, Any]]] = {}
        for point in _record(tables["fluid_points"]):
            points.setdefault(point["fluid"], []).append(point)
        fluids = merger.named(
            "fluid",
            Fluid,
            _record(tables["fluids"]),
            {
                "source": "source_id",
                "density_source": "density_source_id",
                "pressure_viscosity_source": "pressure_viscosity_source_id",
            },
            points,
        )
        if merger.conflicts:
            raise PackageError(
                merger.conflicts
                + [
                    "conflicting names are not overwritten; import with --rename-conflicts to "
                    "bring them in under new names"
                ]
            )
        licenses = descriptor.get("licenses") or []
        dataset = Dataset(
            name=name,
            version=version,
            title=descriptor.get("title") if isinstance(descriptor.get("title"), str) else None,
            description=descriptor.get("description")
            if isinstance(descriptor.get("description"), str)
            else None,
            license=str(licenses[0].get("name"))[:200]
            if licenses and isinstance(licenses[0], dict) and licenses[0].get("name")
            else None,
        )
        package_id = descriptor.get("id")
        if isinstance(package_id, str) and package_id.startswith("https://doi.org/"):
            dataset.doi = package_id.removeprefix("https://doi.org/")[:200]
        session.add(dataset)
        session.flush()
        declared = descriptor.get("granudb:content_hash")
        if declared is not None:
            computed = datasets.hash_frame(tables["collisions"])
            if declared != computed:
                raise PackageError(
                    [
                        f"content hash: computed {computed[:16]}…, the package "
                        f"declares {str(declared)[:16]}…; the collisions changed"
                    ]
                )
        frame = tables["collisions"].copy()
        frame["particle_id"] = frame.pop("particle").map(materials)
        frame["wall_id"] = frame.pop("wall").map(materials)
        frame["fluid_id"] = frame.pop("fluid").map(fluids)
        rows = insert_collisions(session, dataset.id, frame)
        content_hash = datasets.update_content_hash(session, dataset)
        merger.result.dataset, merger.result.version = name, version
        merger.result.rows, merger.result.content_hash = rows, content_hash
        return merger.result
