"""Quantities typed by people become SI floats; anything else is refused by name."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from granudb.errors import ValidationError
from granudb.io.units import parse_quantity, round_significant
from granudb.reporting.format import engineering


@pytest.mark.parametrize(
    ("text", "unit", "expected"),
    [
        ("190 GPa", "pa", 1.9e11),
        ("4.5 cP", "pa_s", 4.5e-3),
        ("23.6 nm", "m", 2.36e-8),
        ("0.1305 µm", "m", 1.305e-7),
        ("0.1305 um", "m", 1.305e-7),
        ("12.7 mm", "m", 0.0127),
        ("7.78 g/cm^3", "kg_m3", 7780.0),
        ("300 mm/s", "m_s", 0.3),
        ("30 deg", "rad", math.radians(30)),
        ("20 degC", "c", 20.0),
        ("293.15 K", "c", 20.0),
        ("6e-9 1/Pa", "pa_inv", 6e-9),
        ("45 %", "fraction", 0.45),
        ("0.45", "fraction", 0.45),
        ("0.27", "", 0.27),
    ],
)
def test_parse_quantity(text: str, unit: str, expected: float) -> None:
    assert parse_quantity(text, unit, "field") == pytest.approx(expected, rel=1e-12)


def test_typed_decimal_survives_conversion_exactly() -> None:
    # Pint alone gives 0.0045000000000000005; the stored value is what the person meant.
    assert parse_quantity("4.5 cP", "pa_s", "--viscosity") == 0.0045


@pytest.mark.parametrize(
    ("text", "unit", "message"),
    [
        ("190", "pa", "x: 190 needs a unit, e.g. '190 GPa'"),
        ("3 m", "kg_m3", "x: 3 m is not a density"),
        ("4.5 cP", "pa", "x: 4.5 cP is not a pressure or modulus"),
        ("nan GPa", "pa", "x: nan GPa must be a finite number"),
        ("inf m", "m", "x: inf m must be a finite number"),
        ("12 parsecs/fortnight squared", "m_s", "x: 12 parsecs/fortnight squared is not"),
        ("", "m", "x: '' is empty"),
        ("1e999 Pa", "pa", "x: 1e999 Pa must be a finite number"),
    ],
)
def test_parse_quantity_refuses_with_one_line(text: str, unit: str, message: str) -> None:
    with pytest.raises(ValidationError) as info:
        parse_quantity(text, unit, "x")
    assert str(info.value).startswith(message)
    assert "\n" not in str(info.value)


def test_engineering_notation() -> None:
    assert engineering(6.0e10, "Pa") == "60 GPa"
    assert engineering(1.305e-7, "m") == "130.5 nm"
    assert engineering(5.1e-6, "s") == "5.1 µs"
    assert engineering(float("nan"), "m") == "—"


@given(st.floats(allow_nan=False, allow_infinity=False, min_value=-1e300, max_value=1e300))
def test_round_significant_is_idempotent_and_close(x: float) -> None:
    once = round_significant(x)
    assert round_significant(once) == once
    assert once == pytest.approx(x, rel=1e-14, abs=0.0)


@given(st.decimals(min_value=-1e6, max_value=1e6, places=6, allow_nan=False))
def test_mm_per_s_round_trips_to_the_decimal_written(d) -> None:
    typed = f"{d} mm/s"
    value = parse_quantity(typed, "m_s", "v")
    assert value == float(f"{float(d) / 1000:.15g}")


@given(
    st.text(max_size=40), st.sampled_from(["pa", "m", "m_s", "pa_s", "c", "rad", "", "fraction"])
)
def test_fuzzed_quantities_parse_or_refuse_cleanly(text: str, unit: str) -> None:
    try:
        value = parse_quantity(text, unit, "x")
    except ValidationError as exc:
        assert "\n" not in str(exc) and str(exc).startswith("x: ")
    else:
        assert math.isfinite(value)
