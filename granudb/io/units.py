"""Units at the edges: parse what people type.

Inside granudb every number is SI and every name carries its unit
(``youngs_modulus_pa``). People type ``"190 GPa"`` or ``"4.5 cP"``; this module turns that
into a float in the column's unit with Pint, refusing a wrong dimension by field name,. Formatting
for people (``60 GPa``, ``130.5 nm``) is ``granudb.report.format``; the unit table both read
is ``granudb.vocabulary.units``.

Pint is imported lazily (one registry for the whole program) so ``granudb --help`` stays fast.
"""

from __future__ import annotations

import math
import re
from functools import cache
from typing import Any

from granudb.errors import ValidationError
from granudb.vocabulary.units import UNITS, Unit


@cache
def registry() -> Any:
    """The program's single Pint registry (creating one is slow)."""
    import pint

    ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    ureg.define("percent_wt = 0.01 = wt_percent")
    return ureg


_NUMBER = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*$")


def _finite(field: str, text: str, value: float) -> float:
    if not math.isfinite(value):
        raise ValidationError(field, text, "must be a finite number")
    # Pint's conversions leave float dust (4.5 cP -> 0.0045000000000000005); what a person
    # typed is stored as they meant it.
    return float(f"{value:.15g}")


def parse_quantity(text: str | float, unit: Unit | str, field: str) -> float:
    """Parse ``"190 GPa"`` into a float in ``unit`` (SI), refusing the wrong dimension.

    A bare number is accepted only for dimensionless quantities (ratios, fractions):
    for anything with a dimension, ``"2540"`` is ambiguous and refused with an example.
    ``"45 %"`` and ``"0.45"`` are the same fraction.
    """
    unit = UNITS[unit] if isinstance(unit, str) else unit
    if isinstance(text, int | float):
        if unit.pint != "dimensionless":
            raise ValidationError(field, text, f"needs a unit, e.g. '{unit.example}'")
        return _finite(field, str(text), float(text))
    raw = str(text).strip()
    if not raw:
        raise ValidationError(field, "''", "is empty")
    if _NUMBER.match(raw):
        if unit.pint != "dimensionless":
            raise ValidationError(field, raw, f"needs a unit, e.g. '{unit.example}'")
        return _finite(field, raw, float(raw))
    import pint

    ureg = registry()
    try:
        quantity = ureg.Quantity(raw.replace("µ", "u").replace("μ", "u"))
        value = float(quantity.to(unit.pint).magnitude)
    except pint.DimensionalityError:
        raise ValidationError(
            field, raw, f"is not {unit.dimension} (expected a unit like '{unit.example}')"
        ) from None
    except Exception as exc:  # noqa: BLE001 - Pint's parser raises many types (TokenError…)
        detail = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise ValidationError(
            field, raw, f"is not a quantity Pint understands ({detail})"
        ) from None
    return _finite(field, raw, value)


@cache
def conversion(from_unit: str, to: Unit) -> tuple[float, float]:
    """``(scale, offset)`` such that ``value_in_to = scale * value + offset``.

    Used for CSV columns whose header names a unit: one Pint call per column, then a
    vectorized multiply, instead of one Pint call per cell. Raises ``ValidationError``
    (field ``unit``) when ``from_unit`` is unknown or has the wrong dimension.
    """
    import pint

    ureg = registry()
    spelled = from_unit.strip().replace("µ", "u").replace("μ", "u")
    if spelled in {"", "-", "1"}:
        spelled = "dimensionless"
    try:
        zero = float(ureg.Quantity(0.0, spelled).to(to.pint).magnitude)
        one = float(ureg.Quantity(1.0, spelled).to(to.pint).magnitude)
    except pint.DimensionalityError:
        raise ValidationError(
            "unit", f"[{from_unit}]", f"is not {to.dimension} (expected e.g. [{to.pint}])"
        ) from None
    except Exception:  # noqa: BLE001 - Pint's parser raises many types (TokenError…)
        raise ValidationError("unit", f"[{from_unit}]", "is not a unit Pint knows") from None
    return one - zero, zero


def round_significant(values: Any, digits: int = 15) -> Any:
    """Round floats to ``digits`` significant digits, vectorized.

    A CSV value in ``mm/s`` times 0.001 picks up float dust (0.1 mm/s → 1.0000000000000002e-4);
    rounding to 15 significant digits gives back the decimal a person wrote, so values
    round-trip through export and import unchanged. Works on scalars and numpy arrays.
    """
    import numpy as np

    x = np.asarray(values, dtype=float)
    out = x.copy()
    finite = np.isfinite(x) & (x != 0)
    if not finite.any():
        return out if out.ndim else float(out)
    magnitude = np.zeros_like(x)
    magnitude[finite] = np.floor(np.log10(np.abs(x[finite])))
    power = (digits - 1) - magnitude
    # 10**k is exact in binary for 0 <= k <= 22: then int / 10**k is correctly rounded.
    exact = finite & (power >= 0) & (power <= 22)
    scale = 10.0 ** power[exact]
    out[exact] = np.round(x[exact] * scale) / scale
    exact_large = finite & (power < 0) & (power >= -22)
    scale = 10.0 ** -power[exact_large]
    out[exact_large] = np.round(x[exact_large] / scale) * scale
    rest = finite & ~exact & ~exact_large
    if rest.any():
        out[rest] = [float(f"{v:.{digits}g}") for v in x[rest]]
    return out if out.ndim else float(out)
