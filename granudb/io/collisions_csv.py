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
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from sqlalchemy import select

from granudb.db import datasets
from granudb.db.models import Collision, CollisionImport, Fluid, Material, name_key
from granudb.errors import ConflictError, ValidationError
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


class _Names:
    """Case-insensitive lookup of material and fluid names to ids, vectorized."""

    def __init__(self, session: Any) -> None:
        self.materials = {
            name_key(n): i for i, n in session.execute(select(Material.id, Material.name))
        }
        self.material_names = sorted(
            (n for (n,) in session.execute(select(Material.name))), key=str.casefold
        )
        self.fluids = {name_key(n): i for i, n in session.execute(select(Fluid.id, Fluid.name))}
        self.fluid_names = sorted(
            (n for (n,) in session.execute(select(Fluid.name))), key=str.casefold
        )

    def ids(
        self, names: Any, table: dict[str, int], known: list[str], header: str, first_row: int
    ) -> Any:
        unique = {n: table.get(name_key(n)) for n in names.dropna().unique() if isinstance(n, str)}
        ids = names.map(unique)
        unknown = names.notna() & ids.isna()
        if unknown.any():
            pos = _first(unknown)
            raise ValidationError(
                header,
                repr(str(names.iloc[pos])),
                f"is not in the database (known: {', '.join(known)})",
                row=first_row + pos,
            )
        return ids


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
    """Import ``path`` into ``dataset`` (created if new), all or nothing."""
    import pandas as pd

    from granudb.db.catalog import get_source
    from granudb.io.tables import convert_frame, map_headers

    path = Path(path)
    if not path.is_file():
        raise ValidationError("FILE", str(path), "is not a file")
    sha256 = file_sha256(path)
    rows = 0
    try:
        _check_shape(path)
        with database.session(write=True) as session:
            source_id = get_source(session, source).id if source is not None else None
            target, _ = datasets.get_or_create_dataset(
                session, dataset, version, title=title, license=license, source_id=source_id
            )
            earlier = session.scalars(
                select(CollisionImport).filter_by(dataset_id=target.id, file_sha256=sha256)
            ).first()
            if earlier is not None:
                raise ConflictError(
                    f"FILE: {path.name} was already imported into dataset {dataset} {version} "
                    f"on {earlier.imported_at:%Y-%m-%d %H:%M} ({earlier.rows} rows); nothing "
                    "was imported again"
                )
            names = _Names(session)
            seen = set(session.scalars(select(Collision.run).filter_by(dataset_id=target.id)))
            mapping = None
            for chunk in _read_chunks(path, chunk_rows):
                first_row = rows + 2  # spreadsheet rows: the header is row 1
                if mapping is None:
                    mapping = map_headers(
                        [str(c) for c in chunk.columns],
                        NUMERIC,
                        TEXT,
                        table=TABLE,
                        aliases=ALIASES,
                    )
                    missing = [c for c in REQUIRED if c not in mapping]
                    if missing:
                        raise ValidationError(
                            f"{TABLE} header",
                            ", ".join(missing),
                            "are required columns but missing",
                        )
                frame = convert_frame(chunk, mapping, table=TABLE, first_row=first_row)
                for column in NUMERIC + TEXT:
                    if column not in frame:
                        frame[column] = np.nan if column in NUMERIC else None
                _check_chunk(frame, chunk, mapping, first_row)
                runs = frame["run"]
                repeated = runs.duplicated() | runs.isin(seen)
                if repeated.any():
                    pos = _first(repeated)
                    raise ValidationError(
                        "run",
                        repr(runs.iloc[pos]),
                        "appears twice (in this file or already in the dataset)",
                        row=first_row + pos,
                    )
                seen.update(runs)
                frame["particle_id"] = names.ids(
                    frame.pop("particle"),
                    names.materials,
                    names.material_names,
                    "particle",
                    first_row,
                )
                frame["wall_id"] = names.ids(
                    frame.pop("wall"), names.materials, names.material_names, "wall", first_row
                )
                frame["fluid_id"] = names.ids(
                    frame.pop("fluid"), names.fluids, names.fluid_names, "fluid", first_row
                )
                rows += insert_collisions(session, target.id, frame)
                if progress is not None:
                    progress(rows)
            if rows == 0:
                raise ValidationError("FILE", path.name, "holds no rows")
            session.add(
                CollisionImport(
                    dataset_id=target.id, file_sha256=sha256, file_name=path.name[:500], rows=rows
                )
            )
            datasets.update_content_hash(session, target)
    except UnicodeDecodeError:
        raise ValidationError("FILE", path.name, "is not UTF-8 text") from None
    except pd.errors.ParserError as exc:
        detail = str(exc).strip().splitlines()[-1]
        raise ValidationError("FILE", path.name, f"is not a well-formed CSV ({detail})") from None
    except pd.errors.EmptyDataError:
        raise ValidationError("FILE", path.name, "is empty") from None
    return ImportResult(dataset, version, rows, sha256, path.name)


INSERT_COLUMNS = ["dataset_id", "run", "particle_id", "wall_id", "fluid_id", *NUMERIC, "notes"]


def insert_collisions(session: Any, dataset_id: int, frame: Any) -> int:
    """Bulk-insert SI rows (ids already resolved); returns the count.

    Rows go to the driver's ``executemany`` as tuples with one parameterised statement:
    several times faster than ORM objects or dicts, and still no SQL built from data.
    """
    n = len(frame)
    if n == 0:
        return 0
    columns: list[list[Any]] = [[dataset_id] * n]
    for name in INSERT_COLUMNS[1:]:
        values = frame[name]
        array = values.to_numpy(dtype=object)
        missing = values.isna().to_numpy()
        if name in ("particle_id", "wall_id", "fluid_id"):
            array = [None if m else int(v) for v, m in zip(array, missing, strict=True)]
        elif missing.any():
            array = [None if m else v for v, m in zip(array, missing, strict=True)]
        else:
            array = array.tolist()
        columns.append(array)
    connection = session.connection()
    mark = "?" if connection.dialect.paramstyle == "qmark" else "%s"
    statement = (
        f"INSERT INTO collisions ({', '.join(INSERT_COLUMNS)}) "
        f"VALUES ({', '.join([mark] * len(INSERT_COLUMNS))})"
    )
    connection.exec_driver_sql(statement, list(zip(*columns, strict=True)))
    return n
