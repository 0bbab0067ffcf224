"""The reference library: published collision data shipped as datasets, and how granudb's
fits and models reproduce them (docs/reference/index.md).

``reference_list()`` names the datasets; ``reference_show(name)`` gives one dataset's
reported values with their provenance; ``reference_reproduce(name)`` runs the fits and
predictions that apply to it and returns each check with its verdict
(``granudb.analysis.reference_checks``).
"""

from __future__ import annotations

from typing import Any

from granudb.analysis import reference_checks
from granudb.io import reference_library

#: The columns ``granudb reference list`` shows.
REFERENCE_COLUMNS = ["name", "version", "values", "title", "licences", "path"]
#: The columns of a reproduction's checks (JSON and CSV), and those a table shows under
#: each kind of check (the reported and computed cells carry their u: "0.092 ± 0.0003").
REFERENCE_CHECK_COLUMNS = list(reference_checks.CHECK_KEYS)
REFERENCE_CHECK_NARROW = ["point", "quantity", "reported", "computed", "residual", "verdict"]
#: The columns ``granudb reference list`` shows in a table.
REFERENCE_NARROW = ["name", "version", "values", "title"]
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
