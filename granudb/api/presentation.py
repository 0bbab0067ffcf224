"""What the command line's face needs to print results for people, from one place.

Values in engineering notation with units (``display``: ``60 GPa``, ``130.5 nm``,
``4.5 mPa·s``; ``display_uncertain``: ``49.0 ± 2.1 nm``), the vocabulary's titles and
symbols (``term``), and the column lists of each listing. Light on purpose: loading
this module imports neither numpy nor pandas.
"""

from __future__ import annotations

from typing import Any

from granudb.reporting import format as formats
from granudb.reporting.fit_view import people_view as fit_people_view
from granudb.reporting.format import display_uncertain
from granudb.scenario import collision_query
from granudb.vocabulary import DERIVED_TERMS, FLUIDS, MATERIALS, Term, term
from granudb.vocabulary.catalog import (
    PAIR_VALUE_COLUMNS,
    POINT_COLUMNS,
    SOURCE_COLUMNS,
    SOURCE_FIELDS,
    SOURCE_NARROW,
    parameter_of,
)
from granudb.vocabulary.escaping import spreadsheet_cell
from granudb.vocabulary.listings import (
    COLLISION_NARROW,
    DATASET_COLUMNS,
    DATASET_GROUP_COLUMNS,
    DIFF_COLUMNS,
    FIT_NARROW,
    PUBLISHED_NARROW,
)
from granudb.vocabulary.people import AUTHOR_FIELDS, author_words

DEFAULT_COLLISION_COLUMNS = COLLISION_NARROW
FIT_TABLE_COLUMNS = FIT_NARROW


def words(value: Any) -> str:
    """A list or mapping in words, never as Python writes it: authors as people
    (``Jane Doe (ORCID …, Lab A); Rick Roe``), a list joined by commas, a mapping as
    ``key: value`` pairs."""
    if isinstance(value, dict):
        if "family_names" in value and set(value) <= set(AUTHOR_FIELDS):
            return author_words(value)
        return "; ".join(f"{k}: {words(v)}" for k, v in value.items())
    if isinstance(value, list | tuple | set):
        parts = [words(v) for v in value]
        joiner = "; " if any(isinstance(v, dict) for v in value) else ", "
        return joiner.join(parts) if parts else "—"
    return formats.display(value, "")


def display(value: Any, column: str, digits: int = 4) -> str:
    """How a table shows the SI ``value`` of ``column`` to a person (``60 GPa``,
    ``130.5 nm``; ``granudb.reporting.format.display``); a list or mapping in ``words``.

    >>> display(["glass", "lubrication"], "keywords")
    'glass, lubrication'
    """
    if isinstance(value, dict | list | tuple | set):
        return words(value)
    return formats.display(value, column, digits)


def derived_terms() -> dict[str, Term]:
    """Every derived quantity ``pair`` and ``derive`` return, with its symbol and title."""
    return dict(DERIVED_TERMS)


__all__ = [
    "DATASET_COLUMNS",
    "DATASET_GROUP_COLUMNS",
    "DEFAULT_COLLISION_COLUMNS",
    "DIFF_COLUMNS",
    "FIT_TABLE_COLUMNS",
    "FLUIDS",
    "MATERIALS",
    "PAIR_VALUE_COLUMNS",
    "POINT_COLUMNS",
    "PUBLISHED_NARROW",
    "SOURCE_COLUMNS",
    "SOURCE_FIELDS",
    "SOURCE_NARROW",
    "derived_terms",
    "fit_people_view",
    "words",
    "display",
    "display_uncertain",
    "parameter_of",
    "spreadsheet_cell",
    "term",
]


#: The collision filters: the Python API's keyword parameters, the command line's options.
COLLISION_FILTERS = collision_query.COLLISION_FILTERS
