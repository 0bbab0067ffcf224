"""Writing imported collisions: one transaction, names resolved, runs unique, all or nothing.

The reader (``granudb.io.collision_import`` or a Data Package) yields checked SI DataFrames
with material and fluid names as text; here they are resolved to ids (case-insensitively),
refused when a run label repeats, bulk-inserted, and the import recorded with the file's
sha256, all inside one write transaction: a failure anywhere, in reading or writing, rolls
everything back.

Rows arrive as ``CollisionChunk`` columns (``granudb.db.bulk_insert``; DataFrames are
converted) and are written by ``bulk_insert.insert_rows``. The file's sha256 may be known
only once the reader has read the whole file (it is hashed while it is parsed, one pass):
then "was this file imported before?" is answered at the end, and at the first run that is
already in the dataset (a repeated file's first row), before the same transaction commits.
When the dataset held no runs before, its content hash is computed from the inserted
arrays (``granudb.db.bulk_hash``, formatting each block on a worker thread while it is
inserted), the same value ``granudb.db.content_hash`` gives.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np
from sqlalchemy import func, select

from granudb.db import datasets
from granudb.db.bulk_hash import BlockHasher
from granudb.db.bulk_insert import (
    BULK_CACHE_KIB,
    CollisionChunk,
    NameColumn,
    PlainIndexes,
    block_from_frame,
    frame_columns,
    insert_rows,
    rebuild_pays,
    unsigned_zeros,
)
from granudb.db.catalog_rows import source_id as find_source
from granudb.db.content_hash import update_content_hash
from granudb.db.models import (
    Collision,
    CollisionImport,
    Fluid,
    FluidPoint,
    Material,
    name_key,
)
from granudb.errors import ConflictError, ValidationError
from granudb.lazy import pyarrow as pa

__all__ = [
    "BULK_CACHE_KIB",
    "FirstProblem",
    "ImportTarget",
    "insert_collisions",
    "store_collisions",
]


@dataclass(frozen=True)
class ImportTarget:
    """Where the rows go and where they came from.

    ``file_sha256`` is the file's hash when known up front; otherwise ``digest`` gives it
    (it finishes reading the file if the reader has not).
    """

    dataset: str
    version: str
    source: str | None
    title: str | None
    license: str | None
    file_sha256: str
    file_name: str
    digest: Callable[[], str] | None = None
    #: About how many rows the file holds (0 = unknown), for ``bulk_insert.rebuild_pays``.
    expected_rows: int = 0

    def sha256(self) -> str:
        return self.file_sha256 or (self.digest() if self.digest is not None else "")


def _first(mask: Any) -> int:
    return int(np.flatnonzero(np.asarray(mask))[0])


class NameIndex:
    """Case-insensitive lookup of material and fluid names to ids, one lookup per distinct
    name of a block."""

    def __init__(self, session: Any) -> None:
        live_materials = select(Material.id, Material.name).where(Material.revision_of.is_(None))
        live_fluids = select(Fluid.id, Fluid.name).where(Fluid.revision_of.is_(None))
        materials = list(session.execute(live_materials))
        fluids = list(session.execute(live_fluids))
        self.materials = {name_key(n): i for i, n in materials}
        self.material_names = sorted((n for _, n in materials), key=str.casefold)
        self.material_by_id = {i: n for i, n in materials}
        self.fluids = {name_key(n): i for i, n in fluids}
        self.fluid_names = sorted((n for _, n in fluids), key=str.casefold)
        self.fluid_by_id = {i: n for i, n in fluids}

    def ids(
        self,
        column: NameColumn,
        table: dict[str, int],
        known: list[str],
        header: str,
        first_row: int,
        problems: Any = None,
    ) -> Any:
        """Ids by row (-1 where empty or unknown); every row naming an unknown name goes to
        ``problems`` (each distinct name looked up once, its rows found with numpy)."""
        problems = problems if problems is not None else FirstProblem()
        found = [table.get(name_key(n), -1) for n in column.names]
        codes = np.asarray(column.codes)
        for code in (k for k, i in enumerate(found) if i < 0):
            name = column.names[code]
            near = difflib.get_close_matches(name_key(name), list(map(name_key, known)), n=1)
            shown = next((k for k in known if name_key(k) in near), None)
            rule = "is not in the database" + (
                f"; did you mean {shown!r}?" if shown else f" (known: {', '.join(known)})"
            )
            problems.add(
                np.flatnonzero(codes == code),
                lambda pos, name=name, rule=rule: ValidationError(
                    header, repr(name), rule, row=first_row + pos
                ),
            )
        lookup = np.array([*found, -1], dtype=np.int64)
        return lookup[codes]


class FirstProblem:
    """A problem collector that refuses the first problem at once (callers that do not
    collect every problem of a file); ``granudb.io.tables.Problems`` collects them all."""

    def __bool__(self) -> bool:
        return False

    def add(self, positions: Any, problem: Callable[[int], ValidationError]) -> None:
        positions = np.asarray(positions)
        if len(positions):
            raise problem(int(positions[0]))

    def raise_any(self) -> None:
        return None


class FluidRanges:
    """Which temperatures each fluid's stored data can serve, so no run is imported that
    every later read (listing, fits, reports) would then fail to derive.

    A run's viscosity comes from the fluid's points (two or more), anchored to the printed
    reference value, anywhere between the lowest and highest point; a fluid with fewer
    points has a viscosity only at its reference temperature. Nothing is extrapolated.
    This mirrors ``granudb.scenario.fluid_state.fluid_states_per_row`` (a test imports
    runs at the edges and checks every read derives them).
    """

    def __init__(self, session: Any) -> None:
        spans = {
            fluid_id: (low, high, count)
            for fluid_id, low, high, count in session.execute(
                select(
                    FluidPoint.fluid_id,
                    func.min(FluidPoint.__table__.c.temperature_c),
                    func.max(FluidPoint.__table__.c.temperature_c),
                    func.count(),
                ).group_by(FluidPoint.fluid_id)
            )
        }
        self.fluids = {
            name_key(name): (name, reference, *spans.get(fluid_id, (None, None, 0)))
            for fluid_id, name, reference in session.execute(
                select(Fluid.id, Fluid.name, Fluid.__table__.c.reference_temperature_c).where(
                    Fluid.revision_of.is_(None)
                )
            )
        }

    def check(self, block: Any, dataset: str, problems: Any = None) -> None:
        """Every row whose temperature its fluid's data does not cover, to ``problems``
        (the first refused at once without one)."""
        problems = problems if problems is not None else FirstProblem()
        if not isinstance(block, CollisionChunk):
            block = block_from_frame(block)
        temperatures = block.values.get("temperature_c")
        if temperatures is None:
            return
        temperatures = np.asarray(temperatures, dtype=float)
        codes = np.asarray(block.fluid.codes)
        given = ~np.isnan(temperatures) & (codes >= 0)
        if not given.any():
            return
        bad = np.zeros(len(block), dtype=bool)
        rules: dict[int, str] = {}
        for code, name in enumerate(block.fluid.names):
            known = self.fluids.get(name_key(str(name)))
            rows = given & (codes == code)
            if known is None or not rows.any():
                continue  # an unknown name is refused when names are resolved
            shown, reference, low, high, count = known
            t = temperatures
            if count < 2:
                off = rows & (t != reference)
                rules[code] = (
                    f"differs from fluid {shown}'s reference temperature ({reference:g} °C) "
                    "and the fluid has no viscosity–temperature points"
                )
            else:
                off = rows & ((t < low) | (t > high))
                rules[code] = (
                    f"is outside fluid {shown}'s viscosity data ({low:g}–{high:g} °C), which "
                    "granudb does not extrapolate"
                )
            bad |= off
        header = block.headers.get("temperature_c", "temperature_c")
        problems.add(
            np.flatnonzero(bad),
            lambda pos: ValidationError(
                header,
                f"{temperatures[pos]:g} °C",
                f"{rules[int(codes[pos])]}; nothing was imported into dataset {dataset}",
                row=block.first_row + pos,
            ),
        )


def _refuse_earlier_import(session: Any, dataset: Any, target: ImportTarget) -> None:
    """``ConflictError`` if this file (by sha256) was imported into the dataset before."""
    earlier = session.scalars(
        select(CollisionImport).filter_by(dataset_id=dataset.id, file_sha256=target.sha256())
    ).first()
    if earlier is not None:
        raise ConflictError(
            f"FILE: {target.file_name} was already imported into dataset {target.dataset} "
            f"{target.version} on {earlier.imported_at:%Y-%m-%d %H:%M} ({earlier.rows} "
            "rows); nothing was imported again"
        )


def store_collisions(
    database: Any,
    target: ImportTarget,
    frames: Iterable[Any],
    *,
    progress: Callable[[int], None] | None = None,
    problems: Any = None,
) -> int:
    """Write every block of ``frames`` (``CollisionChunk``s or DataFrames) into ``target``
    in one write transaction.

    What only the database can find (an unknown material or fluid name, a temperature
    outside a fluid's data, a run label already in the dataset) goes to ``problems``
    (``granudb.io.tables.Problems``: every offending row, capped, counted) and the
    blocks are still checked to the end, but nothing more is written and the transaction
    is refused (rolled back) with all of them; without ``problems`` the first is refused
    at once. ``faulty`` blocks (the file had problems) are checked, never written."""
    problems = problems if problems is not None else FirstProblem()
    rows = 0
    with database.session(write=True) as session:
        connection = session.connection()
        source_id = find_source(connection, target.source) if target.source else None
        dataset, _ = datasets.get_or_create_dataset(
            session,
            target.dataset,
            target.version,
            title=target.title,
            license=target.license,
            source_id=source_id,
        )
        if target.file_sha256:
            _refuse_earlier_import(session, dataset, target)
        names = NameIndex(session)
        ranges = FluidRanges(session)
        seen = RunIndex(session.scalars(select(Collision.run).filter_by(dataset_id=dataset.id)))
        hasher = None
        if not len(seen):
            hasher = BlockHasher(
                names.material_by_id,
                names.fluid_by_id,
                keeps_negative_zero=session.get_bind().dialect.name != "sqlite",
            )
        indexes = _indexes_to_rebuild(session, target)
        try:
            for frame in frames:
                block = frame if isinstance(frame, CollisionChunk) else block_from_frame(frame)
                ranges.check(block, target.dataset, problems)
                rows += _store_block(session, dataset, target, block, names, seen, hasher, problems)
                if progress is not None:
                    progress(rows)
            if not target.file_sha256:
                _refuse_earlier_import(session, dataset, target)  # before its runs' repeats
            problems.raise_any()  # rolls the transaction back
            if indexes is not None:
                if hasher is not None:
                    hasher.start()  # hashed on its thread while SQLite builds the indexes
                indexes.create()
            session.add(
                CollisionImport(
                    dataset_id=dataset.id,
                    file_sha256=target.sha256(),
                    file_name=target.file_name[:500],
                    rows=rows,
                )
            )
            if hasher is None:
                update_content_hash(session, dataset)
            else:
                dataset.content_hash = hasher.hexdigest()
                session.flush()
        finally:
            if hasher is not None:
                hasher.close()
    return rows


def _indexes_to_rebuild(session: Any, target: ImportTarget) -> PlainIndexes | None:
    """The plain indexes, dropped until the last row is in, when that pays (SQLite)."""
    if session.get_bind().dialect.name != "sqlite" or not target.expected_rows:
        return None
    indexes = PlainIndexes(session)
    if not rebuild_pays(target.expected_rows, indexes.existing_rows()):
        return None
    indexes.drop()
    return indexes


class RunIndex:
    """The run labels of the dataset so far, for "does this label repeat?".

    Each label is kept as text in an Arrow array (about 11 bytes a label; a Python set of
    a million labels took about 100 MB) and as Python's 64-bit hash of it, all hashes in
    one sorted array (a block's sorted hashes merged in: a stable sort of two sorted runs
    is a merge), so a block is checked by one binary search, not one per earlier block
    (that grew with the square of the blocks: half a second on a million rows). Equal
    hashes are confirmed on the labels themselves before anything is refused.
    """

    def __init__(self, existing: Iterable[str]) -> None:
        self.parts: list[Any] = []
        self.sorted = np.empty(0, dtype=np.int64)
        self.size = 0
        self._last: tuple[list[str], Any] | None = None
        self.add(list(existing))

    def __len__(self) -> int:
        return self.size

    @staticmethod
    def _hashes(runs: list[str]) -> Any:
        return np.sort(np.fromiter(map(hash, runs), dtype=np.int64, count=len(runs)))

    def repeats(self, runs: list[str]) -> bool:
        """Whether ``runs`` repeats a label, within itself or earlier (exact)."""
        hashes = self._hashes(runs)
        self._last = (runs, hashes)  # ``add`` of the same block reuses them
        suspect = bool((hashes[1:] == hashes[:-1]).any())
        if not suspect and len(self.sorted):
            found = np.searchsorted(self.sorted, hashes).clip(0, len(self.sorted) - 1)
            suspect = bool((self.sorted[found] == hashes).any())
        if not suspect:
            return False
        return len(set(runs)) != len(runs) or not self.as_set().isdisjoint(runs)

    def add(self, runs: list[str]) -> None:
        last, self._last = self._last, None
        if runs:
            hashes = last[1] if last is not None and last[0] is runs else self._hashes(runs)
            self.parts.append(pa.array(runs, type=pa.string()))
            self.sorted = np.sort(np.concatenate([self.sorted, hashes]), kind="stable")
            self.size += len(runs)

    def as_set(self) -> set[str]:
        return {run for part in self.parts for run in part.to_pylist()}


def _repeated_runs(
    session: Any,
    dataset: Any,
    target: ImportTarget,
    block: CollisionChunk,
    index: RunIndex,
    problems: Any,
) -> None:
    """Every run label of ``block`` that repeats (in the file, or already in the dataset)
    to ``problems``; a file imported before is refused as that."""
    if not index.repeats(block.runs):
        return
    seen = index.as_set()
    stored = [run in seen for run in block.runs]
    if any(stored) and not target.file_sha256 and isinstance(problems, FirstProblem):
        # The same file again? Finding out finishes (and stops) the reader, so only when
        # the first problem ends the import anyway; a collecting import reads on and asks
        # once the file is read (``store_collisions``).
        _refuse_earlier_import(session, dataset, target)
    here: set[str] = set()
    repeated = np.zeros(len(block), dtype=bool)
    for pos, run in enumerate(block.runs):
        repeated[pos] = bool(run) and (stored[pos] or run in here)  # "": refused already
        here.add(run)
    problems.add(
        np.flatnonzero(repeated),
        lambda pos: ValidationError(
            block.headers.get("run", "run"),
            repr(block.runs[pos]),
            "appears twice (in this file or already in the dataset)",
            row=block.first_row + pos,
        ),
    )


def _store_block(
    session: Any,
    dataset: Any,
    target: ImportTarget,
    block: CollisionChunk,
    names: NameIndex,
    seen: RunIndex,
    hasher: BlockHasher | None,
    problems: Any,
) -> int:
    """Check ``block`` against the catalogue (problems to ``problems``) and write it if
    neither it nor anything before it had a problem; the rows written."""
    first_row = block.first_row
    _repeated_runs(session, dataset, target, block, seen, problems)
    seen.add(block.runs)
    runs = seen.parts[-1] if block.runs else None
    headers = block.headers
    ids = (
        names.ids(
            block.particle,
            names.materials,
            names.material_names,
            headers.get("particle", "particle"),
            first_row,
            problems,
        ),
        names.ids(
            block.wall,
            names.materials,
            names.material_names,
            headers.get("wall", "wall"),
            first_row,
            problems,
        ),
        names.ids(
            block.fluid,
            names.fluids,
            names.fluid_names,
            headers.get("fluid", "fluid"),
            first_row,
            problems,
        ),
    )
    if block.faulty or problems:
        return 0  # checked only: the transaction is refused at the end
    for column, header in ((ids[0], "particle"), (ids[1], "wall")):
        if (column < 0).any():  # a reader checks required names; this is the last guard
            row = first_row + _first(column < 0)
            raise ValidationError(header, "(empty)", "is required", row=row)
    values = unsigned_zeros(block.values)
    if hasher is not None:
        hasher.add(runs, ids, values, block.notes)
    return insert_rows(session, dataset.id, block.runs, ids, values, block.notes)


def insert_collisions(session: Any, dataset_id: int, frame: Any) -> int:
    """Bulk-insert a DataFrame of SI rows whose ids are already resolved (``particle_id``,
    ``wall_id``, ``fluid_id``) in the session's transaction; the count (Data Packages)."""
    n = len(frame)
    if n == 0:
        return 0
    ids = tuple(
        frame[c].to_numpy(dtype="float64", na_value=-1.0).astype(np.int64)
        for c in ("particle_id", "wall_id", "fluid_id")
    )
    runs, values, notes = frame_columns(frame)
    return insert_rows(session, dataset_id, runs, ids, unsigned_zeros(values), notes)
