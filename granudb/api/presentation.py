"""What the command line's face needs to print results for people, from one place.

Values in engineering notation with units (``display``: ``60 GPa``, ``130.5 nm``,
``4.5 mPa·s``; ``display_uncertain``: ``49.0 ± 2.1 nm``), the vocabulary's titles and
symbols (``term``), and the column lists of each listing. Light on purpose: loading
this module imports neither numpy nor pandas.
"""

from __future__ import annotations

from granudb.analysis import collision_query
from granudb.reporting.format import display, display_uncertain
from granudb.vocabulary import DERIVED_TERMS, FLUIDS, MATERIALS, Term, term
from granudb.vocabulary.catalogue import (
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

DEFAULT_COLLISION_COLUMNS = COLLISION_NARROW
FIT_TABLE_COLUMNS = FIT_NARROW


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
    "display",
    "display_uncertain",
    "parameter_of",
    "spreadsheet_cell",
    "term",
]


#: The collision filters: the Python API's keyword parameters, the command line's options.
COLLISION_FILTERS = collision_query.COLLISION_FILTERS
