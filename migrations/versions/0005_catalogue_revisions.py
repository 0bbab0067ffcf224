"""catalogue revisions: a release keeps the values it used; two-sphere velocity rules

- materials, fluids: ``revision_of``. When a material or fluid that a released (or
  superseded) dataset uses is changed, its values before the change are kept as a
  revision row (same name, ``revision_of`` the live row) and the release's runs point to
  it (``granudb.db.catalog_revisions``): a release never changes. Existing releases keep
  today's values, which are the values they were released with as far as the database
  knows.

- collisions: ``v_n_in > 0`` and ``v_n_out ≥ 0`` hold for a wall or a fixed sphere; with a
  free target (``wall_v_n_in`` given) the rules are on relative velocities, which the
  import checks (an equal-sphere impact leaves the particle moving forward).

The downgrade points every run back at the live row (a release then reads today's
values) and drops the revisions; ``granudb db downgrade`` says how many and asks first.

Revision ID: 0005
Revises: 0004
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op

revision: str = "0005"
down_revision: str | None = "0004"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None


_RELAXED = {
    "v_n_in_positive": ("v_n_in_positive_or_free", "v_n_in_m_s > 0"),
    "v_n_out_non_negative": ("v_n_out_non_negative_or_free", "v_n_out_m_s >= 0"),
}


def upgrade() -> None:
    with op.batch_alter_table("collisions") as batch:
        for old, (new, rule) in _RELAXED.items():
            batch.drop_constraint(op.f(f"ck_collisions_{old}"), type_="check")
            batch.create_check_constraint(
                op.f(f"ck_collisions_{new}"), f"{rule} OR wall_v_n_in_m_s IS NOT NULL"
            )
    for table in ("materials", "fluids"):
        with op.batch_alter_table(table) as batch:
            batch.add_column(sa.Column("revision_of", sa.Integer(), nullable=True))
            batch.create_foreign_key(
                op.f(f"fk_{table}_revision_of_{table}"),
                table,
                ["revision_of"],
                ["id"],
                ondelete="RESTRICT",
            )


#: What ``downgrade()`` drops or alters, as (table, column, SQL condition on the rows
#: that lose something, what happens to them): the only source of what
#: ``granudb db downgrade`` asks consent for (``granudb.db.migration.downgrade_losses``).
DOWNGRADE_LOSSES: list[tuple[str, str, str, str]] = [
    (
        "collisions",
        "v_n_in_m_s",
        "wall_v_n_in_m_s IS NOT NULL AND (v_n_in_m_s <= 0 OR v_n_out_m_s < 0)",
        "removed (two-sphere runs the older schema cannot hold)",
    ),
    (
        "materials",
        "revision_of",
        "revision_of IS NOT NULL",
        "dropped (released datasets then read today's values)",
    ),
    (
        "fluids",
        "revision_of",
        "revision_of IS NOT NULL",
        "dropped (released datasets then read today's values)",
    ),
]


def downgrade() -> None:
    op.execute(
        "DELETE FROM collisions WHERE wall_v_n_in_m_s IS NOT NULL AND "
        "(v_n_in_m_s <= 0 OR v_n_out_m_s < 0)"
    )
    with op.batch_alter_table("collisions") as batch:
        for old, (new, rule) in _RELAXED.items():
            batch.drop_constraint(op.f(f"ck_collisions_{new}"), type_="check")
            batch.create_check_constraint(op.f(f"ck_collisions_{old}"), rule)
    for column, table in (("particle_id", "materials"), ("wall_id", "materials"),
                          ("fluid_id", "fluids")):  # fmt: skip
        op.execute(
            f"UPDATE collisions SET {column} = (SELECT revision_of FROM {table} "
            f"WHERE {table}.id = collisions.{column}) WHERE {column} IN "
            f"(SELECT id FROM {table} WHERE revision_of IS NOT NULL)"
        )
    op.execute(
        "DELETE FROM fluid_points WHERE fluid_id IN "
        "(SELECT id FROM fluids WHERE revision_of IS NOT NULL)"
    )
    for table in ("materials", "fluids"):
        op.execute(f"DELETE FROM {table} WHERE revision_of IS NOT NULL")
        with op.batch_alter_table(table) as batch:
            batch.drop_constraint(op.f(f"fk_{table}_revision_of_{table}"), type_="foreignkey")
            batch.drop_column("revision_of")
