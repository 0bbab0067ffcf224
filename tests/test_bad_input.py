"""Every refusal: one line naming the field and the rule, exit code 1, no traceback, and
the database exactly as it was (compared by a hash of its whole logical content)."""

from __future__ import annotations

from pathlib import Path

import pytest
from support import dump_hash, execute

from granudb.io.seed import read_seed

#: The seeded materials as an unknown name lists them (case-insensitively sorted).
KNOWN = ", ".join(sorted((m["name"] for m in read_seed().materials), key=str.casefold))

MATERIAL = [
    "--density",
    "2540 kg/m^3",
    "--youngs-modulus",
    "60 GPa",
    "--poisson-ratio",
    "0.23",
    "--roughness",
    "0.13 um",
]


def _with(options: list[str], flag: str, value: str) -> list[str]:
    out = list(options)
    out[out.index(flag) + 1] = value
    return out


CASES = [
    # (argv, text the one-line error must contain)
    (
        ["materials", "add", "m", *_with(MATERIAL, "--density", "-3 kg/m^3")],
        "--density: -3 kg/m^3 must be > 0",
    ),
    (
        ["materials", "add", "m", *_with(MATERIAL, "--density", "0 kg/m^3")],
        "--density: 0 kg/m^3 must be > 0",
    ),
    (
        ["materials", "add", "m", *_with(MATERIAL, "--density", "2540")],
        "--density: 2540 needs a unit",
    ),
    (
        ["materials", "add", "m", *_with(MATERIAL, "--youngs-modulus", "60 m/s")],
        "--youngs-modulus: 60 m/s is not a pressure or modulus",
    ),
    (
        ["materials", "add", "m", *_with(MATERIAL, "--youngs-modulus", "nan GPa")],
        "--youngs-modulus: nan GPa must be a finite number",
    ),
    (
        ["materials", "add", "m", *_with(MATERIAL, "--poisson-ratio", "0.5")],
        "--poisson-ratio: 0.5 must be > -1 and < 0.5",
    ),
    (
        ["materials", "add", "m", *_with(MATERIAL, "--poisson-ratio", "-1")],
        "--poisson-ratio: -1 must be > -1 and < 0.5",
    ),
    (
        ["materials", "add", "m", *_with(MATERIAL, "--roughness", "-1 nm")],
        "--roughness: -1 nm must be ≥ 0",
    ),
    (
        ["materials", "add", "m", *MATERIAL, "--shear-modulus", "10 GPa"],
        "implies a Poisson ratio of 2, outside",
    ),
    (["materials", "add", "GLASS", *MATERIAL], "material: 'GLASS' already exists as 'glass'"),
    (["materials", "add", " ", *MATERIAL], "material name: ' ' must not be empty"),
    (
        ["materials", "add", "m", *MATERIAL, "--source", "nobody-1999"],
        "source: 'nobody-1999' is not in the database",
    ),
    (
        ["materials", "update", "unobtainium", "--density", "1 kg/m^3"],
        f"material: 'unobtainium' is not in the database (known: {KNOWN})",
    ),
    (["materials", "update", "glass", "--rename", "Steel"], "material: 'Steel' already exists"),
    (
        ["materials", "update", "glass", "--poisson-ratio", "0.7"],
        "--poisson-ratio: 0.7 must be > -1 and < 0.5",
    ),
    (["materials", "remove", "glass"], "is still used by 16 published values"),
    (
        [
            "fluids",
            "add",
            "f",
            "--reference-viscosity",
            "-1 cP",
            "--reference-density",
            "1000 kg/m^3",
        ],
        "--reference-viscosity: -1 cP must be > 0",
    ),
    (
        [
            "fluids",
            "add",
            "f",
            "--reference-viscosity",
            "1 cP",
            "--reference-density",
            "1000 kg/m^3",
            "--reference-temperature",
            "-300 degC",
        ],
        "--reference-temperature: -300 degC must be > -273.15",
    ),
    (
        [
            "fluids",
            "add",
            "f",
            "--reference-viscosity",
            "1 Pa",
            "--reference-density",
            "1000 kg/m^3",
        ],
        "--reference-viscosity: 1 Pa is not a dynamic viscosity",
    ),
    (
        [
            "fluids",
            "add",
            "f",
            "--reference-viscosity",
            "1 cP",
            "--reference-density",
            "1000 kg/m^3",
            "--glycerol-fraction",
            "120 %",
        ],
        "--glycerol-fraction: 120 % must be ≥ 0 and ≤ 1",
    ),
    (
        [
            "fluids",
            "add",
            "Water",
            "--reference-viscosity",
            "1 cP",
            "--reference-density",
            "1000 kg/m^3",
        ],
        "fluid: 'Water' already exists as 'water'",
    ),
    (["fluids", "remove", "glycerol-45"], "is still used by"),
    (["fluids", "show", "mercury"], "fluid: 'mercury' is not in the database"),
    (["sources", "show", "nope"], "source: 'nope' is not in the database"),
    (
        ["materials", "add", "x'); DROP TABLE materials; --", *_with(MATERIAL, "--density", "1 m")],
        "--density: 1 m is not a density",
    ),
    (["db", "downgrade", "9999"], "revision: '9999'"),
]


@pytest.mark.parametrize(("argv", "expected"), CASES, ids=[" ".join(c[0][:3]) for c in CASES])
def test_refused_in_one_line_with_the_database_unchanged(
    cli, db: str, argv: list[str], expected: str
) -> None:
    before = dump_hash(db)
    result = cli(*argv, db=db)
    assert result.exit_code == 1
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("Error: ")
    assert expected in lines[0]
    assert "Traceback" not in result.stderr + result.stdout
    assert dump_hash(db) == before


@pytest.mark.sqlite_only
def test_missing_database_folder_is_refused_without_creating_it(cli, tmp_path: Path) -> None:
    missing = tmp_path / "no" / "such" / "folder" / "lab.sqlite"
    result = cli("materials", "list", db=missing)
    assert result.exit_code == 1
    assert result.stderr.strip() == (
        f"Error: database: folder {missing.parent} does not exist (create it, or choose "
        "another --db)"
    )
    assert not missing.parent.exists()


@pytest.mark.sqlite_only
def test_a_file_that_is_not_a_database_is_refused_and_left_alone(cli, tmp_path: Path) -> None:
    notes = tmp_path / "notes.txt"
    notes.write_text("lab notebook, not a database\n" * 100)
    before = notes.read_bytes()
    result = cli("materials", "list", db=notes)
    assert result.exit_code == 1
    assert result.stderr.count("\n") == 1 and "not a SQLite database" in result.stderr
    assert notes.read_bytes() == before


def test_a_database_of_another_program_is_refused(cli, new_db: str) -> None:
    other = new_db
    execute(other, "CREATE TABLE samples (id INTEGER PRIMARY KEY, label TEXT)")
    before = dump_hash(other)
    result = cli("materials", "list", db=other)
    assert result.exit_code == 1
    assert "holds tables but no granudb schema revision (samples" in result.stderr
    assert dump_hash(other) == before


def test_a_newer_schema_revision_is_refused(cli, db: str) -> None:
    execute(db, "UPDATE alembic_version SET version_num = 'f00dface'")
    before = dump_hash(db)
    result = cli("materials", "list", db=db)
    assert result.exit_code == 1
    assert "schema revision f00dface is newer than this granudb knows" in result.stderr
    assert dump_hash(db) == before


def test_hostile_names_are_stored_and_shown_verbatim(cli, db: str) -> None:
    import json

    hostile = "<script>alert(1)</script> [bold]x[/bold] '; DROP TABLE materials; --"
    assert cli("materials", "add", hostile, *MATERIAL, db=db).exit_code == 0
    listed = json.loads(cli("materials", "list", "--format", "json", db=db).stdout)
    assert hostile in [m["name"] for m in listed]
    table = cli("materials", "list", db=db).stdout
    assert "[bold]x[/bold]" in table  # Rich markup in data is shown, not interpreted
