"""Values with their standard uncertainty: typed with ±, stored per catalogue value, shown by
``pair`` with the verdicts' probabilities, carried by Data Packages byte for byte."""

from __future__ import annotations

import csv
import hashlib
import io
import json
import math
from pathlib import Path

import pytest
from support import STEEL_ON_ZERODUR, dump_hash

import granudb
from granudb.errors import ValidationError
from granudb.io.units import parse_uncertain_quantity
from granudb.physics.derive import derive as derive_arrays

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "collisions_example.csv"


@pytest.mark.parametrize(
    ("text", "unit", "expected"),
    [
        ("23.6 ± 2 nm", "m", (23.6e-9, 2e-9)),
        ("23.6 nm ± 2 nm", "m", (23.6e-9, 2e-9)),
        ("(23.6 ± 2) nm", "m", (23.6e-9, 2e-9)),
        ("190 GPa ± 5 %", "pa", (190e9, 9.5e9)),
        ("190 GPa +/- 5 GPa", "pa", (190e9, 5e9)),
        ("0.3 m/s +- 10 mm/s", "m_s", (0.3, 0.01)),
        ("20 degC ± 0.5 K", "c", (20.0, 0.5)),
        ("0.27 ± 0.01", "", (0.27, 0.01)),
        ("12.7 mm", "m", (12.7e-3, None)),
    ],
)
def test_plus_minus_is_read_by_the_one_parser(text: str, unit: str, expected: tuple) -> None:
    value, u = parse_uncertain_quantity(text, unit, "x")
    assert value == pytest.approx(expected[0], rel=1e-12)
    assert u == (None if expected[1] is None else pytest.approx(expected[1], rel=1e-12))


@pytest.mark.parametrize(
    ("text", "rule"),
    [
        ("23.6 ± -2 nm", "non-negative"),
        ("190 GPa ± 5 m", "not a pressure"),
        ("190 GPa ± x", "non-negative number"),
    ],
)
def test_a_bad_uncertainty_is_refused_by_name(text: str, rule: str) -> None:
    with pytest.raises(ValidationError, match=rule) as caught:
        parse_uncertain_quantity(text, "pa" if "GPa" in text else "m", "roughness")
    assert caught.value.field == "roughness"


def test_catalogue_stores_the_uncertainty_and_a_new_value_replaces_it(opened) -> None:
    granudb.add_material(
        "lapped-steel",
        density="7780 kg/m^3",
        youngs_modulus="190 GPa ± 5 %",
        poisson_ratio=0.27,
        roughness="46 ± 5 nm",
        db=opened,
    )
    stored = granudb.material("lapped-steel", db=opened)
    assert stored["u_youngs_modulus_pa"] == pytest.approx(9.5e9)
    assert stored["u_roughness_rms_m"] == pytest.approx(5e-9)
    assert stored["u_density_kg_m3"] is None  # not given: empty, not zero
    frame = granudb.materials(db=opened).set_index("name")
    assert frame.loc["lapped-steel", "u_roughness_rms_m"] == pytest.approx(5e-9)
    granudb.update_material("lapped-steel", roughness="40 nm", db=opened)
    assert granudb.material("lapped-steel", db=opened)["u_roughness_rms_m"] is None


def test_refused_uncertainty_leaves_the_database_unchanged(cli, db: str) -> None:
    before = dump_hash(db)
    result = cli(
        "materials", "add", "bad", "--density", "7780 kg/m^3", "--youngs-modulus",
        "190 GPa ± -5 %", "--poisson-ratio", "0.27", "--roughness", "1 nm", db=db,
    )  # fmt: skip
    assert result.exit_code != 0
    assert "--youngs-modulus" in result.stderr and "Traceback" not in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1
    assert dump_hash(db) == before


def test_pair_near_sigma_equal_to_h_m_gives_an_uncertain_contact(cli, db: str, opened) -> None:
    """Steel lapped to σ = 46 ± 5 nm on Zerodur (σ_composite ≈ h_m = 48 nm) in 37 %
    glycerol: P(σ > h_m) is between 0.2 and 0.8, and the verdict says "uncertain"
    in Python, JSON and the table alike."""
    granudb.add_material(
        "lapped-steel",
        density="7780 kg/m^3",
        youngs_modulus="190 GPa ± 5 %",
        poisson_ratio="0.27 ± 0.01",
        roughness="46 ± 5 nm",
        db=opened,
    )
    args = dict(fluid="glycerol-37", diameter="12.7 mm", velocity="0.3 m/s ± 3 %",
                angle="30 deg", temperature="20 degC ± 0.5 K")  # fmt: skip
    result = granudb.pair("lapped-steel", "Zerodur", **args, db=opened)
    probability = result["probability_asperity_contact"]
    assert 0.2 < probability < 0.8
    roughness = next(v for v in result["verdicts"] if v["key"] == "roughness_regime")
    assert f"P(σ > h_m) = {probability:.2f}: uncertain." in roughness["text"]
    assert result["u_normal_stokes_number"] > 0
    options = [f"--{k.replace('_', '-')}={v}" for k, v in args.items()]
    shown = cli("pair", "lapped-steel", "Zerodur", *options, "--format", "json", db=db)
    assert json.loads(shown.stdout)["probability_asperity_contact"] == probability
    table = cli("pair", "lapped-steel", "Zerodur", *options, db=db).stdout
    assert "46 ± 5 nm" in table and "uncertain" in table
    row = next(csv.DictReader(io.StringIO(
        cli("pair", "lapped-steel", "Zerodur", *options, "--format", "csv", db=db).stdout
    )))  # fmt: skip
    assert float(row["probability_asperity_contact"]) == pytest.approx(probability)


def test_temperature_uncertainty_reaches_the_viscosity(opened) -> None:
    """±0.5 K on glycerol-37 at 20 °C moves μ by |dμ/dT|·0.5 K (≈ 1.5 %, several % per
    kelvin for glycerol): it shows in u(μ) and in u(St_n), and nothing else is uncertain."""
    base = dict(fluid="glycerol-37", diameter="12.7 mm", velocity="0.3 m/s", db=opened)
    exact = granudb.pair("steel", "Zerodur", temperature="20 degC", **base)
    warm = granudb.pair("steel", "Zerodur", temperature="21 degC", **base)
    given = granudb.pair("steel", "Zerodur", temperature="20 degC ± 0.5 K", **base)
    slope = abs(warm["fluid"]["viscosity_pa_s"] - exact["fluid"]["viscosity_pa_s"])
    assert given["inputs"]["u_viscosity_pa_s"] == pytest.approx(0.5 * slope, rel=0.05)
    relative = given["u_normal_stokes_number"] / given["normal_stokes_number"]
    assert relative == pytest.approx(0.5 * slope / exact["fluid"]["viscosity_pa_s"], rel=0.05)
    assert math.isnan(exact["u_normal_stokes_number"])  # nothing stated: none, never 0


def test_uncertainties_round_trip_through_a_package_byte_for_byte(
    cli, db: str, new_db: str, tmp_path: Path
) -> None:
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db).exit_code == 0
    for where in (db, new_db):  # the receiver's seeded steel must agree to merge
        changed = cli("materials", "update", "steel", "--youngs-modulus", "190 GPa ± 5 %",
                      "--roughness", "23.6 ± 2 nm", db=where)  # fmt: skip
        assert changed.exit_code == 0, changed.stderr
    first = tmp_path / "one"
    assert cli("dataset", "export", "example", "--output", str(first), db=db).exit_code == 0
    rows = list(csv.DictReader(io.StringIO((first / "data" / "materials.csv").read_text("utf-8"))))
    steel = next(r for r in rows if r["name"] == "steel")
    assert float(steel["u_youngs_modulus_pa"]) == 9.5e9
    imported = cli("dataset", "import", str(first), db=new_db)
    assert imported.exit_code == 0, imported.stderr
    second = tmp_path / "two"
    assert cli("dataset", "export", "example", "--output", str(second), db=new_db).exit_code == 0
    for name in ("materials", "fluids"):
        assert (first / "data" / f"{name}.csv").read_bytes() == (
            second / "data" / f"{name}.csv"
        ).read_bytes()


def test_derive_frame_takes_u_columns_and_carries_the_probabilities() -> None:
    """``granudb.derive`` of a table with ``u_<input>`` columns: the same u and
    probabilities as the physics' arrays give, and a negative u refused by row."""
    frame = {name: [value, value] for name, value in STEEL_ON_ZERODUR.items()}
    frame |= {
        "v_n_in_m_s": [0.3, 0.05],
        "viscosity_pa_s": [3.2e-3, 3.2e-3],
        "fluid_density_kg_m3": [1090.0, 1090.0],
        "u_viscosity_pa_s": [1.6e-4, 1.6e-4],
    }
    out = granudb.derive(frame)
    arrays = derive_arrays(
        **{k: v for k, v in frame.items() if not k.startswith("u_")},
        uncertainties={"u_viscosity_pa_s": frame["u_viscosity_pa_s"]},
    )
    for column in ("u_normal_stokes_number", "u_min_gap_m", "probability_asperity_contact"):
        assert list(out[column]) == list(arrays[column])
    assert out.attrs["units"]["u_min_gap_m"] == "m"
    frame["u_viscosity_pa_s"] = [1.6e-4, -1.0]
    with pytest.raises(ValidationError, match="u_viscosity_pa_s") as caught:
        granudb.derive(frame)
    assert caught.value.row == 2
    # the propagation's options are options, not columns, and are checked as such
    from granudb.api.derivation import INPUTS

    assert "monte_carlo" not in INPUTS and "monte_carlo_draws" not in INPUTS
    frame["u_viscosity_pa_s"] = [0.8e-3, 0.8e-3]  # 25 %: the check sends St to the draws
    with_mc = granudb.derive(frame)["propagation_method"]
    assert all(m.startswith("Monte Carlo") for m in with_mc)
    first = granudb.derive(frame, monte_carlo=False)["propagation_method"]
    assert all(m.startswith("first order (GUM); the check failed for") for m in first)
    spent = granudb.derive(frame, monte_carlo_draws=0)["propagation_method"]
    assert all("Monte Carlo not run" in m for m in spent)
    for option, value in (("monte_carlo", "yes"), ("monte_carlo_draws", -1)):
        with pytest.raises(ValidationError, match=option):
            granudb.derive(frame, **{option: value})


def test_fluid_points_carry_their_uncertainty_into_the_viscosity(opened) -> None:
    """A point's "0.9325 ± 0.005 cP" is stored and, where the reference viscosity states
    none, is the u(μ) of the fluid at that temperature (as a relative u)."""
    granudb.add_fluid_point(
        "water", temperature="23 degC", viscosity="0.9325 ± 0.005 cP",
        density="997.5 ± 0.1 kg/m^3", db=opened,
    )  # fmt: skip
    point = next(p for p in granudb.fluid("water", db=opened)["points"] if p["temperature_c"] == 23)
    assert (point["u_viscosity_pa_s"], point["u_density_kg_m3"]) == (5e-6, 0.1)
    result = granudb.pair(
        "steel", "Zerodur", fluid="water", diameter="12.7 mm", velocity="0.3 m/s",
        temperature="23 degC", db=opened,
    )  # fmt: skip
    relative = result["inputs"]["u_viscosity_pa_s"] / result["fluid"]["viscosity_pa_s"]
    assert relative == pytest.approx(0.005 / 0.9325, rel=1e-9)
    st_n = result["u_normal_stokes_number"] / result["normal_stokes_number"]
    assert st_n == pytest.approx(relative, rel=1e-9)


@pytest.mark.parametrize("dropped", [("u_",), ("u_", "dry_", "brittleness"), ("conditions",)])
def test_a_package_from_before_the_uncertainties_still_imports(
    cli, db: str, new_db: str, tmp_path: Path, dropped: tuple[str, ...]
) -> None:
    """A package whose materials, fluids and points lack the u columns, or also the dry
    values, their origin and brittleness (earlier releases' packages), or only the
    conditions (the previous release's), is read with them empty; a package of today
    carries them and round-trips them."""
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db).exit_code == 0
    out = tmp_path / "old"
    assert cli("dataset", "export", "example", "--output", str(out), db=db).exit_code == 0
    descriptor = json.loads((out / "datapackage.json").read_text("utf-8"))
    for resource in descriptor["resources"]:
        path = out / resource["path"]
        rows = list(csv.reader(io.StringIO(path.read_text("utf-8"), newline="")))
        keep = [i for i, name in enumerate(rows[0]) if not name.startswith(dropped)]
        buffer = io.StringIO(newline="")
        csv.writer(buffer, lineterminator="\n").writerows([[r[i] for i in keep] for r in rows])
        payload = buffer.getvalue().encode("utf-8")
        path.write_bytes(payload)
        resource["bytes"] = len(payload)
        resource["hash"] = "sha256:" + hashlib.sha256(payload).hexdigest()
        fields = resource["schema"]["fields"]
        resource["schema"]["fields"] = [f for f in fields if not f["name"].startswith(dropped)]
    (out / "datapackage.json").write_text(json.dumps(descriptor), "utf-8")
    result = cli("dataset", "import", str(out), db=new_db)
    assert result.exit_code == 0, result.stderr


def test_a_release_keeps_the_values_and_uncertainties_it_was_released_with(cli, db: str) -> None:
    """Giving steel an uncertainty after a release is a change like any other: the
    release's runs keep steel as it was (no u), the live steel carries the new u."""
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db).exit_code == 0
    assert cli("dataset", "release", "example", db=db).exit_code == 0
    assert cli("materials", "update", "steel", "--roughness", "23.6 ± 2 nm", db=db).exit_code == 0
    history = json.loads(cli("materials", "history", "steel", "--format", "json", db=db).stdout)
    assert [r["u_roughness_rms_m"] for r in history] == [2e-9, None]
