"""collisions: the stated standard uncertainty of each measured value

- collisions: ``u_diameter_m``, ``u_v_n_in_m_s``, ``u_v_t_in_m_s``, ``u_omega_in_rad_s``,
  ``u_v_n_out_m_s``, ``u_v_t_out_m_s``, ``u_omega_out_rad_s``, ``u_temperature_c``.

Each is the measured value's standard uncertainty in its unit (GUM, JCGM 100:2008), NULL
where none is stated, ≥ 0 and finite (``granudb.vocabulary.terms.COLLISION_UNCERTAINTIES``).
Every existing run is kept, with no uncertainty (none was stored). The downgrade drops the
columns, and with them any uncertainty stored since; ``granudb db downgrade`` asks first.

Revision ID: 0008
Revises: 0007
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op

from granudb.db.base import finite_check

revision: str = "0008"
down_revision: str | None = "0007"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None

#: The columns, in the model's order (written out: a migration never changes with the code).
COLUMNS = (
    "u_diameter_m",
    "u_v_n_in_m_s",
    "u_v_t_in_m_s",
    "u_omega_in_rad_s",
    "u_v_n_out_m_s",
    "u_v_t_out_m_s",
    "u_omega_out_rad_s",
    "u_temperature_c",
)


def upgrade() -> None:
    with op.batch_alter_table("collisions") as batch:
        for name in COLUMNS:
            batch.add_column(sa.Column(name, sa.Float(), nullable=True))
            batch.create_check_constraint(
                op.f(f"ck_collisions_{name}_non_negative"), f"{name} IS NULL OR {name} >= 0"
            )
            batch.create_check_constraint(op.f(f"ck_collisions_{name}_finite"), finite_check(name))


#: What ``downgrade()`` drops or alters, as (table, column, SQL condition on the rows
#: that lose something, what happens to them): the only source of what
#: ``granudb db downgrade`` asks consent for (``granudb.db.migration.downgrade_losses``).
DOWNGRADE_LOSSES: list[tuple[str, str, str, str]] = [
    (
        "collisions",
        "u_diameter_m",
        "u_diameter_m IS NOT NULL",
        "dropped (the stated standard uncertainty)",
    ),
    (
        "collisions",
        "u_v_n_in_m_s",
        "u_v_n_in_m_s IS NOT NULL",
        "dropped (the stated standard uncertainty)",
    ),
    (
        "collisions",
        "u_v_t_in_m_s",
        "u_v_t_in_m_s IS NOT NULL",
        "dropped (the stated standard uncertainty)",
    ),
    (
        "collisions",
        "u_omega_in_rad_s",
        "u_omega_in_rad_s IS NOT NULL",
        "dropped (the stated standard uncertainty)",
    ),
    (
        "collisions",
        "u_v_n_out_m_s",
        "u_v_n_out_m_s IS NOT NULL",
        "dropped (the stated standard uncertainty)",
    ),
    (
        "collisions",
        "u_v_t_out_m_s",
        "u_v_t_out_m_s IS NOT NULL",
        "dropped (the stated standard uncertainty)",
    ),
    (
        "collisions",
        "u_omega_out_rad_s",
        "u_omega_out_rad_s IS NOT NULL",
        "dropped (the stated standard uncertainty)",
    ),
    (
        "collisions",
        "u_temperature_c",
        "u_temperature_c IS NOT NULL",
        "dropped (the stated standard uncertainty)",
    ),
]


def downgrade() -> None:
    with op.batch_alter_table("collisions") as batch:
        for name in reversed(COLUMNS):
            batch.drop_constraint(op.f(f"ck_collisions_{name}_finite"), type_="check")
            batch.drop_constraint(op.f(f"ck_collisions_{name}_non_negative"), type_="check")
            batch.drop_column(name)
