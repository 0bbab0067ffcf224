"""Adding and removing measured collisions: ``granudb collisions import`` and
``granudb collisions remove`` (``dataset remove-runs`` is the same function).

An import reads a CSV file (one row per run, units in the headers; README "Importing
collisions" lists the columns and rules) and writes all of it or none, in one
transaction; the same file is never imported into the same dataset twice.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from granudb.api import inputs
from granudb.api.consent import Confirm, agreed, unchanged
from granudb.api.database import opened
from granudb.db import datasets as dataset_store
from granudb.io.collision_import import ImportResult
from granudb.io.collision_import import import_collisions as import_file
from granudb.io.tables import column_mapping


def import_collisions(
    file: str | Path,
    *,
    dataset: str | None = None,
    version: str = "1.0.0",
    source: str | None = None,
    title: str | None = None,
    license: str | None = None,
    delimiter: str | None = None,
    decimal: str = ".",
    columns: dict[str, str] | str | Path | None = None,
    uncertainty: dict[str, str] | str | None = None,
    progress: Callable[[int], None] | None = None,
    db: Any = None,
) -> ImportResult:
    """Import a CSV of collisions into ``dataset`` (created, with ``title``, ``license``
    and ``source``, if new) at ``version``: every row or none. ``delimiter`` is ``,``,
    ``;`` or ``tab`` (None: ``;`` or tab where the header has them and no comma);
    ``decimal`` is ``.`` or ``,`` (never guessed); ``columns`` maps a lab's own headers
    to granudb's columns (``{"speed [mm/s]": "v_n_in", "shot": "run"}``, the same as text
    ``"speed [mm/s]=v_n_in,shot=run"``, or a file of such lines); ``uncertainty`` states
    the dataset's default standard uncertainty of measured columns (``{"v_n_in": "± 3 %",
    "v_n_out": "± 0.5 mm/s"}``, or ``"v_n_in=± 3 %, v_n_out=± 0.5 mm/s"``), given to every
    run whose file leaves its ``u(v_n_in) [mm/s]`` cell empty; ``progress(rows)`` is
    called as rows are read. Every problem of the file is refused at once, in row order.
    Returns the dataset, version, row count and the file's sha256.

    Examples
    --------
    >>> import granudb
    >>> result = granudb.import_collisions(example_csv, dataset="example", db=db)
    >>> result.rows
    12
    """
    if dataset is None:
        raise inputs.missing("dataset", "is required: the dataset to add the runs to")
    inputs.name(dataset, "dataset")
    inputs.name(version, "version")
    path = Path(inputs.path(file, "file"))
    mapping = column_mapping(columns)
    with opened(db) as database:
        return import_file(
            database,
            path,
            dataset=dataset,
            version=version,
            source=source,
            title=title,
            license=license,
            delimiter=delimiter,
            decimal=decimal,
            columns=mapping,
            uncertainty=uncertainty,
            progress=progress,
        )


def remove_collisions(
    dataset: str,
    runs: Sequence[str],
    *,
    version: str | None = None,
    confirm: Confirm | None = None,
    db: Any = None,
) -> int:
    """Delete runs (by label) from a draft dataset version (``dataset`` as NAME or
    NAME@VERSION); returns how many. ``confirm(action, losses)`` is asked first (the
    command line's prompt); without it the call itself is the consent.

    Examples
    --------
    >>> import granudb
    >>> _ = granudb.import_collisions(example_csv, dataset="trimmed", db=db)
    >>> granudb.remove_collisions("trimmed", ["steel-dry-1"], db=db)
    1
    """
    name, version = inputs.dataset_ref(dataset, version)
    labels = [inputs.text(run, "runs") for run in inputs.sequence(runs, "runs")]
    action = f"collisions remove {dataset}"
    with opened(db) as database:
        with database.session() as session:
            losses = _losses(session, name, version, labels)
        agreed(confirm, action, losses)
        with database.session(write=True) as session:
            unchanged(action, losses, _losses(session, name, version, labels))
            chosen = dataset_store.get_dataset(session, name, version)
            wanted = dataset_store.runs_to_remove(session, chosen, labels)
            return dataset_store.remove_runs(session, chosen, wanted)


def _losses(session: Any, name: str, version: str | None, runs: list[str]) -> list[str]:
    chosen = dataset_store.get_dataset(session, name, version)
    wanted = dataset_store.runs_to_remove(session, chosen, runs)
    few = ", ".join(wanted[:5]) + (f", … {len(wanted) - 5} more" if len(wanted) > 5 else "")
    return [f"{len(wanted)} runs of dataset {dataset_store.label(chosen)} ({few})"]
