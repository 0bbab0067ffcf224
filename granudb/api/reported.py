"""Runs as papers report them: import, list and fit (``granudb reported …``; issue 37).

A paper often gives, per run, e, e_t, ω_out or an incidence angle rather than the
velocities. These are stored as such in ``reported_runs`` (what was stated, with its u),
listed with what follows from them by stated relations, and fitted: a run with e enters
the restitution fit of its pair, a run with θ and e_t and no spin in enters a Walton fit
through the exact relations of ``granudb.physics.reported``. No velocity is made or shown
(docs/reference/index.md, "Runs as papers report them").
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from granudb.analysis import reported_runs as analysis
from granudb.api import inputs
from granudb.api.database import opened
from granudb.db import reported_store
from granudb.errors import ValidationError
from granudb.io import reported_file
from granudb.vocabulary.text import check_text

#: The columns ``granudb reported list`` shows (JSON and CSV) and those a table shows.
REPORTED_COLUMNS = [
    "collection", "run", "particle", "wall", "fluid", "diameter_m", "incidence_angle_rad",
    "normal_restitution", "tangential_restitution", "omega_out_rad_s",
    "u_incidence_angle_rad", "u_normal_restitution", "u_tangential_restitution",
    "u_omega_out_rad_s", "no_spin_in", "stated", "effective_incidence", "effective_rebound",
    "derived_by", "source", "source_locator", "digitiser", "licence", "reference_package",
    "notes",
]  # fmt: skip
REPORTED_NARROW = [
    "collection", "run", "particle", "wall", "incidence_angle_rad", "normal_restitution",
    "tangential_restitution", "omega_out_rad_s", "effective_incidence", "effective_rebound",
]  # fmt: skip
#: The fits of reported runs.
REPORTED_FITS = ("walton", "restitution")
YES, NO = ("yes", "true", "1", "y"), ("no", "false", "0", "n", "")


def _cell(text: str, column: str, unit: str | None, field: str, row: int) -> Any:
    if column in ("run", "particle", "wall", "fluid"):
        return text or None
    if column in ("source_locator", "digitiser", "licence", "notes"):
        return check_text(column, text) if text else None
    if column == "no_spin_in":
        if text.lower() in YES:
            return True
        if text.lower() in NO:
            return False
        raise ValidationError(field, text, "must be yes or no", row=row)
    if not text:
        return None
    spelled = f"{text} {unit}" if unit else text
    base = column.removeprefix("u_")
    try:
        value = inputs.quantity(spelled, base, field, check=column == base)
    except ValidationError as exc:
        raise ValidationError(field, exc.value, exc.rule, row=row) from None
    if column != base and not (value is not None and math.isfinite(value) and value >= 0):
        raise ValidationError(field, text, "must be a finite number ≥ 0", row=row)
    return value


def import_reported_runs(
    file: str | Path,
    *,
    collection: str,
    source: str | None = None,
    no_spin_in: bool = False,
    db: Any = None,
) -> dict[str, Any]:
    """Import a CSV file of runs as a paper reports them into ``collection`` (columns:
    ``granudb.io.reported_file``); ``source`` a source key for every run; ``no_spin_in``
    states for every row without its own ``no_spin_in`` cell that the sphere arrived
    without spin. A bad cell, an unknown name or a velocity column is refused in one line
    and nothing is stored. Returns the collection and the number of runs stored.

    Examples
    --------
    >>> import granudb
    >>> path = tmp / "paper.csv"
    >>> _ = path.write_text("run,particle,wall,e\\nr1,steel,Zerodur,0.95\\n")
    >>> granudb.import_reported_runs(path, collection="a paper", db=db)["runs"]
    1
    """
    name = check_text("collection", inputs.text(collection, "collection"))
    headers, raw = reported_file.read(Path(file))
    rows = []
    for number, cells in enumerate(raw, start=2):
        row: dict[str, Any] = {}
        for header, (column, unit) in headers.items():
            row[column] = _cell(cells[header], column, unit, header.strip(), number)
        for needed in ("run", "particle", "wall"):
            if not row.get(needed):
                raise ValidationError(needed, "''", "is empty", row=number)
        if row.get("normal_restitution") is None and row.get("tangential_restitution") is None:
            raise ValidationError("e", "''", "a run states e or e_t (or both)", row=number)
        row.setdefault("no_spin_in", no_spin_in)
        if source is not None:
            row["source"] = inputs.text(source, "source")
        rows.append(row)
    with opened(db) as database, database.session(write=True) as session:
        count = reported_store.store(session, name, rows)
    return {"collection": name, "runs": count}


def reported_runs(collection: str | None = None, *, db: Any = None) -> list[dict[str, Any]]:
    """Every run as its paper reports it (of ``collection``): what the paper states, with
    its u, and Ψ_in, Ψ_out where the exact no-spin-in relation gives them (``derived_by``
    says which relation, or why not). No velocity column.

    Examples
    --------
    >>> import granudb
    >>> path = tmp / "angles.csv"
    >>> _ = path.write_text("run,particle,wall,incidence_angle [deg],e,e_t\\n"
    ...                     "k1,steel,Zerodur,45,0.98,0.9\\n")
    >>> _ = granudb.import_reported_runs(path, collection="angles", no_spin_in=True, db=db)
    >>> run = granudb.reported_runs("angles", db=db)[0]
    >>> round(run["effective_incidence"], 6), round(run["effective_rebound"], 6)
    (1.0, 0.65)
    """
    with opened(db) as database, database.session() as session:
        records = reported_store.read(session, collection)
    return [analysis.derived(r) for r in records]


def fit_reported(
    collection: str | None = None,
    *,
    model: str = "walton",
    seed: int = 0,
    db: Any = None,
) -> list[dict[str, Any]]:
    """Fit runs as papers report them: ``model`` "walton" (β, μ_f and ē of the runs with
    θ, e_t, e and no spin in, through the exact relations; ``relation`` says which) or
    "restitution" (ē of the runs that state e, with its t interval), per collection,
    particle, wall and fluid.

    Examples
    --------
    >>> import granudb
    >>> path = tmp / "e only.csv"
    >>> _ = path.write_text("run,particle,wall,e\\nr1,steel,Zerodur,0.95\\n"
    ...                     "r2,steel,Zerodur,0.97\\n")
    >>> _ = granudb.import_reported_runs(path, collection="e only", db=db)
    >>> fit = granudb.fit_reported("e only", model="restitution", db=db)[0]
    >>> fit["n_runs"], round(fit["normal_restitution_mean"], 4)
    (2, 0.96)
    """
    if model not in REPORTED_FITS:
        raise ValidationError("model", model, f"is not one of {', '.join(REPORTED_FITS)}",
                              parameter=True)  # fmt: skip
    with opened(db) as database, database.session() as session:
        records = reported_store.read(session, collection)
    if model == "walton":
        return analysis.walton(records, seed)
    return analysis.restitution(records)
