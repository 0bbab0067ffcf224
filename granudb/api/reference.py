"""The reference library: published collision data shipped as datasets, and how granudb's
fits and models reproduce them (docs/reference/index.md).

``reference_list()`` names the datasets; ``reference_show(name)`` gives one dataset's
reported values with their provenance; ``reference_reproduce(name)`` runs the fits and
predictions that apply to it and returns each check with its verdict
(``granudb.analysis.reference_checks``).
"""

from __future__ import annotations

import math
import re
from typing import Any

from granudb.analysis import reference_checks
from granudb.api import inputs
from granudb.api.database import opened
from granudb.db import catalog_rows, reported_store, source_changes
from granudb.dem import reference_runs
from granudb.errors import NotFoundError, ValidationError
from granudb.io import reference_library
from granudb.vocabulary.text import check_text

#: The columns ``granudb reference list`` shows.
REFERENCE_COLUMNS = ["name", "version", "values", "title", "licences", "path"]
#: The columns of a reproduction's checks (JSON and CSV), and those a table shows under
#: each kind of check (the reported and computed cells carry their u: "0.092 ± 0.0003").
REFERENCE_CHECK_COLUMNS = list(reference_checks.CHECK_KEYS)
REFERENCE_CHECK_NARROW = ["point", "quantity", "reported", "computed", "residual", "verdict"]
#: The columns ``granudb reference list`` shows in a table.
REFERENCE_NARROW = ["name", "version", "values", "title"]
#: The columns of a DEM reproduction's rows, and those a table shows.
REFERENCE_DEM_COLUMNS = [
    "code",
    "point",
    "angle_deg",
    "status",
    *reference_checks.CHECK_KEYS[3:10],
    "note",
]
REFERENCE_DEM_NARROW = ["code", "point", "angle_deg", "reported", "computed", "residual", "verdict"]
#: The datasets a DEM deck reproduces (a dry oblique sweep), and the codes it runs in.
DEM_REFERENCE = ("kharaz-gorham-salman-2001",)
DEM_REFERENCE_CODES = ("liggghts", "lammps", "yade")
#: The columns ``granudb reference show`` prints in a table.
REFERENCE_VALUE_COLUMNS = ["point", "quantity", "value", "unit", "u", "role", "locator"]


def reference_list() -> list[dict[str, Any]]:
    """Every reference dataset shipped with granudb: name, version, number of values,
    title, licences and the folder of its Data Package.

    Examples
    --------
    >>> import granudb
    >>> "vssuq-dry-collisions" in [d["name"] for d in granudb.reference_list()]
    True
    """
    found = []
    for name in reference_library.names():
        meta = reference_library.descriptor(name)
        found.append(
            {
                "name": name,
                "version": meta["version"],
                "values": meta["granudb_reference"]["values"],
                "title": meta["title"],
                "licences": "; ".join(item["title"] for item in meta["licenses"]),
                "path": str(reference_library.package_dir(name)),
            }
        )
    return found


def reference_show(name: str) -> dict[str, Any]:
    """One reference dataset: its descriptor's fields and every reported value (text as
    written in the package, with source, locator, digitiser, licence, u, repository, file
    and commit).

    Examples
    --------
    >>> import granudb
    >>> shown = granudb.reference_show("kharaz-gorham-salman-2001")
    >>> sorted({v["role"] for v in shown["values"]})
    ['condition', 'measured']
    """
    meta = reference_library.descriptor(name)
    return {
        "name": name,
        "version": meta["version"],
        "title": meta["title"],
        "sources": [s["title"] for s in meta["sources"]],
        "licences": [item["title"] for item in meta["licenses"]],
        "meanings": meta["granudb_reference"]["meanings"],
        "path": str(reference_library.package_dir(name)),
        "values": reference_library.values(name),
    }


def reference_reproduce(name: str) -> dict[str, Any]:
    """Run granudb's fits and model predictions against reference dataset ``name``: each
    check (reported value, what granudb computes, residual, combined u, verdict) and a
    summary in sentences.

    Examples
    --------
    >>> import granudb
    >>> result = granudb.reference_reproduce("vssuq-dry-collisions")
    >>> {c["verdict"] for c in result["checks"]}
    {'agrees'}
    """
    rows = reference_library.values(name)
    if name == "kharaz-gorham-salman-2001":
        found = reference_checks.kharaz(name, rows)
    elif name == "vssuq-dry-collisions":
        found = reference_checks.vssuq(name, rows)
    elif name == "gondret-lance-petit-2002":
        found = reference_checks.gondret(name, rows)
    elif name == "joseph-hunt-2004-walberla":
        seeded = reference_library.values("joseph-hunt-2004-tables")
        found = reference_checks.joseph_walberla(name, rows, seeded)
    elif name == "joseph-hunt-2004-tables":
        walberla = reference_library.values("joseph-hunt-2004-walberla")
        found = reference_checks.joseph_tables(name, rows, walberla)
    else:
        found = {"checks": [], "summary": ["no reproduction is defined for this dataset"]}
    meta = reference_library.descriptor(name)
    return {
        "name": name,
        "version": meta["version"],
        "title": meta["title"],
        "summary": found["summary"],
        "checks": found["checks"],
        "curves": found.get("curves", {}),
    }


def reference_dem(
    name: str,
    codes: list[str] | None = None,
    points: list[str] | None = None,
) -> dict[str, Any]:
    """Run the DEM deck a reference dataset states in LIGGGHTS, LAMMPS and Yade over its
    conditions, and compare each code's output with the experiment per point: e_t per
    incidence angle for Kharaz et al. (the codes run with the dataset's e and μ_f; each
    code's e_t from its rebound by the exact no-spin-in relation), verdict within 2 u_c of
    the experiment's u. ``codes``: a subset of ``DEM_REFERENCE_CODES``; ``points``: the
    dataset's figure points to run (``et-01`` …; all when None). A code that is not
    installed gives "not checked" rows.

    Examples
    --------
    >>> import granudb
    >>> out = granudb.reference_dem("kharaz-gorham-salman-2001", codes=["lammps"],
    ...                             points=["et-05"])
    >>> out["rows"][0]["point"], out["rows"][0]["status"] in ("checked", "not checked")
    ('et-05', True)
    """
    if name not in DEM_REFERENCE:
        reference_library.package_dir(name)  # an unknown name: "did you mean"
        raise ValidationError(
            "name",
            name,
            "has no DEM reproduction: only a dry oblique sweep "
            f"({', '.join(DEM_REFERENCE)}) is run in the codes; a wet case needs e(St), "
            "which a constant-e deck cannot follow (granudb dem verify says so per speed)",
            parameter=True,
        )
    chosen = list(codes) if codes else list(DEM_REFERENCE_CODES)
    for code in chosen:
        if code not in DEM_REFERENCE_CODES:
            raise ValidationError(
                "codes", code, f"is not one of {', '.join(DEM_REFERENCE_CODES)}", parameter=True
            )
    rows = reference_library.values(name)
    conditions = {r["quantity"]: float(r["value"]) for r in rows if r["point"] == "conditions"}
    measured = reference_checks.figure_points(rows, "et")
    known = [p["point"] for p in measured]
    if points:
        for given in points:
            if given not in known:
                raise ValidationError(
                    "points", given, f"is not one of {', '.join(known)}", parameter=True
                )
        measured = [p for p in measured if p["point"] in points]
    angles = [math.degrees(p["theta"]) for p in measured]
    provenance = f"reference dataset {name} conditions"
    found = reference_runs.oblique_sweep(conditions, angles, chosen, provenance)
    out = []
    for row in found:
        point = next(p for p, a in zip(measured, angles, strict=True) if a == row["angle_deg"])
        check = reference_checks.compare(
            f"{row['code']}: e_t from its rebound",
            point["point"],
            "tangential_restitution",
            (row["tangential_restitution"], 0.0),
            (point["value"], point["u"]),
            row["note"] or "",
        )
        if row["status"] != "checked":
            check["verdict"] = "not checked"
        out.append({**check, **{k: row[k] for k in ("code", "angle_deg", "status", "note")}})
    return {
        "name": name,
        "inputs": {k: conditions[k] for k in sorted(conditions)},
        "rows": out,
    }


def _package_source(session: Any, name: str, meta: dict[str, Any]) -> str:
    """The source key runs imported from reference package ``name`` cite: the package's
    name, added (citation, DOI, year of the publication) when the database lacks it."""
    connection = session.connection()
    try:
        catalog_rows.source_id(connection, name)
    except NotFoundError:
        cited = "; ".join(s["title"] for s in meta["sources"])
        doi = re.search(r"doi:(10\.\S+?)\.?$", meta["sources"][0]["title"])
        year = re.search(r"\((\d{4})\)", cited)
        values: dict[str, Any] = {
            "key": name,
            "citation": cited,
            "notes": f"granudb reference dataset {name} (cite it as its CITATION.cff says)",
        }
        if doi:
            values["doi"] = doi.group(1)
        if year:
            values["year"] = int(year.group(1))
        source_changes.add_source(session, values)
    return name


def reference_import(
    name: str,
    *,
    collection: str | None = None,
    materials: dict[str, str] | None = None,
    db: Any = None,
) -> dict[str, Any]:
    """Import reference dataset ``name`` (a shipped one, or the folder of a lab's own
    package written as ``tools/build_reference.py`` writes them) into the database as
    reported runs (collection ``collection``, the dataset's name when None): one run per
    point that states a measured e or e_t, each with its u, source (the package, added as
    a source citing the publication), locator, digitiser, licence and the package's name
    and version; list and fit them with ``reported_runs`` and ``fit_reported``.
    ``materials`` maps a particle or wall name of the package to a material of the
    database ("aluminium oxide" → "alumina"). The same version imported twice is refused
    in one line, nothing stored. Returns the collection, the number of runs and the
    quantities left in the package.

    Examples
    --------
    >>> import granudb
    >>> done = granudb.reference_import(
    ...     "kharaz-gorham-salman-2001", db=db,
    ...     materials={"aluminium oxide": "alumina",
    ...                "soda-lime glass": "soda-lime glass (Kharaz anvil)"})
    >>> done["runs"], done["version"]
    (11, '1.0.0')
    """
    given = inputs.text(name, "name")
    meta = reference_library.descriptor(given)
    name = meta["name"]
    chosen = check_text("collection", inputs.text(collection or name, "collection"))
    mapping = {}
    for package_name, ours in (materials or {}).items():
        if not str(package_name).strip() or not str(ours).strip():
            rule = "must be PACKAGE=DATABASE, both names given"
            raise ValidationError("materials", f"{package_name}={ours}", rule, parameter=True)
        mapping[inputs.text(package_name, "materials")] = inputs.text(ours, "materials")
    runs, left = reference_library.reported_runs(given)
    if not runs:
        raise ValidationError(
            "name", name, "states no run with a measured e or e_t (its values are conditions, "
            f"derived and fitted numbers): read them with `granudb reference show {name}`",
            parameter=True,
        )  # fmt: skip
    package = f"{name} {meta['version']}"
    for run in runs:
        run["particle"] = mapping.get(run["particle"], run["particle"])
        run["wall"] = mapping.get(run["wall"], run["wall"])
        run["reference_package"] = package
    with opened(db) as database, database.session(write=True) as session:
        imported = reported_store.packages(session)
        if package in imported:
            raise ValidationError(
                "name", name, f"version {meta['version']} is already imported "
                f"(collection {imported[package]!r}); nothing was changed", parameter=True,
            )  # fmt: skip
        connection = session.connection()
        for kind, given in sorted({(k, r[k]) for r in runs for k in ("particle", "wall")}):
            if catalog_rows.entry_name(connection, "material", given) is None:
                raise ValidationError(
                    "materials", given, f"is the package's {kind} and not a material of "
                    f"the database: map it, e.g. --material '{given}=NAME' (granudb "
                    "materials list names them)", parameter=True,
                )  # fmt: skip
        source = _package_source(session, name, meta)
        for run in runs:
            run["source"] = source
        count = reported_store.store(session, chosen, runs)
    return {
        "name": name,
        "version": meta["version"],
        "collection": chosen,
        "runs": count,
        "left_in_package": left,
    }
