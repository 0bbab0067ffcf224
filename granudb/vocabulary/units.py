"""The SI units granudb stores, keyed by the suffix every column name ends with.

``youngs_modulus_pa`` is in pascals because it ends in ``_pa``. This table says, for each
suffix, how Pint spells the unit (for parsing at the edges), how an error message names
the dimension, an example people can copy, and the unit a person reads in a table.
Parsing lives in ``granudb.io.units`` and formatting in ``granudb.reporting.format``; both
read this one table. ``KNOWN_UNITS`` (below) holds the units people type that granudb
converts itself, without importing Pint (``si_value``).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass


@dataclass(frozen=True)
class Unit:
    """The unit a column is stored in, e.g. ``Unit("pa", "Pa", "a pressure or modulus", …)``.

    ``suffix`` is what the column name ends with, ``pint`` how Pint spells the unit,
    ``dimension`` how an error message names what was expected, ``example`` a value people
    can type, ``display`` the unit a person reads (``None``: a pure number).
    """

    suffix: str
    pint: str
    dimension: str
    example: str
    display: str | None = None


UNITS: dict[str, Unit] = {
    "kg_m3": Unit("kg_m3", "kg/m^3", "a density", "2540 kg/m^3", "kg/m³"),
    "pa": Unit("pa", "Pa", "a pressure or modulus", "190 GPa", "Pa"),
    "pa_inv": Unit("pa_inv", "1/Pa", "an inverse pressure", "6e-9 1/Pa", "1/Pa"),
    "pa_s": Unit("pa_s", "Pa*s", "a dynamic viscosity", "4.5 cP", "mPa·s"),
    "m": Unit("m", "m", "a length", "12.7 mm", "m"),
    "m_s": Unit("m_s", "m/s", "a velocity", "0.3 m/s", "m/s"),
    "rad": Unit("rad", "rad", "an angle", "30 deg", "°"),
    "rad_s": Unit("rad_s", "rad/s", "an angular velocity", "6.3 rad/s", "rad/s"),
    "c": Unit("c", "degC", "a temperature", "20 degC", "°C"),
    "s": Unit("s", "s", "a time", "6.6 s", "s"),
    "n_m": Unit("n_m", "N*m", "a torque or torsional stiffness", "3.8e-6 N*m", "N·m"),
    "n": Unit("n", "N", "a force", "10 N", "N"),
    "kg": Unit("kg", "kg", "a mass", "8.4 g", "g"),
    "fraction": Unit("fraction", "dimensionless", "a fraction", "45 %", "%"),
    "": Unit("", "dimensionless", "a pure number", "0.23", None),
}


def unit_of_column(column: str) -> Unit:
    """The ``Unit`` a unit-suffixed column name (``v_n_in_m_s``) is stored in."""
    for suffix in sorted((s for s in UNITS if s), key=len, reverse=True):
        if column.endswith("_" + suffix):
            return UNITS[suffix]
    return UNITS[""]


# --- Units granudb converts without Pint -------------------------------------------------
#
# Pint's import and registry cost about 0.3 s, longer than everything else a command like
# ``granudb pair`` does. The units people type for granudb's quantities ("12.7 mm",
# "0.3 m/s", "30 deg", "190 GPa", "4.5 cP") are few; this table gives each its SI value and
# dimension, and ``si_value`` reads a checked expression made only of them. Anything else
# goes to Pint (``granudb.io.units``). tests/io/test_units_fast_path.py proves every unit
# here (each prefix on each prefixable unit) equal to Pint's reading to 1e-12.

#: Dimension exponents of metre, kilogram, second and kelvin.
Dimension = tuple[int, int, int, int]


@dataclass(frozen=True)
class KnownUnit:
    """One unit: ``pint_name`` is Pint's canonical name (``"hertz"``: Pint's angle rule
    reads it), ``factor`` its value in SI (radians for angles), ``dimension`` its SI
    dimension, ``radians`` the exponent of the radian in it (dimensionless to Pint, an
    angle to granudb), ``prefixable`` whether SI prefixes apply, ``offset`` the kelvin of
    its zero (temperatures; None for every other unit)."""

    pint_name: str
    factor: float
    dimension: Dimension = (0, 0, 0, 0)
    radians: int = 0
    prefixable: bool = False
    offset: float | None = None


#: SI prefixes: symbol → (Pint's name, factor). µ and μ are rewritten to u before this.
SI_PREFIXES: dict[str, tuple[str, float]] = {
    "Y": ("yotta", 1e24),
    "Z": ("zetta", 1e21),
    "E": ("exa", 1e18),
    "P": ("peta", 1e15),
    "T": ("tera", 1e12),
    "G": ("giga", 1e9),
    "M": ("mega", 1e6),
    "k": ("kilo", 1e3),
    "h": ("hecto", 1e2),
    "da": ("deca", 1e1),
    "d": ("deci", 1e-1),
    "c": ("centi", 1e-2),
    "m": ("milli", 1e-3),
    "u": ("micro", 1e-6),
    "n": ("nano", 1e-9),
    "p": ("pico", 1e-12),
    "f": ("femto", 1e-15),
    "a": ("atto", 1e-18),
    "z": ("zepto", 1e-21),
    "y": ("yocto", 1e-24),
}

_PRESSURE: Dimension = (-1, 1, -2, 0)
_PER_SECOND: Dimension = (0, 0, -1, 0)
_DEGREE = math.pi / 180.0

#: The units read without Pint, by the spelling people type (Pint's symbols and aliases).
KNOWN_UNITS: dict[str, KnownUnit] = {
    "m": KnownUnit("meter", 1.0, (1, 0, 0, 0), prefixable=True),
    "g": KnownUnit("gram", 1e-3, (0, 1, 0, 0), prefixable=True),
    "s": KnownUnit("second", 1.0, (0, 0, 1, 0), prefixable=True),
    "min": KnownUnit("minute", 60.0, (0, 0, 1, 0)),
    "h": KnownUnit("hour", 3600.0, (0, 0, 1, 0)),
    "L": KnownUnit("liter", 1e-3, (3, 0, 0, 0), prefixable=True),
    "l": KnownUnit("liter", 1e-3, (3, 0, 0, 0), prefixable=True),
    "Pa": KnownUnit("pascal", 1.0, _PRESSURE, prefixable=True),
    "bar": KnownUnit("bar", 1e5, _PRESSURE, prefixable=True),
    "N": KnownUnit("newton", 1.0, (1, 1, -2, 0), prefixable=True),
    "P": KnownUnit("poise", 0.1, (-1, 1, -1, 0), prefixable=True),
    "Hz": KnownUnit("hertz", 1.0, _PER_SECOND, prefixable=True),
    "rad": KnownUnit("radian", 1.0, radians=1, prefixable=True),
    "deg": KnownUnit("degree", _DEGREE, radians=1),
    "°": KnownUnit("degree", _DEGREE, radians=1),
    "arcmin": KnownUnit("arcminute", _DEGREE / 60.0, radians=1),
    "rpm": KnownUnit("revolutions_per_minute", 2.0 * math.pi / 60.0, _PER_SECOND, 1),
    "rps": KnownUnit("revolutions_per_second", 2.0 * math.pi, _PER_SECOND, 1),
    "percent": KnownUnit("percent", 0.01),
    "permille": KnownUnit("permille", 1e-3),
    "ppm": KnownUnit("ppm", 1e-6),
    "dimensionless": KnownUnit("dimensionless", 1.0),
    "K": KnownUnit("kelvin", 1.0, (0, 0, 0, 1), offset=0.0),
    "degC": KnownUnit("degree_Celsius", 1.0, (0, 0, 0, 1), offset=273.15),
    "°C": KnownUnit("degree_Celsius", 1.0, (0, 0, 0, 1), offset=273.15),
}

#: Prefix + unit spellings that Pint reads as another unit: hbar is ħ, not a hectobar.
NOT_PREFIXED = frozenset({"hbar"})


def known_unit(name: str) -> tuple[str, KnownUnit, float] | None:
    """``(Pint's full name, unit, prefix factor)`` for a spelling such as ``"mm"``, or None.

    An exact spelling wins over a prefixed reading (``"Pa"`` is the pascal, as in Pint).
    """
    unit = KNOWN_UNITS.get(name)
    if unit is not None:
        return unit.pint_name, unit, 1.0
    if name in NOT_PREFIXED:
        return None
    for prefix, (prefix_name, factor) in SI_PREFIXES.items():
        if name.startswith(prefix):
            unit = KNOWN_UNITS.get(name[len(prefix) :])
            if unit is not None and unit.prefixable:
                return prefix_name + unit.pint_name, unit, factor
    return None


@dataclass(frozen=True)
class SiValue:
    """What a unit expression means in SI: one of it is ``factor`` SI units of
    ``dimension``; ``radians`` is the radian's exponent; ``names`` Pint's names of its units
    with their exponents; ``temperature`` the single offset unit it is, if it is one."""

    factor: float
    dimension: Dimension
    radians: int
    names: dict[str, int]
    temperature: KnownUnit | None = None


#: One factor of a checked expression: a name with an optional integer exponent.
_FACTOR = re.compile(r"(?P<op>\s*[*/]\s*|\s+|^)(?P<name>[A-Za-z_°Ω]+)(?:\*\*(?P<exp>[-+]?\d+))?")


def si_value(spelled: str) -> SiValue | None:
    """The SI meaning of an expression checked by ``granudb.io.units.check_unit_expression``
    (``"kg/m**3"``, ``"mPa*s"``, ``"1/Pa"``), or None when any part of it is not in
    ``KNOWN_UNITS`` or not simple (parentheses, numbers other than a leading ``1/``,
    fractional exponents): then Pint reads it.

    As in Pint, ``*``, ``/`` and a space have equal precedence and apply left to right
    (``"kg/m s"`` is kg·s/m). A temperature (K, degC) is read only alone, with its offset.

    >>> value = si_value("g/cm**3")
    >>> round(value.factor, 12), value.dimension
    (1000.0, (-3, 1, 0, 0))
    """
    text = spelled.strip()
    if text.startswith("1/"):  # "1/Pa": the one number Pint sees in a unit we read
        text = "dimensionless/" + text[2:]
    factor, radians, position = 1.0, 0, 0
    dimension = [0, 0, 0, 0]
    names: dict[str, int] = {}
    temperature: KnownUnit | None = None
    count = 0
    while position < len(text):
        match = _FACTOR.match(text, position)
        if match is None or (count == 0) != (match["op"] == ""):
            return None
        position, count = match.end(), count + 1
        found = known_unit(match["name"])
        if found is None:
            return None
        pint_name, unit, prefix = found
        power = int(match["exp"] or 1) * (-1 if match["op"].strip() == "/" else 1)
        if unit.offset is not None:
            temperature = unit
        try:
            factor *= (prefix * unit.factor) ** power
        except OverflowError:  # "Pm**21": beyond a float; not a unit anyone means
            return None
        if not math.isfinite(factor) or factor == 0.0:
            return None
        radians += unit.radians * power
        for axis, exponent in enumerate(unit.dimension):
            dimension[axis] += exponent * power
        if unit.dimension != (0, 0, 0, 0) or unit.radians or unit.factor != 1.0:
            names[pint_name] = names.get(pint_name, 0) + power  # Pint drops "dimensionless"
    if count == 0:
        return None
    if temperature is not None and (count != 1 or names != {temperature.pint_name: 1}):
        return None  # a temperature inside a product: Pint's rules for offset units
    names = {name: power for name, power in names.items() if power}
    return SiValue(
        factor,
        (dimension[0], dimension[1], dimension[2], dimension[3]),
        radians,
        names,
        temperature,
    )
