"""catalogue revisions: a release keeps the values it used

- materials, fluids: ``revision_of``. When a material or fluid that a released (or
  superseded) dataset uses is changed, its values before the change are kept as a
  revision row (same name, ``revision_of`` the live row) and the release's runs point to
  it (``granudb.db.catalog_revisions``): a release never changes. Existing releases keep
  today's values, which are the values they were released with as far as the database
  knows.

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


def upgrade() -> None:
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


def downgrade() -> None:
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
