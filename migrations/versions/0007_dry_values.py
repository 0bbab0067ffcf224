"""per-material and per-pair dry values with their source; brittleness as a property

- materials: ``dry_restitution`` (0 < e ≤ 1), ``dry_friction`` (≥ 0), ``dry_provenance``
  (where they come from) and ``brittleness`` ("brittle" or "ductile"), all empty on
  existing rows: nothing a user stored changes, and an empty value means "not known"
  (the resolver then says which value it borrowed, docs/physics.md §18).
- pair_values: dry values a source measured for one pair of materials (and its friction
  where asperities touch in a liquid), with the source and where in it; ``created_at`` lets a release read only what existed when released.

The downgrade drops the four columns and the table (the values they held are lost:
``granudb db downgrade`` says so and asks first).

Revision ID: 0007
Revises: 0006
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op

revision: str = "0007"
down_revision: str | None = "0006"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None

MAX = "1.7976931348623157e308"
RULES = {
    "dry_restitution_range": "dry_restitution IS NULL OR "
    "(dry_restitution > 0 AND dry_restitution <= 1)",
    "dry_friction_non_negative": "dry_friction IS NULL OR dry_friction >= 0",
}
FLOATS = ("dry_restitution", "dry_friction")
#: Their standard uncertainties (migration 0006's rule: NULL or ≥ 0, finite).
UNCERTAINTIES = ("u_dry_restitution", "u_dry_friction")


def _finite(column: str) -> str:
    return f"{column} IS NULL OR ({column} >= -{MAX} AND {column} <= {MAX})"


def upgrade() -> None:
    with op.batch_alter_table("materials") as batch:
        batch.add_column(sa.Column("dry_restitution", sa.Float(), nullable=True))
        batch.add_column(sa.Column("dry_friction", sa.Float(), nullable=True))
        batch.add_column(sa.Column("dry_provenance", sa.Text(), nullable=True))
        batch.add_column(sa.Column("brittleness", sa.String(length=20), nullable=True))
        for name in UNCERTAINTIES:
            batch.add_column(sa.Column(name, sa.Float(), nullable=True))
            batch.create_check_constraint(
                op.f(f"ck_materials_{name}_non_negative"), f"{name} IS NULL OR {name} >= 0"
            )
            batch.create_check_constraint(op.f(f"ck_materials_{name}_finite"), _finite(name))
        for name, rule in RULES.items():
            batch.create_check_constraint(op.f(f"ck_materials_{name}"), rule)
        batch.create_check_constraint(
            op.f("ck_materials_brittleness_word"),
            "brittleness IS NULL OR brittleness IN ('brittle', 'ductile')",
        )
        for column in FLOATS:
            batch.create_check_constraint(op.f(f"ck_materials_{column}_finite"), _finite(column))
    op.create_table(
        "pair_values",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("particle_id", sa.Integer(), nullable=False),
        sa.Column("wall_id", sa.Integer(), nullable=False),
        sa.Column("dry_restitution", sa.Float(), nullable=True),
        sa.Column("dry_friction", sa.Float(), nullable=True),
        sa.Column("immersed_friction", sa.Float(), nullable=True),
        sa.Column("source_id", sa.Integer(), nullable=True),
        sa.Column("source_locator", sa.String(length=200), nullable=True),
        sa.Column("notes", sa.Text(), nullable=True),
        sa.Column(
            "created_at",
            sa.DateTime(timezone=True),
            server_default=sa.func.current_timestamp(),
            nullable=False,
        ),
        sa.Column(
            "updated_at",
            sa.DateTime(timezone=True),
            server_default=sa.func.current_timestamp(),
            nullable=False,
        ),
        sa.CheckConstraint(
            "dry_restitution IS NOT NULL OR dry_friction IS NOT NULL "
            "OR immersed_friction IS NOT NULL",
            name=op.f("ck_pair_values_has_a_value"),
        ),
        sa.CheckConstraint(
            "immersed_friction IS NULL OR immersed_friction >= 0",
            name=op.f("ck_pair_values_immersed_friction_non_negative"),
        ),
        *(sa.CheckConstraint(rule, name=op.f(f"ck_pair_values_{n}")) for n, rule in RULES.items()),
        *(
            sa.CheckConstraint(_finite(c), name=op.f(f"ck_pair_values_{c}_finite"))
            for c in (*FLOATS, "immersed_friction")
        ),
        sa.ForeignKeyConstraint(
            ["particle_id"],
            ["materials.id"],
            name=op.f("fk_pair_values_particle_id_materials"),
            ondelete="RESTRICT",
        ),
        sa.ForeignKeyConstraint(
            ["wall_id"],
            ["materials.id"],
            name=op.f("fk_pair_values_wall_id_materials"),
            ondelete="RESTRICT",
        ),
        sa.ForeignKeyConstraint(
            ["source_id"],
            ["sources.id"],
            name=op.f("fk_pair_values_source_id_sources"),
            ondelete="RESTRICT",
        ),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_pair_values")),
        sa.UniqueConstraint(
            "particle_id", "wall_id", name=op.f("uq_pair_values_particle_id_wall_id")
        ),
    )


#: What ``downgrade()`` drops or alters, as (table, column, SQL condition on the rows
#: that lose something, what happens to them): the only source of what
#: ``granudb db downgrade`` asks consent for (``granudb.db.migration.downgrade_losses``).
DOWNGRADE_LOSSES: list[tuple[str, str, str, str]] = [
    ("materials", "dry_restitution", "dry_restitution IS NOT NULL", "dropped"),
    ("materials", "dry_friction", "dry_friction IS NOT NULL", "dropped"),
    ("materials", "dry_provenance", "dry_provenance IS NOT NULL", "dropped"),
    ("materials", "brittleness", "brittleness IS NOT NULL", "dropped"),
    ("materials", "u_dry_restitution", "u_dry_restitution IS NOT NULL", "dropped"),
    ("materials", "u_dry_friction", "u_dry_friction IS NOT NULL", "dropped"),
    ("pair_values", "dry_restitution", "1 = 1", "dropped (the pair values table goes)"),
]


def downgrade() -> None:
    op.drop_table("pair_values")
    with op.batch_alter_table("materials") as batch:
        for name in reversed(UNCERTAINTIES):
            batch.drop_constraint(op.f(f"ck_materials_{name}_finite"), type_="check")
            batch.drop_constraint(op.f(f"ck_materials_{name}_non_negative"), type_="check")
            batch.drop_column(name)
        for column in FLOATS:
            batch.drop_constraint(op.f(f"ck_materials_{column}_finite"), type_="check")
        batch.drop_constraint(op.f("ck_materials_brittleness_word"), type_="check")
        for name in RULES:
            batch.drop_constraint(op.f(f"ck_materials_{name}"), type_="check")
        for column in ("brittleness", "dry_provenance", "dry_friction", "dry_restitution"):
            batch.drop_column(column)
