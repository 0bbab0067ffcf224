"""materials and fluids: the conditions of their values

- materials, fluids: ``conditions``, optional one-line text: the conditions of the values
  where the source gives them (temperature, method: "E by ultrasonic pulse-echo at 20 °C;
  σ from SEM images"), issue 27. Empty on every existing row: nothing a user stored
  changes. A revision of an entry (``revision_of``) lives in the same table, so it follows.

The downgrade drops the column (the conditions stored are lost: ``granudb db downgrade``
names them and asks first).

Revision ID: 0011
Revises: 0010
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op

revision: str = "0011"
down_revision: str | None = "0010"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None

TABLES = ("materials", "fluids")


def upgrade() -> None:
    for table in TABLES:
        with op.batch_alter_table(table) as batch:
            batch.add_column(sa.Column("conditions", sa.Text(), nullable=True))


#: What ``downgrade()`` drops or alters, as (table, column, SQL condition on the rows
#: that lose something, what happens to them): the only source of what
#: ``granudb db downgrade`` asks consent for (``granudb.db.migration.downgrade_losses``).
DOWNGRADE_LOSSES: list[tuple[str, str, str, str]] = [
    ("materials", "conditions", "conditions IS NOT NULL", "dropped (the values' conditions)"),
    ("fluids", "conditions", "conditions IS NOT NULL", "dropped (the values' conditions)"),
]


def downgrade() -> None:
    # the stored conditions go; ``granudb db downgrade`` names them and asks (``_STEP_LOSSES``)
    for table in TABLES:
        with op.batch_alter_table(table) as batch:
            batch.drop_column("conditions")
