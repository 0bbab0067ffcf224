"""One concept, one name: the same name and value in the database column, the DataFrame,
JSON, CSV and the vocabulary (issue 12's naming conflicts, one test each)."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "collisions_example.csv"


def test_every_derived_column_has_one_vocabulary_entry() -> None:
    from granudb.physics.derive import derive
    from granudb.vocabulary import DERIVED_TERMS, TERMS

    out = derive(
        particle_density_kg_m3=7780.0,
        particle_youngs_modulus_pa=190e9,
        particle_poisson_ratio=0.27,
        particle_roughness_rms_m=23.6e-9,
        wall_density_kg_m3=2540.0,
        wall_youngs_modulus_pa=91e9,
        wall_poisson_ratio=0.24,
        wall_roughness_rms_m=15.5e-9,
        diameter_m=0.0127,
        v_n_in_m_s=0.3,
    )
    assert set(out) == set(DERIVED_TERMS)
    # a stored name never means a derived quantity too
    assert not set(TERMS) & set(DERIVED_TERMS)


def test_fluid_reference_and_state_viscosity_have_different_names(cli, db: str) -> None:
    """``viscosity_pa_s`` was the printed reference in ``fluids show`` and the value at the
    temperature in ``pair``; now the reference is ``reference_viscosity_pa_s`` everywhere."""
    shown = json.loads(cli("fluids", "show", "glycerol-45", "--format", "json", db=db).stdout)
    assert shown["reference_viscosity_pa_s"] == pytest.approx(4.5e-3)
    assert "viscosity_pa_s" not in shown
    document = json.loads(
        cli(
            "pair",
            "glass",
            "Zerodur",
            "--fluid",
            "glycerol-45",
            "--diameter",
            "12.7 mm",
            "--velocity",
            "0.1 m/s",
            "--temperature",
            "30 degC",
            "--format",
            "json",
            db=db,
        ).stdout
    )
    fluid = document["fluid"]
    assert fluid["reference_viscosity_pa_s"] == pytest.approx(4.5e-3)  # as stored
    assert fluid["viscosity_pa_s"] < 4.5e-3  # at 30 °C: thinner
    import granudb

    frame = granudb.fluids(db=db).set_index("name")
    assert frame.loc["glycerol-45", "reference_viscosity_pa_s"] == pytest.approx(4.5e-3)
    assert frame.attrs["units"]["reference_viscosity_pa_s"] == "Pa*s"


def test_stored_angle_and_derived_incidence_angle_are_two_columns(cli, db: str) -> None:
    """The stored (nominal) angle and ζ_in of the contact point are different columns."""
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "ex", db=db).exit_code == 0
    rows = json.loads(cli("collisions", "list", "--wide", "--format", "json", db=db).stdout)
    spun = [r for r in rows if r["omega_in_rad_s"]]
    for row in rows:
        assert 0 <= row["incidence_angle_rad"] < 1.5708
        assert "nominal_angle_rad" in row
    import granudb

    frame = granudb.collisions(db=db, wide=True)
    assert {"incidence_angle_rad", "nominal_angle_rad"} <= set(frame.columns)
    assert frame.attrs["units"]["incidence_angle_rad"] == "rad"
    assert len(spun) == len([r for r in rows if r["omega_in_rad_s"]])


def test_velocity_is_the_impact_speed_with_its_own_rule(cli, db: str) -> None:
    document = json.loads(
        cli(
            "pair",
            "steel",
            "Zerodur",
            "--diameter",
            "12.7 mm",
            "--velocity",
            "0.3 m/s",
            "--angle",
            "30 deg",
            "--format",
            "json",
            db=db,
        ).stdout
    )
    assert document["inputs"]["impact_speed_m_s"] == pytest.approx(0.3)
    assert document["impact_speed_m_s"] == pytest.approx(0.3)
    refused = cli("pair", "steel", "Zerodur", "--diameter", "12.7 mm", "--velocity", "0 m/s", db=db)
    assert refused.exit_code == 1
    assert refused.stderr.startswith("Error: --velocity: 0 m/s must be > 0")


def test_fluid_dry_means_dry_in_pair_and_listing(cli, db: str) -> None:
    dry = cli(
        "pair",
        "steel",
        "Zerodur",
        "--fluid",
        "dry",
        "--diameter",
        "12.7 mm",
        "--velocity",
        "0.3 m/s",
        "--format",
        "json",
        db=db,
    )
    assert dry.exit_code == 0, dry.stderr
    assert json.loads(dry.stdout)["fluid"] is None
    assert cli("collisions", "list", "--fluid", "dry", db=db).exit_code == 0


def test_pair_offers_csv_and_delivers_it(cli, db: str) -> None:
    out = cli(
        "pair",
        "steel",
        "Zerodur",
        "--diameter",
        "12.7 mm",
        "--velocity",
        "0.3 m/s",
        "--format",
        "csv",
        db=db,
    )
    assert out.exit_code == 0, out.stderr
    rows = list(csv.DictReader(io.StringIO(out.stdout)))
    assert len(rows) == 1
    assert float(rows[0]["reduced_modulus_pa"]) == pytest.approx(65.64e9, rel=1e-3)


def test_listing_columns_are_the_same_in_every_format(cli, db: str) -> None:
    cli("collisions", "import", str(EXAMPLE), "--dataset", "ex", db=db)
    as_json = json.loads(cli("collisions", "list", "--format", "json", db=db).stdout)
    as_csv = cli("collisions", "list", "--format", "csv", db=db).stdout.splitlines()[0]
    assert list(as_json[0]) == as_csv.split(",")
    chosen = cli(
        "collisions", "list", "--columns", "run,normal_restitution", "--format", "csv", db=db
    ).stdout.splitlines()
    assert chosen[0] == "run,normal_restitution"
    bad = cli("collisions", "list", "--columns", "bogus", db=db)
    assert bad.exit_code == 1 and "--columns: bogus are not columns" in bad.stderr


def test_runs_sort_naturally(cli, db: str, tmp_path: Path) -> None:
    text = EXAMPLE.read_text(encoding="utf-8").splitlines()
    header, first = text[0], text[1].split(",", 1)[1]
    lines = [header] + [f"run-{i},{first}" for i in (10, 2, 1)]
    path = tmp_path / "runs.csv"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    assert cli("collisions", "import", str(path), "--dataset", "n", db=db).exit_code == 0
    rows = json.loads(cli("collisions", "list", "--dataset", "n", "--format", "json", db=db).stdout)
    assert [r["run"] for r in rows] == ["run-1", "run-2", "run-10"]


def test_library_errors_name_the_python_parameter_and_the_cli_its_option(cli, db: str) -> None:
    import granudb
    from granudb.errors import ValidationError

    with pytest.raises(ValidationError, match=r"^regime: bogus must be one of"):
        granudb.collisions(db=db, regime="bogus")
    frame = granudb.collisions(db=db, angle_range="20..60 deg")
    assert frame.empty
    with pytest.raises(ValidationError, match=r"^angle_range: "):
        granudb.collisions(db=db, angle_range="60..20 deg")
    out = cli("collisions", "list", "--regime", "bogus", db=db)
    assert out.stderr.startswith("Error: --regime: bogus must be one of")


def test_the_readme_one_liner(db: str) -> None:
    import granudb

    result = granudb.pair(
        "steel",
        "Zerodur",
        fluid="glycerol-37",
        diameter="12.7 mm",
        velocity="0.3 m/s",
        angle="30 deg",
        db=db,
    )
    assert result["reduced_modulus_pa"] == pytest.approx(65.64e9, rel=1e-4)
    assert granudb.materials(db=db).set_index("name").loc["glass", "youngs_modulus_pa"] == 6.0e10


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (
            [
                "fluids",
                "add",
                "Dry",
                "--reference-viscosity",
                "1 cP",
                "--reference-density",
                "1000 kg/m^3",
            ],
            "fluid name: Dry is reserved",
        ),
        (
            [
                "materials",
                "add",
                "st\u202eeel",
                "--density",
                "1 kg/m^3",
                "--youngs-modulus",
                "1 GPa",
                "--poisson-ratio",
                "0.3",
                "--roughness",
                "1 nm",
            ],
            "must not contain U+202E",
        ),
        (
            [
                "materials",
                "add",
                "zero\u200bwidth",
                "--density",
                "1 kg/m^3",
                "--youngs-modulus",
                "1 GPa",
                "--poisson-ratio",
                "0.3",
                "--roughness",
                "1 nm",
            ],
            "must not contain U+200B",
        ),
    ],
)
def test_catalogue_names_follow_the_shared_rules(cli, db: str, argv, expected) -> None:
    """One set of name rules for CLI, CSV and packages (``vocabulary/text.py``); "dry" is
    no fluid's name, because it means no fluid everywhere."""
    from support import dump_hash

    before = dump_hash(db)
    out = cli(*argv, db=db)
    assert out.exit_code == 1 and expected in out.stderr and out.stderr.count("\n") == 1
    assert dump_hash(db) == before


def test_human_messages_use_engineering_notation(cli, db: str) -> None:
    """``materials update`` said ``roughness_rms_m 2e-07 → 1.8e-07``: raw SI for a person."""
    out = cli("materials", "update", "glass", "--roughness", "120 nm", db=db)
    assert out.exit_code == 0, out.stderr
    assert "roughness_rms_m 130.5 nm → 120 nm" in out.stdout


def test_collisions_list_fits_100_columns(cli, db: str, monkeypatch) -> None:
    """The default table: symbol headers, one line per run, nothing cut, at 100 columns."""
    cli("collisions", "import", str(EXAMPLE), "--dataset", "ex", db=db)
    monkeypatch.setenv("COLUMNS", "100")
    out = cli("collisions", "list", db=db).stdout
    lines = out.splitlines()
    assert max(len(line.rstrip()) for line in lines) <= 100
    assert "…" not in out
    assert lines[1].split()[:4] == ["run", "pair", "fluid", "v_n,in"]
    assert len([line for line in lines if line.startswith(("glass-", "steel-"))]) == 12


def test_a_yield_stress_reaches_the_verdict(cli, db: str) -> None:
    """A stored yield stress gives the yield speed and, above it, the elastic state."""
    assert cli("materials", "update", "steel", "--yield-stress", "1.7 GPa", db=db).exit_code == 0
    import granudb

    # with the wall's yield stress unknown, "elastic" cannot be claimed
    one_known = granudb.pair("steel", "Zerodur", diameter="12.7 mm", velocity="0.3 m/s", db=db)
    assert one_known["elastic_state"] == "unknown"
    assert cli("materials", "update", "Zerodur", "--yield-stress", "5 GPa", db=db).exit_code == 0

    slow = granudb.pair("steel", "Zerodur", diameter="12.7 mm", velocity="0.3 m/s", db=db)
    fast = granudb.pair("steel", "Zerodur", diameter="12.7 mm", velocity="5 m/s", db=db)
    assert slow["yield_speed_m_s"] > 0.3 and slow["elastic_state"] == "elastic"
    assert fast["elastic_state"] == "yield_exceeded" and not fast["quasi_static_valid"]
    unknown = granudb.pair("glass", "Zerodur", diameter="12.7 mm", velocity="5 m/s", db=db)
    assert unknown["elastic_state"] == "unknown"


def test_listed_csv_cannot_run_as_a_spreadsheet_formula(cli, db: str) -> None:
    for name in ('=HYPERLINK("http://x")', "+1+1", "@SUM(A1)"):
        out = cli(
            "materials",
            "add",
            name,
            "--density",
            "1 kg/m^3",
            "--youngs-modulus",
            "1 GPa",
            "--poisson-ratio",
            "0.3",
            "--roughness",
            "1 nm",
            db=db,
        )
        assert out.exit_code == 0, out.stderr
    rows = list(
        csv.DictReader(io.StringIO(cli("materials", "list", "--format", "csv", db=db).stdout))
    )
    names = {r["name"] for r in rows}
    assert {'\'=HYPERLINK("http://x")', "'+1+1", "'@SUM(A1)"} <= names
    shown = json.loads(cli("materials", "list", "--format", "json", db=db).stdout)
    assert '=HYPERLINK("http://x")' in {m["name"] for m in shown}  # stored as typed
    assert all(not r["density_kg_m3"].startswith("'") for r in rows)


def test_names_are_printed_as_typed_not_as_emoji(cli, db) -> None:
    """Rich's console turned ``:smile:`` in a dataset name into 😄 in the import's
    confirmation; a name is data, printed as typed."""
    result = cli("collisions", "import", str(EXAMPLE), "--dataset", ":smile: [b]x[/b]", db=db)
    assert result.exit_code == 0, result.stderr
    assert "into dataset :smile: [b]x[/b] 1.0.0" in result.stdout
