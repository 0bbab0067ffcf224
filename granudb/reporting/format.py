"""Numbers for people: SI floats in engineering notation with the unit a person reads.

``60 GPa``, ``130.5 nm``, ``4.5 mPa·s``, ``30°``. Used by the terminal tables and the
reports alike; the units come from ``granudb.vocabulary.units``.
"""

from __future__ import annotations

import math
import numbers
import re
from typing import Any, TypeGuard

from granudb.vocabulary.escaping import shown_text
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


#: Columns whose empty value has a meaning a bare "—" would hide (docs/physics.md §4).
EMPTY_WORDS = {"roughness_rms_m": "not stated"}


def display(value: Any, column: str, digits: int = 4) -> str:
    """How a table shows the SI ``value`` of ``column`` to a person (``digits``
    significant digits; a narrow terminal table uses 3).

    >>> display(None, "roughness_rms_m"), display(None, "yield_stress_pa")
    ('not stated', '—')
    """
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return EMPTY_WORDS.get(column, "—")
    if isinstance(value, bool):
        return "yes" if value else "no"
    if hasattr(value, "item") and not isinstance(value, str):
        value = value.item()  # a numpy scalar
    if not isinstance(value, int | float):
        return shown_text(str(value))  # a stored control character shown, never acted on
    if isinstance(value, float) and math.isnan(value):
        return EMPTY_WORDS.get(column, "—")
    unit = unit_of_column(column)
    shown = unit.display
    g = f".{digits}g"
    if shown is None:
        if 10**digits <= abs(value) < 1e7:
            return f"{value:.0f}"  # 1098, not 1.1e+03: a Stokes number reads as a number
        return format(value, g)
    if unit.suffix == "pa_s":
        return f"{format(value * 1e3, g)} mPa·s"
    if unit.suffix == "rad":
        return f"{format(math.degrees(value), g)}°"
    if unit.suffix == "kg":
        return engineering(value * 1e3, "g", digits) if abs(value) < 1 else f"{value:{g}} kg"
    if unit.suffix == "fraction":
        return f"{format(value * 100, g)} %"
    if shown in _PREFIXABLE:
        return engineering(float(value), shown, digits)
    return f"{format(value, g)} {shown}"


def _decimals_for(error: float) -> int:
    """Decimal places that keep 1–2 significant digits of ``error``: two when the
    leading digit is 1 or 2 (rounding 0.14 to 0.1 would lose a third of it), else one."""
    exponent = math.floor(math.log10(abs(error)))
    leading = abs(error) / 10**exponent
    digits = 2 if leading < 3 else 1
    return digits - 1 - exponent


def _fixed(value: float, decimals: int) -> str:
    if decimals > 0:
        return f"{value:.{decimals}f}"
    step = 10 ** (-decimals)
    return f"{round(value / step) * step:.0f}"


def plus_minus(value: Any, error: Any, *, exact_below: float = 1e-9) -> str:
    """``value ± error`` to the precision the uncertainty supports.

    The uncertainty keeps one or two significant digits and the value is rounded to the
    same decimal place, so ``0.34 ± 3.2e-05`` reads ``0.34000 ± 0.00003``. An uncertainty
    below ``exact_below`` × |value| is floating-point noise of a perfect fit: the value is
    shown without a ± (never ``± 1.4e-17`` or ``± 0``), saying its uncertainty is not
    determined.

    >>> plus_minus(0.10999999, 1.4e-17)
    '0.11 (uncertainty not determined: a perfect fit)'
    >>> plus_minus(0.3412, 0.0712)
    '0.34 ± 0.07'
    >>> plus_minus(0.97, 0.0123)
    '0.970 ± 0.012'
    """
    if not is_number(value):
        return "—"
    value = float(value)
    if not is_number(error):
        return f"{value:.3g}"
    error = abs(float(error))
    if error <= exact_below * max(abs(value), 1e-300) or error == 0:
        return f"{value:.3g} (uncertainty not determined: a perfect fit)"
    decimals = _decimals_for(error)
    if error >= 1e4 or abs(value) >= 1e6 or (error < 1e-4 and abs(value) < 1e-3):
        exponent = math.floor(math.log10(abs(value) if value else error))
        scale = 10.0**exponent
        shown = plus_minus(value / scale, error / scale, exact_below=exact_below)
        return f"({shown}) × 10{superscript(str(exponent))}"
    return f"{_fixed(value, decimals)} ± {_fixed(error, decimals)}"


def _display_scale(value: float, column: str) -> tuple[float, str]:
    """The factor and unit ``display`` shows ``column``'s ``value`` in (``1e9, "nm"``)."""
    unit = unit_of_column(column)
    shown = unit.display
    fixed = {"pa_s": (1e3, "mPa·s"), "rad": (180.0 / math.pi, "°"), "fraction": (100.0, "%")}
    if shown is None:
        return 1.0, ""
    if unit.suffix in fixed:
        return fixed[unit.suffix]
    if unit.suffix == "kg":
        value, shown = value * 1e3, "g"
    if shown not in _PREFIXABLE and unit.suffix != "kg":
        return 1.0, shown
    if value == 0 or not math.isfinite(value):
        return (1e3 if unit.suffix == "kg" else 1.0), shown
    exponent = max(min(int(math.floor(math.log10(abs(value)) / 3) * 3), 12), -15)
    return (1e3 if unit.suffix == "kg" else 1.0) / 10**exponent, f"{_PREFIXES[exponent]}{shown}"


def display_uncertain(value: Any, u: Any, column: str) -> str:
    """``column``'s SI ``value`` with its standard uncertainty ``u``, as ``plus_minus``
    rounds them (one or two significant digits of u), in the unit ``display`` uses.
    Without a positive ``u`` it is ``display(value, column)``.

    >>> display_uncertain(4.896e-8, 2.15e-9, "min_gap_m")
    '49.0 ± 2.1 nm'
    >>> display_uncertain(951.2, 38.4, "normal_stokes_number")
    '950 ± 40'
    """
    if not (is_number(value) and is_number(u) and float(u) > 0):
        return display(value, column)
    factor, unit = _display_scale(float(value), column)
    return f"{plus_minus(float(value) * factor, float(u) * factor)} {unit}".strip()


def interval(value: Any, low: Any, high: Any) -> str:
    """A value with an asymmetric interval, ``0.34 [0.30, 0.39]``, rounded like
    ``plus_minus`` on the larger half-width. An interval of no width (below 10⁻⁹ of the
    value: every resample gave the same number) is not an interval: the value is shown
    with "interval not determined", never as exact.

    >>> interval(0.3412, 0.30, 0.39)
    '0.34 [0.30, 0.39]'
    >>> interval(0.0854, float("nan"), float("nan"))
    '0.0854 (interval not determined)'
    >>> interval(0.96999999999999986, 0.96999999999999986, 0.97000000000000008)
    '0.97 (interval not determined: every resample gave the same value)'
    """
    if not is_number(value):
        return "—"
    if not (is_number(low) and is_number(high)):  # the fit gave none (too few runs, degenerate)
        return f"{float(value):.3g} (interval not determined)"
    half = max(abs(float(high) - float(value)), abs(float(value) - float(low)))
    if half <= 1e-9 * abs(float(value)) or half == 0:
        return f"{float(value):.3g} (interval not determined: every resample gave the same value)"
    decimals = max(_decimals_for(half), 0)
    return (
        f"{_fixed(float(value), decimals)} "
        f"[{_fixed(float(low), decimals)}, {_fixed(float(high), decimals)}]"
    )


def is_number(value: Any) -> TypeGuard[float]:
    """True for a finite real number (numpy's included); False for NaN, ±inf, a bool,
    ``None`` or text.

    >>> [is_number(v) for v in (1, 2.5, float("nan"), True, None, "3")]
    [True, True, False, False, False, False]
    """
    return (
        isinstance(value, numbers.Real)
        and not isinstance(value, bool)
        and math.isfinite(float(value))
    )


def as_number(value: Any) -> float:
    """``value`` as a float when it is a finite real number, else NaN.

    >>> as_number(3), as_number("3")
    (3.0, nan)
    """
    return float(value) if is_number(value) else math.nan


_SUPERSCRIPT = str.maketrans("0123456789+-−=()n/.", "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻⁻⁼⁽⁾ⁿ⁄·")
_SUBSCRIPT = str.maketrans("0123456789+-=()", "₀₁₂₃₄₅₆₇₈₉₊₋₌₍₎")


def superscript(text: str) -> str:
    """``text`` in Unicode superscript characters (digits, signs, the fraction slash)."""
    return text.translate(_SUPERSCRIPT)


def unicode_math(text: Any) -> str:
    """Formulas without TeX source: ``R^{3/2}`` becomes ``R³⁄²``, ``x_{1}`` ``x₁``.

    Exponents the Unicode superscripts cannot spell are kept readable in parentheses
    (``^(a+b)``) rather than as TeX braces.

    >>> unicode_math("(μ₀U/(E*R))^{2/7} and a^{1/3}")
    '(μ₀U/(E*R))²⁄⁷ and a¹⁄³'
    """

    def sup(match: re.Match[str]) -> str:
        body = match.group(1)
        if re.fullmatch(r"[0-9+\-−=()n/.]+", body):
            return superscript(body)
        return f"^({body})"

    def sub(match: re.Match[str]) -> str:
        body = match.group(1)
        if re.fullmatch(r"[0-9+\-=()]+", body):
            return body.translate(_SUBSCRIPT)
        return f"_{body}"

    out = re.sub(r"\^\{([^{}]*)\}", sup, "" if text is None else str(text))
    out = re.sub(r"\^([0-9])", lambda m: superscript(m.group(1)), out)
    return re.sub(r"_\{([^{}]*)\}", sub, out)


def _catalogue_value(value: Any, field: str) -> str:
    if value is None:
        return "(none)"
    return repr(value) if isinstance(value, str) else display(value, field)


def _catalogue_entry(change: dict[str, Any]) -> str:
    """``steel youngs_modulus_pa``, ``glycerol-37 viscosity_pa_s at 20 °C``."""
    at = change.get("temperature_c")
    where = "" if at is None else f" at {format(at, 'g')} °C"
    return f"{change['name']} {change['field']}{where}"


def pinned_line(change: dict[str, Any]) -> str:
    """One line saying what a release pins that today's catalogue has changed (a record
    of ``granudb.db.catalog_differences.pinned_changes``).

    >>> pinned_line({"kind": "material", "name": "steel", "field": "youngs_modulus_pa",
    ...   "temperature_c": None, "first": 1.9e11, "second": 1e11, "revision": 1,
    ...   "kept_at": None})
    'steel youngs_modulus_pa: release pins 190 GPa (revision 1), catalogue now 100 GPa'

    A source's text is cited, not pinned: the line names the revision the release cites
    and today's, as ``sources history`` numbers them.

    >>> pinned_line({"kind": "source", "name": "cheng-2008", "field": "doi",
    ...   "temperature_c": None, "first": "10.1021/x", "second": None,
    ...   "revision": 1, "now_revision": 2, "kept_at": None})
    "source cheng-2008 doi: release cites revision 1, '10.1021/x'; revision 2 now reads (none)"
    """
    field, revision, kept = change["field"], change.get("revision"), change.get("kept_at")
    if change["kind"] == "source":
        return (
            f"source {_catalogue_entry(change)}: release cites revision {revision}, "
            f"{_catalogue_value(change['first'], field)}; revision {change.get('now_revision')} "
            f"now reads {_catalogue_value(change['second'], field)}"
        )
    # a pair's values have no revision: the release reads those stored before it
    when = "" if kept is None else f", kept {kept:%Y-%m-%d %H:%M} UTC"
    which = "" if revision is None else f" (revision {revision}{when})"
    return (
        f"{_catalogue_entry(change)}: release pins {_catalogue_value(change['first'], field)}"
        f"{which}, catalogue now {_catalogue_value(change['second'], field)}"
    )


def difference_line(change: dict[str, Any]) -> str:
    """One catalogue difference between two datasets (``catalogue_diff``): ``first →
    second``.

    >>> difference_line({"kind": "fluid point", "name": "water", "field": "viscosity_pa_s",
    ...   "temperature_c": 20.0, "first": 1.0e-3, "second": None})
    'water viscosity_pa_s at 20 °C: 1 mPa·s → (none)'
    """
    field = change["field"]
    return (
        f"{_catalogue_entry(change)}: {_catalogue_value(change['first'], field)} → "
        f"{_catalogue_value(change['second'], field)}"
    )
