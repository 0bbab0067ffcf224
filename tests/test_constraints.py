"""The database itself refuses unphysical rows, whatever program writes them.

Rows are inserted with plain SQL through a bare engine, as another tool would, so only the
schema's CHECK, NOT NULL, UNIQUE and FOREIGN KEY constraints stand in the way.
"""

from __future__ import annotations

import pytest
from sqlalchemy.exc import IntegrityError
from support import execute

GOOD_MATERIAL = {
    "name": "m",
    "name_key": "m",
    "density_kg_m3": 1000.0,
    "youngs_modulus_pa": 1e9,
    "poisson_ratio": 0.3,
    "roughness_rms_m": 1e-8,
}


def _insert(db: str, table: str, row: dict[str, object]) -> None:
    columns = ", ".join(row)
    marks = ", ".join(f":{c}" for c in row)
    execute(db, f"INSERT INTO {table} ({columns}) VALUES ({marks})", row)


def _insert_material(db: str, **changes: object) -> None:
    _insert(db, "materials", {**GOOD_MATERIAL, **changes})


@pytest.mark.parametrize(
    ("column", "value"),
    [
        ("density_kg_m3", 0.0),
        ("density_kg_m3", -1.0),
        ("density_kg_m3", None),
        ("youngs_modulus_pa", 0.0),
        ("youngs_modulus_pa", None),
        ("poisson_ratio", 0.5),
        ("poisson_ratio", -1.0),
        ("poisson_ratio", 0.7),
        ("roughness_rms_m", -1e-9),
        ("correlation_length_m", 0.0),
        ("shear_modulus_pa", -1.0),
        ("name", ""),
        ("source_id", 9999),
    ],
)
def test_material_rules(db: str, column: str, value: object) -> None:
    with pytest.raises(IntegrityError):
        _insert_material(db, **{column: value})


def test_a_good_material_row_is_accepted_and_names_are_unique(db: str) -> None:
    _insert_material(db)
    with pytest.raises(IntegrityError, match="(?i)unique"):
        _insert_material(db, name="M")  # name_key "m" again


def _insert_collision(db: str, **changes: object) -> None:
    execute(
        db,
        "INSERT INTO datasets (name, version) SELECT 'd', '1' WHERE NOT EXISTS "
        "(SELECT 1 FROM datasets WHERE name = 'd')",
    )
    row = {
        "run": "r1",
        "particle_id": 1,
        "wall_id": 2,
        "fluid_id": None,
        "diameter_m": 0.0127,
        "nominal_angle_rad": 0.3,
        "v_n_in_m_s": 0.3,
        "v_t_in_m_s": 0.1,
        "omega_in_rad_s": 0.0,
        "v_n_out_m_s": 0.2,
        "v_t_out_m_s": 0.05,
        "omega_out_rad_s": 3.0,
        **changes,
    }
    columns = ", ".join(row)
    marks = ", ".join(f":{c}" for c in row)
    execute(
        db,
        f"INSERT INTO collisions (dataset_id, {columns}) "
        f"SELECT id, {marks} FROM datasets WHERE name = 'd'",
        row,
    )


@pytest.mark.parametrize(
    ("column", "value"),
    [
        ("diameter_m", 0.0),
        ("v_n_in_m_s", 0.0),
        ("v_n_in_m_s", -0.1),
        ("v_t_in_m_s", -0.1),
        ("v_n_out_m_s", -0.1),
        ("nominal_angle_rad", -0.1),
        ("nominal_angle_rad", 1.5708),
        ("particle_id", 999),
        ("fluid_id", 999),
        ("run", ""),
        ("v_t_out_m_s", None),
        ("temperature_c", -300.0),
        ("wall_diameter_m", 0.0),
    ],
)
def test_collision_rules(db: str, column: str, value: object) -> None:
    with pytest.raises(IntegrityError):
        _insert_collision(db, **{column: value})


def test_a_good_collision_is_accepted_and_runs_are_unique_per_dataset(db: str) -> None:
    _insert_collision(db)
    with pytest.raises(IntegrityError, match="(?i)unique"):
        _insert_collision(db)


@pytest.mark.parametrize(
    ("column", "value"),
    [
        ("reference_viscosity_pa_s", 0.0),
        ("reference_viscosity_pa_s", -1e-3),
        ("reference_density_kg_m3", 0.0),
        ("pressure_viscosity_pa_inv", -1e-9),
        ("glycerol_mass_fraction", 1.5),
        ("reference_temperature_c", -274.0),
    ],
)
def test_fluid_rules(db: str, column: str, value: object) -> None:
    row = {
        "name": "f",
        "name_key": "f",
        "reference_density_kg_m3": 1000.0,
        "reference_viscosity_pa_s": 1e-3,
        "reference_temperature_c": 20.0,
        column: value,
    }
    with pytest.raises(IntegrityError):
        _insert(db, "fluids", row)


def test_rules_module_matches_the_database(db: str) -> None:
    """The pre-write checks and the CHECK constraints agree at every boundary."""
    from granudb.vocabulary.rules import RULES

    for column in ("density_kg_m3", "youngs_modulus_pa", "poisson_ratio", "roughness_rms_m"):
        rule = RULES[column]
        for edge in (rule.minimum, rule.maximum):
            if edge is None:
                continue
            name = f"{column}{edge}"
            try:
                _insert_material(db, name=name, name_key=name, **{column: edge})
                ok_in_db = True
            except IntegrityError:
                ok_in_db = False
            assert rule.holds(edge) == ok_in_db, (column, edge)


NON_FINITE = [float("nan"), float("inf"), float("-inf")]


def _read(db: str, sql: str) -> object:
    from sqlalchemy import text
    from support import engine_for

    engine = engine_for(db)
    try:
        with engine.connect() as connection:
            return connection.execute(text(sql)).scalar()
    finally:
        engine.dispose()


def _stored_or_refused(insert, read) -> None:
    """A non-finite number is refused, or (SQLite's driver turns NaN into NULL) stored as
    "no value" in an optional column: never as NaN or infinity."""
    try:
        insert()
    except IntegrityError:
        return
    assert read() is None


@pytest.mark.parametrize("value", NON_FINITE, ids=["nan", "inf", "-inf"])
@pytest.mark.parametrize(
    "column", ["density_kg_m3", "youngs_modulus_pa", "roughness_rms_m", "shear_modulus_pa"]
)
def test_materials_refuse_nan_and_infinity(db: str, column: str, value: float) -> None:
    """README: rows written by other tools obey the rules too — NaN and ±inf included
    (PostgreSQL sorts 'NaN' above every number, so `density > 0` alone accepted it)."""
    _stored_or_refused(
        lambda: _insert_material(db, **{column: value}),
        lambda: _read(db, f"SELECT {column} FROM materials WHERE name = 'm'"),
    )


@pytest.mark.parametrize("value", NON_FINITE, ids=["nan", "inf", "-inf"])
@pytest.mark.parametrize("column", ["v_n_in_m_s", "v_t_out_m_s", "omega_in_rad_s", "temperature_c"])
def test_collisions_refuse_nan_and_infinity(db: str, column: str, value: float) -> None:
    _stored_or_refused(
        lambda: _insert_collision(db, **{column: value}),
        lambda: _read(db, f"SELECT {column} FROM collisions WHERE run = 'r1'"),
    )


@pytest.mark.sqlite_only
def test_sqlite_text_overflow_is_refused(db: str) -> None:
    """SQLite reads the literal 9e999 as +infinity: the CHECK refuses it."""
    with pytest.raises(IntegrityError):
        execute(
            db,
            "INSERT INTO materials (name, name_key, density_kg_m3, youngs_modulus_pa, "
            "poisson_ratio, roughness_rms_m) VALUES ('x', 'x', 9e999, 1e9, 0.3, 0)",
        )


@pytest.mark.parametrize("value", NON_FINITE, ids=["nan", "inf", "-inf"])
def test_fluids_refuse_nan_and_infinity(db: str, value: float) -> None:
    row = {
        "name": "f",
        "name_key": "f",
        "reference_density_kg_m3": 1000.0,
        "reference_viscosity_pa_s": value,
        "reference_temperature_c": 20.0,
    }
    with pytest.raises(IntegrityError):
        _insert(db, "fluids", row)
