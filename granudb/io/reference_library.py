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
    """The folder of reference dataset ``name``; ``ValidationError`` naming the nearest."""
    known = names()
    if name not in known:
        near = difflib.get_close_matches(str(name), known, n=1)
        rule = "is not a reference dataset" + (
            f"; did you mean {near[0]}?" if near else f" (known: {', '.join(known)})"
        )
        raise ValidationError("name", name, rule, parameter=True)
    return library_dir() / name


def descriptor(name: str) -> dict[str, Any]:
    """The package's ``datapackage.json``."""
    return json.loads((package_dir(name) / "datapackage.json").read_text(encoding="utf-8"))


def values(name: str) -> list[dict[str, str]]:
    """The rows of the package's ``data/values.csv`` (text, as written)."""
    path = package_dir(name) / "data" / "values.csv"
    with path.open(encoding="utf-8", newline="") as f:
        return list(csv.DictReader(f))
