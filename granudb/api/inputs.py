"""Turning what a caller passes (SI numbers, or strings with units) into checked SI floats.

The command line and the Python API share these, so ``"12.7 mm"`` means the same in both,
and an error names the parameter (``diameter``), which the command line shows as its
option (``--diameter``).
"""

from __future__ import annotations

import math
from typing import Any

from granudb.errors import ValidationError
from granudb.vocabulary import check_value, unit_of_column


def _as_parameter(exc: ValidationError, parameter: str) -> ValidationError:
    return ValidationError(parameter, exc.value, exc.rule, row=exc.row, parameter=True)


def quantity(value: Any, column: str, parameter: str, *, check: bool = True) -> float | None:
    """``value`` in ``column``'s SI unit: a number is taken as SI, a string is parsed with
    its unit (``"190 GPa"``); the column's physical rule is checked (unless ``check`` is
    false). ``None`` stays."""
    if value is None:
        return None
    from granudb.io.units import parse_quantity

    try:
        if isinstance(value, bool):
            raise ValidationError(parameter, value, "must be a number or a quantity")
        if isinstance(value, int | float):
            number = float(value)
            if not math.isfinite(number):
                raise ValidationError(parameter, value, "must be a finite number")
        else:
            number = parse_quantity(str(value), unit_of_column(column), parameter)
        if check:
            check_value(column, number, field=parameter, shown=str(value))
    except ValidationError as exc:
        raise _as_parameter(exc, parameter) from None
    return number


def angle(value: Any, parameter: str = "angle") -> float:
    """An incidence angle in radians from ``"30 deg"``, ``"0.5 rad"`` or a number (rad),
    in [0°, 90°)."""
    radians = quantity(value, "incidence_angle_rad", parameter, check=False)
    assert radians is not None
    if not 0.0 <= radians < math.pi / 2:
        raise ValidationError(parameter, value, "must be ≥ 0° and < 90°", parameter=True)
    return radians


def angle_range(value: Any, parameter: str = "angle_range") -> tuple[float, float] | None:
    """``"20..60 deg"``, ``"20 deg..60 deg"`` or a (low, high) pair → radians."""
    if value is None:
        return None
    if isinstance(value, str):
        low, sep, high = value.partition("..")
        if not sep or not low.strip() or not high.strip():
            raise ValidationError(
                parameter, value, "must be LOW..HIGH, e.g. '10..40 deg'", parameter=True
            )
        low, high = low.strip(), high.strip()
        unit = high.lstrip("0123456789.eE+- ").strip()
        if unit and not low.lstrip("0123456789.eE+- ").strip():
            low = f"{low} {unit}"  # "20..60 deg": the unit applies to both ends
        pair = (low, high)
    else:
        try:
            pair = tuple(value)
        except TypeError:
            raise ValidationError(
                parameter, value, "must be LOW..HIGH or a (low, high) pair", parameter=True
            ) from None
        if len(pair) != 2:
            raise ValidationError(
                parameter, value, "must be LOW..HIGH or a (low, high) pair", parameter=True
            )
    low_rad, high_rad = (angle(v, parameter) for v in pair)
    if low_rad > high_rad:
        raise ValidationError(parameter, value, "must have LOW ≤ HIGH", parameter=True)
    return (low_rad, high_rad)
