"""The physical rules every stored value obeys, checked before anything is written.

The database holds the same rules as CHECK constraints (``granudb.db.models``); checking
here first lets granudb refuse bad input with a line that names the field, the value as the
user typed it and the rule, instead of a driver error. Data Package schemas reuse
``RULES`` for their field constraints, so the three places cannot drift apart.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from granudb.errors import ValidationError
from granudb.lazy import numpy as np


@dataclass(frozen=True)
class Rule:
    """An allowed range: ``minimum``/``maximum`` with inclusive or exclusive ends."""

    minimum: float | None = None
    maximum: float | None = None
    min_inclusive: bool = True
    max_inclusive: bool = True

    @property
    def text(self) -> str:
        parts = []
        if self.minimum is not None:
            parts.append(f"{'≥' if self.min_inclusive else '>'} {self.minimum:g}")
        if self.maximum is not None:
            parts.append(f"{'≤' if self.max_inclusive else '<'} {self.maximum:g}")
        return "must be " + " and ".join(parts)

    def holds(self, value: float) -> bool:
        if math.isnan(value) or math.isinf(value):
            return False
        if self.minimum is not None and (
            value < self.minimum or (value == self.minimum and not self.min_inclusive)
        ):
            return False
        return self.maximum is None or not (
            value > self.maximum or (value == self.maximum and not self.max_inclusive)
        )

    def holds_array(self, values: Any) -> Any:
        """Vectorized ``holds`` (NaN counts as "no value" and passes; required-ness is
        checked separately)."""
        values = np.asarray(values, dtype=float)
        ok = np.isnan(values) | np.isfinite(values)
        if self.minimum is not None:
            ok &= np.isnan(values) | (
                values >= self.minimum if self.min_inclusive else values > self.minimum
            )
        if self.maximum is not None:
            ok &= np.isnan(values) | (
                values <= self.maximum if self.max_inclusive else values < self.maximum
            )
        return ok


#: No speed (or speed uncertainty) may be larger than this, in m/s, from a CSV cell, a
#: package cell or an option alike: above any impact apparatus (light-gas guns reach
#: about 8 km/s); every derived quantity squares the speed, and a value like 1e300 m/s
#: would turn them into overflows, not numbers.
MAX_SPEED_M_S = 1e4

POSITIVE = Rule(minimum=0.0, min_inclusive=False)
NON_NEGATIVE = Rule(minimum=0.0)
ABOVE_ABSOLUTE_ZERO = Rule(minimum=-273.15, min_inclusive=False)

RULES: dict[str, Rule] = {
    "density_kg_m3": POSITIVE,
    "youngs_modulus_pa": POSITIVE,
    "shear_modulus_pa": POSITIVE,
    "poisson_ratio": Rule(-1.0, 0.5, min_inclusive=False, max_inclusive=False),
    "roughness_rms_m": NON_NEGATIVE,
    "correlation_length_m": POSITIVE,
    "glycerol_mass_fraction": Rule(0.0, 1.0),
    "viscosity_pa_s": POSITIVE,
    "reference_temperature_c": ABOVE_ABSOLUTE_ZERO,
    "temperature_c": ABOVE_ABSOLUTE_ZERO,
    # C = 0 makes Gohar's film (5.6) vanish and the lubricated friction (5.8) infinite;
    # a fluid whose coefficient is not known leaves it empty.
    "pressure_viscosity_pa_inv": POSITIVE,
    "diameter_m": POSITIVE,
    "wall_diameter_m": POSITIVE,
    "nominal_angle_rad": Rule(0.0, math.pi / 2, max_inclusive=False),
    "incidence_angle_rad": Rule(0.0, math.pi / 2, max_inclusive=False),
    "impact_speed_m_s": POSITIVE,
    # No rebound below St_c: a threshold of the verdict, positive and finite.
    "critical_stokes": POSITIVE,
    "reference_viscosity_pa_s": POSITIVE,
    "reference_density_kg_m3": POSITIVE,
    "yield_stress_pa": POSITIVE,
    "dry_restitution": Rule(0.0, 1.0, min_inclusive=False),
    "dry_friction": NON_NEGATIVE,
    "immersed_friction": NON_NEGATIVE,
    "v_n_in_m_s": POSITIVE,
    "v_t_in_m_s": NON_NEGATIVE,
    "v_n_out_m_s": NON_NEGATIVE,
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
