"""Units at the edges: parse what people type, with bounded cost and no guessing.

Inside granudb every number is SI and every name carries its unit
(``youngs_modulus_pa``). People type ``"190 GPa"`` or ``"4.5 cP"``, and files carry units
in their headers (``v_n_in [mm/s]``); this module turns both into a float in the column's
unit with Pint, refusing a wrong dimension by field name. Formatting for people
(``60 GPa``, ``130.5 nm``) is ``granudb.reporting.format``; the unit table both read is
``granudb.vocabulary.units``.

Every unit expression, from any door (an option, a CSV header, a package schema), first
goes through ``check_unit_expression``: a short allow-list grammar (names, ``*``, ``/``,
small literal exponents, at most three levels of parentheses, at most 60 characters).
Pint evaluates what it parses as Python-like arithmetic, so ``m**(9**9**9)`` would
otherwise run for ever (holding whatever lock the caller holds); after this check Pint
only ever sees a few tokens with exponents of at most 12.

Three readings Pint would make silently are refused or made explicit here:

- a comma inside a number (``"2,5 g/cm^3"``: Pint drops it and reads 25) is refused with
  the number written with a decimal point;
- radians are dimensionless to Pint, so ``%`` would be an angle and ``deg`` a fraction:
  an angle needs an angle unit (deg, rad, …) and a fraction must not be one;
- a frequency in an angular-velocity column: ``Hz`` (and kHz, …) is read as revolutions
  per second and converted with 2π (10 Hz = 62.83 rad/s), as ``rpm`` already is; a bare
  inverse time (``1/s``) is refused as ambiguous (rad/s or rev/s?).

Pint is imported lazily (one registry for the whole program), and only for units outside
granudb's table (``granudb.vocabulary.units.KNOWN_UNITS``: prefixed m, g, s, Pa, N, P, Hz;
deg, rpm, %, degC, K, …), which ``_fast_conversion`` converts with the same rules and
refusals: Pint's import and registry cost ~0.3 s, more than the rest of ``granudb pair``.
"""

from __future__ import annotations

import math
import re
from functools import cache, lru_cache
from typing import Any

from granudb.errors import ValidationError
from granudb.lazy import numpy as np
from granudb.lazy import pint as pint
from granudb.vocabulary.units import UNITS, SiValue, Unit, si_value

#: Longest quantity (``"12.7 mm"``) and unit expression (``"kg/m^3"``) read, in characters.
MAX_QUANTITY_CHARS = 100
MAX_UNIT_CHARS = 60
#: Largest exponent magnitude (``m^3``, ``s^-2``; no physical unit needs more) and
#: parenthesis depth in a unit expression.
MAX_EXPONENT = 12
MAX_DEPTH = 3


@cache
def registry() -> Any:
    """The program's single Pint registry (creating one is slow)."""
    ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    ureg.define("percent_wt = 0.01 = wt_percent")
    return ureg


class UnitSyntaxError(ValueError):
    """A unit expression outside the allowed grammar; ``str()`` is the rule broken."""


_SUPERSCRIPT = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺", "0123456789-+")
#: One token of a unit expression, tried in this order at each position.
_TOKEN = re.compile(
    r"(?P<space>\s+)"
    r"|(?P<power>\*\*|\^)"
    r"|(?P<op>[*/·⋅×])"
    r"|(?P<open>\()|(?P<close>\))"
    r"|(?P<name>[A-Za-z_°µμΩ]+|%|‰)(?P<implicit>-?[0-9]+(?![0-9.]))?(?P<sup>[⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺]+)?"
    r"|(?P<number>[0-9]+(?:\.[0-9]+)?(?:[eE][-+]?[0-9]{1,3})?(?![0-9]))"
)
#: What may follow ``^`` or ``**``: a small number, or a fraction in parentheses.
_EXPONENT = re.compile(
    r"\s*(?:(?P<plain>[-+]?[0-9]{1,2}(?:\.[0-9]{1,3})?(?![0-9A-Za-z_.]))"
    r"|\(\s*(?P<num>[-+]?[0-9]{1,2}(?:\.[0-9]{1,3})?)\s*(?:/\s*(?P<den>[0-9]{1,2})\s*)?\))"
)


def _exponent(text: str) -> str:
    """A checked exponent as Pint should read it (``3``, ``-1``, ``(1/2)``)."""
    try:
        value = float(text.strip("()").split("/")[0])
    except ValueError:
        raise UnitSyntaxError(f"has an exponent {text!r} that is not a number") from None
    if abs(value) > MAX_EXPONENT:
        raise UnitSyntaxError(f"has an exponent {text} larger than {MAX_EXPONENT}")
    return text.replace(" ", "")


def _name(match: re.Match[str]) -> str:
    name = match["name"].replace("µ", "u").replace("μ", "u")
    name = {"%": "percent", "‰": "permille"}.get(name, name)
    power = match["implicit"] or (match["sup"] or "").translate(_SUPERSCRIPT)
    # m3, s-1, m³: the exponent written straight after the name, as lab files do.
    return f"{name}**{_exponent(power)}" if power else name


def check_unit_expression(text: str) -> str:
    """``text`` rewritten for Pint, or ``UnitSyntaxError`` naming what is not allowed.

    The one gate every unit string passes before Pint sees it, so parsing costs at most a
    few dozen tokens whatever the input. ``kg/m3``, ``m s-1`` and ``m³`` are accepted
    (exponents straight after a name), and numbers as factors (``1/Pa``,
    ``cSt * 0.96 g/cm^3``); an exponent that is not a literal of at most ``MAX_EXPONENT``,
    more than ``MAX_DEPTH`` nested parentheses or any other character is refused.

    >>> check_unit_expression("kg/m3")
    'kg/m**3'
    """
    text = text.strip()
    if len(text) > MAX_UNIT_CHARS:
        raise UnitSyntaxError(f"is longer than {MAX_UNIT_CHARS} characters")
    out: list[str] = []
    depth = position = 0
    while position < len(text):
        match = _TOKEN.match(text, position)
        if match is None:
            raise UnitSyntaxError(_bad_character(text[position]))
        position = match.end()
        kind = match.lastgroup if match.lastgroup not in {"implicit", "sup"} else "name"
        if kind == "power":
            # 10**9**9**9 is 10**(9**9**9) to Python, and so is µ9**9 (µ**9**9): an exponent
            # after an exponent, written or straight after a name, is refused
            if out and "**" in out[-1]:
                raise UnitSyntaxError("has an exponent of an exponent (write one, e.g. m^3)")
            exponent = _EXPONENT.match(text, position)
            if exponent is None:
                raise UnitSyntaxError(
                    f"has an exponent that is not a small number (write e.g. m^3, s^-2, "
                    f"m^(1/2); at most {MAX_EXPONENT})"
                )
            position = exponent.end()
            out.append("**" + _exponent(exponent.group().strip()))
        elif kind == "name":
            out.append(_name(match))
        elif kind == "number":
            if out and out[-1] not in {"*", "/", "(", " "}:
                out.append(" ")  # "m²1": a factor after an exponent, not "m**21"
            out.append(match.group())  # a factor: "10 cSt * 0.96 g/cm^3", "1/Pa"
        elif kind == "open":
            depth += 1
            if depth > MAX_DEPTH:
                raise UnitSyntaxError(f"nests parentheses deeper than {MAX_DEPTH}")
            out.append("(")
        elif kind == "close":
            depth -= 1
            if depth < 0:
                raise UnitSyntaxError("has a ')' without its '('")
            out.append(")")
        elif kind == "op":
            out.append("/" if match.group() == "/" else "*")
        else:
            out.append(" ")
    if depth:
        raise UnitSyntaxError("has a '(' without its ')'")
    return "".join(out).strip()


def _bad_character(character: str) -> str:
    if character == ",":
        return "has a comma: use a decimal point, and no thousands separators"
    code = f"U+{ord(character):04X}"
    shown = f"{character!r} ({code})" if character.isprintable() else code
    return f"has the character {shown}, which no unit holds"


#: Units of an angle and of a fraction, as Pint's root units (radian is dimensionless to
#: Pint, so its exponent is what tells an angle from a percentage).
_ANGULAR = {"rad", "rad_s"}
_PURE = {"fraction", ""}


def _angle_rule(units: Any, to: Unit) -> tuple[float, str | None]:
    """An extra factor for Pint's ``units`` → ``to`` (2π for Hz), or the rule it breaks."""
    ureg = registry()
    _, root = ureg.get_root_units(units)
    radians = dict(root._units).get("radian", 0)
    return _angle_rule_for(radians, [str(name) for name in units._units], to)


def _angle_rule_for(radians: int, names: list[str], to: Unit) -> tuple[float, str | None]:
    """The angle rules from the radian's exponent and the unit names (Pint's spelling)."""
    if to.suffix == "rad" and radians != 1:
        return 1.0, "is not an angle: an angle needs deg or rad (e.g. '30 deg')"
    if to.suffix in _PURE and radians != 0:
        return 1.0, f"is an angle, not {to.dimension} (e.g. '{to.example}')"
    if to.suffix == "rad_s" and radians != 1:
        if radians == 0 and any(name.endswith("hertz") for name in names):
            return 2.0 * math.pi, None  # revolutions per second, as rpm is per minute
        return 1.0, (
            "is not an angular velocity: write rad/s, deg/s, rpm, or Hz (revolutions per "
            "second); a bare 1/s is ambiguous"
        )
    return 1.0, None


@lru_cache(maxsize=1024)
def _conversion(spelled: str, suffix: str) -> tuple[float, float]:
    """``(scale, offset)`` from a checked expression to ``UNITS[suffix]``; raises
    ``UnitSyntaxError`` with the rule. From granudb's table when every unit is in it, else
    from Pint."""
    fast = _fast_conversion(spelled, UNITS[suffix])
    return fast if fast is not None else _pint_conversion(spelled, suffix)


@cache
def _target(suffix: str) -> SiValue:
    """What one stored unit (``UNITS[suffix]``) is in SI, from granudb's table."""
    value = si_value(check_unit_expression(UNITS[suffix].pint))
    if value is None:  # every stored unit is in the table (tests/io/test_units_fast_path.py)
        raise LookupError(f"unit {UNITS[suffix].pint!r} is not in KNOWN_UNITS")
    return value


def _fast_conversion(spelled: str, to: Unit) -> tuple[float, float] | None:
    """``_pint_conversion``'s answer and refusals computed from granudb's unit table, or None
    when ``spelled`` has a unit outside it (then Pint decides)."""
    value, target = si_value(spelled), _target(to.suffix)
    if value is None:
        return None
    if value.dimension != target.dimension:  # radians are dimensionless, as to Pint
        raise UnitSyntaxError(f"is not {to.dimension} (expected a unit like '{to.example}')")
    source, goal = value.temperature, target.temperature
    if source is not None and goal is not None and source.offset != goal.offset:
        # through kelvin, as Pint converts offset units (K = x·factor + offset); a
        # temperature unit always has an offset (0 for K)
        shift = (source.offset or 0.0) - (goal.offset or 0.0)
        zero, one = ((x * source.factor + shift) / goal.factor for x in (0.0, 1.0))
    else:
        zero, one = 0.0, value.factor / target.factor
    scale = one - zero
    if to.suffix in _ANGULAR | _PURE:
        extra, rule = _angle_rule_for(value.radians, list(value.names), to)
        if rule:
            raise UnitSyntaxError(rule)
        scale *= extra
    if not (math.isfinite(scale) and math.isfinite(zero)) or scale == 0.0:
        raise UnitSyntaxError("is not a usable unit (its scale is zero or not finite)")
    return scale, zero


def _pint_conversion(spelled: str, suffix: str) -> tuple[float, float]:
    """``_conversion`` through Pint, for expressions with units outside granudb's table."""
    to = UNITS[suffix]
    ureg = registry()
    try:
        parsed = ureg.parse_expression(spelled)
        units = parsed.units if isinstance(parsed, ureg.Quantity) else ureg.dimensionless
        factor = float(parsed.magnitude) if isinstance(parsed, ureg.Quantity) else float(parsed)
        zero = float(ureg.Quantity(0.0, units).to(to.pint).magnitude)
        one = float(ureg.Quantity(1.0, units).to(to.pint).magnitude)
    except pint.DimensionalityError:
        raise UnitSyntaxError(
            f"is not {to.dimension} (expected a unit like '{to.example}')"
        ) from None
    except Exception as exc:  # noqa: BLE001 - Pint's parser raises many types (TokenError…)
        raise UnitSyntaxError(f"is not a unit Pint knows ({_first_line(exc)})") from None
    if zero != 0.0 and factor != 1.0:
        raise UnitSyntaxError("scales a temperature with an offset (write degC, K or degF)")
    if to.suffix in _ANGULAR | _PURE:
        extra, rule = _angle_rule(units, to)
        if rule:
            raise UnitSyntaxError(rule)
        factor *= extra
    scale = (one - zero) * factor
    if not (math.isfinite(scale) and math.isfinite(zero)) or scale == 0.0:
        raise UnitSyntaxError("is not a usable unit (its scale is zero or not finite)")
    return scale, zero


def _first_line(exc: Exception) -> str:
    text = str(exc).strip()
    return text.splitlines()[0][:80] if text else type(exc).__name__


def _spelled(text: str) -> str:
    """The unit text checked and rewritten, with the spellings of "no unit" made one."""
    stripped = text.strip()
    if stripped in {"", "-", "1"}:
        return "dimensionless"
    return check_unit_expression(stripped)


def conversion(from_unit: str, to: Unit) -> tuple[float, float]:
    """``(scale, offset)`` such that ``value_in_to = scale * value + offset``.

    Used for CSV columns whose header names a unit: one Pint call per column, then a
    vectorized multiply, instead of one Pint call per cell. Raises ``ValidationError``
    (field ``unit``) when ``from_unit`` is not allowed, unknown or of the wrong dimension.
    """
    try:
        return _conversion(_spelled(from_unit), to.suffix)
    except UnitSyntaxError as exc:
        raise ValidationError("unit", f"[{from_unit}]", str(exc)) from None


#: A number at the start of a quantity; what follows is the unit.
_LEADING_NUMBER = re.compile(r"[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?")
_NOT_FINITE = re.compile(r"[-+]?(?:nan|inf|infinity)\b", re.IGNORECASE)
_COMMA_IN_NUMBER = re.compile(r"[0-9],[0-9]")
#: A unit part that starts with a number other than the 1 of "1/Pa": "1 000 Pa", "2 3 m".
_SECOND_NUMBER = re.compile(r"(?!1\s*/)[0-9.]")
_THOUSANDS = re.compile(r"^[-+]?[0-9]{1,3}(?:,[0-9]{3})+(?![0-9])")


#: The rule for a number too small to be a value: below the smallest normal double in
#: SI (about 2.2e-308), where a float keeps fewer significant digits (a subnormal), or
#: that a unit's conversion turns into 0 (5e-324 mm/s). No measurement is that small;
#: storing it would store a different number (0, or fewer digits).
TINY_RULE = "is too small to be a value: not 0 but below 2.2e-308 in SI (a subnormal number)"


def _finite(field: str, text: str, value: float, written: float | None = None) -> float:
    """``value`` (SI) rounded to the 15 digits a person typed, if finite and, when the
    number ``written`` was not 0, not 0 or subnormal in SI (``TINY_RULE``): the one rule
    for a number from an option, as for a CSV cell."""
    if not math.isfinite(value):
        raise ValidationError(field, text, "must be a finite number")
    if (written is None or written != 0) and value != 0 and abs(value) < _TINY:
        raise ValidationError(field, text, TINY_RULE)
    if written is not None and written != 0 and value == 0:
        raise ValidationError(field, text, TINY_RULE)
    # Pint's conversions leave float dust (4.5 cP -> 0.0045000000000000005); what a person
    # typed is stored as they meant it.
    return float(f"{value:.15g}")


def _refuse_commas(field: str, raw: str) -> None:
    """Pint drops a comma inside a number ("2,5" is 25): refuse it, saying how to write it."""
    if not _COMMA_IN_NUMBER.search(raw):
        return
    pointed = raw.replace(",", ".", 1) if raw.count(",") == 1 else None
    if _THOUSANDS.match(raw):
        plain = _THOUSANDS.sub(lambda m: m.group().replace(",", ""), raw)
        rule = f"has a comma in the number: write {plain!r} (no thousands separators)"
        if pointed:
            rule += f", or {pointed!r} if the comma is a decimal comma"
        raise ValidationError(field, raw, rule)
    example = f": {pointed}" if pointed else ""
    raise ValidationError(field, raw, f"has a decimal comma: use a decimal point{example}")


def parse_quantity(text: str | float, unit: Unit | str, field: str) -> float:
    """Parse ``"190 GPa"`` into a float in ``unit`` (SI), refusing the wrong dimension.

    A bare number is accepted only for dimensionless quantities (ratios, fractions):
    for anything with a dimension, ``"2540"`` is ambiguous and refused with an example.
    ``"45 %"`` and ``"0.45"`` are the same fraction. The number is read by granudb and
    only the unit by Pint (through ``conversion``'s checks), so what any quantity costs
    to parse is bounded.
    """
    unit = UNITS[unit] if isinstance(unit, str) else unit
    if isinstance(text, int | float):
        if unit.pint != "dimensionless":
            raise ValidationError(field, text, f"needs a unit, e.g. '{unit.example}'")
        return _finite(field, str(text), float(text))
    raw = str(text).strip()
    if not raw:
        raise ValidationError(field, "''", "is empty")
    if len(raw) > MAX_QUANTITY_CHARS:
        raise ValidationError(
            field, repr(raw[:20] + "…"), f"is longer than {MAX_QUANTITY_CHARS} characters"
        )
    _refuse_commas(field, raw)
    if _NOT_FINITE.match(raw):
        raise ValidationError(field, raw, "must be a finite number")
    number = _LEADING_NUMBER.match(raw)
    if number is None:
        raise ValidationError(field, raw, f"needs a number and a unit, e.g. '{unit.example}'")
    unit_text = raw[number.end() :].strip()
    if not unit_text:
        if unit.pint != "dimensionless":
            raise ValidationError(field, raw, f"needs a unit, e.g. '{unit.example}'")
        return _finite(field, raw, float(number.group()), float(number.group()))
    if _SECOND_NUMBER.match(unit_text):
        raise ValidationError(
            field, raw, "has a space inside the number or two numbers: write e.g. 1000 Pa"
        )
    try:
        scale, offset = _conversion(_spelled(unit_text), unit.suffix)
    except UnitSyntaxError as exc:
        raise ValidationError(field, raw, str(exc)) from None
    written = float(number.group())
    # with an offset (273.15 K is 0 degC) a value that is 0 in SI is a value
    return _finite(field, raw, written * scale + offset, written if offset == 0 else None)


def round_significant(values: Any, digits: int = 15) -> Any:
    """Round floats to ``digits`` significant digits, vectorized.

    A CSV value in ``mm/s`` times 0.001 picks up float dust (0.1 mm/s → 1.0000000000000002e-4);
    rounding to 15 significant digits gives back the decimal a person wrote, so values
    round-trip through export and import unchanged. Works on scalars and numpy arrays.
    """
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


# --- A value with its standard uncertainty ------------------------------------------------
#
# "23.6 ± 2 nm", "190 GPa ± 5 %", "0.3 m/s +/- 0.01 m/s", "(23.6 ± 2) nm": the number
# before the sign is the value, the one after it its standard uncertainty u (GUM's
# "value ± u", JCGM 100:2008 §7.2.2; granudb stores u, never an expanded U = k·u).

#: The signs that separate a value from its uncertainty.
PLUS_MINUS = re.compile(r"\s*(?:±|\+/-|\+-)\s*")
_PARENTHESISED = re.compile(r"^\((?P<inner>[^()]*)\)\s*(?P<unit>.*)$")
#: A percentage followed by a unit: "1 % kg/m^3" after a ± is ambiguous.
_PERCENT_THEN_UNIT = re.compile(r"^(?:%|percent)\s*(?P<rest>\S.*)$")
_TINY = 2.2250738585072014e-308  # the smallest normal double


def split_uncertain(text: str) -> tuple[str, str] | None:
    """``(value text, uncertainty text)`` of ``"23.6 ± 2 nm"``, with the unit written
    once after the uncertainty, or in parentheses (``"(23.6 ± 2) nm"``), given to both;
    None when there is no ± (or ``+/-``).

    >>> split_uncertain("23.6 ± 2 nm"), split_uncertain("190 GPa +/- 5 %")
    (('23.6 nm', '2 nm'), ('190 GPa', '5 %'))
    """
    raw = text.strip()
    bracket = _PARENTHESISED.match(raw)
    if bracket is not None and PLUS_MINUS.search(bracket["inner"]):
        value, u = PLUS_MINUS.split(bracket["inner"], maxsplit=1)
        return f"{value} {bracket['unit']}".strip(), f"{u} {bracket['unit']}".strip()
    parts = PLUS_MINUS.split(raw, maxsplit=1)
    if len(parts) != 2:
        return None
    value, u = (part.strip() for part in parts)
    number = _LEADING_NUMBER.match(value)
    u_number = _LEADING_NUMBER.match(u)
    if number is not None and number.end() == len(value) and u_number is not None:
        u_unit = u[u_number.end() :].strip()
        percent = _PERCENT_THEN_UNIT.match(u_unit)
        if percent is not None:  # "7780 ± 1 % kg/m^3": 1 % of 7780 kg/m^3, or 77.8 ± 0.01?
            rest = percent["rest"]
            raise ValidationError(
                "value",
                raw,
                f"is ambiguous: write '{value} {rest} ± {u_number.group()} %' (a relative "
                f"uncertainty) or '({value} ± {u_number.group()}) % {rest}' (a value in %)",
            )
        if u_unit not in {"%", "percent"}:  # "23.6 ± 2 nm": the unit belongs to both
            value = f"{value} {u_unit}".strip()
    return value, u


def parse_uncertain_quantity(
    text: str | float, unit: Unit | str, field: str
) -> tuple[float, float | None]:
    """``(value, standard uncertainty)`` in ``unit`` (SI) from ``"23.6 ± 2 nm"``,
    ``"190 GPa ± 5 %"`` (a relative uncertainty: 5 % of the value), ``"20 degC ± 0.5 K"``
    or ``"(0.30 ± 0.01) m/s"``; ``"±"`` may be written ``"+/-"``. Without a ± the
    uncertainty is None (not given — not zero). The uncertainty is converted as a
    difference (no temperature offset), must be finite and ≥ 0, and is refused in a unit of
    another dimension, by field name, as ``parse_quantity`` refuses a value.

    >>> parse_uncertain_quantity("190 GPa ± 5 %", "pa", "youngs_modulus")
    (190000000000.0, 9500000000.0)
    >>> parse_uncertain_quantity("20 degC ± 0.5 K", "c", "temperature")
    (20.0, 0.5)
    """
    unit = UNITS[unit] if isinstance(unit, str) else unit
    try:
        split = split_uncertain(text) if isinstance(text, str) else None
    except ValidationError as exc:
        raise ValidationError(field, exc.value, exc.rule) from None
    if split is None or not isinstance(text, str):  # a number: no uncertainty in it
        return parse_quantity(text, unit, field), None
    value_text, u_text = split
    value = parse_quantity(value_text, unit, field)
    u, relative = _uncertainty(u_text, unit, field, text)
    if relative and unit.suffix == "c":
        # a fraction of a Celsius number is not a fraction of the temperature
        if not _KELVIN.search(value_text):
            rule = _RELATIVE_CELSIUS[:-1] + ", or the temperature in K ('293.15 K ± 1 %')"
            raise ValidationError(field, text, rule)
        return value, _finite(field, text, (value + 273.15) * u)
    return value, _finite(field, text, abs(value) * u if relative else u)


def parse_uncertainty(text: str, unit: Unit | str, field: str) -> tuple[float, bool]:
    """A standard uncertainty on its own, as a dataset states it for a measured column:
    ``(u in unit (SI), False)`` from ``"± 0.5 mm/s"``, or ``(fraction, True)`` from a
    relative ``"± 3 %"`` (of each value); the ``±`` may be left out. Refused as
    ``parse_uncertain_quantity`` refuses the part after its ``±``.

    >>> parse_uncertainty("± 0.5 mm/s", "m_s", "v_n_in")
    (0.0005, False)
    >>> parse_uncertainty("3 %", "m_s", "v_n_in")
    (0.03, True)
    """
    unit = UNITS[unit] if isinstance(unit, str) else unit
    raw = str(text).strip()
    sign = PLUS_MINUS.match(raw)
    u, relative = _uncertainty(raw[sign.end() :] if sign else raw, unit, field, raw)
    if relative and unit.suffix == "c":
        raise ValidationError(field, raw, _RELATIVE_CELSIUS)
    return _finite(field, raw, u, u), relative


#: A relative uncertainty of a temperature is a fraction of the absolute temperature only.
_KELVIN = re.compile(r"[0-9.]\s*(?:K|kelvin)\s*$")
_RELATIVE_CELSIUS = (
    "is a relative uncertainty of a Celsius temperature (3 % of 20 degC is not 3 % of the "
    "temperature): give it in K ('± 0.5 K')"
)


def _uncertainty(u_text: str, unit: Unit, field: str, text: str) -> tuple[float, bool]:
    """(magnitude, relative) of the text after a ±: a fraction when relative (``%``), else
    converted to ``unit`` as a difference (no temperature offset)."""
    number = _LEADING_NUMBER.match(u_text)
    if number is None or u_text.startswith(("-", "+")):
        raise ValidationError(
            field, text, "needs a non-negative number after ±, e.g. '23.6 ± 2 nm' or '± 5 %'"
        )
    u_unit = u_text[number.end() :].strip()
    magnitude = float(number.group())
    if u_unit in {"%", "percent"}:
        u, relative = magnitude / 100.0, True
    elif not u_unit:
        if unit.pint != "dimensionless":
            raise ValidationError(field, text, f"needs a unit after ±, e.g. '{unit.example} ± 1 %'")
        u, relative = magnitude, False
    else:
        try:
            scale, _ = _conversion(_spelled(u_unit), unit.suffix)
        except UnitSyntaxError as exc:
            raise ValidationError(field, text, f"has an uncertainty that {exc}") from None
        u, relative = magnitude * abs(scale), False
    if not math.isfinite(u):
        raise ValidationError(field, text, "needs a finite uncertainty")
    if magnitude != 0 and u < _TINY:  # 5e-324 mm/s is 0 in m/s: not what was written
        raise ValidationError(field, text, f"has an uncertainty that {TINY_RULE}")
    return u, relative
