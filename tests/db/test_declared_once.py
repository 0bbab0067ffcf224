"""Each stored column is declared once (issue 34): its name is spelled in one file of
``granudb/db/`` and ``granudb/vocabulary/``, its declaration (``vocabulary/terms.py``,
``STORED``), and everything else (the model's column and CHECK, the Core row, the rule, the
catalogue, the Data Package schema, listings and options) is generated from it.

Code that *uses* a value for a computation may name it: those uses are listed below, each
with what it computes. A docstring is prose and is not counted; identifiers and every other
string literal (SQL included) are.
"""

from __future__ import annotations

import ast
import re
from collections import defaultdict
from pathlib import Path

import granudb
from granudb.vocabulary.terms import STORED, stored

PACKAGE = Path(granudb.__file__).parent
DECLARING = "vocabulary/terms.py"
#: The tables whose stored value columns are counted: every column of theirs declared in
#: ``STORED``. A source's and a dataset's columns are declared there too (their models, a
#: source's revisions and its Core row come from them), but their names (key, kind, doi,
#: year, version, state, title) are everyday words of the code and are not counted.
TABLES = ("materials", "fluids", "fluid_points", "collisions", "pair_values", "reported_runs")

#: file → the declared names it may spell because it computes with the value (or names a
#: derived quantity of the same name), each with what it does.
USES: dict[str, set[str]] = {
    # a point is matched by its temperature and reported in mPa·s
    "db/catalog_changes.py": {"temperature_c", "viscosity_pa_s"},
    # G = E / (2(1 + ν)) where no shear modulus is stored
    "db/catalog_rows.py": {"poisson_ratio", "shear_modulus_pa", "youngs_modulus_pa"},
    # a run's temperature must lie within its fluid's points (or be its reference)
    "db/collision_store.py": {"reference_temperature_c", "temperature_c"},
    "db/package_store.py": {"temperature_c"},
    # the shipped reference packages imported, each with its collection
    "db/reported_store.py": {"reference_package"},
    # the Poisson ratio E and G imply must lie in (−1, 0.5)
    "vocabulary/catalog.py": {"shear_modulus_pa", "youngs_modulus_pa"},
    # the derived quantities a reported run states (ζ_in, e) and the fluid's viscosity at a
    # run's temperature: derived columns of the same names, declared as derived terms
    "vocabulary/derived.py": {"incidence_angle_rad", "normal_restitution"},
    "vocabulary/listings.py": {"incidence_angle_rad", "normal_restitution", "viscosity_pa_s"},
    "vocabulary/uncertainty.py": {"incidence_angle_rad", "normal_restitution"},
}


def _docstrings(tree: ast.AST) -> set[int]:
    found = set()
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if isinstance(body, list) and body and isinstance(body[0], ast.Expr):
            value = body[0].value
            if isinstance(value, ast.Constant) and isinstance(value.value, str):
                found.add(id(value))
    return found


def spellings(path: Path) -> list[str]:
    """Every identifier and (non-docstring) string literal of a module."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    skip = _docstrings(tree)
    words: list[str] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Name):
            words.append(node.id)
        elif isinstance(node, ast.Attribute):
            words.append(node.attr)
        elif isinstance(node, ast.arg | ast.keyword) and node.arg:
            words.append(node.arg)
        elif isinstance(node, ast.FunctionDef | ast.ClassDef | ast.AsyncFunctionDef):
            words.append(node.name)
        elif isinstance(node, ast.alias):
            words.append(node.asname or node.name)
        elif (
            isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in skip
        ):
            words.append(node.value)
    return words


def declared_names() -> set[str]:
    """The declared columns counted (with their ``u_`` columns)."""
    return {s.column for table in TABLES for s in stored(table, uncertainties=True)}


def test_every_stored_column_is_spelled_in_its_declaration_only() -> None:
    names = declared_names()
    pattern = re.compile(r"\b(" + "|".join(sorted(names, key=len, reverse=True)) + r")\b")
    spelled: dict[str, set[str]] = defaultdict(set)
    for folder in ("db", "vocabulary"):
        for path in sorted((PACKAGE / folder).rglob("*.py")):
            where = path.relative_to(PACKAGE).as_posix()
            for word in spellings(path):
                for name in pattern.findall(word):
                    spelled[name].add(where)
    elsewhere = {
        name: sorted(f for f in files if f != DECLARING and name not in USES.get(f, set()))
        for name, files in spelled.items()
    }
    assert {n: f for n, f in elsewhere.items() if f} == {}
    # the declaration is found (a ``u_`` column is made from its column's name, unspelled)
    counted = [s for s in STORED if s.table in TABLES]
    assert {s.column for s in counted} <= set(spelled)
    assert all(spelled[s.column] >= {DECLARING} for s in counted)


def test_the_declared_tables_have_no_undeclared_value_column() -> None:
    from sqlalchemy import Float

    from granudb.db.models import Base

    names = declared_names()
    for table in TABLES:
        numbers = {c.name for c in Base.metadata.tables[table].columns if isinstance(c.type, Float)}
        assert numbers <= names, table
    assert {s.table for s in STORED} <= {*TABLES, "sources", "datasets"}


def test_the_core_rows_read_every_column_of_their_tables() -> None:
    """The other direction of ``test_catalog_rows``: a model column missing from the Core
    row would never be read."""
    from granudb.db import catalog_rows
    from granudb.db.models import Base

    unread = {"pair_values": {"updated_at"}}  # a pair's values are never changed
    for clause in (
        catalog_rows.MATERIALS,
        catalog_rows.FLUIDS,
        catalog_rows.FLUID_POINTS,
        catalog_rows.PAIR_VALUES,
        catalog_rows.SOURCES,
    ):
        model = set(Base.metadata.tables[clause.name].c.keys())
        assert model - set(clause.c.keys()) == unread.get(clause.name, set()), clause.name


#: A throw-away column, declared as the recipe says (CONTRIBUTING.md, "A new stored
#: column"): its term and its declaration, in a copy of the package.
_TERM = '    "hardness_pa": Term("Hardness", "Pa", "Vickers hardness H.", option="--hardness"),\n'
_DECLARATION = (
    '    Stored("hardness_pa", "materials", rule=POSITIVE, check="hardness_positive",\n'
    "           uncertain=True, listed=True),\n"
)
_OUTPUTS = """
import json, sys
from dataclasses import fields
from sqlalchemy import CheckConstraint
from alembic.autogenerate import compare_metadata
from alembic.runtime.migration import MigrationContext
from granudb.api.database import connect
from granudb.db.catalog_rows import MaterialRow
from granudb.db.models import Base, Material
from granudb.io.package_schema import table_schema
from granudb.vocabulary.catalog import MATERIALS, parameter_of
from granudb.vocabulary.rules import RULES

table = Material.__table__
checks = [c for c in table.constraints if isinstance(c, CheckConstraint)]
database = connect(sys.argv[1])
with database.engine.connect() as connection:
    context = MigrationContext.configure(connection, opts={"compare_type": True})
    added = [d[3].name for d in compare_metadata(context, Base.metadata)]
database.dispose()
print(json.dumps({
    "model": [c.name for c in table.c if "hardness" in c.name],
    "checks": sorted(str(c.sqltext) for c in checks if str(c.name).endswith("hardness_positive")),
    "row": [f.name for f in fields(MaterialRow) if "hardness" in f.name],
    "schema": [(f["name"], f.get("constraints")) for f in table_schema("materials")["fields"]
               if "hardness" in f["name"] or f["name"] == "yield_stress_pa"],
    "listing": [c for c in MATERIALS.columns if "hardness" in c],
    "narrow": "hardness_pa" in MATERIALS.narrow,
    "rule": RULES["hardness_pa"].text,
    "parameter": parameter_of("hardness_pa"),
    "migration": added,
}))
"""


def test_the_recipe_a_declaration_reaches_every_output(tmp_path: Path, db: str) -> None:
    """Adding a stored column is its declaration, a migration and tests: a copy of the
    package with one more declaration carries the column into the model and its CHECK,
    the Core row, the rule, the Data Package schema, the listing and the option; the
    database still lacks it, and Alembic's comparison names exactly what the migration
    must add."""
    import os
    import shutil
    import subprocess
    import sys

    root = PACKAGE.parent
    ignore = shutil.ignore_patterns("__pycache__")
    shutil.copytree(PACKAGE, tmp_path / "granudb", ignore=ignore)
    for shipped in ("migrations", "seed_data"):  # beside the package in a checkout only
        if not (PACKAGE / shipped).is_dir():
            shutil.copytree(root / shipped, tmp_path / shipped, ignore=ignore)
    terms = tmp_path / "granudb" / DECLARING
    text = terms.read_text(encoding="utf-8")
    for anchor, line in (("TERMS: dict[str, Term] = {\n", _TERM),
                         ("STORED: tuple[Stored, ...] = (\n", _DECLARATION)):  # fmt: skip
        assert text.count(anchor) == 1
        text = text.replace(anchor, anchor + line)
    terms.write_text(text, encoding="utf-8")
    env = {**os.environ, "PYTHONPATH": str(tmp_path)}
    done = subprocess.run(
        [sys.executable, "-c", _OUTPUTS, db], capture_output=True, text=True, env=env,
        cwd=tmp_path,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-3000:]
    import json

    seen = json.loads(done.stdout.strip().splitlines()[-1])
    both = ["hardness_pa", "u_hardness_pa"]
    assert sorted(seen["model"]) == both
    assert seen["checks"] == ["hardness_pa IS NULL OR hardness_pa > 0"]
    assert seen["row"] == both
    schema = dict(seen["schema"])
    assert [name for name in schema if "hardness" in name] == both
    # the same rule as the yield stress (> 0, optional): the same field constraints
    assert schema["hardness_pa"] == schema["yield_stress_pa"]
    assert schema["hardness_pa"] is not None
    assert seen["listing"] == both and seen["narrow"]
    assert seen["rule"] == "must be > 0"
    assert seen["parameter"] == "hardness"
    assert sorted(seen["migration"]) == both
    help_text = subprocess.run(
        [sys.executable, "-m", "granudb", "materials", "add", "--help"],
        capture_output=True, text=True, env={**env, "COLUMNS": "200"}, cwd=tmp_path,
    ).stdout  # fmt: skip
    assert "--hardness" in help_text
