"""A pair's dry values: the ones a source measured for the pair (``granudb pairs add``,
``pairs list``) and the values every prediction uses, with where each came from
(``granudb pairs show``; docs/physics.md §18)."""

from __future__ import annotations

from typing import Any

from granudb.api import inputs
from granudb.api.database import opened
from granudb.api.frames import records_frame
from granudb.db import catalog_rows, lookup_rows
from granudb.db import pair_values as pair_store
from granudb.scenario.dry_values import dry_values as resolve_dry_values
from granudb.vocabulary.catalog import PAIR_VALUE_COLUMNS
from granudb.vocabulary.text import check_text


def pair_values(db: Any = None, *, as_frame: bool = True) -> Any:
    """Every pair's measured dry values with their source, by particle and wall: a
    DataFrame, or a list of records with ``as_frame=False``.

    Examples
    --------
    >>> import granudb
    >>> rows = granudb.pair_values(db=db, as_frame=False)
    >>> [(r["particle"], r["wall"], r["dry_friction"]) for r in rows if r["particle"] == "glass"]
    [('glass', 'Zerodur', 0.106)]
    """
    with opened(db) as database, database.reading() as connection:
        records = [
            catalog_rows.pair_value_record(r) for r in catalog_rows.pair_value_rows(connection)
        ]
    return records_frame(records, PAIR_VALUE_COLUMNS) if as_frame else records


def add_pair_value(
    particle: str,
    wall: str,
    *,
    dry_restitution: Any = None,
    dry_friction: Any = None,
    immersed_friction: Any = None,
    source: str | None = None,
    source_locator: str | None = None,
    notes: str | None = None,
    db: Any = None,
) -> dict[str, Any]:
    """Store the dry restitution and/or friction measured for ``particle`` on ``wall``
    (either way round), and its ``immersed_friction`` where asperities touch in a
    liquid, with ``source`` (a source key) and ``source_locator``, or ``notes`` saying
    where they come from (one of them is required). They come before the two materials'
    own values in every prediction (``dry_values``). A pair's values are never changed
    once stored (released datasets read them); returns the pair's values as
    ``dry_values`` gives them.

    Examples
    --------
    >>> import granudb
    >>> values = granudb.add_pair_value("steel", "glass", dry_friction=0.12,
    ...                                 notes="our lab, run book 7", db=db)
    >>> values["dry_friction_source"]
    'measured for steel on glass (our lab, run book 7)'
    """
    particle, wall = inputs.text(particle, "particle"), inputs.text(wall, "wall")
    if source is None and notes is None:
        raise inputs.missing("source", "is required unless notes say where the values come from")
    source = None if source is None else inputs.text(source, "source")
    given = {
        "dry_restitution": dry_restitution,
        "dry_friction": dry_friction,
        "immersed_friction": immersed_friction,
    }
    values: dict[str, float] = {}
    for column, value in given.items():
        quantity = inputs.quantity(value, column, column)
        if quantity is not None:
            values[column] = quantity
    texts = {
        name: check_text(name, inputs.text(given, name))
        for name, given in (("source_locator", source_locator), ("notes", notes))
        if given is not None
    }
    with opened(db) as database:
        with database.session(write=True) as session:
            pair_store.add_pair_value(session, particle, wall, values, source, **texts)
        return dry_values(particle, wall, db=database)


def dry_values(
    particle: str, wall: str, *, dataset: str | None = None, db: Any = None
) -> dict[str, Any]:
    """The dry restitution and friction every prediction uses for ``particle`` on
    ``wall``, each with its basis ("pair": measured for this pair; "materials": from the
    two materials' own values by granudb's rule; "borrowed": Joseph & Hunt's steel on
    Zerodur) and its source in words. With ``dataset`` (``NAME`` or ``NAME@VERSION``) as
    that dataset's runs use the materials: a release reads what it was released with.

    Examples
    --------
    >>> import granudb
    >>> values = granudb.dry_values("steel", "Zerodur", db=db)
    >>> values["dry_restitution"], values["dry_restitution_basis"]
    (0.97, 'pair')
    """
    particle, wall = inputs.text(particle, "particle"), inputs.text(wall, "wall")
    with opened(db) as database, database.reading() as connection:
        dataset_id = None
        if dataset is not None:
            name, version = inputs.dataset_ref(dataset)
            dataset_id = lookup_rows.dataset_row(connection, name, version).id
        found = resolve_dry_values(connection, particle, wall, dataset_id)
    return {"particle": particle, "wall": wall, **found.record()}
