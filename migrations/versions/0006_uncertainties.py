"""standard uncertainties: every catalogue property may carry its u

- materials: ``u_density_kg_m3``, ``u_youngs_modulus_pa``, ``u_poisson_ratio``,
  ``u_roughness_rms_m``, ``u_correlation_length_m``, ``u_shear_modulus_pa``,
  ``u_yield_stress_pa``;
- fluids: ``u_glycerol_mass_fraction``, ``u_reference_density_kg_m3``,
  ``u_reference_viscosity_pa_s``, ``u_reference_temperature_c``,
  ``u_pressure_viscosity_pa_inv``;
- fluid_points: ``u_viscosity_pa_s``, ``u_density_kg_m3``.

Each is the property's standard uncertainty in its unit (GUM, JCGM 100:2008), NULL where
none is given, ≥ 0 and finite (``granudb.vocabulary.uncertainty``). Every existing row is
kept, with no uncertainty (none was stored). The downgrade drops the columns, and with
them any uncertainty stored since; ``granudb db downgrade`` asks first.

Revision ID: 0006
Revises: 0005
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op

from granudb.db.base import finite_check

revision: str = "0006"
down_revision: str | None = "0005"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None

#: The uncertainty columns each table gets, in the models' order.
COLUMNS = {
    "materials": (
        "u_density_kg_m3",
        "u_youngs_modulus_pa",
        "u_poisson_ratio",
        "u_roughness_rms_m",
        "u_correlation_length_m",
        "u_shear_modulus_pa",
        "u_yield_stress_pa",
    ),
    "fluids": (
        "u_glycerol_mass_fraction",
        "u_reference_density_kg_m3",
        "u_reference_viscosity_pa_s",
        "u_reference_temperature_c",
        "u_pressure_viscosity_pa_inv",
    ),
    "fluid_points": ("u_viscosity_pa_s", "u_density_kg_m3"),
}


def upgrade() -> None:
    for table, columns in COLUMNS.items():
        with op.batch_alter_table(table) as batch:
            for name in columns:
                batch.add_column(sa.Column(name, sa.Float(), nullable=True))
                batch.create_check_constraint(
                    op.f(f"ck_{table}_{name}_non_negative"), f"{name} IS NULL OR {name} >= 0"
                )
                batch.create_check_constraint(op.f(f"ck_{table}_{name}_finite"), finite_check(name))


#: What ``downgrade()`` drops or alters, as (table, column, SQL condition on the rows
#: that lose something, what happens to them): the only source of what
#: ``granudb db downgrade`` asks consent for (``granudb.db.migration.downgrade_losses``).
DOWNGRADE_LOSSES: list[tuple[str, str, str, str]] = [
    (
        "materials",
        "u_density_kg_m3",
        "u_density_kg_m3 IS NOT NULL",
        "dropped (the standard uncertainty)",
    ),
    (
        "materials",
        "u_youngs_modulus_pa",
        "u_youngs_modulus_pa IS NOT NULL",
        "dropped (the standard uncertainty)",
    ),
    (
        "materials",
        "u_poisson_ratio",
        "u_poisson_ratio IS NOT NULL",
        "dropped (the standard uncertainty)",
    ),
    (
        "materials",
        "u_roughness_rms_m",
        "u_roughness_rms_m IS NOT NULL",
        "dropped (the standard uncertainty)",
    ),
    (
        "materials",
        "u_correlation_length_m",
        "u_correlation_length_m IS NOT NULL",
        "dropped (the standard uncertainty)",
    ),
    (
        "materials",
        "u_shear_modulus_pa",
        "u_shear_modulus_pa IS NOT NULL",
        "dropped (the standard uncertainty)",
    ),
    (
        "materials",
        "u_yield_stress_pa",
        "u_yield_stress_pa IS NOT NULL",
        "dropped (the standard uncertainty)",
    ),
    (
        "fluids",
        "u_glycerol_mass_fraction",
        "u_glycerol_mass_fraction IS NOT NULL",
        "dropped (the standard uncertainty)",
    ),
    (
        "fluids",
        "u_reference_density_kg_m3",
        "u_reference_density_kg_m3 IS NOT NULL",
        "dropped (the standard uncertainty)",
    ),
    (
        "fluids",
        "u_reference_viscosity_pa_s",
        "u_reference_viscosity_pa_s IS NOT NULL",
        "dropped (the standard uncertainty)",
    ),
    (
        "fluids",
        "u_reference_temperature_c",
        "u_reference_temperature_c IS NOT NULL",
        "dropped (the standard uncertainty)",
    ),
    (
        "fluids",
        "u_pressure_viscosity_pa_inv",
        "u_pressure_viscosity_pa_inv IS NOT NULL",
        "dropped (the standard uncertainty)",
    ),
    (
        "fluid_points",
        "u_viscosity_pa_s",
        "u_viscosity_pa_s IS NOT NULL",
        "dropped (the standard uncertainty)",
    ),
    (
        "fluid_points",
        "u_density_kg_m3",
        "u_density_kg_m3 IS NOT NULL",
        "dropped (the standard uncertainty)",
    ),
]


def downgrade() -> None:
    for table, columns in COLUMNS.items():
        with op.batch_alter_table(table) as batch:
            for name in reversed(columns):
                batch.drop_constraint(op.f(f"ck_{table}_{name}_finite"), type_="check")
                batch.drop_constraint(op.f(f"ck_{table}_{name}_non_negative"), type_="check")
                batch.drop_column(name)
