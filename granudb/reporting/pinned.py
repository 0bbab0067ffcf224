"""What a release pins that today's catalogue has changed, as the lines every output
says (``dataset show|list|diff|export``, reports, DEM decks, run listings): the records
of ``granudb.db.catalog_differences.pinned_changes``, each said by ``pinned_line``."""

from __future__ import annotations

import logging
from typing import Any

from granudb.db.catalog_differences import pinned_changes
from granudb.reporting.format import pinned_line


def pinned_notes(connection: Any, dataset_id: int | None) -> list[str]:
    """One line per catalogue value dataset ``dataset_id`` pins that differs from today's
    catalogue ("steel youngs_modulus_pa: release pins 190 GPa (revision 1, kept …),
    catalogue now 100 GPa"); none for a draft, which reads today's values, or for no
    dataset."""
    if dataset_id is None:
        return []
    return [pinned_line(change) for change in pinned_changes(connection, dataset_id)]


def announce_pinned(connection: Any, dataset_id: int | None, ref: str) -> list[str]:
    """``pinned_notes``, also said through the ``granudb`` logger (the command line
    prints them as notes), for outputs whose bytes must not carry them (a release's DEM
    deck, its runs); ``ref`` names the dataset as NAME@VERSION."""
    notes = pinned_notes(connection, dataset_id)
    for line in notes:
        logging.getLogger("granudb").info("%s pins a value changed since: %s", ref, line)
    return notes
