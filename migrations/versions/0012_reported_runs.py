"""reported runs: runs as papers report them (e, e_t, ω_out, an incidence angle)

- reported_runs: one row per run a paper states by its restitution coefficients, spin or
  angle rather than by velocities (issue 37): ``collection`` (what was imported together),
  ``run``, particle, wall, fluid (NULL: dry), diameter, and the quantities the paper gives
  (``incidence_angle_rad``, ``normal_restitution``, ``tangential_restitution``,
  ``omega_out_rad_s``, each NULL when not stated, each with its ``u_``), whether the paper
  states no spin in (``no_spin_in``), the source and its locator. No velocity column: a
  velocity the paper did not measure is never stored. A new table: no existing row changes.

The downgrade drops the table (the reported runs are lost: ``granudb db downgrade`` says
how many and asks first).

Revision ID: 0012
Revises: 0011
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op

from granudb.db.base import finite_check

revision: str = "0012"
down_revision: str | None = "0011"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None

QUANTITIES = (
    "incidence_angle_rad",
    "normal_restitution",
    "tangential_restitution",
    "omega_out_rad_s",
)
FLOATS = ("diameter_m", *QUANTITIES, *(f"u_{q}" for q in QUANTITIES))


def upgrade() -> None:
    op.create_table(
        "reported_runs",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("collection", sa.String(length=200), nullable=False),
        sa.Column("run", sa.String(length=200), nullable=False),
        sa.Column("particle_id", sa.Integer(), nullable=False),
        sa.Column("wall_id", sa.Integer(), nullable=False),
        sa.Column("fluid_id", sa.Integer(), nullable=True),
        *(sa.Column(c, sa.Float(), nullable=True) for c in FLOATS),
        sa.Column("no_spin_in", sa.Boolean(), nullable=False),
        sa.Column("source_id", sa.Integer(), nullable=True),
        sa.Column("source_locator", sa.String(length=200), nullable=True),
        sa.Column("notes", sa.Text(), nullable=True),
        sa.CheckConstraint(
            "length(collection) > 0", name=op.f("ck_reported_runs_collection_not_empty")
        ),
        sa.CheckConstraint("length(run) > 0", name=op.f("ck_reported_runs_run_not_empty")),
        sa.CheckConstraint(
            "diameter_m IS NULL OR diameter_m > 0", name=op.f("ck_reported_runs_diameter_positive")
        ),
        sa.CheckConstraint(
            "normal_restitution IS NOT NULL OR tangential_restitution IS NOT NULL",
            name=op.f("ck_reported_runs_states_a_restitution"),
        ),
        sa.CheckConstraint(
            "incidence_angle_rad IS NULL OR "
            "(incidence_angle_rad >= 0 AND incidence_angle_rad < 1.5707963267948966)",
            name=op.f("ck_reported_runs_incidence_angle_range"),
        ),
        sa.CheckConstraint(
            "normal_restitution IS NULL OR normal_restitution >= 0",
            name=op.f("ck_reported_runs_normal_restitution_non_negative"),
        ),
        *(
            sa.CheckConstraint(
                f"u_{q} IS NULL OR u_{q} >= 0", name=op.f(f"ck_reported_runs_u_{q}_non_negative")
            )
            for q in QUANTITIES
        ),
        *(
            sa.CheckConstraint(finite_check(c), name=op.f(f"ck_reported_runs_{c}_finite"))
            for c in FLOATS
        ),
        sa.ForeignKeyConstraint(
            ["particle_id"],
            ["materials.id"],
            name=op.f("fk_reported_runs_particle_id_materials"),
            ondelete="RESTRICT",
        ),
        sa.ForeignKeyConstraint(
            ["wall_id"],
            ["materials.id"],
            name=op.f("fk_reported_runs_wall_id_materials"),
            ondelete="RESTRICT",
        ),
        sa.ForeignKeyConstraint(
            ["fluid_id"],
            ["fluids.id"],
            name=op.f("fk_reported_runs_fluid_id_fluids"),
            ondelete="RESTRICT",
        ),
        sa.ForeignKeyConstraint(
            ["source_id"],
            ["sources.id"],
            name=op.f("fk_reported_runs_source_id_sources"),
            ondelete="RESTRICT",
        ),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_reported_runs")),
        sa.UniqueConstraint("collection", "run", name=op.f("uq_reported_runs_collection_run")),
    )


#: What ``downgrade()`` drops, as (table, column, SQL condition on the rows that lose
#: something, what happens to them): what ``granudb db downgrade`` asks consent for
#: (``granudb.db.migration.downgrade_losses``).
DOWNGRADE_LOSSES: list[tuple[str, str, str, str]] = [
    ("reported_runs", "run", "1 = 1", "dropped (the runs as papers report them)"),
]


def downgrade() -> None:
    # the reported runs go; ``granudb db downgrade`` names them and asks first
    op.drop_table("reported_runs")
