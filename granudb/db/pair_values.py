"""Storing the dry values a source measured for one pair of materials (docs/physics.md
§18). A pair's values are added once and never changed: a released dataset reads the
pair values stored before its release (``catalog_rows.pair_value_rows``), so changing
one in place would change a release. A wrong value is corrected by the seed file (which
keeps releases as they were by the same rule) or reported as a new source's pair."""

from __future__ import annotations

from sqlalchemy.orm import Session

from granudb.db import catalog_rows
from granudb.db.models import PairValue
from granudb.errors import ConflictError, ValidationError
from granudb.vocabulary import check_record
from granudb.vocabulary.terms import stored_values

#: The numbers a pair's row may hold.
PAIR_NUMBERS = tuple(stored_values("pair_values"))


def add_pair_value(
    session: Session,
    particle: str,
    wall: str,
    values: dict[str, float],
    source: str | None,
    source_locator: str | None = None,
    notes: str | None = None,
) -> PairValue:
    """Store ``values`` (``dry_restitution`` and/or ``dry_friction``, SI) measured for
    ``particle`` on ``wall`` by ``source`` (a source key; None: ``notes`` say where from);
    refuses a pair that has values already
    (either way round), a pair without a value, and values that break a rule."""
    if not any(values.get(c) is not None for c in PAIR_NUMBERS):
        first, *others = PAIR_NUMBERS
        raise ValidationError(
            first, "(missing)", f"or {' or '.join(others)} is needed to add a pair's values"
        )
    check_record(values)
    connection = session.connection()
    particle_id = catalog_rows.entry_id(connection, "material", particle)
    wall_id = catalog_rows.entry_id(connection, "material", wall)
    existing = catalog_rows.pair_value_rows(connection, particle, wall)
    if existing:
        present = existing[0]
        raise ConflictError(
            f"pair {present.particle} on {present.wall}: already has dry values "
            f"({catalog_rows.source_key(present.source)}); a pair's values are never changed, "
            "as released datasets read them"
        )
    row = PairValue(
        particle_id=particle_id,
        wall_id=wall_id,
        source_id=None if source is None else catalog_rows.source_id(connection, source),
        source_locator=source_locator,
        notes=notes,
        **{c: values.get(c) for c in PAIR_NUMBERS},
    )
    session.add(row)
    session.flush()
    return row
