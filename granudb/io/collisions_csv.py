"""Importing measured collisions from CSV: streamed, validated, all or nothing.

The contract (README, "Importing collisions"): one row per run; text columns ``run``,
``particle``, ``wall``, ``fluid`` (empty = dry), ``notes``; numeric columns with their unit
in the header (``v_n_in [mm/s]``, ``incidence_angle [deg]``, ``temperature [degC]``) or
under granudb's SI column name (``v_n_in_m_s``). The file is read in chunks (memory is
bounded whatever its size), each chunk is converted and checked with vectorized rules, and
rows are bulk-inserted with SQLAlchemy Core inside one write transaction: one bad row
anywhere rejects the whole file and nothing is written. A file (by sha256) is imported into
a dataset at most once.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from granudb.db import datasets
from granudb.errors import ValidationError
from granudb.vocabulary import COLLISION_MEASURED, COLLISION_TEXT
from granudb.vocabulary.rules import RULES

NUMERIC = list(COLLISION_MEASURED)  # the measured columns, SI
TEXT = list(COLLISION_TEXT)
#: Empty spin cells mean "not measured" and stay empty; the angle is optional (it is
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
MAX_LENGTH = {"run": 200, "particle": 200, "wall": 200, "fluid": 200, "notes": 10_000}
CHUNK_ROWS = 100_000
TABLE = "collisions.csv"


@dataclass
class ImportResult:
    dataset: str
    version: str
    rows: int
    sha256: str
    file_name: str


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
        values = frame[column]
        missing = values.isna()
        if missing.any():
            pos = _first(missing)
            raise ValidationError(
                _header_of(mapping, column), "(empty)", "is required", row=first_row + pos
            )
    for column in NUMERIC:
        rule = RULES.get(column)
        if rule is None:
            continue
        values = frame[column].to_numpy(dtype=float)
        broken = ~rule.holds_array(values)
        if broken.any():
            pos = _first(broken)
            header = _header_of(mapping, column)
            shown = str(raw[mapping[column].header].iloc[pos]).strip()
            raise ValidationError(
                header, shown, rule.text + _in_units(column, mapping), row=first_row + pos
            )
    e = frame["v_n_out_m_s"].to_numpy(dtype=float) / frame["v_n_in_m_s"].to_numpy(dtype=float)
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
    for column in TEXT:
        if column not in frame:
            continue
        values = frame[column]
        text = values.fillna("")
        long = text.str.len() > MAX_LENGTH[column]
        if long.any():
            pos = _first(long)
            raise ValidationError(
                column,
                repr(text.iloc[pos][:20] + "…"),
                f"must be at most {MAX_LENGTH[column]} characters",
                row=first_row + pos,
            )
        pattern = r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]" if column == "notes" else r"[\x00-\x1f\x7f]"
        control = text.str.contains(pattern, regex=True)
        if control.any():
            pos = _first(control)
            raise ValidationError(
                column,
                repr(text.iloc[pos][:40]),
                "must not contain control characters",
                row=first_row + pos,
            )


def _in_units(column: str, mapping: dict[str, Any]) -> str:
    cmap = mapping.get(column)
    if cmap is None or (cmap.scale == 1.0 and cmap.offset == 0.0):
        return ""
    rule = RULES[column]
    if column == "nominal_angle_rad" and rule.maximum is not None:
        return " rad, i.e. below 90°"
    return f" {cmap.unit.pint} (in SI)"


def _check_shape(path: Path) -> None:
    """Every row has as many cells as the header. pandas silently drops the extra cells of
    a long row and pads a short (truncated) one, so rows are counted here first."""
    import csv

    with path.open(encoding="utf-8", newline="") as handle:
        reader = csv.reader(handle)
        header = next(reader, None)
        if not header:
            return
        width = len(header)
        for number, row in enumerate(reader, start=2):
            if len(row) != width:
                if not row:
                    continue  # a blank line, which pandas skips too
                what = "more" if len(row) > width else "fewer"
                hint = "" if what == "more" else " (truncated?)"
                raise ValidationError(
                    "FILE", f"row {number}", f"has {what} cells than the header{hint}"
                )


def _read_chunks(path: Path, chunk_rows: int) -> Any:
    import pandas as pd

    return pd.read_csv(
        path,
        dtype=str,
        keep_default_na=False,
        na_filter=False,
        encoding="utf-8",
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
) -> ImportResult:
    """Import ``path`` into ``dataset`` (created if new), all or nothing.

    This module reads and checks the file (``collision_frames``); ``granudb.db.collision_store``
    resolves names, refuses repeated runs and writes everything in one transaction.
    """
    from granudb.db.collision_store import ImportTarget, store_collisions

    path = Path(path)
    if not path.is_file():
        raise ValidationError("FILE", str(path), "is not a file")
    sha256 = file_sha256(path)
    try:
        _check_shape(path)
    except UnicodeDecodeError:
        raise ValidationError("FILE", path.name, "is not UTF-8 text") from None
    target = ImportTarget(dataset, version, source, title, license, sha256, path.name)
    rows = store_collisions(database, target, collision_frames(path, chunk_rows), progress=progress)
    return ImportResult(dataset, version, rows, sha256, path.name)


def collision_frames(path: Path, chunk_rows: int = CHUNK_ROWS) -> Iterator[Any]:
    """The file's rows as checked SI DataFrames, chunk by chunk, names still as text.

    Each frame's ``attrs["first_row"]`` is the spreadsheet row of its first line (the
    header is row 1), so later checks can name the row.
    """
    import pandas as pd

    from granudb.io.tables import convert_frame, map_headers

    mapping = None
    rows = 0
    try:
        for chunk in _read_chunks(path, chunk_rows):
            first_row = rows + 2
            if mapping is None:
                mapping = map_headers(
                    [str(c) for c in chunk.columns], NUMERIC, TEXT, table=TABLE, aliases=ALIASES
                )
                missing = [c for c in REQUIRED if c not in mapping]
                if missing:
                    raise ValidationError(
                        f"{TABLE} header", ", ".join(missing), "are required columns but missing"
                    )
            frame = convert_frame(chunk, mapping, table=TABLE, first_row=first_row)
            for column in NUMERIC + TEXT:
                if column not in frame:
                    frame[column] = np.nan if column in NUMERIC else None
            _check_chunk(frame, chunk, mapping, first_row)
            frame.attrs["first_row"] = first_row
            rows += len(frame)
            yield frame
    except UnicodeDecodeError:
        raise ValidationError("FILE", path.name, "is not UTF-8 text") from None
    except pd.errors.ParserError as exc:
        detail = str(exc).strip().splitlines()[-1]
        raise ValidationError("FILE", path.name, f"is not a well-formed CSV ({detail})") from None
    except pd.errors.EmptyDataError:
        raise ValidationError("FILE", path.name, "is empty") from None
    if rows == 0:
        raise ValidationError("FILE", path.name, "holds no rows")
