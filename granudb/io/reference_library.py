"""The reference library of published collision data shipped with granudb.

One Frictionless Data Package per published dataset, in ``seed_data/reference/NAME/``
(installed as ``granudb/seed_data/reference``): ``datapackage.json``, ``data/values.csv``
(one row per reported value with its source, locator, digitiser, licence, u and the public
repository, file and commit it was read from) and ``CITATION.cff``. They are written by
``tools/build_reference.py`` from the copies of the public digitisations; this module only
reads them.
"""

from __future__ import annotations

import csv
import difflib
import json
import math
from pathlib import Path
from typing import Any

from granudb.errors import ValidationError
from granudb.resources import shipped_dir


def library_dir() -> Path:
    """The folder holding the shipped reference packages."""
    return shipped_dir("seed_data") / "reference"


def names() -> list[str]:
    """The reference datasets, by name."""
    folder = library_dir()
    if not folder.is_dir():
        return []
    return sorted(p.name for p in folder.iterdir() if (p / "datapackage.json").is_file())


def package_dir(name: str) -> Path:
    """The folder of reference dataset ``name`` (a shipped one, or the folder of a package
    of reported values written as ``tools/build_reference.py`` writes them, a lab's own);
    ``ValidationError`` naming the nearest shipped one."""
    known = names()
    if name not in known and _own_package(Path(name)):
        return Path(name)
    if name not in known:
        near = difflib.get_close_matches(str(name), known, n=1)
        rule = "is not a reference dataset" + (
            f"; did you mean {near[0]}?" if near else f" (known: {', '.join(known)})"
        )
        raise ValidationError("name", name, rule, parameter=True)
    return library_dir() / name


def _own_package(folder: Path) -> bool:
    """Whether ``folder`` holds a package of reported values (``granudb_reference``)."""
    described = folder / "datapackage.json"
    if not described.is_file():
        return False
    try:
        meta = json.loads(described.read_text(encoding="utf-8"))
    except (ValueError, OSError, RecursionError):
        return False
    kind = meta.get("granudb_reference") if isinstance(meta, dict) else None
    return isinstance(kind, dict) and kind.get("kind") == "reported values"


def descriptor(name: str) -> dict[str, Any]:
    """The package's ``datapackage.json``."""
    return json.loads((package_dir(name) / "datapackage.json").read_text(encoding="utf-8"))


def values(name: str) -> list[dict[str, str]]:
    """The rows of the package's ``data/values.csv`` (text, as written)."""
    path = package_dir(name) / "data" / "values.csv"
    with path.open(encoding="utf-8", newline="") as f:
        return list(csv.DictReader(f))


#: The package quantities a reported run stores, with the factor to its SI column.
RUN_QUANTITIES = {
    "incidence_angle_deg": ("incidence_angle_rad", math.pi / 180.0),
    "incidence_angle_rad": ("incidence_angle_rad", 1.0),
    "normal_restitution": ("normal_restitution", 1.0),
    "tangential_restitution": ("tangential_restitution", 1.0),
    "angular_velocity_out_rad_s": ("omega_out_rad_s", 1.0),
    "omega_out_rad_s": ("omega_out_rad_s", 1.0),
}
#: The conditions a run takes from the package when it does not state them itself.
RUN_CONDITIONS = ("normal_restitution", "diameter_m")


def _provenance(row: dict[str, str]) -> str:
    where = " ".join(x for x in (row["repository"], row["file"]) if x)
    return f"read from {where} at {row['commit']}" if row["commit"] else f"read from {where}"


def reported_runs(name: str) -> tuple[list[dict[str, Any]], list[str]]:
    """The package's values as reported runs (``granudb reference import``): one run per
    point that states a measured e or e_t, its other measured values (θ, ω_out) with their
    u in SI, the package's conditions e and diameter where the point does not state them
    (``notes`` says so), ``no_spin_in`` when the package's meaning of e_t says "no spin
    in", and each run's source locator, digitiser, licence and notes from the row of the
    restitution it states. Also the quantities left in the package (no column of a run)."""
    rows = values(name)
    meta = descriptor(name)
    no_spin = "no spin in" in meta["granudb_reference"]["meanings"].get(
        "tangential_restitution", ""
    )
    conditions = {r["quantity"]: r for r in rows if r["point"] == "conditions"}
    by_point: dict[str, list[dict[str, str]]] = {}
    for r in rows:
        if r["point"] != "conditions":
            by_point.setdefault(r["point"], []).append(r)
    runs: list[dict[str, Any]] = []
    left: list[str] = []
    for point, group in by_point.items():
        measured = {r["quantity"]: r for r in group if r["role"] == "measured"}
        states = [q for q in ("normal_restitution", "tangential_restitution") if q in measured]
        if not states or not group[0]["particle"] or not group[0]["wall"]:
            left.extend(r["quantity"] for r in group)
            continue
        main = measured[states[0]]
        run: dict[str, Any] = {"run": point, "particle": main["particle"], "wall": main["wall"]}
        run["fluid"] = main["fluid"] or None
        notes: list[str] = []
        for quantity, r in measured.items():
            if quantity not in RUN_QUANTITIES:
                left.append(quantity)
                continue
            column, factor = RUN_QUANTITIES[quantity]
            run[column] = float(r["value"]) * factor
            run[f"u_{column}"] = float(r["u"]) * factor
            notes.extend(x for x in (r["notes"], f"u({quantity}): {r['u_basis']}") if x)
        for quantity in RUN_CONDITIONS:
            if quantity in conditions and run.get(quantity) is None:
                c = conditions[quantity]
                run[quantity] = float(c["value"])
                if quantity == "normal_restitution":
                    run["u_normal_restitution"] = float(c["u"])
                notes.append(
                    f"{quantity} = {c['value']} is the dataset's condition, not measured in "
                    f"this run ({c['locator']}; {c['notes'] or _provenance(c)})"
                )
        notes.append(_provenance(main))
        run.update(
            no_spin_in=no_spin and "tangential_restitution" in measured,
            source_locator=main["locator"],
            digitiser=main["digitiser"],
            licence=main["licence"],
            notes="; ".join(dict.fromkeys(notes)),
        )
        runs.append(run)
    return runs, sorted(set(left))
