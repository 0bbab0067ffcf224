"""A dataset's content hash computed from the arrays an import inserts, not re-read.

``granudb.db.datasets.content_hash`` defines the hash (sha256 over the runs sorted by the
UTF-8 bytes of their labels, each written as names and ``repr`` of its SI floats) and
computes it by reading every row back from the database and formatting it in Python, which
took a fifth of a million-row import. An import into an empty dataset already holds exactly
the values it inserts (float64 arrays, the names the database resolved them to), so the
same bytes are produced here, columnar: Arrow formats the floats (the shortest text that
reads back as the same double, the digits ``repr`` writes too), sorts the labels bytewise
and joins the fields, and only the rare float ``repr`` writes in exponent form is
formatted by Python. Tests check the result against ``datasets.content_hash`` of the
stored rows.

Memory: the arrays of every block are kept until the end (about 100 bytes a row for the
usual columns), then formatted and hashed ``HASH_BLOCK_ROWS`` rows at a time.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from granudb.vocabulary import COLLISION_MEASURED as COLUMNS
from granudb.vocabulary import COLLISION_TARGET

#: Rows formatted at once when hashing; bounds the text held in memory (~5 MB).
HASH_BLOCK_ROWS = 20_000
WORKERS = 2
#: Where Arrow's text of a float is ``repr``'s (plus ".0" when integral): ``repr`` is
#: positional for 1e-4 <= |x| < 1e16, Arrow for about 1e-7 <= |x| < 1e10; zero is
#: positional in both. Outside this range Python formats the (rare) value itself.
_POSITIONAL_LOW, _POSITIONAL_HIGH = 1e-4, 1e10
_ALWAYS = [c for c in COLUMNS if c not in COLLISION_TARGET]


def float_texts(values: Any) -> Any:
    """``repr`` of each float64 as an Arrow string array, ``""`` where NaN (no value).

    Arrow's cast writes the shortest round-trip digits, as ``repr`` does; where ``repr``
    switches to exponent form (``1e-05``, ``1e+16``) the few such values are formatted by
    Python, so every element equals ``repr(float(v))``.
    """
    import pyarrow as pa
    import pyarrow.compute as pc

    values = np.asarray(values, dtype=np.float64)
    missing = np.isnan(values)
    magnitude = np.abs(values)
    positional = (magnitude >= _POSITIONAL_LOW) & (magnitude < _POSITIONAL_HIGH)
    positional |= magnitude == 0
    text = pc.cast(pa.array(np.where(positional, values, 0.0)), pa.string())
    integral = pc.invert(pc.match_substring(text, "."))
    text = pc.if_else(integral, pc.binary_join_element_wise(text, ".0", ""), text)
    other = ~positional & ~missing
    if other.any():  # rare: exponent form, formatted by Python
        texts = text.to_numpy(zero_copy_only=False).astype(object)
        texts[other] = [repr(v) for v in values[other].tolist()]
        text = pa.array(texts, type=pa.string())
    if missing.any():
        text = pc.if_else(pa.array(missing), "", text)
    return text


@dataclass
class BlockHasher:
    """Collects the inserted arrays block by block; ``hexdigest`` gives the content hash.

    ``add`` takes the run labels, the resolved material/fluid ids (fluid -1 = dry), the SI
    columns (float64, NaN = no value; a column absent from ``values`` is empty) and the
    notes (None or a list with None for no note).
    """

    runs: list[Any] = field(default_factory=list)
    ids: list[tuple[Any, Any, Any]] = field(default_factory=list)
    values: list[dict[str, Any]] = field(default_factory=list)
    notes: list[Any] = field(default_factory=list)
    sizes: list[int] = field(default_factory=list)

    def add(
        self,
        runs: Any,
        ids: tuple[Any, Any, Any],
        values: dict[str, Any],
        notes: list[str | None] | None,
    ) -> None:
        """Keep one block's rows (``runs`` an Arrow string array); empty columns are not
        kept, so memory is what the file holds."""
        import pyarrow as pa

        self.runs.append(runs)
        self.ids.append(tuple(np.asarray(i, dtype=np.int32) for i in ids))
        self.values.append(
            {c: np.asarray(v, dtype=np.float64) for c, v in values.items() if not np.isnan(v).all()}
        )
        self.notes.append(None if notes is None else pa.array(notes, type=pa.string()))
        self.sizes.append(len(runs))

    def _gather(self, name: str, blocks: Any, local: Any) -> Any:
        """Column ``name`` at the rows given as (block, position in block); None if the
        column is empty in every block. Gathered from the blocks' own arrays, so no column
        is ever copied whole."""
        if not any(name in v for v in self.values):
            return None
        out = np.full(len(local), np.nan)
        for number, values in enumerate(self.values):
            if name in values:
                here = blocks == number
                out[here] = values[name][local[here]]
        return out

    def hexdigest(self, material_names: dict[int, str], fluid_names: dict[int, str]) -> str:
        """sha256 of the collected rows in ``datasets.content_hash``'s canonical form."""
        import pyarrow as pa
        import pyarrow.compute as pc

        digest = hashlib.sha256()
        total = sum(self.sizes)
        if total == 0:
            return digest.hexdigest()
        runs = pa.chunked_array(self.runs, type=pa.string()).combine_chunks()
        self.runs = []
        order = pc.sort_indices(runs.cast(pa.binary())).to_numpy().astype(np.int64)
        ids = [np.concatenate([i[k] for i in self.ids]) for k in range(3)]
        notes = pa.chunked_array(
            [
                pa.nulls(n, pa.string()) if part is None else part
                for part, n in zip(self.notes, self.sizes, strict=True)
            ],
            type=pa.string(),
        ).combine_chunks()
        names = _name_lookup(material_names, fluid_names)
        self.notes, self.ids = [], []
        starts = np.cumsum([0, *self.sizes])
        for start in range(0, total, HASH_BLOCK_ROWS):
            rows = order[start : start + HASH_BLOCK_ROWS]
            blocks = np.searchsorted(starts, rows, side="right") - 1
            local = rows - starts[blocks]
            columns = {c: self._gather(c, blocks, local) for c in COLUMNS}
            digest.update(_block_bytes(runs, ids, columns, notes, rows, names))
        return digest.hexdigest()


def _name_lookup(materials: dict[int, str], fluids: dict[int, str]) -> tuple[Any, Any]:
    """Arrays indexable by id: material names, fluid names ("" at index 0 for dry = -1+1)."""
    import pyarrow as pa

    material_array = [""] * (max(materials, default=0) + 1)
    for i, name in materials.items():
        material_array[i] = name
    fluid_array = [""] * (max(fluids, default=0) + 2)
    for i, name in fluids.items():
        fluid_array[i + 1] = name
    return pa.array(material_array, pa.string()), pa.array(fluid_array, pa.string())


def _float_columns(columns: dict[str, Any]) -> dict[str, Any]:
    """``float_texts`` of each non-empty column, two at a time (Arrow's casts release
    the GIL, so both cores format)."""
    from concurrent.futures import ThreadPoolExecutor

    present = {c: v for c, v in columns.items() if v is not None}
    with ThreadPoolExecutor(max_workers=WORKERS) as pool:
        return dict(zip(present, pool.map(float_texts, present.values()), strict=True))


def _block_bytes(
    runs: Any, ids: list[Any], columns: dict[str, Any], notes: Any, rows: Any, names: Any
) -> memoryview:
    """The canonical text of ``rows`` (already in hash order) as UTF-8 bytes; ``columns``
    are the SI columns at those rows (None = empty)."""
    import pyarrow as pa
    import pyarrow.compute as pc

    materials, fluids = names
    take = pa.array(rows)
    empty = pa.array([""] * len(rows), type=pa.string())
    texts = _float_columns(columns)
    fields = [
        runs.take(take),
        materials.take(pa.array(ids[0][rows])),
        materials.take(pa.array(ids[1][rows])),
        fluids.take(pa.array(ids[2][rows] + 1)),
        *(texts.get(c, empty) for c in _ALWAYS),
        pc.fill_null(notes.take(take), ""),
    ]
    kept = pc.binary_join_element_wise(*fields, "\x1f")
    has_target = np.zeros(len(rows), dtype=bool)
    for c in COLLISION_TARGET:
        if columns[c] is not None:
            has_target |= ~np.isnan(columns[c])
    if has_target.any():
        target = pc.binary_join_element_wise(
            *(texts.get(c, empty) for c in COLLISION_TARGET), "\x1f"
        )
        kept = pc.if_else(
            pa.array(has_target), pc.binary_join_element_wise(kept, target, "\x1f"), kept
        )
    line = pc.binary_join_element_wise(kept, "", "\x1e")
    offsets = np.frombuffer(line.buffers()[1], dtype=np.int32)[line.offset :]
    return memoryview(line.buffers()[2])[int(offsets[0]) : int(offsets[len(line)])]
