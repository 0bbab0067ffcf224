"""Validate and import a Data Package made by granudb (or by anyone following its schema).

Nothing from a package is trusted: ``granudb.io.package_files`` opens it (zip entries
checked before extraction, the descriptor bounded and free of duplicate keys); here every
resource's bytes and sha256 must match the descriptor, every field must be one granudb
knows with the unit granudb stores, every value must pass the database's rules, and every
name and text the same rules as on the command line and in CSV files
(``granudb.vocabulary.text``). Validation collects every problem it finds; import refuses
on any, before the database is touched.

Storing (the merge of materials, fluids and sources by name, and the insert of the runs)
is ``granudb.db.package_store``: one transaction, so a refusal leaves the database as it
was.

Content hash: it is computed over the names the collisions' rows carry. Import checks the
declared ``granudb:content_hash`` against the package's own rows, as written; the hash
stored (and shown by ``dataset show``, and declared by the next export) is over the names
the rows have in this database. They are equal unless a material or fluid was matched
under a name differing in case, or renamed by ``--rename-conflicts``: import then says so.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from granudb.db.content_hash import hash_frame
from granudb.db.package_store import MergeConflict, PackageContent, store_package
from granudb.errors import ValidationError
from granudb.io.collision_file import MAX_RESTITUTION, MAX_SPEED_M_S, SPEEDS
from granudb.io.package_files import (
    MAX_RESOURCE_BYTES,
    PackageError,
    package_root,
    read_descriptor,
    safe_relative,
    sha256,
)
from granudb.io.package_schema import FOREIGN_KEYS, PRIMARY_KEYS, RESOURCES, check_schema, columns
from granudb.io.tables import TINY_RULE, underflows
from granudb.lazy import numpy as np
from granudb.lazy import pandas as pd
from granudb.vocabulary.rules import RULES
from granudb.vocabulary.text import check_name, check_text, name_key

__all__ = ["PackageError", "Validated", "import_package", "validate_package"]

#: Resources whose names granudb matches case-insensitively (``name_key``): two rows
#: whose names differ only in case would be one material or fluid.
CASE_INSENSITIVE = ("materials", "fluids")

MAX_ROWS = 20_000_000
MAX_CELL_CHARS = 10_000
REQUIRED_RESOURCES = {"collisions", "materials", "fluids", "sources"}
SHOWN_PER_PROBLEM = 5
#: Columns holding names (single-line, no padding) and their longest allowed length; other
#: string columns are free text (line breaks allowed) up to ``MAX_CELL_CHARS`` or the
#: length given here (the database's column width).
NAME_COLUMNS = {
    "key": 100,
    "name": 200,
    "fluid": 200,
    "run": 200,
    "particle": 200,
    "wall": 200,
    "source": 100,
    "density_source": 100,
    "pressure_viscosity_source": 100,
}
TEXT_LENGTHS = {
    "doi": 200,
    "url": 500,
    "kind": 40,
    "source_locator": 200,
    "density_locator": 200,
    "pressure_viscosity_locator": 200,
}


@dataclass
class Validated:
    """A package that passed validation: its descriptor and SI tables (pandas frames)."""

    descriptor: dict[str, Any]
    tables: dict[str, Any]
    problems: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not self.problems


def _rows(mask: Any) -> str:
    index = np.flatnonzero(np.asarray(mask)) + 2  # spreadsheet rows: header is row 1
    shown = ", ".join(str(i) for i in index[:SHOWN_PER_PROBLEM])
    more = f" and {len(index) - SHOWN_PER_PROBLEM} more" if len(index) > SHOWN_PER_PROBLEM else ""
    return f"row{'s' if len(index) > 1 else ''} {shown}{more}"


def _read_table(name: str, path: Path, problems: list[str]) -> Any:
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
    except OSError as exc:
        problems.append(f"{name}: {path.name} cannot be read ({exc.strerror or exc})")
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
        # Text is kept byte for byte (a note of one space stays one space); only a
        # number column treats surrounding spaces as nothing.
        empty = raw == "" if kind == "string" else raw.str.strip() == ""
        if required and empty.any():
            problems.append(f"{name}.{column}: empty in {_rows(empty)} (required)")
        if kind == "string":
            _check_strings(name, column, raw, problems)
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
        numbers = values.to_numpy(dtype=float)
        tiny = underflows(numbers, numbers)
        if tiny.any():
            problems.append(f"{name}.{column}: {TINY_RULE} — in {_rows(tiny)}")
        if name == "collisions" and column in SPEEDS:
            with np.errstate(invalid="ignore"):
                fast = np.abs(numbers) > MAX_SPEED_M_S
            if fast.any():
                problems.append(
                    f"{name}.{column}: faster than {MAX_SPEED_M_S:g} m/s (beyond any impact "
                    f"apparatus) in {_rows(fast)}"
                )
        out[column] = values
    key = PRIMARY_KEYS[name]
    duplicated = frame.duplicated(subset=key, keep="first")
    if duplicated.any():
        problems.append(f"{name}: duplicate {'+'.join(key)} in {_rows(duplicated)}")
    elif name in CASE_INSENSITIVE:
        keys = frame[key[0]].map(lambda n: name_key(n) if isinstance(n, str) else n)
        twins = keys.duplicated(keep=False) & frame[key[0]].notna()
        if twins.any():
            shown = ", ".join(repr(n) for n in frame[key[0]][twins].iloc[:4])
            problems.append(
                f"{name}.{key[0]}: {shown} differ only in case or spacing (names match "
                f"case-insensitively) in {_rows(twins)}"
            )
    return out


def _check_references(tables: dict[str, Any], problems: list[str]) -> None:
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


def _check_strings(name: str, column: str, raw: Any, problems: list[str]) -> None:
    """Apply the shared name or text rule to each distinct non-empty value of a column."""
    limit = NAME_COLUMNS.get(column)
    for value in raw[raw != ""].unique():
        try:
            if limit is not None:
                check_name(column, value, max_length=limit)
            else:
                check_text(column, value, max_length=TEXT_LENGTHS.get(column, MAX_CELL_CHARS))
        except ValidationError as exc:
            shown = exc.value if len(str(exc.value)) <= 60 else str(exc.value)[:60] + "…"
            problems.append(f"{name}.{column}: {shown} {exc.rule} in {_rows(raw == value)}")
            return


def _resource_file(
    root: Path, name: str, resource: dict[str, Any], problems: list[str]
) -> Path | None:
    """The checked file of one resource (inside the package, size and hash as declared)."""
    if "data" in resource:
        problems.append(f"{name}: inline 'data' is not accepted; use a CSV file")
        return None
    relative = safe_relative(resource.get("path"))
    if relative is None:
        problems.append(
            f"{name}: path {str(resource.get('path'))[:80]!r} is not a relative path "
            "inside the package (no absolute paths, '..' or URLs)"
        )
        return None
    file = (root / relative).resolve()
    if not file.is_relative_to(root.resolve()) or not file.is_file():
        problems.append(f"{name}: file {relative} is not in the package")
        return None
    try:
        size, digest = sha256(file)
    except OSError as exc:
        problems.append(f"{name}: {relative} cannot be read ({exc.strerror or exc})")
        return None
    if size > MAX_RESOURCE_BYTES:
        problems.append(f"{name}: {size} bytes, more than {MAX_RESOURCE_BYTES}")
        return None
    declared_size = resource.get("bytes")
    if "bytes" in resource and (type(declared_size) is not int):
        problems.append(
            f"{name}: bytes must be a whole number (Table Schema), not "
            f"{type(declared_size).__name__} {str(declared_size)[:30]!r}"
        )
    elif "bytes" in resource and declared_size != size:
        problems.append(f"{name}: {size} bytes, the descriptor says {declared_size}")
    declared = resource.get("hash")
    if declared is None:
        problems.append(f"{name}: no sha256 hash in the descriptor")
    elif str(declared).removeprefix("sha256:") != digest:
        problems.append(
            f"{name}: sha256 {digest[:12]}… does not match the descriptor's "
            f"{str(declared).removeprefix('sha256:')[:12]}…"
        )
    return file


def _resources(descriptor: dict[str, Any], problems: list[str]) -> dict[str, dict[str, Any]]:
    by_name: dict[str, dict[str, Any]] = {}
    for resource in descriptor["resources"]:
        if not isinstance(resource, dict) or not isinstance(resource.get("name"), str):
            problems.append("datapackage.json: a resource has no name")
            continue
        if resource["name"] in by_name:
            problems.append(f"{resource['name'][:80]}: resource name used twice")
        by_name[resource["name"]] = resource
    for missing in sorted(REQUIRED_RESOURCES - set(by_name)):
        problems.append(f"{missing}: resource is missing")
    for name in list(by_name):
        if name not in RESOURCES:
            problems.append(
                f"{name[:80]!r}: is not a resource granudb knows (known: {', '.join(RESOURCES)})"
            )
            del by_name[name]
    return by_name


def _check_metadata(descriptor: dict[str, Any], problems: list[str]) -> None:
    """The descriptor's dataset name, version, title, description obey the shared rules."""
    checks = [
        ("datapackage.json: granudb:dataset", descriptor.get("granudb:dataset"), 200, True),
        ("datapackage.json: name", descriptor.get("name"), 200, True),
        ("datapackage.json: version", descriptor.get("version"), 50, True),
        ("datapackage.json: title", descriptor.get("title"), MAX_CELL_CHARS, False),
        ("datapackage.json: description", descriptor.get("description"), MAX_CELL_CHARS, False),
    ]
    for where, value, limit, is_name in checks:
        if value is None:
            continue
        if not isinstance(value, str):
            problems.append(f"{where}: must be a string, not {type(value).__name__}")
            continue
        try:
            check_name(where, value, max_length=limit) if is_name else check_text(
                where, value, max_length=limit
            )
        except ValidationError as exc:
            problems.append(str(exc))
    if not isinstance(descriptor.get("granudb:dataset") or descriptor.get("name"), str):
        problems.append("datapackage.json: needs a dataset name ('name')")


def validate_root(root: Path) -> Validated:
    """Validate an unpacked package folder; never raises for data problems."""
    descriptor = read_descriptor(root)
    problems: list[str] = []
    tables: dict[str, Any] = {}
    for name, resource in _resources(descriptor, problems).items():
        file = _resource_file(root, name, resource, problems)
        if file is None:
            continue
        check_schema(name, resource, problems)
        tables[name] = _read_table(name, file, problems)
    if "fluid_points" not in tables:
        tables["fluid_points"] = pd.DataFrame({c: [] for c in columns("fluid_points")})
    _check_references(tables, problems)
    _check_restitution(tables, problems)
    _check_metadata(descriptor, problems)
    return Validated(descriptor, tables, problems)


def validate_package(path: Path) -> Validated:
    """Validate a package folder, ``datapackage.json`` or zip; problems are collected."""
    with package_root(path) as root:
        return validate_root(root)


def _license(descriptor: dict[str, Any]) -> str | None:
    licenses = descriptor.get("licenses")
    if not isinstance(licenses, list) or not licenses or not isinstance(licenses[0], dict):
        return None
    value = licenses[0].get("name") or licenses[0].get("title")
    return str(value)[:200] if isinstance(value, str) and value.strip() else None


def _content(validated: Validated, as_name: str | None) -> Any:
    descriptor = validated.descriptor
    name = as_name or descriptor.get("granudb:dataset") or descriptor["name"]
    package_id = descriptor.get("id")
    doi = None
    if isinstance(package_id, str) and package_id.startswith("https://doi.org/"):
        doi = package_id.removeprefix("https://doi.org/")[:200]
    text = {k: v if isinstance(v, str) else None for k, v in descriptor.items()}
    return PackageContent(
        dataset=name,
        version=str(descriptor.get("version") or "1.0.0"),
        package=str(descriptor.get("name") or name),
        title=text.get("title"),
        description=text.get("description"),
        license=_license(descriptor),
        doi=doi,
        tables=validated.tables,
    )


def import_package(
    database: Any, path: Path, *, as_name: str | None = None, rename_conflicts: bool = False
) -> Any:
    """Validate ``path`` and store it (``granudb.db.package_store``, one transaction);
    raise ``PackageError`` naming every problem or conflict, changing nothing, otherwise.

    Returns a ``PackageImport``; its ``declared_hash`` is the package's content hash."""
    if as_name is not None:
        check_name("--as", as_name)
    validated = validate_package(path)
    if validated.problems:
        raise PackageError(validated.problems, hint="; `granudb dataset validate` lists them")
    declared = validated.descriptor.get("granudb:content_hash")
    if declared is not None:
        computed = hash_frame(validated.tables["collisions"])
        if declared != computed:
            raise PackageError(
                [
                    f"content hash: computed {computed[:16]}…, the package declares "
                    f"{str(declared)[:16]}…; the collisions changed"
                ]
            )
    try:
        result = store_package(
            database, _content(validated, as_name), rename_conflicts=rename_conflicts
        )
    except MergeConflict as exc:
        hint = (
            "conflicting names are not overwritten; import with --rename-conflicts to bring "
            "them in under new names"
        )
        raise PackageError([*exc.conflicts, hint], hint="") from None
    result.declared_hash = declared
    return result
