"""materials: the roughness may be "not stated"

- materials: ``roughness_rms_m`` nullable. A source that gives a solid's density and
  elastic constants but not its surface roughness (Kharaz, Gorham & Salman 2001, as read
  in its secondary sources) is stored without one, never with an invented value; every
  σ-dependent output then says the roughness is not stated (docs/physics.md §18). A
  revision of a material (``revision_of``) lives in the same table, so it follows.

Every existing row keeps its roughness. The downgrade makes the column required again: a
roughness not stated becomes 0.0 there (the older schema cannot hold "not stated"), which
``granudb db downgrade`` names as a loss and asks before; an upgrade cannot tell it from a
measured 0, so restate those materials' roughness as not stated afterwards.

Revision ID: 0010
Revises: 0009
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op

revision: str = "0010"
down_revision: str | None = "0009"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None


def upgrade() -> None:
    with op.batch_alter_table("materials") as batch:
        batch.alter_column("roughness_rms_m", existing_type=sa.Float(), nullable=True)


#: What ``downgrade()`` drops or alters, as (table, column, SQL condition on the rows
#: that lose something, what happens to them): the only source of what
#: ``granudb db downgrade`` asks consent for (``granudb.db.migration.downgrade_losses``).
DOWNGRADE_LOSSES: list[tuple[str, str, str, str]] = [
    (
        "materials",
        "roughness_rms_m",
        "roughness_rms_m IS NULL",
        "not stated, become 0.0 (the older schema needs a number; an upgrade keeps the 0)",
    ),
]


def downgrade() -> None:
    # the older schema needs a number: a roughness not stated becomes 0.0, which
    # ``granudb db downgrade`` names as a loss and asks before (``_STEP_LOSSES``)
    op.execute("UPDATE materials SET roughness_rms_m = 0.0 WHERE roughness_rms_m IS NULL")
    with op.batch_alter_table("materials") as batch:
        batch.alter_column("roughness_rms_m", existing_type=sa.Float(), nullable=False)
