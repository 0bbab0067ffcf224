"""``db seed`` never reverts a user's edit (issue 14: it silently reverted a
``materials update`` of a seed material and only reported it afterwards)."""

from __future__ import annotations

import csv
import json
import shutil
from pathlib import Path

import pytest
from support import dump_hash, execute

import granudb
from granudb.io.seed import read_seed
from granudb.resources import shipped_dir


def _density(cli, db: str, name: str = "steel") -> float:
    return json.loads(cli("materials", "show", name, "--format", "json", db=db).stdout)[
        "density_kg_m3"
    ]


def test_reseed_keeps_a_users_edit_and_reports_it(cli, db: str) -> None:
    assert cli("materials", "update", "steel", "--density", "7000 kg/m^3", db=db).exit_code == 0
    result = cli("db", "seed", db=db)
    assert result.exit_code == 0, result.stderr
    assert "kept your edit of material steel: density_kg_m3 7000.0 (seed: 7780.0)" in result.stdout
    assert "1 of your edits kept" in result.stdout
    assert _density(cli, db) == 7000.0
    before = dump_hash(db)
    assert cli("db", "seed", db=db).exit_code == 0  # and again: still kept, nothing changes
    assert dump_hash(db) == before


def test_an_edit_made_by_another_tool_is_kept_too(cli, db: str) -> None:
    execute(
        db,
        "UPDATE fluid_points SET viscosity_pa_s = 0.5 "
        "WHERE id = (SELECT min(id) FROM fluid_points)",
    )
    before = dump_hash(db)
    lines = granudb.db_seed(db=db)
    assert any(line.startswith("kept your edit of fluid point") for line in lines)
    assert dump_hash(db) == before


def test_overwrite_edits_says_what_it_reverts_and_needs_yes(cli, db: str) -> None:
    assert cli("materials", "update", "steel", "--density", "7000 kg/m^3", db=db).exit_code == 0
    before = dump_hash(db)
    refused = cli("db", "seed", "--overwrite-edits", db=db)
    assert refused.exit_code == 1
    lines = refused.stderr.strip().splitlines()
    assert len(lines) == 1 and "material steel: density_kg_m3 7000.0 → 7780.0" in lines[0]
    assert "--yes" in lines[0]
    assert dump_hash(db) == before
    assert _reverts(db) == ["your edit of material steel: density_kg_m3 7000.0 → 7780.0"]
    assert dump_hash(db) == before  # the trial run changed nothing
    done = cli("db", "seed", "--overwrite-edits", "--yes", db=db)
    assert done.exit_code == 0, done.stderr
    assert "reverted your edit of material steel" in done.stdout
    assert _density(cli, db) == 7780.0


def test_a_renamed_seed_material_is_not_added_back(cli, db: str) -> None:
    assert cli("materials", "update", "steel", "--rename", "AISI 52100", db=db).exit_code == 0
    result = cli("db", "seed", db=db)
    assert result.exit_code == 0, result.stderr
    assert "kept your edit of material steel" in result.stdout
    names = {m["name"] for m in json.loads(cli("materials", "list", "-f", "json", db=db).stdout)}
    seeded = {m["name"] for m in read_seed().materials}
    assert names == seeded - {"steel"} | {"AISI 52100"}


def test_a_seed_file_change_still_updates_an_unedited_value(cli, db: str, tmp_path: Path) -> None:
    folder = tmp_path / "seed"
    shutil.copytree(shipped_dir("seed_data"), folder)
    path = folder / "materials.csv"
    rows = list(csv.DictReader(path.open(encoding="utf-8")))
    for row in rows:
        if row["name"] == "glass":
            row["youngs_modulus [GPa]"] = "63"
    with path.open("w", encoding="utf-8", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    assert cli("materials", "update", "steel", "--density", "7000 kg/m^3", db=db).exit_code == 0
    lines = granudb.db_seed(db=db, folder=folder)
    assert "updated material glass: youngs_modulus_pa 60000000000.0 → 63000000000.0" in lines
    assert _density(cli, db) == 7000.0


def _reverts(db: str) -> list[str]:
    """What ``db_seed(overwrite_edits=True)`` asks consent for (declined: nothing changes)."""
    asked: list[str] = []

    def decline(_action: str, losses: list[str]) -> bool:
        asked.extend(losses)
        return False

    with pytest.raises(granudb.ConfirmationNeeded):
        granudb.db_seed(overwrite_edits=True, confirm=decline, db=db)
    return asked
