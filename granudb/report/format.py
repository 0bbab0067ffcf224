"""Numbers for people: SI floats in engineering notation with the unit a person reads.

``60 GPa``, ``130.5 nm``, ``4.5 mPa·s``, ``30°``. Used by the terminal tables and the
reports alike; the units come from ``granudb.vocabulary.units``.
"""

from __future__ import annotations

import math
from typing import Any

from granudb.vocabulary.units import unit_of_column

_PREFIXES = {-15: "f", -12: "p", -9: "n", -6: "µ", -3: "m", 0: "", 3: "k", 6: "M", 9: "G", 12: "T"}
# Units that read naturally with an SI prefix; the rest are shown plainly.
_PREFIXABLE = {"Pa", "m", "s", "N", "m/s", "N·m"}


def engineering(value: float, unit: str, digits: int = 4) -> str:
    """Format ``value`` with an SI prefix chosen so the mantissa is in [1, 1000).

    >>> engineering(6.0e10, "Pa")
    '60 GPa'
    >>> engineering(1.305e-7, "m")
    '130.5 nm'
    """
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "—"
    if value == 0 or not math.isfinite(value):
        return f"{value:g} {unit}".strip()
    exponent = int(math.floor(math.log10(abs(value)) / 3) * 3)
    exponent = max(min(exponent, 12), -15)
    mantissa = value / 10**exponent
    text = f"{mantissa:.{digits}g}"
    return f"{text} {_PREFIXES[exponent]}{unit}".strip()


def display(value: Any, column: str) -> str:
    """How a table shows the SI ``value`` of ``column`` to a person."""
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if not isinstance(value, int | float):
        return str(value)
    if isinstance(value, float) and math.isnan(value):
        return "—"
    unit = unit_of_column(column)
    shown = unit.display
    if shown is None:
        return f"{value:.4g}"
    if unit.suffix == "pa_s":
        return f"{value * 1e3:.4g} mPa·s"
    if unit.suffix == "rad":
        return f"{math.degrees(value):.4g}°"
    if unit.suffix == "kg":
        return engineering(value * 1e3, "g") if abs(value) < 1 else f"{value:.4g} kg"
    if unit.suffix == "fraction":
        return f"{value * 100:.4g} %"
    if shown in _PREFIXABLE:
        return engineering(float(value), shown)
    return f"{value:.4g} {shown}"
