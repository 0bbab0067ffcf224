"""The database itself refuses unphysical rows, whatever program writes them."""

from __future__ import annotations

import sqlite3
from pathlib import Path

import pytest

GOOD = {
    "name": "m",
    "name_key": "m",
    "density_kg_m3": 1000.0,
    "youngs_modulus_pa": 1e9,
    "poisson_ratio": 0.3,
    "roughness_rms_m": 1e-8,
}


def _insert_material(path: Path, **changes: object) -> None:
    row = {**GOOD, **changes}
    columns = ", ".join(row)
    marks = ", ".join("?" for _ in row)
    connection = sqlite3.connect(path)
    try:
        connection.execute("PRAGMA foreign_keys=ON")
        with connection:
            connection.execute(
                f"INSERT INTO materials ({columns}) VALUES ({marks})", list(row.values())
            )
    finally:
        connection.close()


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
def test_material_rules(db_path: Path, column: str, value: object) -> None:
    with pytest.raises(sqlite3.IntegrityError):
        _insert_material(db_path, **{column: value})


def test_a_good_material_row_is_accepted(db_path: Path) -> None:
    _insert_material(db_path)
    with pytest.raises(sqlite3.IntegrityError, match="UNIQUE"):
        _insert_material(db_path, name="M")  # name_key m again


def _insert_collision(path: Path, **changes: object) -> None:
    connection = sqlite3.connect(path)
    try:
        connection.execute("PRAGMA foreign_keys=ON")
        with connection:
            connection.execute(
                "INSERT OR IGNORE INTO datasets (id, name, version) VALUES (1, 'd', '1')"
            )
            row = {
                "dataset_id": 1,
                "run": "r1",
                "particle_id": 1,
                "wall_id": 2,
                "fluid_id": None,
                "diameter_m": 0.0127,
                "incidence_angle_rad": 0.3,
                "v_n_in_m_s": 0.3,
                "v_t_in_m_s": 0.1,
                "omega_in_rad_s": 0.0,
                "v_n_out_m_s": 0.2,
                "v_t_out_m_s": 0.05,
                "omega_out_rad_s": 3.0,
                **changes,
            }
            connection.execute(
                f"INSERT INTO collisions ({', '.join(row)}) VALUES ({', '.join('?' * len(row))})",
                list(row.values()),
            )
    finally:
        connection.close()


@pytest.mark.parametrize(
    ("column", "value"),
    [
        ("diameter_m", 0.0),
        ("v_n_in_m_s", 0.0),
        ("v_n_in_m_s", -0.1),
        ("v_t_in_m_s", -0.1),
        ("v_n_out_m_s", -0.1),
        ("incidence_angle_rad", -0.1),
        ("incidence_angle_rad", 1.5708),
        ("particle_id", 999),
        ("fluid_id", 999),
        ("run", ""),
        ("v_t_out_m_s", None),
        ("temperature_c", -300.0),
        ("wall_diameter_m", 0.0),
    ],
)
def test_collision_rules(db_path: Path, column: str, value: object) -> None:
    with pytest.raises(sqlite3.IntegrityError):
        _insert_collision(db_path, **{column: value})


def test_a_good_collision_is_accepted_and_runs_are_unique_per_dataset(db_path: Path) -> None:
    _insert_collision(db_path)
    with pytest.raises(sqlite3.IntegrityError, match="UNIQUE"):
        _insert_collision(db_path)


@pytest.mark.parametrize(
    ("column", "value"),
    [
        ("viscosity_pa_s", 0.0),
        ("viscosity_pa_s", -1e-3),
        ("density_kg_m3", 0.0),
        ("pressure_viscosity_pa_inv", -1e-9),
        ("glycerol_mass_fraction", 1.5),
        ("reference_temperature_c", -274.0),
    ],
)
def test_fluid_rules(db_path: Path, column: str, value: object) -> None:
    row = {
        "name": "f",
        "name_key": "f",
        "density_kg_m3": 1000.0,
        "viscosity_pa_s": 1e-3,
        "reference_temperature_c": 20.0,
        column: value,
    }
    with sqlite3.connect(db_path) as connection, pytest.raises(sqlite3.IntegrityError):
        connection.execute(
            f"INSERT INTO fluids ({', '.join(row)}) VALUES ({', '.join('?' * len(row))})",
            list(row.values()),
        )


def test_rules_module_matches_the_database(db_path: Path) -> None:
    """The pre-write checks and the CHECK constraints agree at every boundary."""
    from granudb.io.rules import RULES

    for column in ("density_kg_m3", "youngs_modulus_pa", "poisson_ratio", "roughness_rms_m"):
        rule = RULES[column]
        for edge in (rule.minimum, rule.maximum):
            if edge is None:
                continue
            ok_in_python = rule.holds(edge)
            try:
                _insert_material(
                    db_path, name=f"{column}{edge}", name_key=f"{column}{edge}", **{column: edge}
                )
                ok_in_db = True
            except sqlite3.IntegrityError:
                ok_in_db = False
            assert ok_in_python == ok_in_db, (column, edge)
