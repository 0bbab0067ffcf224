"""source revisions: a source's values before each change, with when and why

- source_revisions: one row per change of a source (today: a re-seed that changed its
  citation, DOI, URL, year, kind or notes), holding the values before the change, when
  (``kept_at``) and why (``reason``). A released dataset reads each source as it was
  when released (the first revision kept after its release, else the live row), so its
  package's ``sources.csv`` never changes. Existing releases pin today's values: there
  is no history before this revision, so the table starts empty and no row changes.

The downgrade drops the table (the sources' history is lost: ``granudb db downgrade``
says how many rows and asks first); the live sources are kept as they are.

Revision ID: 0009
Revises: 0008
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op

revision: str = "0009"
down_revision: str | None = "0008"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None


def upgrade() -> None:
    op.create_table(
        "source_revisions",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("source_id", sa.Integer(), nullable=False),
        sa.Column("key", sa.String(length=100), nullable=False),
        sa.Column("citation", sa.Text(), nullable=False),
        sa.Column("doi", sa.String(length=200), nullable=True),
        sa.Column("url", sa.String(length=500), nullable=True),
        sa.Column("year", sa.Integer(), nullable=True),
        sa.Column("kind", sa.String(length=40), nullable=False),
        sa.Column("notes", sa.Text(), nullable=True),
        sa.Column("kept_at", sa.DateTime(timezone=True), nullable=False),
        sa.Column("reason", sa.Text(), nullable=False),
        sa.ForeignKeyConstraint(
            ["source_id"],
            ["sources.id"],
            name=op.f("fk_source_revisions_source_id_sources"),
            ondelete="CASCADE",
        ),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_source_revisions")),
    )


#: What ``downgrade()`` drops or alters, as (table, column, SQL condition on the rows
#: that lose something, what happens to them): the only source of what
#: ``granudb db downgrade`` asks consent for (``granudb.db.migration.downgrade_losses``).
DOWNGRADE_LOSSES: list[tuple[str, str, str, str]] = [
    (
        "source_revisions",
        "citation",
        "1 = 1",
        "dropped (the sources' history; released datasets then read today's sources)",
    ),
]


def downgrade() -> None:
    op.drop_table("source_revisions")
