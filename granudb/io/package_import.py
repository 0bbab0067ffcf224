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

import csv
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from granudb.db.package_store import HashMismatch, MergeConflict, PackageContent, store_package
from granudb.errors import ValidationError
from granudb.io import reference_library
from granudb.io.collision_file import MAX_RESTITUTION, MAX_SPEED_M_S, SPEEDS
from granudb.io.package_dataset import dataset_record
from granudb.io.package_files import (
    MAX_RESOURCE_BYTES,
    PackageError,
    package_root,
    read_descriptor,
    safe_relative,
    sha256,
)
from granudb.io.package_schema import (
    FOREIGN_KEYS,
    OPTIONAL_COLUMNS,
    PRIMARY_KEYS,
    RESOURCES,
    check_schema,
    columns,
)
from granudb.io.tables import MAX_HEADER_BYTES, MAX_HEADERS, TINY_RULE, Problems, underflows
from granudb.lazy import numpy as np
from granudb.lazy import pandas as pd
from granudb.vocabulary.catalog import MATERIALS, ONE_LINE_TEXTS, check_source
from granudb.vocabulary.rules import RULES
from granudb.vocabulary.text import check_name, check_text, name_key

__all__ = ["PackageError", "Validated", "import_package", "validate_package"]

#: Resources whose names granudb matches case-insensitively (``name_key``): two rows
#: whose names differ only in case would be one material or fluid.
CASE_INSENSITIVE = ("materials", "fluids")

MAX_ROWS = 20_000_000
MAX_CELL_CHARS = 10_000
#: Rows checked at a time: a block of text cells is the memory validation needs.
CHUNK_ROWS = 50_000
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
    **ONE_LINE_TEXTS,  # a material's or fluid's conditions: one line
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
    #: Rows read per resource (also of a table not kept).
    counts: dict[str, int] = field(default_factory=dict)
    #: Each resource's CSV file in the opened package (an import re-reads the collisions
    #: from it block by block).
    files: dict[str, Path] = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return not self.problems


def _row_list(rows: Any, count: int) -> str:
    shown = ", ".join(str(i) for i in rows[:SHOWN_PER_PROBLEM])
    more = f" and {count - SHOWN_PER_PROBLEM} more" if count > SHOWN_PER_PROBLEM else ""
    return f"row{'s' if count > 1 else ''} {shown}{more}"


class _Findings:
    """Problems of one table read in blocks: each problem's first rows and its count,
    gathered over every block (memory: a few numbers per distinct problem)."""

    def __init__(self) -> None:
        self.rows: dict[str, tuple[list[int], int]] = {}

    def add(self, text: str, mask: Any, first_row: int) -> None:
        index = np.flatnonzero(np.asarray(mask))
        if not len(index):
            return
        shown, count = self.rows.get(text, ([], 0))
        if len(shown) < SHOWN_PER_PROBLEM:
            shown = shown + [int(i) + first_row for i in index[:SHOWN_PER_PROBLEM]]
        self.rows[text] = (shown[:SHOWN_PER_PROBLEM], count + len(index))

    def problems(self) -> list[str]:
        found = []
        for text, (shown, count) in self.rows.items():
            head, _, tail = text.rpartition("{rows}")
            found.append(f"{head}{_row_list(shown, count)}{tail}")
        return found


def _absent(name: str, header: list[str]) -> list[str] | None:
    """The optional columns (``OPTIONAL_COLUMNS``) an older package's header lacks, read
    as empty; None where the header is not the schema's with some of them left out."""
    expected = columns(name)
    absent = [c for c in expected if c not in header]
    if header != [c for c in expected if c in header]:
        return None
    return absent if set(absent) <= set(OPTIONAL_COLUMNS.get(name, ())) else None


def _header_problem(name: str, header: list[str]) -> str | None:
    expected = columns(name)
    if _absent(name, header) is not None:
        return None
    missing = [c for c in expected if c not in header]
    extra = [c for c in header if c not in expected]
    detail = "; ".join(
        filter(
            None,
            [
                f"missing {', '.join(missing)}" if missing else "",
                f"unknown {', '.join(map(str, extra[:20]))}"
                + (f" and {len(extra) - 20} more" if len(extra) > 20 else "")
                if extra
                else "",
                "columns out of order" if not missing and not extra else "",
            ],
        )
    )
    return f"{name}: header does not match the schema ({detail})"


def _check_block(
    name: str, frame: Any, first_row: int, found: _Findings, bad: dict[str, tuple[str, str]]
) -> Any:
    """One block of a table's text cells: every column's rule, as SI values."""
    out = pd.DataFrame(index=frame.index)
    for column, kind, required in RESOURCES[name]:
        raw = frame[column]
        # Text is kept byte for byte (a note of one space stays one space); only a
        # number column treats surrounding spaces as nothing.
        empty = raw == "" if kind == "string" else raw.str.strip() == ""
        if required:
            found.add(f"{name}.{column}: empty in {{rows}} (required)", empty, first_row)
        if kind == "string":
            _check_strings(name, column, raw, found, first_row, bad)
            words = MATERIALS.texts.get(column) if name == "materials" else None
            if words:  # brittleness: one of its words, as the command line asks
                found.add(
                    f"{name}.{column}: must be one of {', '.join(words)} in {{rows}}",
                    ~empty & ~raw.isin(words),
                    first_row,
                )
            out[column] = raw.where(~empty, None)
            continue
        values = pd.to_numeric(raw.where(~empty, None), errors="coerce")
        found.add(f"{name}.{column}: not a number in {{rows}}", ~empty & values.isna(), first_row)
        if kind == "integer":
            fractional = values.notna() & (values != np.floor(values))
            found.add(f"{name}.{column}: not an integer in {{rows}}", fractional, first_row)
        rule = RULES.get(column)
        if rule is not None:
            broken = values.notna() & ~rule.holds_array(values.to_numpy(dtype=float))
            found.add(f"{name}.{column}: {rule.text} — broken in {{rows}}", broken, first_row)
        else:
            infinite = values.notna() & ~np.isfinite(values.to_numpy(dtype=float))
            found.add(f"{name}.{column}: not finite in {{rows}}", infinite, first_row)
        numbers = values.to_numpy(dtype=float)
        found.add(
            f"{name}.{column}: {TINY_RULE} — in {{rows}}", underflows(numbers, numbers), first_row
        )
        if name == "collisions" and column in SPEEDS:
            with np.errstate(invalid="ignore"):
                fast = np.abs(numbers) > MAX_SPEED_M_S
            found.add(
                f"{name}.{column}: faster than {MAX_SPEED_M_S:g} m/s (beyond any impact "
                "apparatus) in {rows}",
                fast,
                first_row,
            )
        out[column] = values
    if name == "collisions":
        e = out["v_n_out_m_s"] / out["v_n_in_m_s"]
        found.add(
            f"collisions: v_n_out_m_s / v_n_in_m_s above {MAX_RESTITUTION} "
            "(energy from nowhere) in {rows}",
            e > MAX_RESTITUTION,
            first_row,
        )
    if name == "sources":  # the rules a source typed on the command line follows
        for index, row in enumerate(out.to_dict("records")):
            stated = {k: v for k, v in row.items() if v is not None and v == v}
            if "year" in stated and float(stated["year"]).is_integer():
                stated["year"] = int(stated["year"])  # a fractional one is refused above
            try:
                check_source(stated)
            except ValidationError as exc:
                shown = np.zeros(len(out), dtype=bool)
                shown[index] = True
                found.add(
                    f"{name}.{exc.field}: {exc.value} {exc.rule} in {{rows}}", shown, first_row
                )
    if name in CASE_INSENSITIVE:  # materials and fluids: one block, a table of names
        column = PRIMARY_KEYS[name][0]
        raw = frame[column]
        keys = raw.map(lambda n: name_key(n) if isinstance(n, str) else n)
        twins = keys.duplicated(keep=False) & ~raw.duplicated(keep=False) & (raw != "")
        if twins.any():
            shown = ", ".join(repr(n) for n in raw[twins].iloc[:4])
            found.add(
                f"{name}.{column}: {shown} differ only in case or spacing (names match "
                "case-insensitively) in {rows}",
                twins,
                first_row,
            )
    return out


def _duplicate_rows(key_hashes: list[Any]) -> Any:
    """Mask of rows whose key (as a 64-bit hash) came earlier: 8 bytes a row while
    reading, twice that while sorting once at the end."""
    hashes = np.concatenate(key_hashes) if key_hashes else np.zeros(0, dtype=np.uint64)
    order = np.argsort(hashes, kind="stable")
    ordered = hashes[order]
    repeated = np.zeros(len(hashes), dtype=bool)
    repeated[order[1:][ordered[1:] == ordered[:-1]]] = True
    return repeated


def _csv_blocks(path: Path) -> Any:
    """A resource's CSV as text cells, ``CHUNK_ROWS`` rows at a time."""
    return pd.read_csv(
        path,
        dtype=str,
        keep_default_na=False,
        encoding="utf-8",
        na_filter=False,
        on_bad_lines="error",
        chunksize=CHUNK_ROWS,
    )


def _known_columns(name: str, frame: Any) -> tuple[Any, list[str]]:
    """A block with the resource's columns in order, an absent optional column added
    empty (checked as empty, then left out: not stated); and those absent columns."""
    absent = _absent(name, list(frame.columns)) or []
    for column in absent:
        frame[column] = ""
    return frame[columns(name)], absent


def stored_blocks(name: str, path: Path) -> Iterator[Any]:
    """The rows of a validated resource as the SI blocks validation checked, one block of
    ``CHUNK_ROWS`` at a time, for an import that never holds the whole table: memory is
    bounded by a block, whatever the row count."""
    found = _Findings()
    bad: dict[str, tuple[str, str]] = {}
    rows = 0
    with _csv_blocks(path) as reader:
        for frame in reader:
            frame, absent = _known_columns(name, frame)
            block = _check_block(name, frame, rows + 2, found, bad)
            block.attrs["first_row"] = rows + 2  # the CSV line a problem names
            rows += len(frame)
            yield block.drop(columns=absent)


def _read_table(
    name: str, path: Path, problems: list[str], known: dict[str, Any], *, keep: bool = True
) -> tuple[Any, int]:
    """Check a resource's CSV in blocks of ``CHUNK_ROWS`` (memory bounded by the block,
    plus 8 bytes a row for the duplicate-key check); returns (SI table or None, rows).
    ``keep=False`` (validation only) keeps no rows."""
    found = _Findings()
    bad: dict[str, tuple[str, str]] = {}
    kept, key_hashes = [], []
    rows = 0
    try:
        with _csv_blocks(path) as reader:
            for frame in reader:
                if rows == 0:
                    header = _header_problem(name, list(frame.columns))
                    if header is not None:
                        problems.append(header)
                        return None, 0
                frame, absent = _known_columns(name, frame)
                if rows + len(frame) > MAX_ROWS:
                    problems.append(f"{name}: more than {MAX_ROWS} rows")
                    return None, rows + len(frame)
                block = _check_block(name, frame, rows + 2, found, bad)
                _check_references(name, block, known, found, rows + 2, bad)
                key_hashes.append(
                    pd.util.hash_pandas_object(frame[PRIMARY_KEYS[name]], index=False).to_numpy()
                )
                if keep:  # an absent column is not stated: the merge leaves it as it is
                    kept.append(block.drop(columns=absent))
                rows += len(frame)
    except UnicodeDecodeError:
        problems.append(f"{name}: {path.name} is not UTF-8 text")
        return None, rows
    except OSError as exc:
        problems.append(f"{name}: {path.name} cannot be read ({exc.strerror or exc})")
        return None, rows
    except (pd.errors.ParserError, pd.errors.EmptyDataError, ValueError) as exc:
        problems.append(f"{name}: {path.name} cannot be read as CSV ({str(exc).splitlines()[0]})")
        return None, rows
    if rows == 0:
        header = _header_problem(name, _header_only(path))
        if header is not None:
            problems.append(header)
            return None, 0
    key = PRIMARY_KEYS[name]
    found.add(f"{name}: duplicate {'+'.join(key)} in {{rows}}", _duplicate_rows(key_hashes), 2)
    problems.extend(found.problems())
    if not keep:
        return None, rows
    if not kept:
        return pd.DataFrame({c: [] for c in columns(name)}), 0
    return pd.concat(kept, ignore_index=True), rows


def _header_bound(name: str, path: Path) -> str | None:
    """The problem of a resource's header line, read with a size limit before anything
    parses it: longer than ``MAX_HEADER_BYTES``, wider than ``MAX_HEADERS`` columns (the
    bounds of a CSV file's header), or not text. A header of a million columns is
    refused after reading 16 KiB, not after pandas has built a million-column frame."""
    try:
        with path.open("rb") as handle:
            head = handle.read(MAX_HEADER_BYTES + 1)
    except OSError as exc:
        return f"{name}: {path.name} cannot be read ({exc.strerror or exc})"
    end = head.find(b"\n")
    line = head[: end if end >= 0 else len(head)]
    if b"\x00" in line:
        return f"{name}: {path.name} is not a text file (it holds NUL bytes)"
    if end < 0 and len(head) > MAX_HEADER_BYTES:
        return (
            f"{name}: {path.name} has a header line longer than {MAX_HEADER_BYTES:,} bytes "
            f"(a header has at most {MAX_HEADERS} columns)"
        )
    try:
        text = line.decode("utf-8").rstrip("\r")
    except UnicodeDecodeError:
        return f"{name}: {path.name} is not UTF-8 text"
    width = len(next(csv.reader([text]), []))
    if width > MAX_HEADERS:
        return f"{name}: {path.name} has {width:,} columns, more than {MAX_HEADERS}"
    return None


def _header_only(path: Path) -> list[str]:
    return list(pd.read_csv(path, dtype=str, nrows=0, encoding="utf-8").columns)


def _check_references(
    name: str,
    block: Any,
    tables: dict[str, Any],
    found: _Findings,
    first_row: int,
    bad: dict[str, tuple[str, str]],
) -> None:
    """Each foreign key of one block against the (already read) table it names; the first
    dangling value of a column names the problem, its rows counted in every block."""
    for column, other, there in FOREIGN_KEYS.get(name, []):
        target = tables.get(other)
        if target is None:
            continue
        values = block[column]
        dangling = values.notna() & ~values.isin(set(target[there].dropna()))
        if not dangling.any():
            continue
        marker = f"\x00{column}"
        if marker not in bad:
            first = values[dangling].iloc[0]
            text = f"{name}.{column}: {first!r} (in {{rows}}) is not a {there} in {other}"
            bad[marker] = (text, "")
        found.add(bad[marker][0], dangling, first_row)


def _check_strings(
    name: str,
    column: str,
    raw: Any,
    found: _Findings,
    first_row: int,
    bad: dict[str, tuple[str, str]],
) -> None:
    """Apply the shared name or text rule to each distinct non-empty value of a column;
    the first value that breaks it is the column's problem (its rows counted in every
    block)."""
    limit = NAME_COLUMNS.get(column)
    if column in bad:
        text, value = bad[column]
        found.add(text, raw == value, first_row)
        return
    for value in raw[raw != ""].unique():
        try:
            if limit is not None:
                check_name(column, value, max_length=limit)
            else:
                check_text(column, value, max_length=TEXT_LENGTHS.get(column, MAX_CELL_CHARS))
        except ValidationError as exc:
            shown = exc.value if len(str(exc.value)) <= 60 else str(exc.value)[:60] + "…"
            text = f"{name}.{column}: {shown} {exc.rule} in {{rows}}"
            bad[column] = (text, value)
            found.add(text, raw == value, first_row)
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


#: The order resources are read in: a table before the tables whose keys point at it.
READ_ORDER = ["sources", "materials", "fluids", "fluid_points", "collisions"]


def validate_root(root: Path, *, keep_collisions: bool = True) -> Validated:
    """Validate an unpacked package folder; never raises for data problems.

    Each table is read in blocks (``_read_table``); ``keep_collisions=False`` (validation
    without import) keeps none of the collisions' rows, so memory does not grow with
    their number but for the 8 bytes a row of the duplicate-run check."""
    descriptor = read_descriptor(root)
    reference = descriptor.get("granudb_reference")
    if isinstance(reference, dict) and reference.get("kind") == "reported values":
        name = str(descriptor.get("name"))
        shipped = name in reference_library.names()
        door = name if shipped else "FOLDER (the package's folder; unzip a zip first)"
        said = (
            f"a package of reported values ({name} {descriptor.get('version')}), not of "
            f"collisions: import it with `granudb reference import {door}`"
        )
        return Validated(descriptor, {}, [said], {}, {})
    problems: list[str] = []
    tables: dict[str, Any] = {}
    counts: dict[str, int] = {}
    files: dict[str, Path] = {}
    found = _resources(descriptor, problems)
    checked = {name: _resource_file(root, name, found[name], problems) for name in found}
    # every header bounded before pandas (or Pint, for the schemas) is even imported: a
    # million-column header costs what reading 16 KiB costs
    bounds = [_header_bound(name, file) for name, file in checked.items() if file is not None]
    if any(bounds):
        problems += [b for b in bounds if b is not None]
        _check_metadata(descriptor, problems)
        return Validated(descriptor, {}, problems, {}, {})
    for name in sorted(found, key=READ_ORDER.index):
        file = checked[name]
        if file is None:
            continue
        check_schema(name, found[name], problems)
        keep = keep_collisions or name != "collisions"
        tables[name], counts[name] = _read_table(name, file, problems, tables, keep=keep)
        files[name] = file
    if "fluid_points" not in tables:
        tables["fluid_points"] = pd.DataFrame({c: [] for c in columns("fluid_points")})
        counts["fluid_points"] = 0
    _check_metadata(descriptor, problems)
    keys = set(tables["sources"]["key"].dropna()) if "sources" in tables else set()
    dataset_record(descriptor, keys, problems)
    return Validated(descriptor, tables, problems, counts, files)


def validate_package(path: Path, *, keep_collisions: bool = True) -> Validated:
    """Validate a package folder, ``datapackage.json`` or zip; problems are collected."""
    with package_root(path) as root:
        return validate_root(root, keep_collisions=keep_collisions)


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
    record = dataset_record(descriptor, set(validated.tables["sources"]["key"].dropna()), [])
    return PackageContent(
        dataset=name,
        version=str(descriptor.get("version") or "1.0.0"),
        package=str(descriptor.get("name") or name),
        title=record.title,
        description=record.description,
        license=_license(descriptor),
        doi=doi,
        tables=validated.tables,
        authors=record.authors,
        keywords=record.keywords,
        source=record.source,
        status=record.status,
        created=record.created,
    )


def import_package(
    database: Any, path: Path, *, as_name: str | None = None, rename_conflicts: bool = False
) -> Any:
    """Validate ``path`` and store it (``granudb.db.package_store``, one transaction);
    raise ``PackageError`` naming every problem or conflict, changing nothing, otherwise.

    The collisions are never held whole: validation reads them in blocks and keeps none,
    then the store reads them again block by block (``stored_blocks``) and inserts each,
    and the declared ``granudb:content_hash`` is checked against the stored rows (the
    database sorts them), inside the same transaction: peak memory is bounded by a block,
    whatever the row count. Returns a ``PackageImport``; its ``declared_hash`` is the
    package's content hash."""
    if as_name is not None:
        check_name("as_name", as_name)
    with package_root(path) as root:
        validated = validate_root(root, keep_collisions=False)
        if validated.problems:
            raise PackageError(validated.problems, hint="; `granudb dataset validate` lists them")
        declared = validated.descriptor.get("granudb:content_hash")
        content = _content(validated, as_name)
        content.tables["collisions"] = stored_blocks("collisions", validated.files["collisions"])
        try:
            result = store_package(
                database,
                content,
                rename_conflicts=rename_conflicts,
                declared_hash=declared,
                problems=Problems(validated.files["collisions"].name),
            )
        except MergeConflict as exc:
            hint = (
                "conflicting names are not overwritten; import with --rename-conflicts to "
                "bring them in under new names"
            )
            raise PackageError([*exc.conflicts, hint], hint="") from None
        except HashMismatch as exc:
            raise PackageError([str(exc)]) from None
    result.declared_hash = declared
    return result
