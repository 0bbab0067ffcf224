"""The SI units granudb stores, keyed by the suffix every column name ends with.

``youngs_modulus_pa`` is in pascals because it ends in ``_pa``. This table says, for each
suffix, how Pint spells the unit (for parsing at the edges), how an error message names
the dimension, an example people can copy, and the unit a person reads in a table.
Parsing lives in ``granudb.io.units`` and formatting in ``granudb.report.format``; both
read this one table.
"""

from __future__ import annotations

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
