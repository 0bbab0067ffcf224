"""Importing measured collisions from CSV: streamed, validated, all or nothing.

The contract (README, "Importing collisions"): one row per run; text columns ``run``,
``particle``, ``wall``, ``fluid`` (empty = dry), ``notes``; numeric columns with their unit
in the header (``v_n_in [mm/s]``, ``incidence_angle (deg)``, ``Temperature [degC]``;
names case-insensitive) or under granudb's SI column name (``v_n_in_m_s``).

Everything that can be checked without the database is checked before the write
transaction opens (``open_collision_file``): the header is read with a size limit, every
column mapped and every unit parsed (all header problems in one refusal), and every row
counted. So a hostile header costs milliseconds and never holds SQLite's write lock. The
rows are then read in chunks (memory is bounded whatever the file's size), converted and
checked with vectorized rules, and bulk-inserted by ``granudb.db.collision_store`` in one
transaction: one bad row anywhere rejects the whole file and nothing is written. A file
(by sha256) is imported into a dataset at most once.

Semicolon-delimited files with decimal commas, as European spreadsheets write them, are
read with ``delimiter=";"`` and ``decimal=","`` (``--delimiter ';' --decimal ','``); without
those options such a file is refused with that hint, never misread.
"""

from __future__ import annotations

import hashlib
import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from granudb.db import datasets
from granudb.errors import ValidationError
from granudb.io.tables import ColumnMap
from granudb.vocabulary import COLLISION_MEASURED, COLLISION_TEXT
from granudb.vocabulary.rules import RULES
from granudb.vocabulary.text import (
    check_name,
    check_text,
    name_forbidden_pattern,
    text_forbidden_pattern,
)

NUMERIC = list(COLLISION_MEASURED)  # the measured columns, SI
TEXT = list(COLLISION_TEXT)
#: Empty spin cells mean "not measured" and stay empty (NULL); the angle is optional (it is
#: derived from the velocities), and so are the target sphere's velocities.
REQUIRED = [
    "run",
    "particle",
    "wall",
    "diameter_m",
    "v_n_in_m_s",
    "v_t_in_m_s",
    "v_n_out_m_s",
    "v_t_out_m_s",
]
#: Headers of earlier granudb files, read as today's columns.
ALIASES = {"incidence_angle": "nominal_angle"}
#: e = v_n_out / v_n_in above this is refused: energy from nowhere, beyond measurement error.
MAX_RESTITUTION = 1.05
#: How far a stated angle may differ from atan(v_t_in / v_n_in), the angle the velocities
#: give. Velocities from high-speed video are good to about 2 % of the speed (a pixel or
#: two of a track fifty to a hundred pixels long), which moves atan(v_t/v_n) by about
#: δv/|v| ≈ 0.02 rad ≈ 1.2°; an apparatus's nominal angle (a tilted plane, a launcher) is
#: set to about ±1°. Their sum rounds up to 3°; a difference larger than that is a wrong
#: column or a wrong unit (the physics review found one of tens of degrees), not noise.
ANGLE_TOLERANCE_RAD = math.radians(3.0)
CHUNK_ROWS = 100_000
TABLE = "collisions.csv"


@dataclass
class ImportResult:
    dataset: str
    version: str
    rows: int
    sha256: str
    file_name: str


@dataclass(frozen=True)
class CollisionFile:
    """A collision CSV whose header has been read and mapped, ready to stream."""

    path: Path
    delimiter: str
    decimal: str
    mapping: dict[str, ColumnMap]


def file_sha256(path: Path) -> str:
    digest = hashlib.sha256()
    with path.open("rb") as handle:
        while chunk := handle.read(1 << 20):
            digest.update(chunk)
    return digest.hexdigest()


def _first(mask: Any) -> int:
    return int(np.flatnonzero(np.asarray(mask))[0])


def _header_of(mapping: dict[str, Any], column: str) -> str:
    return mapping[column].header if column in mapping else column


def _check_chunk(frame: Any, raw: Any, mapping: dict[str, Any], first_row: int) -> None:
    """Every rule on one converted chunk; raises on the first broken row."""
    for column in REQUIRED:
        missing = frame[column].isna()
        if missing.any():
            pos = _first(missing)
            raise ValidationError(
                _header_of(mapping, column), "(empty)", "is required", row=first_row + pos
            )
    for column in NUMERIC:
        rule = RULES.get(column)
        if rule is None:
            continue
        broken = ~rule.holds_array(frame[column].to_numpy(dtype=float))
        if broken.any():
            pos = _first(broken)
            header = _header_of(mapping, column)
            shown = str(raw[mapping[column].header].iloc[pos]).strip()
            raise ValidationError(
                header, shown, rule.text + _in_units(column, mapping), row=first_row + pos
            )
    v_n_in = frame["v_n_in_m_s"].to_numpy(dtype=float)
    e = frame["v_n_out_m_s"].to_numpy(dtype=float) / v_n_in
    too_high = e > MAX_RESTITUTION
    if too_high.any():
        pos = _first(too_high)
        raise ValidationError(
            "v_n_out / v_n_in",
            f"{e[pos]:.4g}",
            f"must be ≤ {MAX_RESTITUTION} (a rebound faster than the impact, beyond "
            "measurement error)",
            row=first_row + pos,
        )
    _check_angle(frame, raw, mapping, first_row)
    _check_text(frame, mapping, first_row)


def _check_angle(frame: Any, raw: Any, mapping: dict[str, Any], first_row: int) -> None:
    """A stated angle must agree with the velocities it describes (``ANGLE_TOLERANCE_RAD``)."""
    if "nominal_angle_rad" not in mapping:
        return
    stated = frame["nominal_angle_rad"].to_numpy(dtype=float)
    derived = np.arctan2(
        frame["v_t_in_m_s"].to_numpy(dtype=float), frame["v_n_in_m_s"].to_numpy(dtype=float)
    )
    off = np.abs(stated - derived) > ANGLE_TOLERANCE_RAD  # NaN (empty) compares False
    if off.any():
        pos = _first(off)
        header = mapping["nominal_angle_rad"].header
        raise ValidationError(
            header,
            str(raw[header].iloc[pos]).strip(),
            f"disagrees with atan(v_t_in / v_n_in) = {math.degrees(derived[pos]):.2f}° by more "
            f"than {math.degrees(ANGLE_TOLERANCE_RAD):g}° (check the column and its unit, or "
            "leave it empty: the angle is derived from the velocities)",
            row=first_row + pos,
        )


def _check_text(frame: Any, mapping: dict[str, Any], first_row: int) -> None:
    """Names and notes obey ``granudb.vocabulary.text``'s rules (the same as every door).

    Found vectorized; the first offender is re-checked by ``check_name``/``check_text``,
    whose message is the one every other door gives.
    """
    from granudb.vocabulary.text import MAX_NAME, MAX_TEXT

    for column in TEXT:
        values = frame[column]
        present = values.notna()
        if not present.any():
            continue
        text = values.where(present, "").astype(str)
        if column == "notes":
            bad = text.str.contains(text_forbidden_pattern(), regex=True)
            bad |= text.str.len() > MAX_TEXT
        else:
            bad = text.str.contains(name_forbidden_pattern(), regex=True)
            bad |= (text.str.len() > MAX_NAME) | (text != text.str.strip())
        bad &= present
        if bad.any():
            pos = _first(bad)
            check = check_text if column == "notes" else check_name
            try:
                check(column, text.iloc[pos])
            except ValidationError as exc:
                raise ValidationError(
                    _header_of(mapping, column), exc.value, exc.rule, row=first_row + pos
                ) from None


def _in_units(column: str, mapping: dict[str, Any]) -> str:
    cmap = mapping.get(column)
    if cmap is None or (cmap.scale == 1.0 and cmap.offset == 0.0):
        return ""
    rule = RULES[column]
    if column == "nominal_angle_rad" and rule.maximum is not None:
        return " rad, i.e. below 90°"
    return f" {cmap.unit.pint} (in SI)"


def open_collision_file(path: Path, *, delimiter: str = ",", decimal: str = ".") -> CollisionFile:
    """Read and map the header and count every row's cells; no database is touched.

    Everything here happens before ``store_collisions`` opens the write transaction, so
    a bad header or a ragged file is refused without ever holding the lock.
    """
    from granudb.io.tables import check_shape, csv_options, map_headers, read_header

    delimiter, decimal = csv_options(delimiter, decimal)
    path = Path(path)
    if not path.is_file():
        raise ValidationError("FILE", str(path), "is not a file")
    headers = read_header(path, delimiter)
    try:
        check_shape(path, delimiter)
    except UnicodeDecodeError:
        raise ValidationError("FILE", path.name, "is not UTF-8 text") from None
    mapping = map_headers(headers, NUMERIC, TEXT, table=TABLE, aliases=ALIASES, required=REQUIRED)
    return CollisionFile(path, delimiter, decimal, mapping)


def _read_chunks(source: CollisionFile, chunk_rows: int) -> Any:
    import pandas as pd

    return pd.read_csv(
        source.path,
        sep=source.delimiter,
        dtype=str,
        keep_default_na=False,
        na_filter=False,
        encoding="utf-8-sig",
        chunksize=chunk_rows,
        index_col=False,
    )


def import_collisions(
    database: Any,
    path: Path,
    *,
    dataset: str,
    version: str = datasets.DEFAULT_VERSION,
    source: str | None = None,
    title: str | None = None,
    license: str | None = None,
    progress: Callable[[int], None] | None = None,
    chunk_rows: int = CHUNK_ROWS,
    delimiter: str = ",",
    decimal: str = ".",
) -> ImportResult:
    """Import ``path`` into ``dataset`` (created if new), all or nothing.

    This module reads and checks the file (``open_collision_file`` before any transaction,
    then ``collision_frames``); ``granudb.db.collision_store`` resolves names, refuses
    repeated runs and temperatures outside a fluid's data, and writes everything in one
    transaction.
    """
    from granudb.db.collision_store import ImportTarget, store_collisions

    check_name("dataset", dataset)
    check_name("version", version)
    opened = open_collision_file(Path(path), delimiter=delimiter, decimal=decimal)
    sha256 = file_sha256(opened.path)
    name = opened.path.name
    target = ImportTarget(dataset, version, source, title, license, sha256, name)
    rows = store_collisions(
        database, target, collision_frames(opened, chunk_rows), progress=progress
    )
    return ImportResult(dataset, version, rows, sha256, name)


def collision_frames(source: Path | CollisionFile, chunk_rows: int = CHUNK_ROWS) -> Iterator[Any]:
    """The file's rows as checked SI DataFrames, chunk by chunk, names still as text.

    ``source`` is a path (read as a comma-separated file) or what ``open_collision_file``
    returned. Each frame's ``attrs["first_row"]`` is the spreadsheet row of its first line
    (the header is row 1) and ``attrs["headers"]`` the file's header of each column, so
    later checks can name the row and the column as the file does.
    """
    import pandas as pd

    from granudb.io.tables import convert_frame

    if not isinstance(source, CollisionFile):
        source = open_collision_file(Path(source))
    mapping = source.mapping
    headers = {column: cmap.header for column, cmap in mapping.items()}
    rows = 0
    try:
        for chunk in _read_chunks(source, chunk_rows):
            if rows == 0 and [str(c) for c in chunk.columns] != list(headers.values()):
                raise ValidationError(
                    "FILE", source.path.name, "has a header that is not one line of cells"
                )
            first_row = rows + 2
            frame = convert_frame(
                chunk, mapping, table=TABLE, first_row=first_row, decimal=source.decimal
            )
            for column in NUMERIC + TEXT:
                if column not in frame:
                    frame[column] = np.nan if column in NUMERIC else None
            _check_chunk(frame, chunk, mapping, first_row)
            frame.attrs["first_row"] = first_row
            frame.attrs["headers"] = headers
            rows += len(frame)
            yield frame
    except UnicodeDecodeError:
        raise ValidationError("FILE", source.path.name, "is not UTF-8 text") from None
    except pd.errors.ParserError as exc:
        detail = str(exc).strip().splitlines()[-1]
        raise ValidationError(
            "FILE", source.path.name, f"is not a well-formed CSV ({detail})"
        ) from None
    except pd.errors.EmptyDataError:
        raise ValidationError("FILE", source.path.name, "is empty") from None
    if rows == 0:
        raise ValidationError("FILE", source.path.name, "holds no rows")
