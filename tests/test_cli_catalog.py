"""The catalogue commands, end to end through the CLI, on a real SQLite file."""

from __future__ import annotations

import csv
import io
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from granudb.io.seed import read_seed

#: The seeded materials as listings sort them (case-insensitively).
SEEDED_NAMES = sorted((m["name"] for m in read_seed().materials), key=str.casefold)


def test_first_use_in_an_empty_data_directory_prints_the_seed_materials_in_si(
    tmp_path: Path,
) -> None:
    env = {**os.environ}  # HOME/XDG_DATA_HOME already point into tmp_path (conftest)
    out = subprocess.run(
        [sys.executable, "-m", "granudb", "materials", "list", "--format", "json"],
        capture_output=True,
        text=True,
        env=env,
        check=True,
    )
    materials = {m["name"]: m for m in json.loads(out.stdout)}
    assert set(materials) == {m["name"] for m in read_seed().materials}
    glass = materials["glass"]
    assert glass["youngs_modulus_pa"] == 6.0e10
    assert glass["density_kg_m3"] == 2540.0
    assert glass["poisson_ratio"] == 0.23
    assert glass["roughness_rms_m"] == pytest.approx(1.305e-7, rel=1e-12)
    assert materials["steel"]["youngs_modulus_pa"] == 1.9e11
    assert materials["Zerodur"]["roughness_rms_m"] == pytest.approx(1.55e-8, rel=1e-12)
    assert glass["source"] == "joseph-hunt-2004" and glass["source_locator"] == "table 1"
    created = Path(os.environ["XDG_DATA_HOME"]) / "granudb" / "granudb.sqlite"
    assert created.is_file()
    assert "created" in out.stderr  # said once, on stderr, so the JSON stays clean


def test_json_output_is_a_plain_array_with_unit_suffixed_names(cli, db: str) -> None:
    data = json.loads(cli("fluids", "list", "--format", "json", db=db).stdout)
    assert isinstance(data, list)
    water = next(f for f in data if f["name"] == "water")
    assert water["reference_viscosity_pa_s"] == pytest.approx(1.0e-3)
    assert water["pressure_viscosity_pa_inv"] is None
    glycerol = next(f for f in data if f["name"] == "glycerol-45")
    assert glycerol["pressure_viscosity_pa_inv"] == 6e-9
    assert glycerol["glycerol_mass_fraction"] == 0.45


def test_csv_output_has_the_same_names(cli, db: str) -> None:
    text = cli("materials", "list", "--format", "csv", db=db).stdout
    rows = list(csv.DictReader(io.StringIO(text)))
    assert [r["name"] for r in rows] == SEEDED_NAMES
    steel = next(r for r in rows if r["name"] == "steel")
    assert float(steel["youngs_modulus_pa"]) == 1.9e11


def test_table_output_shows_units_a_person_reads(cli, db: str) -> None:
    out = cli("materials", "list", db=db).stdout
    assert "60 GPa" in out and "130.5 nm" in out and "7780 kg/m³" in out


def test_add_show_update_remove_a_material(cli, db: str) -> None:
    added = cli(
        "materials",
        "add",
        "PTFE",
        "--density",
        "2.2 g/cm^3",
        "--youngs-modulus",
        "0.5 GPa",
        "--poisson-ratio",
        "0.46",
        "--roughness",
        "0.2 um",
        "--description",
        "Teflon sphere",
        "--source",
        "johnson-1985",
        db=db,
    )
    assert added.exit_code == 0, added.stderr
    shown = json.loads(cli("materials", "show", "ptfe", "--format", "json", db=db).stdout)
    assert shown["density_kg_m3"] == 2200.0
    assert shown["youngs_modulus_pa"] == 5e8
    assert shown["roughness_rms_m"] == 2e-7
    assert shown["shear_modulus_derived"] is True
    assert shown["shear_modulus_pa"] == pytest.approx(5e8 / (2 * 1.46))
    assert shown["citation"].startswith("Johnson, K. L.")

    updated = cli("materials", "update", "Ptfe", "--youngs-modulus", "0.55 GPa", db=db)
    assert updated.exit_code == 0
    assert "youngs_modulus_pa 500 MPa → 550 MPa" in updated.stdout
    same = cli("materials", "update", "PTFE", "--youngs-modulus", "550 MPa", db=db)
    assert "unchanged" in same.stdout

    assert cli("materials", "remove", "PTFE", "--yes", db=db).exit_code == 0
    gone = cli("materials", "show", "PTFE", db=db)
    assert gone.exit_code == 1
    assert f"known: {', '.join(SEEDED_NAMES)})" in gone.stderr


def test_add_update_remove_a_fluid(cli, db: str) -> None:
    added = cli(
        "fluids",
        "add",
        "silicone oil",
        "--reference-viscosity",
        "10 cSt * 0.96 g/cm^3",
        "--reference-density",
        "960 kg/m^3",
        "--reference-temperature",
        "25 degC",
        db=db,
    )
    assert added.exit_code == 0, added.stderr
    shown = json.loads(cli("fluids", "show", "Silicone Oil", "--format", "json", db=db).stdout)
    assert shown["reference_viscosity_pa_s"] == pytest.approx(9.6e-3)
    assert shown["reference_temperature_c"] == 25.0
    assert shown["points"] == []
    updated = cli(
        "fluids",
        "update",
        "silicone oil",
        "--pressure-viscosity",
        "2e-8 1/Pa",
        "--rename",
        "PDMS 10 cSt",
        db=db,
    )
    assert "name 'silicone oil' → 'PDMS 10 cSt'" in updated.stdout
    assert cli("fluids", "remove", "pdms 10 cst", "--yes", db=db).exit_code == 0


def test_removing_a_material_in_use_says_by_what(cli, db: str) -> None:
    from granudb.api.database import connect as open_database
    from granudb.db.catalog_rows import entry_id
    from granudb.db.models import Collision, Dataset

    database = open_database(db)
    with database.session(write=True) as session:
        cli_added = Dataset(name="drops", version="1.0.0")
        session.add(cli_added)
        session.flush()
        for run in range(3):
            session.add(
                Collision(
                    dataset_id=cli_added.id,
                    run=f"r{run}",
                    particle_id=entry_id(session.connection(), "material", "steel"),
                    wall_id=entry_id(session.connection(), "material", "Zerodur"),
                    diameter_m=0.0127,
                    nominal_angle_rad=0.1,
                    v_n_in_m_s=0.3,
                    v_t_in_m_s=0.03,
                    v_n_out_m_s=0.2,
                    v_t_out_m_s=0.02,
                )
            )
    database.dispose()
    result = cli("materials", "remove", "steel", db=db)
    assert result.exit_code == 1
    assert "3 collisions in dataset drops 1.0.0 (as particle)" in result.stderr
    result = cli("materials", "remove", "zerodur", db=db)
    assert "3 collisions in dataset drops 1.0.0 (as wall)" in result.stderr


def test_sources_show_lists_what_cites_it(cli, db: str) -> None:
    data = json.loads(cli("sources", "show", "joseph-hunt-2004", "--format", "json", db=db).stdout)
    assert data["doi"] == "10.1017/S002211200400919X"
    assert data["cited_by"]["materials"] == 3
    labels = {(p["label"], p["quantity"]) for p in data["published_values"]}
    assert ("dry steel on Zerodur", "rotational_restitution") in labels


def test_db_commands(cli, db: str) -> None:
    current = json.loads(cli("db", "current", "--format", "json", db=db).stdout)
    assert current["revision"] == current["head"] and current["up_to_date"] is True
    history = json.loads(cli("db", "history", "--format", "json").stdout)
    assert history[-1]["down_revision"] is None
    assert "0 added, 0 updated" in cli("db", "seed", db=db).stdout


def test_help_does_not_import_heavy_libraries() -> None:
    code = (
        "import sys; from granudb.cli.main import app\n"
        "try:\n    app(['--help'])\nexcept SystemExit:\n    pass\n"
        "heavy = [m for m in ('sqlalchemy', 'pandas', 'numpy', 'pint', 'alembic', 'scipy')"
        " if m in sys.modules]\n"
        "print('HEAVY=' + ','.join(heavy))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip().splitlines()[-1] == "HEAVY="


#: The conditions of a material's values as a source might state them (issue 27).
CONDITIONS = 'E by ultrasonic pulse-echo at 20 °C; σ from SEM images, "ring" method'


def test_conditions_of_the_values_are_stored_shown_and_listed(cli, db: str) -> None:
    """A material's and a fluid's conditions (temperature, method): added, shown, listed
    (JSON and CSV carry the same text), updated, and in ``pair``'s materials table and
    document; a control character or a line break is refused in one line, nothing
    changed."""
    added = cli(
        "materials", "add", "PEEK", "--density", "1.3 g/cm^3", "--youngs-modulus", "3.6 GPa",
        "--poisson-ratio", "0.38", "--conditions", CONDITIONS, db=db,
    )  # fmt: skip
    assert added.exit_code == 0, added.stderr
    shown = json.loads(cli("materials", "show", "PEEK", "--format", "json", db=db).stdout)
    assert shown["conditions"] == CONDITIONS
    listed = json.loads(cli("materials", "list", "--format", "json", db=db).stdout)
    assert {m["name"]: m["conditions"] for m in listed}["PEEK"] == CONDITIONS
    assert {m["conditions"] for m in listed if m["name"] != "PEEK"} == {None}
    rows = csv.DictReader(io.StringIO(cli("materials", "list", "--format", "csv", db=db).stdout))
    assert {r["name"]: r["conditions"] for r in rows}["PEEK"] == CONDITIONS
    table = cli("materials", "show", "PEEK", db=db).stdout
    assert "pulse-echo" in table

    pair = cli("pair", "PEEK", "glass", "--diameter", "5 mm", "--velocity", "0.3 m/s", db=db)
    assert pair.exit_code == 0, pair.stderr
    assert "conditions" in pair.stdout and "pulse-echo" in pair.stdout
    plain = cli("pair", "steel", "glass", "--diameter", "5 mm", "--velocity", "0.3 m/s", db=db)
    assert "conditions" not in plain.stdout  # neither side states any: no row
    document = json.loads(
        cli("pair", "PEEK", "glass", "--diameter", "5 mm", "--velocity", "0.3 m/s",
            "--format", "json", db=db).stdout
    )  # fmt: skip
    assert (document["particle"]["conditions"], document["wall"]["conditions"]) == (
        CONDITIONS,
        None,
    )

    later = "E by nanoindentation at 23 °C"
    updated = cli("materials", "update", "peek", "--conditions", later, db=db)
    assert updated.exit_code == 0, updated.stderr
    assert f"conditions {CONDITIONS!r} → {later!r}" in updated.stdout
    for bad in ("at 20 °C\x07", "line one\nline two"):
        refused = cli("materials", "update", "PEEK", "--conditions", bad, db=db)
        assert refused.exit_code != 0
        assert len(refused.stderr.strip().splitlines()) == 1, refused.stderr
        assert "conditions" in refused.stderr and "Traceback" not in refused.stderr
    shown = json.loads(cli("materials", "show", "PEEK", "--format", "json", db=db).stdout)
    assert shown["conditions"] == later  # unchanged by the refused updates

    fluid = cli(
        "fluids", "add", "PDMS", "--reference-viscosity", "0.0096 Pa*s",
        "--reference-density", "960 kg/m^3", "--conditions", "rotational rheometer at 25 °C",
        db=db,
    )  # fmt: skip
    assert fluid.exit_code == 0, fluid.stderr
    shown = json.loads(cli("fluids", "show", "PDMS", "--format", "json", db=db).stdout)
    assert shown["conditions"] == "rotational rheometer at 25 °C"
    assert cli("fluids", "update", "PDMS", "--conditions", "\x1b[31m", db=db).exit_code != 0


def test_conditions_from_python_and_the_report_block(opened) -> None:
    """The Python keywords are the options' names; the report's materials table shows
    the conditions as a row of their own, only where they are stated."""
    import granudb
    from granudb.reporting.sections import material_section

    added = granudb.add_material(
        "PEEK", density="1.3 g/cm^3", youngs_modulus="3.6 GPa", poisson_ratio=0.38,
        conditions=CONDITIONS, db=opened,
    )  # fmt: skip
    assert added["conditions"] == CONDITIONS
    rows = material_section("Particle", added)["rows"]
    assert [r["value"] for r in rows if r["name"] == "conditions"] == [CONDITIONS]
    steel = granudb.material("steel", db=opened)
    assert "conditions" not in [r["name"] for r in material_section("Wall", steel)["rows"]]
    with pytest.raises(granudb.ValidationError, match="conditions"):
        granudb.update_material("PEEK", conditions="a\tb", db=opened)


def test_a_release_keeps_the_conditions_it_was_released_with(cli, db: str) -> None:
    """Stating steel's conditions after a release is a change like any other: the
    history keeps steel as released (no conditions) beside the live one."""
    example = Path(__file__).resolve().parent.parent / "examples" / "collisions_example.csv"
    assert cli("collisions", "import", str(example), "--dataset", "example", db=db).exit_code == 0
    assert cli("dataset", "release", "example", db=db).exit_code == 0
    changed = cli("materials", "update", "steel", "--conditions", CONDITIONS, db=db)
    assert changed.exit_code == 0, changed.stderr
    history = json.loads(cli("materials", "history", "steel", "--format", "json", db=db).stdout)
    assert [r["conditions"] for r in history] == [CONDITIONS, None]
