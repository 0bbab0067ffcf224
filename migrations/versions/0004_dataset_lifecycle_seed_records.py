"""dataset lifecycle (authors, keywords, release state); seed records

- datasets: ``authors`` and ``keywords`` (JSON text), ``state`` (draft → released →
  superseded; existing datasets become drafts, editable as before) and ``released_at``.
- seed_records: the values ``db seed`` last wrote to each seeded row, so a re-seed leaves
  a value the user changed alone (``granudb.db.seed_store``).

The downgrade drops these; ``granudb db downgrade`` says how many values that loses and
asks first (``granudb.db.migration.downgrade_losses``).

Revision ID: 0004
Revises: 0003
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op

revision: str = "0004"
down_revision: str | None = "0003"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None


def upgrade() -> None:
    with op.batch_alter_table("datasets") as batch:
        batch.add_column(sa.Column("authors", sa.Text(), nullable=True))
        batch.add_column(sa.Column("keywords", sa.Text(), nullable=True))
        batch.add_column(
            sa.Column("state", sa.String(length=20), nullable=False, server_default="draft")
        )
        batch.add_column(sa.Column("released_at", sa.DateTime(timezone=True), nullable=True))
        batch.create_check_constraint(
            op.f("ck_datasets_state_known"), "state IN ('draft', 'released', 'superseded')"
        )
    op.create_table(
        "seed_records",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("table_name", sa.String(length=40), nullable=False),
        sa.Column("seed_key", sa.String(length=500), nullable=False),
        sa.Column("seeded_values", sa.Text(), nullable=False),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_seed_records")),
        sa.UniqueConstraint(
            "table_name", "seed_key", name=op.f("uq_seed_records_table_name_seed_key")
        ),
    )


#: What ``downgrade()`` drops or alters, as (table, column, SQL condition on the rows
#: that lose something, what happens to them): the only source of what
#: ``granudb db downgrade`` asks consent for (``granudb.db.migration.downgrade_losses``).
DOWNGRADE_LOSSES: list[tuple[str, str, str, str]] = [
    ("datasets", "authors", "authors IS NOT NULL", "dropped"),
    ("datasets", "keywords", "keywords IS NOT NULL", "dropped"),
    ("datasets", "state", "state <> 'draft'", "dropped (released versions become drafts)"),
    ("datasets", "released_at", "released_at IS NOT NULL", "dropped"),
]


def downgrade() -> None:
    op.drop_table("seed_records")
    with op.batch_alter_table("datasets") as batch:
        batch.drop_constraint(op.f("ck_datasets_state_known"), type_="check")
        batch.drop_column("released_at")
        batch.drop_column("state")
        batch.drop_column("keywords")
        batch.drop_column("authors")
