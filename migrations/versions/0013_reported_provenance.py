"""reported runs' provenance: who digitised them, their licence, the reference package

- reported_runs: three nullable columns, NULL on every existing row (no value changes):
  ``digitiser`` (who read the values from the figure or file), ``licence`` (of the file
  they were read from) and ``reference_package`` ("NAME VERSION" of the shipped reference
  dataset a run was imported from by ``granudb reference import``; NULL: a user's file).

The downgrade drops the three columns (the runs stay; their digitiser, licence and package
are lost: ``granudb db downgrade`` says how many and asks first).

Revision ID: 0013
Revises: 0012
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op

revision: str = "0013"
down_revision: str | None = "0012"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None


def upgrade() -> None:
    with op.batch_alter_table("reported_runs") as batch:
        batch.add_column(sa.Column("digitiser", sa.Text(), nullable=True))
        batch.add_column(sa.Column("licence", sa.Text(), nullable=True))
        batch.add_column(sa.Column("reference_package", sa.String(length=200), nullable=True))


#: What ``downgrade()`` drops (``granudb.db.migration.downgrade_losses``).
DOWNGRADE_LOSSES: list[tuple[str, str, str, str]] = [
    (
        "reported_runs",
        "digitiser",
        "digitiser IS NOT NULL OR licence IS NOT NULL OR reference_package IS NOT NULL",
        "lose their digitiser, licence and reference package (the runs stay)",
    ),
]


def downgrade() -> None:
    with op.batch_alter_table("reported_runs") as batch:
        batch.drop_column("reference_package")
        batch.drop_column("licence")
        batch.drop_column("digitiser")
