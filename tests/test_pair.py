"""``granudb pair``: one collision, from stored properties to verdicts."""

from __future__ import annotations

import json

import pytest
from support import dump_hash

from granudb.io.seed import read_seed

REQUIRED_KEYS = [
    "reduced_modulus_pa",
    "reduced_shear_modulus_pa",
    "effective_radius_m",
    "effective_mass_kg",
    "reynolds_number",
    "stokes_number",
    "normal_stokes_number",
    "impact_load_n",
    "contact_radius_m",
    "max_pressure_pa",
    "max_approach_m",
    "contact_time_s",
    "elastic_length_m",
    "min_gap_m",
    "piezoviscous_length_m",
    "traction_film_m",
    "lubricated_friction",
    "composite_roughness_m",
    "film_parameter",
    "roughness_exceeds_gap",
    "rebound_expected",
    "tangential_regime",
]


def _json(cli, db, *args: str) -> dict:
    result = cli("pair", *args, "--format", "json", db=db)
    assert result.exit_code == 0, result.stderr
    return json.loads(result.stdout)


def test_json_has_every_documented_key_in_si(cli, db: str) -> None:
    data = _json(
        cli,
        db,
        "steel",
        "zerodur",
        "--fluid",
        "glycerol-37",
        "--diameter",
        "12.7 mm",
        "--velocity",
        "0.3 m/s",
    )
    for key in REQUIRED_KEYS:
        assert key in data, key
    assert data["reduced_modulus_pa"] == pytest.approx(65.64e9, rel=1e-3)
    assert data["effective_radius_m"] == pytest.approx(6.35e-3)
    assert isinstance(data["roughness_exceeds_gap"], bool)
    assert data["tangential_regime"] in {"stick", "slip_then_stick", "gross_slip"}
    assert data["particle"]["name"] == "steel" and data["wall"]["source"] == "joseph-hunt-2004"
    assert data["fluid"]["pressure_viscosity_pa_inv"] == 6e-9
    assert "joseph-hunt-2004" in data["sources"]


def test_glass_in_45_percent_glycerol_is_flagged_and_steel_is_not(cli, db: str) -> None:
    # §4: glass roughness exceeds h_m (asperity contact); steel stays below (or near) it.
    glass = _json(
        cli,
        db,
        "glass",
        "Zerodur",
        "--fluid",
        "glycerol-45",
        "--diameter",
        "12.7 mm",
        "--velocity",
        "0.1 m/s",
    )
    assert glass["roughness_exceeds_gap"] is True
    assert glass["composite_roughness_m"] / glass["min_gap_m"] == pytest.approx(2.8, rel=0.15)
    steel = _json(
        cli,
        db,
        "steel",
        "Zerodur",
        "--fluid",
        "glycerol-78",
        "--diameter",
        "12.7 mm",
        "--velocity",
        "0.1 m/s",
    )
    assert steel["roughness_exceeds_gap"] is False
    assert steel["film_parameter"] > 1


def test_figure_3_numbers_through_the_cli(cli, db: str) -> None:
    data = _json(
        cli,
        db,
        "glass",
        "Zerodur",
        "--fluid",
        "glycerol-45",
        "--diameter",
        "12.7 mm",
        "--velocity",
        "0.1193 m/s",
    )
    assert data["stokes_number"] == pytest.approx(95, abs=0.5)
    # the seeded density (Volk & Kähler at 20 °C, 1112.5 kg/m³) gives Re ≈ 374
    assert data["reynolds_number"] == pytest.approx(374, abs=1.5)


def test_dry_collision_has_no_fluid_quantities(cli, db: str) -> None:
    data = _json(
        cli,
        db,
        "steel",
        "Zerodur",
        "--diameter",
        "12.7 mm",
        "--velocity",
        "0.3 m/s",
        "--angle",
        "30 deg",
    )
    assert data["fluid"] is None
    assert data["stokes_number"] is None and data["min_gap_m"] is None
    assert data["rebound_expected"] is True and data["roughness_exceeds_gap"] is False
    assert data["inputs"]["v_t_in_m_s"] == pytest.approx(0.15)


def test_slow_viscous_impact_does_not_rebound(cli, db: str) -> None:
    data = _json(
        cli,
        db,
        "glass",
        "Zerodur",
        "--fluid",
        "glycerol-78",
        "--diameter",
        "3 mm",
        "--velocity",
        "5 mm/s",
    )
    assert data["normal_stokes_number"] < 10 and data["rebound_expected"] is False


def test_temperature_interpolates_the_fluid_points(cli, db: str) -> None:
    data = _json(
        cli,
        db,
        "steel",
        "Zerodur",
        "--fluid",
        "water",
        "--diameter",
        "12.7 mm",
        "--velocity",
        "0.3 m/s",
        "--temperature",
        "30 degC",
    )
    assert data["fluid"]["viscosity_pa_s"] == pytest.approx(0.797e-3, rel=0.01)
    assert "at 30 °C" in data["fluid"]["viscosity_basis"]
    assert "scaled through the printed" in data["fluid"]["viscosity_basis"]
    override = _json(
        cli,
        db,
        "steel",
        "Zerodur",
        "--fluid",
        "water",
        "--diameter",
        "12.7 mm",
        "--velocity",
        "0.3 m/s",
        "--viscosity",
        "0.8 cP",
    )
    assert override["fluid"]["viscosity_pa_s"] == pytest.approx(0.8e-3)


def test_table_output_speaks_in_words_and_units(cli, db: str) -> None:
    result = cli(
        "pair",
        "glass",
        "Zerodur",
        "--fluid",
        "glycerol-45",
        "--diameter",
        "12.7 mm",
        "--velocity",
        "0.1 m/s",
        "--angle",
        "20 deg",
        db=db,
    )
    assert result.exit_code == 0, result.stderr
    out = result.stdout
    assert "38.25 GPa" in out and "nm" in out and "µs" in out
    assert "Roughness exceeds the gap" in out and "Asperities touch" in out
    assert "h_m = x₁/3" in out


@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (["--velocity", "-0.3 m/s"], "--velocity: -0.3 m/s must be > 0"),
        (["--velocity", "0.3 m"], "--velocity: 0.3 m is not a velocity"),
        (["--velocity", "0.3"], "--velocity: 0.3 needs a unit"),
        (["--angle", "90 deg"], "--angle: 90 deg must be ≥ 0° and < 90°"),
        (["--angle", "-5 deg"], "--angle: -5 deg must be ≥ 0° and < 90°"),
        (["--diameter", "0 mm"], "--diameter: 0 mm must be > 0"),
        (["--fluid", "mercury"], "fluid: 'mercury' is not in the database"),
        (
            ["--fluid", "water", "--temperature", "80 degC"],
            "--temperature: 80 °C is outside the temperature range 10 to 60 °C",
        ),
        (["--viscosity", "1 cP"], "--viscosity: 1 cP needs a fluid"),
    ],
)
def test_bad_input(cli, db: str, args: list[str], expected: str) -> None:
    base = {"--diameter": "12.7 mm", "--velocity": "0.3 m/s"}
    argv = ["pair", "steel", "Zerodur"]
    for option, value in base.items():
        if option not in args:
            argv += [option, value]
    before = dump_hash(db)
    result = cli(*argv, *args, db=db)
    assert result.exit_code == 1
    assert result.stderr.count("\n") == 1 and expected in result.stderr, result.stderr
    assert dump_hash(db) == before


def test_unknown_material_lists_the_known_ones(cli, db: str) -> None:
    result = cli("pair", "brass", "Zerodur", "--diameter", "1 mm", "--velocity", "1 m/s", db=db)
    assert result.exit_code == 1
    known = ", ".join(sorted((m["name"] for m in read_seed().materials), key=str.casefold))
    assert f"material: 'brass' is not in the database (known: {known})" in result.stderr
