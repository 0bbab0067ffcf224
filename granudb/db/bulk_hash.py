"""A dataset's content hash computed from the arrays an import inserts, not re-read.

``granudb.db.content_hash`` defines the hash (sha256 over the runs sorted by the
UTF-8 bytes of their labels, each written as names and ``repr`` of its SI floats) and
computes it by reading every row back from the database and formatting it in Python, which
took a fifth of a million-row import. An import into an empty dataset already holds exactly
the values it inserts (float64 arrays, the names the database resolved them to), so the
same bytes are produced here, columnar: Arrow formats the floats (the shortest text that
reads back as the same double, the digits ``repr`` writes too), sorts the labels bytewise
and joins the fields, and only the rare float ``repr`` writes in exponent form is
formatted by Python. Tests check the result against ``content_hash.content_hash`` of the
stored rows.

When: only the sort needs every row, so each block's text after its run label (names,
floats, notes) is written as soon as the block is added, on one worker thread, while the
block is inserted (Arrow's kernels release the GIL, and so does SQLite inside each step,
so the two cores work at once). Formatting after the last insert took about a fifth of a
million-row import. What is kept is that text (about as large as the float64 arrays it
replaces: about 100 bytes a row for the usual columns); at the end the labels are sorted
and the texts gathered in that order and hashed ``HASH_BLOCK_ROWS`` rows at a time.
"""

from __future__ import annotations

import hashlib
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np

from granudb.db.content_hash import (
    ALWAYS_HASHED,
    FIELD_SEPARATOR,
    ROW_SEPARATOR,
    TARGET_HASHED,
    UNCERTAINTY_HASHED,
)
from granudb.lazy import pyarrow as pa
from granudb.lazy import pyarrow_compute as pc
from granudb.vocabulary.text import name_key

#: Rows formatted at once when hashing; bounds the text held in memory (~5 MB).
HASH_BLOCK_ROWS = 20_000
#: Where Arrow's text of a float is ``repr``'s (plus ".0" when integral): ``repr`` is
#: positional for 1e-4 <= |x| < 1e16, Arrow for about 1e-7 <= |x| < 1e10; zero is
#: positional in both. Outside this range Python formats the (rare) value itself.
_POSITIONAL_LOW, _POSITIONAL_HIGH = 1e-4, 1e10


def float_texts(values: Any) -> Any:
    """``repr`` of each float64 as an Arrow string array, ``""`` where NaN (no value).

    Arrow's cast writes the shortest round-trip digits, as ``repr`` does; where ``repr``
    switches to exponent form (``1e-05``, ``1e+16``) the few such values are formatted by
    Python, so every element equals ``repr(float(v))``. A column holding one value in
    every row (a diameter, a temperature) is formatted once; the ``.0`` that ``repr``
    adds to an integral value is looked for only when numpy finds an integral value.
    """
    values = np.asarray(values, dtype=np.float64)
    bits = values.view(np.int64)
    if len(values) > 1 and (bits == bits[0]).all():  # bitwise: 0.0 and -0.0 differ
        return pa.repeat(float_texts(values[:1])[0], len(values))
    missing = np.isnan(values)
    magnitude = np.abs(values)
    positional = (magnitude >= _POSITIONAL_LOW) & (magnitude < _POSITIONAL_HIGH)
    positional |= magnitude == 0
    cast = np.where(positional, values, 0.0)
    text = pc.cast(pa.array(cast), pa.string())
    if (cast == np.trunc(cast)).any():  # Arrow writes "20" where repr writes "20.0"
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


class BlockHasher:
    """Takes the inserted rows block by block; ``hexdigest`` gives the content hash.

    ``material_names`` and ``fluid_names`` map ids to names. ``add`` takes the run labels
    (an Arrow string array), the resolved material/fluid ids (fluid -1 = dry), the SI
    columns (float64, NaN = no value; a column absent from ``values`` is empty) and the
    notes (None or a list with None for no note), and hands the formatting to the worker
    thread; nothing it is given may change afterwards. ``close`` stops the worker (an
    import that fails does not wait for texts it will never hash). ``keeps_negative_zero``
    is False where the database reads a stored -0.0 back as 0.0 (SQLite).

    Kept per row: the run label (the caller's array, not copied), the text of the floats
    and notes, and one 32-bit code for the (particle, wall, fluid) names, whose text is
    kept once per distinct triple (a million rows name a handful: about 25 bytes a row
    less than keeping the names' text).
    """

    def __init__(
        self,
        material_names: dict[int, str],
        fluid_names: dict[int, str],
        *,
        keeps_negative_zero: bool = True,
    ) -> None:
        self._names = _Names(material_names, fluid_names)
        self._signed = keeps_negative_zero
        self._runs: list[Any] = []
        self._texts: list[Any] = []
        self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix="granudb-hash")
        self._digest: Any = None

    def add(
        self,
        runs: Any,
        ids: tuple[Any, Any, Any],
        values: dict[str, Any],
        notes: list[str | None] | None,
    ) -> None:
        """Queue one block's rows for formatting (in the order the rows are inserted)."""
        self._runs.append(runs)
        if not self._signed:
            values = {c: _unsigned_zero(v) for c, v in values.items()}
        self._texts.append(self._pool.submit(_row_texts, self._names, ids, values, notes))

    def close(self) -> None:
        """Stop the worker; formatting not yet started is dropped."""
        self._pool.shutdown(wait=True, cancel_futures=True)

    def start(self) -> None:
        """Begin the digest on the worker thread, after the blocks queued before it, so
        the caller works meanwhile (the import creates its indexes: SQLite releases the
        GIL for the whole statement)."""
        if self._digest is None:
            self._digest = self._pool.submit(self._compute)

    def hexdigest(self) -> str:
        """sha256 of the collected rows in ``granudb.db.content_hash``'s canonical form."""
        self.start()
        try:
            return self._digest.result()
        finally:
            self.close()

    def _compute(self) -> str:
        """The digest (on the worker thread: every block before it is formatted)."""
        done = [future.result() for future in self._texts]
        self._texts = []
        digest = hashlib.sha256()
        sizes = [len(texts) for _, texts in done]
        total = sum(sizes)
        if total == 0:
            return digest.hexdigest()
        codes = np.concatenate([codes for codes, _ in done])
        texts = [texts for _, texts in done]
        del done
        prefixes = pa.array(self._names.prefixes, type=pa.string())
        runs, self._runs = self._runs, []
        order = pc.sort_indices(pa.chunked_array(runs, type=pa.string()).cast(pa.binary()))
        order = order.to_numpy().astype(np.int64)
        starts = np.cumsum([0, *sizes])
        for start in range(0, total, HASH_BLOCK_ROWS):
            rows = order[start : start + HASH_BLOCK_ROWS]
            plan = _Gather(starts, rows)
            line = pc.binary_join_element_wise(
                plan.take(runs),
                prefixes.take(pa.array(codes[rows])),
                plan.take(texts),
                FIELD_SEPARATOR,
            )
            digest.update(_data(line))
        return digest.hexdigest()


class _Names:
    """The text of each (particle, wall, fluid) triple of ids met so far, by code.

    Used by the worker thread only, until ``hexdigest`` reads ``prefixes`` after the
    worker has finished."""

    def __init__(self, materials: dict[int, str], fluids: dict[int, str]) -> None:
        self.materials = materials
        self.fluids = fluids
        self.codes: dict[tuple[int, int, int], int] = {}
        self.prefixes: list[str] = []

    def encode(self, ids: tuple[Any, Any, Any]) -> Any:
        """A 32-bit code by row for its (particle, wall, fluid) names."""
        particle, wall, fluid = (np.asarray(i, dtype=np.int64) for i in ids)
        # One integer per triple (ids are small: a key never comes near 2**63).
        span = max(int(particle.max(initial=0)), int(wall.max(initial=0))) + 1
        fluids = int(fluid.max(initial=0)) + 2
        key = (particle * span + wall) * fluids + (fluid + 1)
        distinct, inverse = np.unique(key, return_inverse=True)
        lookup = np.empty(len(distinct), dtype=np.int32)
        for k, value in enumerate(distinct.tolist()):
            pair, fluid_id = divmod(value, fluids)
            triple = (*divmod(pair, span), fluid_id - 1)
            if triple not in self.codes:
                self.codes[triple] = len(self.prefixes)
                self.prefixes.append(
                    FIELD_SEPARATOR.join(  # canonical names, as content_hash writes them
                        (
                            name_key(self.materials[triple[0]]),
                            name_key(self.materials[triple[1]]),
                            name_key(self.fluids.get(triple[2], "")),
                        )
                    )
                )
            lookup[k] = self.codes[triple]
        return lookup[np.asarray(inverse).reshape(-1)]


class _Gather:
    """Where the overall positions ``rows`` fall in arrays kept one per block, so each
    array is taken block by block (``take`` on a chunked array of strings joins the
    chunks first: about eight times slower here)."""

    def __init__(self, starts: Any, rows: Any) -> None:
        blocks = np.searchsorted(starts, rows, side="right") - 1
        grouped = np.argsort(blocks, kind="stable")  # by block, in ``rows`` order within
        self.parts = []
        for number in np.unique(blocks):
            here = grouped[blocks[grouped] == number]
            self.parts.append((int(number), rows[here] - starts[number]))
        self.back = np.empty_like(grouped)
        self.back[grouped] = np.arange(len(grouped))

    def take(self, arrays: list[Any]) -> Any:
        """``arrays`` (one per block) at ``rows``, in that order."""
        parts = [arrays[number].take(pa.array(local)) for number, local in self.parts]
        return pa.concat_arrays(parts).take(pa.array(self.back))


def _data(line: Any) -> memoryview:
    """The UTF-8 bytes of a string array's values, end to end."""
    offsets = np.frombuffer(line.buffers()[1], dtype=np.int32)[line.offset :]
    return memoryview(line.buffers()[2])[int(offsets[0]) : int(offsets[len(line)])]


def _row_texts(
    names: _Names,
    ids: tuple[Any, Any, Any],
    values: dict[str, Any],
    notes: list[str | None] | None,
) -> tuple[Any, Any]:
    """(names' code by row, each row's canonical text after its names): the floats, notes
    (and the target sphere's columns and the stated uncertainties, as
    ``granudb.db.content_hash`` says when), joined by the unit separator,
    then the record separator that ends the row. Runs on the worker thread."""
    n = len(ids[0])
    columns = {
        c: _column(values.get(c)) for c in (*ALWAYS_HASHED, *TARGET_HASHED, *UNCERTAINTY_HASHED)
    }
    texts = {c: float_texts(v) for c, v in columns.items() if v is not None}
    empty = pa.array([""] * n, type=pa.string())
    note_texts = empty if notes is None else pc.fill_null(pa.array(notes, pa.string()), "")
    kept = pc.binary_join_element_wise(
        *(texts.get(c, empty) for c in ALWAYS_HASHED), note_texts, FIELD_SEPARATOR
    )
    has_stated = _has_any(columns, UNCERTAINTY_HASHED, n)
    has_target = _has_any(columns, TARGET_HASHED, n) | has_stated
    for group, present in ((TARGET_HASHED, has_target), (UNCERTAINTY_HASHED, has_stated)):
        if present.any():
            more = pc.binary_join_element_wise(
                *(texts.get(c, empty) for c in group), FIELD_SEPARATOR
            )
            kept = pc.if_else(
                pa.array(present), pc.binary_join_element_wise(kept, more, FIELD_SEPARATOR), kept
            )
    return names.encode(ids), pc.binary_join_element_wise(kept, "", ROW_SEPARATOR)


def _has_any(columns: dict[str, Any], group: tuple[str, ...], n: int) -> Any:
    """By row: does any column of ``group`` hold a value?"""
    present = np.zeros(n, dtype=bool)
    for c in group:
        if columns[c] is not None:
            present |= ~np.isnan(columns[c])
    return present


def _unsigned_zero(values: Any) -> Any:
    """``values`` with -0.0 as 0.0: SQLite stores an integral REAL as an integer, so a
    stored -0.0 reads back as 0.0, and the hash is of what the database gives back."""
    values = np.asarray(values, dtype=np.float64)
    return values + 0.0 if (values == 0).any() else values


def _column(values: Any) -> Any:
    """A float64 column, or None when it holds no value at all."""
    if values is None:
        return None
    values = np.asarray(values, dtype=np.float64)
    return None if np.isnan(values).all() else values
