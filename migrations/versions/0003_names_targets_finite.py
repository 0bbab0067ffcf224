"""one name per concept; target-sphere velocities; yield stress; finite-only numbers

- fluids: ``density_kg_m3`` → ``reference_density_kg_m3`` and ``viscosity_pa_s`` →
  ``reference_viscosity_pa_s`` (the printed values at the reference temperature; the state
  at a temperature is ``viscosity_pa_s`` everywhere else).
- collisions: the stored angle ``incidence_angle_rad`` → ``nominal_angle_rad`` (the
  set-up's nominal angle, optional; ζ_in is derived from the velocities); spins nullable
  (NULL = not measured); the velocities and spins of a free target sphere
  (``wall_v_n_in_m_s`` …, NULL for a flat wall or a fixed sphere).
- materials: ``yield_stress_pa`` (optional).
- every floating-point column: a CHECK that refuses NaN and ±infinity.

Every step keeps the data, both ways (``tests/test_migrations.py`` counts rows).

Revision ID: 0003
Revises: 0002
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op

revision: str = "0003"
down_revision: str | None = "0002"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None

MAX = "1.7976931348623157e308"

FLOATS = {
    "materials": [
        "density_kg_m3",
        "youngs_modulus_pa",
        "poisson_ratio",
        "roughness_rms_m",
        "correlation_length_m",
        "shear_modulus_pa",
    ],
    "fluids": [
        "glycerol_mass_fraction",
        "reference_density_kg_m3",
        "reference_viscosity_pa_s",
        "reference_temperature_c",
        "pressure_viscosity_pa_inv",
    ],
    "fluid_points": ["temperature_c", "viscosity_pa_s", "density_kg_m3"],
    "collisions": [
        "diameter_m",
        "wall_diameter_m",
        "nominal_angle_rad",
        "v_n_in_m_s",
        "v_t_in_m_s",
        "omega_in_rad_s",
        "v_n_out_m_s",
        "v_t_out_m_s",
        "omega_out_rad_s",
        "temperature_c",
    ],
    "published_values": ["value", "uncertainty"],
}
WALL_VELOCITIES = [
    "wall_v_n_in_m_s",
    "wall_v_t_in_m_s",
    "wall_omega_in_rad_s",
    "wall_v_n_out_m_s",
    "wall_v_t_out_m_s",
    "wall_omega_out_rad_s",
]


def _finite(column: str) -> str:
    return f"{column} IS NULL OR ({column} >= -{MAX} AND {column} <= {MAX})"


def _add_finite(batch: object, table: str, columns: list[str]) -> None:
    for column in columns:
        batch.create_check_constraint(op.f(f"ck_{table}_{column}_finite"), _finite(column))


def _drop_finite(batch: object, table: str, columns: list[str]) -> None:
    for column in columns:
        batch.drop_constraint(op.f(f"ck_{table}_{column}_finite"), type_="check")


def upgrade() -> None:
    with op.batch_alter_table("materials") as batch:
        batch.add_column(sa.Column("yield_stress_pa", sa.Float(), nullable=True))
        batch.create_check_constraint(
            op.f("ck_materials_yield_stress_positive"),
            "yield_stress_pa IS NULL OR yield_stress_pa > 0",
        )
        _add_finite(batch, "materials", [*FLOATS["materials"], "yield_stress_pa"])

    with op.batch_alter_table("fluids") as batch:
        batch.drop_constraint(op.f("ck_fluids_density_positive"), type_="check")
        batch.drop_constraint(op.f("ck_fluids_viscosity_positive"), type_="check")
        batch.alter_column("density_kg_m3", new_column_name="reference_density_kg_m3")
        batch.alter_column("viscosity_pa_s", new_column_name="reference_viscosity_pa_s")
        batch.create_check_constraint(
            op.f("ck_fluids_density_positive"), "reference_density_kg_m3 > 0"
        )
        batch.create_check_constraint(
            op.f("ck_fluids_viscosity_positive"), "reference_viscosity_pa_s > 0"
        )
        # C = 0 would make the lubricated friction infinite: unknown is NULL, not 0.
        batch.drop_constraint(op.f("ck_fluids_pressure_viscosity_non_negative"), type_="check")
        batch.create_check_constraint(
            op.f("ck_fluids_pressure_viscosity_positive"),
            "pressure_viscosity_pa_inv IS NULL OR pressure_viscosity_pa_inv > 0",
        )
        _add_finite(batch, "fluids", FLOATS["fluids"])

    with op.batch_alter_table("fluid_points") as batch:
        _add_finite(batch, "fluid_points", FLOATS["fluid_points"])

    with op.batch_alter_table("published_values") as batch:
        _add_finite(batch, "published_values", FLOATS["published_values"])

    with op.batch_alter_table("collisions") as batch:
        batch.drop_constraint(op.f("ck_collisions_incidence_angle_range"), type_="check")
        batch.alter_column(
            "incidence_angle_rad",
            new_column_name="nominal_angle_rad",
            existing_type=sa.Float(),
            nullable=True,
        )
        batch.alter_column("omega_in_rad_s", existing_type=sa.Float(), nullable=True)
        batch.alter_column("omega_out_rad_s", existing_type=sa.Float(), nullable=True)
        for column in WALL_VELOCITIES:
            batch.add_column(sa.Column(column, sa.Float(), nullable=True))
        batch.create_check_constraint(
            op.f("ck_collisions_nominal_angle_range"),
            "nominal_angle_rad IS NULL OR "
            "(nominal_angle_rad >= 0 AND nominal_angle_rad < 1.5707963267948966)",
        )
        _add_finite(batch, "collisions", [*FLOATS["collisions"], *WALL_VELOCITIES])


#: What ``downgrade()`` drops or alters, as (table, column, SQL condition on the rows
#: that lose something, what happens to them): the only source of what
#: ``granudb db downgrade`` asks consent for (``granudb.db.migration.downgrade_losses``).
DOWNGRADE_LOSSES: list[tuple[str, str, str, str]] = [
    ("materials", "yield_stress_pa", "yield_stress_pa IS NOT NULL", "dropped"),
    ("collisions", "wall_v_n_in_m_s", "wall_v_n_in_m_s IS NOT NULL", "dropped"),
    ("collisions", "wall_v_t_in_m_s", "wall_v_t_in_m_s IS NOT NULL", "dropped"),
    ("collisions", "wall_omega_in_rad_s", "wall_omega_in_rad_s IS NOT NULL", "dropped"),
    ("collisions", "wall_v_n_out_m_s", "wall_v_n_out_m_s IS NOT NULL", "dropped"),
    ("collisions", "wall_v_t_out_m_s", "wall_v_t_out_m_s IS NOT NULL", "dropped"),
    ("collisions", "wall_omega_out_rad_s", "wall_omega_out_rad_s IS NOT NULL", "dropped"),
    ("collisions", "omega_in_rad_s", "omega_in_rad_s IS NULL", "not measured, become 0.0"),
    ("collisions", "omega_out_rad_s", "omega_out_rad_s IS NULL", "not measured, become 0.0"),
    (
        "collisions",
        "nominal_angle_rad",
        "nominal_angle_rad IS NULL",
        "not recorded, become the centre's path angle",
    ),
]


def downgrade() -> None:
    with op.batch_alter_table("collisions") as batch:
        _drop_finite(batch, "collisions", [*FLOATS["collisions"], *WALL_VELOCITIES])
        batch.drop_constraint(op.f("ck_collisions_nominal_angle_range"), type_="check")
        for column in WALL_VELOCITIES:
            batch.drop_column(column)
    # The first schema required an angle and both spins: fill what is missing the way
    # that revision would have (the angle of the centre's path, no spin) before
    # restoring NOT NULL, so no row is lost on the way back.
    bind = op.get_bind()
    missing = bind.execute(
        sa.text("SELECT id, v_n_in_m_s, v_t_in_m_s FROM collisions WHERE nominal_angle_rad IS NULL")
    ).all()
    if missing:
        bind.execute(
            sa.text("UPDATE collisions SET nominal_angle_rad = :angle WHERE id = :id"),
            [{"id": i, "angle": math.atan2(vt, vn)} for i, vn, vt in missing],
        )
    op.execute("UPDATE collisions SET omega_in_rad_s = 0.0 WHERE omega_in_rad_s IS NULL")
    op.execute("UPDATE collisions SET omega_out_rad_s = 0.0 WHERE omega_out_rad_s IS NULL")
    with op.batch_alter_table("collisions") as batch:
        batch.alter_column(
            "nominal_angle_rad",
            new_column_name="incidence_angle_rad",
            existing_type=sa.Float(),
            nullable=False,
        )
        batch.alter_column("omega_in_rad_s", existing_type=sa.Float(), nullable=False)
        batch.alter_column("omega_out_rad_s", existing_type=sa.Float(), nullable=False)
        batch.create_check_constraint(
            op.f("ck_collisions_incidence_angle_range"),
            "incidence_angle_rad >= 0 AND incidence_angle_rad < 1.5707963267948966",
        )

    with op.batch_alter_table("published_values") as batch:
        _drop_finite(batch, "published_values", FLOATS["published_values"])

    with op.batch_alter_table("fluid_points") as batch:
        _drop_finite(batch, "fluid_points", FLOATS["fluid_points"])

    with op.batch_alter_table("fluids") as batch:
        _drop_finite(batch, "fluids", FLOATS["fluids"])
        batch.drop_constraint(op.f("ck_fluids_density_positive"), type_="check")
        batch.drop_constraint(op.f("ck_fluids_viscosity_positive"), type_="check")
        batch.alter_column("reference_density_kg_m3", new_column_name="density_kg_m3")
        batch.alter_column("reference_viscosity_pa_s", new_column_name="viscosity_pa_s")
        batch.create_check_constraint(op.f("ck_fluids_density_positive"), "density_kg_m3 > 0")
        batch.create_check_constraint(op.f("ck_fluids_viscosity_positive"), "viscosity_pa_s > 0")
        batch.drop_constraint(op.f("ck_fluids_pressure_viscosity_positive"), type_="check")
        batch.create_check_constraint(
            op.f("ck_fluids_pressure_viscosity_non_negative"),
            "pressure_viscosity_pa_inv IS NULL OR pressure_viscosity_pa_inv >= 0",
        )

    with op.batch_alter_table("materials") as batch:
        _drop_finite(batch, "materials", [*FLOATS["materials"], "yield_stress_pa"])
        batch.drop_constraint(op.f("ck_materials_yield_stress_positive"), type_="check")
        batch.drop_column("yield_stress_pa")
