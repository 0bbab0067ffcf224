"""The physical rules every stored value obeys, checked before anything is written.

The database holds the same rules as CHECK constraints (``granudb.db.models``); checking
here first lets granudb refuse bad input with a line that names the field, the value as the
user typed it and the rule, instead of a driver error. Data Package schemas reuse
``RULES`` for their field constraints, so the three places cannot drift apart.
"""

from __future__ import annotations

import math
from typing import Any

from granudb.errors import ValidationError
from granudb.vocabulary.ranges import NON_NEGATIVE, POSITIVE, Rule
from granudb.vocabulary.terms import STORED_RULES

__all__ = [
    "MAX_SPEED_M_S",
    "NON_NEGATIVE",
    "POSITIVE",
    "RULES",
    "Rule",
    "check_record",
    "check_value",
]

#: No speed (or speed uncertainty) may be larger than this, in m/s, from a CSV cell, a
#: package cell or an option alike: above any impact apparatus (light-gas guns reach
#: about 8 km/s); every derived quantity squares the speed, and a value like 1e300 m/s
#: would turn them into overflows, not numbers.
MAX_SPEED_M_S = 1e4

#: Each stored column's rule comes from its declaration (``granudb.vocabulary.terms``);
#: the quantities below are not stored but are checked as they are typed.
RULES: dict[str, Rule] = {
    **STORED_RULES,
    "impact_speed_m_s": POSITIVE,
    # No rebound below St_c: a threshold of the verdict, positive and finite.
    "critical_stokes": POSITIVE,
}


def check_value(
    column: str,
    value: float | None,
    *,
    field: str | None = None,
    shown: str | None = None,
    row: int | None = None,
) -> None:
    """Raise ``ValidationError`` if ``value`` (SI, for ``column``) breaks its rule.

    ``field`` is how the user named the value (``--density``, a CSV header) and ``shown``
    the text they typed; both default to the column and the SI value.
    """
    rule = RULES.get(column)
    if rule is None or value is None:
        return
    if not rule.holds(float(value)):
        raise ValidationError(
            field or column, shown if shown is not None else value, rule.text, row=row
        )


def check_record(record: dict[str, Any], *, row: int | None = None) -> None:
    """Check every ruled column of an SI record."""
    for column, value in record.items():
        if isinstance(value, int | float) and not isinstance(value, bool):
            check_value(column, value, row=row)


def same_value(old: Any, new: Any) -> bool:
    """Equal, with floats compared to 1e-12 relative (a CSV's text is not bit-exact): the
    one rule by which granudb tells a changed stored value from an unchanged one.

    >>> same_value(0.1 + 0.2, 0.3), same_value(1.0, 1.1), same_value("a", "a")
    (True, False, True)
    """
    if isinstance(old, float) and isinstance(new, float | int):
        return math.isclose(old, float(new), rel_tol=1e-12, abs_tol=0.0)
    equal: bool = old == new
    return equal
