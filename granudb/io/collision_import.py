"""Importing measured collisions from a CSV file: streamed, validated, all or nothing.

``open_collision_file`` (``granudb.io.collision_file``) reads and maps the header before
any transaction; the rows are then read once, hashed as they are read
(``granudb.io.collision_chunks``), in chunks (memory is bounded whatever the file's size),
converted and checked with vectorized rules, and bulk-inserted by
``granudb.db.collision_store`` in one transaction: bad rows or ragged lines anywhere
reject the whole file, every one of them listed in one refusal that names the file, and
nothing is written. A file (by sha256) is imported into a
dataset at most once.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from granudb.db import datasets
from granudb.db.collision_store import ImportTarget, store_collisions
from granudb.errors import ValidationError
from granudb.io.collision_chunks import HashingFile, Prefetched, arrow_memory, read_chunks
from granudb.io.collision_file import (
    CHUNK_ROWS,
    NUMERIC,
    CollisionFile,
    estimate_rows,
    fill_stated,
    open_collision_file,
    stated_uncertainties,
)
from granudb.io.tables import FileProblems, Problems
from granudb.lazy import pandas as pd
from granudb.vocabulary.text import check_name


@dataclass
class ImportResult:
    dataset: str
    version: str
    rows: int
    sha256: str
    file_name: str


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
    delimiter: str | None = None,
    decimal: str = ".",
    columns: dict[str, str] | None = None,
    uncertainty: dict[str, str] | str | None = None,
) -> ImportResult:
    """Import ``path`` into ``dataset`` (created if new), all or nothing.

    This module reads the header (``open_collision_file``, before any transaction);
    ``granudb.io.collision_chunks`` reads, hashes and checks the rows in one pass;
    ``granudb.db.collision_store`` resolves names, refuses repeated runs, a repeated file
    and temperatures outside a fluid's data, and writes everything in one transaction.
    ``uncertainty`` states the dataset's default standard uncertainty of measured columns
    (``stated_uncertainties``), given to every run whose own ``u_`` cell is empty.
    """
    check_name("dataset", dataset)
    check_name("version", version)
    stated = stated_uncertainties(uncertainty)
    opened = open_collision_file(Path(path), delimiter=delimiter, decimal=decimal, columns=columns)
    name = opened.path.name
    stream = HashingFile(opened.path)
    try:
        with arrow_memory():
            blocks = Prefetched(_with_stated(read_chunks(opened, stream, chunk_rows), stated))

            def digest() -> str:  # the reader thread stops before the rest is hashed
                blocks.close()
                return stream.hexdigest()

            target = ImportTarget(
                dataset,
                version,
                source,
                title,
                license,
                "",
                name,
                digest,
                expected_rows=estimate_rows(opened.path),
            )
            found = Problems(name)  # what only the database finds: names, runs, ranges
            try:
                rows = store_collisions(database, target, blocks, progress=progress, problems=found)
            except FileProblems as exc:  # the file's own problems and the database's
                raise found.merged(exc) from None
            except ValidationError as exc:
                if exc.row is None:
                    raise
                raise FileProblems(name, [exc], 1) from None  # a row's last guard
            finally:
                blocks.close()
            sha256 = stream.hexdigest()
    finally:
        stream.close()
    return ImportResult(dataset, version, rows, sha256, name)


def _with_stated(blocks: Iterator[Any], stated: dict[str, tuple[float, bool]]) -> Iterator[Any]:
    """The blocks with the dataset's default uncertainties filled in (``fill_stated``)."""
    for block in blocks:
        fill_stated(block.values, stated)
        yield block


def collision_frames(source: Path | CollisionFile, chunk_rows: int = CHUNK_ROWS) -> Iterator[Any]:
    """The file's rows as checked SI DataFrames, chunk by chunk, names still as text.

    ``source`` is a path (read as a comma-separated file) or what ``open_collision_file``
    returned. Each frame's ``attrs["first_row"]`` is the spreadsheet row of its first line
    (the header is row 1) and ``attrs["headers"]`` the file's header of each column, so
    later checks can name the row and the column as the file does. (The import reads
    ``CollisionChunk``s, ``granudb.io.collision_chunks``; this is the same rows as frames.)
    """
    if not isinstance(source, CollisionFile):
        source = open_collision_file(Path(source))
    stream = HashingFile(source.path)
    try:
        for block in read_chunks(source, stream, chunk_rows):
            if block.faulty:
                continue  # the file is refused with every problem at the end
            frame = pd.DataFrame({"run": block.runs})
            for column, names in (("particle", block.particle), ("wall", block.wall)):
                frame[column] = block.names_by_row(names)
            frame["fluid"] = block.names_by_row(block.fluid)
            for column in NUMERIC:
                frame[column] = block.values.get(column, np.full(len(block), np.nan))
            frame["notes"] = block.notes if block.notes is not None else None
            frame.attrs["first_row"] = block.first_row
            frame.attrs["headers"] = block.headers
            yield frame
    finally:
        stream.close()
