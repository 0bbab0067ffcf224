"""The Python API is as strict as the command line: each bad input to ``granudb.derive``
and to a quantity is refused in one line naming the column or parameter, the value and
the rule, and what is good but of another numeric type is taken as the same number."""

from __future__ import annotations

from decimal import Decimal
from fractions import Fraction

import numpy as np
import pandas as pd
import pytest

import granudb
from granudb.api import inputs
from granudb.errors import MissingInput, ValidationError

STEEL_ON_ZERODUR = {
    "particle_density_kg_m3": 7780.0,
    "particle_youngs_modulus_pa": 190e9,
    "particle_poisson_ratio": 0.27,
    "particle_roughness_rms_m": 23.6e-9,
    "wall_density_kg_m3": 2540.0,
    "wall_youngs_modulus_pa": 91e9,
    "wall_poisson_ratio": 0.24,
    "wall_roughness_rms_m": 15.5e-9,
    "diameter_m": 0.0127,
    "v_n_in_m_s": 0.3,
    "v_n_out_m_s": 0.1,
}
IN_GLYCEROL = {"viscosity_pa_s": 4.5e-3, "fluid_density_kg_m3": 1090.0}


def _frame(**changes: object) -> pd.DataFrame:
    row = {**STEEL_ON_ZERODUR, **IN_GLYCEROL}
    for column, value in changes.items():
        if value is ...:
            row.pop(column)
        else:
            row[column] = value
    return pd.DataFrame({c: [v] for c, v in row.items()})


def _refusal(call) -> str:
    with pytest.raises(ValidationError) as caught:
        call()
    line = str(caught.value)
    assert "\n" not in line and "Traceback" not in line
    return line


BAD_FRAMES = [
    # (what a user did, the frame's changes, words the refusal must hold)
    ("misnamed viscosity", {"viscosity_pa_s": ..., "viscosity": 4.5e-3}, ["viscosity_pa_s"]),
    ("misnamed diameter", {"diameter_m": ..., "diameter": 0.0127}, ["diameter_m"]),
    ("near miss", {"diameter_m": ..., "diamter_m": 0.0127}, ["diameter_m"]),
    ("option as column", {"critical_stokes": 5.0}, ["option", "keyword"]),
    ("missing inputs", {"diameter_m": ..., "v_n_in_m_s": ...}, ["diameter_m", "v_n_in_m_s"]),
    ("text with a unit", {"diameter_m": "12.7 mm"}, ["diameter_m", "12.7 mm", "not text"]),
    ("a bool", {"v_n_in_m_s": True}, ["v_n_in_m_s", "True/False"]),
    ("complex", {"diameter_m": 0.0127 + 1j}, ["diameter_m", "real"]),
    ("infinite diameter", {"diameter_m": np.inf}, ["diameter_m", "finite"]),
    ("negative roughness", {"particle_roughness_rms_m": -1.0}, ["roughness", "≥ 0"]),
    ("negative viscosity", {"viscosity_pa_s": -1e-3}, ["viscosity_pa_s", "> 0"]),
    ("Poisson ratio 0.7", {"wall_poisson_ratio": 0.7}, ["wall_poisson_ratio"]),
    ("a required NaN", {"v_n_in_m_s": None}, ["v_n_in_m_s", "every row"]),
    ("zero density", {"wall_density_kg_m3": 0.0}, ["wall_density_kg_m3", "> 0"]),
]


@pytest.mark.parametrize(
    ("changes", "words"), [c[1:] for c in BAD_FRAMES], ids=[c[0] for c in BAD_FRAMES]
)
def test_derive_refuses_in_one_line(changes: dict, words: list[str]) -> None:
    line = _refusal(lambda: granudb.derive(_frame(**changes)))
    for word in words:
        assert word in line, line


@pytest.mark.parametrize(
    ("options", "words"),
    [
        ({"critical_stokes": float("nan")}, ["critical_stokes", "finite"]),
        ({"critical_stokes": -3}, ["critical_stokes", "> 0"]),
        ({"critical_stokes": 1j}, ["critical_stokes", "real"]),
        ({"critical_stoke": 10}, ["critical_stoke", "critical_stokes"]),
        ({"dry_restitution": 1.5}, ["dry_restitution", "≤ 1"]),
        ({"threads": 4}, ["threads", "not an option"]),
    ],
)
def test_derive_checks_its_options_as_the_command_line(options: dict, words: list[str]) -> None:
    line = _refusal(lambda: granudb.derive(_frame(), **options))
    for word in words:
        assert word in line, line


def test_a_misnamed_column_is_not_silently_dry() -> None:
    """The issue's case: ``viscosity`` instead of ``viscosity_pa_s`` gave a dry result
    (St_n NaN, e 0.97); now it is refused, and the right name gives the wet numbers."""
    wet = granudb.derive(_frame())
    assert np.isfinite(wet["normal_stokes_number"][0])
    with pytest.raises(ValidationError):
        granudb.derive(_frame(viscosity_pa_s=..., viscosity=4.5e-3))


def test_other_numeric_types_are_the_same_numbers() -> None:
    plain = granudb.derive(_frame())
    for value in (np.float32(0.0127), Decimal("0.0127"), Fraction(127, 10_000)):
        other = granudb.derive(_frame(diameter_m=value))
        np.testing.assert_allclose(
            other["normal_stokes_number"], plain["normal_stokes_number"], rtol=1e-6
        )
    as_int = granudb.derive(_frame(wall_density_kg_m3=np.int64(2540)))
    assert as_int["reduced_modulus_pa"][0] == plain["reduced_modulus_pa"][0]


def test_extra_columns_are_carried_through_and_the_input_is_not_changed() -> None:
    frame = _frame().assign(run="r1", operator="me")
    before = frame.copy()
    out = granudb.derive(frame)
    assert list(out["run"]) == ["r1"] and "reduced_modulus_pa" in out
    pd.testing.assert_frame_equal(frame, before)


def test_a_mapping_of_columns_is_a_table_and_anything_else_is_refused() -> None:
    out = granudb.derive({c: [v] for c, v in STEEL_ON_ZERODUR.items()})
    assert out["reduced_modulus_pa"][0] == pytest.approx(65.64e9, rel=1e-3)
    assert "DataFrame" in _refusal(lambda: granudb.derive([1, 2, 3]))


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        (0.3, 0.3),
        (np.float32(0.25), 0.25),
        (np.int64(2), 2.0),
        (Decimal("0.3"), 0.3),
        (Fraction(1, 4), 0.25),
        ("0.3 m/s", 0.3),
        ("30 cm/s", 0.3),
    ],
)
def test_a_quantity_takes_every_real_number(value: object, expected: float) -> None:
    assert inputs.quantity(value, "v_n_in_m_s", "velocity") == pytest.approx(expected)


@pytest.mark.parametrize(
    ("value", "words"),
    [
        (True, "True/False"),
        (np.bool_(False), "True/False"),
        (1 + 2j, "real"),
        (float("nan"), "finite"),
        (float("inf"), "finite"),
        ([0.3], "number or a quantity"),
        (object(), "number or a quantity"),
        ("0.3", "unit"),
        ("-0.3 m/s", "> 0"),
        ("0.3 kg", "velocity"),
    ],
)
def test_a_quantity_refuses_by_parameter_name(value: object, words: str) -> None:
    line = _refusal(lambda: inputs.quantity(value, "v_n_in_m_s", "velocity"))
    assert line.startswith("velocity") or "velocity" in line.split(":")[0], line
    assert words in line, line


def test_a_missing_required_value_is_a_missing_input(tmp_path) -> None:
    db = granudb.connect(tmp_path / "g.sqlite")
    try:
        with pytest.raises(MissingInput):
            granudb.pair("steel", "Zerodur", diameter="12.7 mm", velocity=None, db=db)
        line = _refusal(
            lambda: granudb.pair("steel", "Zerodur", diameter=True, velocity=0.3, db=db)
        )
        assert "diameter" in line
    finally:
        db.dispose()


def test_a_catalogue_value_the_specification_lacks_is_refused_by_name(tmp_path) -> None:
    """``add_material`` and friends take the specification's values as keywords: a
    misspelt one is a one-line refusal with the nearest name, and nothing is stored."""
    db = granudb.connect(tmp_path / "g.sqlite")
    try:
        line = _refusal(
            lambda: granudb.add_material(
                "PTFE", densty=2200, youngs_modulus=5e8, poisson_ratio=0.46, roughness=0, db=db
            )
        )
        assert line.startswith("densty") and "did you mean density?" in line, line
        line = _refusal(lambda: granudb.update_fluid("water", viscosity="1 cP", db=db))
        assert line.startswith("viscosity") and "viscosity?" in line, line
        assert "PTFE" not in set(granudb.materials(db=db)["name"])
    finally:
        db.dispose()


def test_a_refusal_names_the_parameter_in_python_and_the_option_on_the_command_line(
    tmp_path,
) -> None:
    """Refusals raised below the API with the option's spelling (``--output``) and those
    of the physics kernels (a temperature outside a fluid's data) read as the parameter a
    Python caller typed, and as the option on the command line: one error, two spellings."""
    db = granudb.connect(tmp_path / "g.sqlite")
    existing = tmp_path / "taken.html"
    existing.write_text("mine")
    try:
        hot = _refusal(
            lambda: granudb.pair(
                "steel", "Zerodur", diameter="12.7 mm", velocity="0.3 m/s", fluid="water",
                temperature="80 degC", db=db,
            )
        )  # fmt: skip
        assert hot.startswith("temperature: 80 °C is outside the temperature range 10 to 60 °C")
        taken = _refusal(lambda: granudb.report(output=existing, db=db))
        assert taken.startswith(f"output: {existing} exists"), taken
        csv = tmp_path / "runs.csv"
        csv.write_text("run\n")
        split = _refusal(lambda: granudb.import_collisions(csv, dataset="d", delimiter="|", db=db))
        assert split.startswith("delimiter: '|' must be"), split
    finally:
        db.dispose()
    assert existing.read_text() == "mine"
    with pytest.raises(ValidationError) as caught:
        raise ValidationError("--output", "x.html", "exists")
    assert str(caught.value) == "output: x.html exists"
    assert caught.value.as_option() == "--output: x.html exists"
