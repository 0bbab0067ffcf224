"""A user's fluid gets viscosity–temperature points (issue 14): then it has a viscosity at
any temperature between them; a stored point is never replaced silently."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from support import dump_hash

OIL = ["fluids", "add", "oil", "--reference-viscosity", "9.6 cP", "--reference-density",
       "960 kg/m^3", "--reference-temperature", "25 degC"]  # fmt: skip


def test_points_give_a_fluid_a_viscosity_at_other_temperatures(cli, db: str, tmp_path: Path):
    assert cli(*OIL, db=db).exit_code == 0
    scenario = [
        *("pair", "steel", "Zerodur", "--fluid", "oil", "--diameter", "12.7 mm"),
        *("--velocity", "0.3 m/s", "--temperature", "35 degC", "--format", "json"),
    ]
    refused = cli(*scenario, db=db)
    assert refused.exit_code == 1 and "no viscosity–temperature points" in refused.stderr
    csv = tmp_path / "oil.csv"
    csv.write_text("temperature [degC],viscosity [cP]\n15,12.5\n25,9.6\n45,6.1\n", "utf-8")
    imported = cli("fluids", "points", "import", "oil", str(csv), db=db)
    assert imported.exit_code == 0, imported.stderr
    assert imported.stdout.count("added oil") == 3
    fluid = json.loads(cli(*scenario, db=db).stdout)["fluid"]
    assert 6.1e-3 < fluid["viscosity_pa_s"] < 9.6e-3


def test_a_point_is_never_replaced_silently(cli, db: str) -> None:
    assert cli(*OIL, db=db).exit_code == 0
    point = ["fluids", "points", "add", "oil", "--temperature", "30 degC", "--viscosity", "8 cP"]
    assert cli(*point, db=db).exit_code == 0
    before = dump_hash(db)
    again = cli(*point[:-1], "7 cP", db=db)
    assert again.exit_code == 1 and "exists already (8 mPa·s)" in again.stderr
    assert dump_hash(db) == before
    replaced = cli(*point[:-1], "7 cP", "--replace", db=db)
    assert replaced.exit_code == 0 and "8 → 7 mPa·s" in replaced.stdout


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("temperature [degC],viscosity [cP]\n30,-1\n", "must be > 0"),
        ("temperature [degC],viscosity [cP]\n30,1\n30,2\n", "appears twice"),
        ("temperature [degC],viscosity [Pa]\n30,1\n", "is not a dynamic viscosity"),
    ],
)
def test_bad_points_are_refused_whole(cli, db: str, tmp_path: Path, text: str, expected: str):
    assert cli(*OIL, db=db).exit_code == 0
    path = tmp_path / "bad.csv"
    path.write_text(text, "utf-8")
    before = dump_hash(db)
    out = cli("fluids", "points", "import", "oil", str(path), db=db)
    assert out.exit_code == 1 and expected in out.stderr and out.stderr.count("\n") == 1
    assert dump_hash(db) == before
